// A convex hull against every other shape through FCL's convex type (fcl_pairs.h): registered for
// each pair; at 200 random samples per pair (seed 12345) near contact along a known direction
// (SamplePair below): separated, the gap is the exact distance; penetrating by up to 2 mm, the
// gap lies between the sampled depth and 0 and equals the projection gap along its own normal;
// and a box as a hull gives the box's gap (its closed form against a sphere), for 500 hulls made
// and freed one after the other (new hulls at the addresses of freed ones: CollideFcl's cache of
// fcl::Convex per hull must not mistake one for another); faces touching face to face give the
// corners of their overlap, so that a hull die rests on a box or hull table.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>

#include "../core/collision_test_util.h"
#include "../core/scene_builders.h"
#include "nonsmooth_sim/collision_fcl/fcl_pairs.h"
#include "nonsmooth_sim/core/collision/sphere_box.h"
#include "nonsmooth_sim/core/simulator.h"
#include "../measured_value.h"

namespace nonsmooth_sim {
namespace {

using test::Scientific;

using namespace collision_test;  // NOLINT

constexpr ShapeType kOthers[] = {ShapeType::kSphere, ShapeType::kCapsule, ShapeType::kEllipsoid,
                                 ShapeType::kCylinder, ShapeType::kBox, ShapeType::kConvexHull};

// A mesh's shapes, its hull and its body of revolution (plane_revolution.h), against every shape
// and each other by FCL; against the plane by their closed forms.
TEST(FclHull, MeshShapesRegisteredAgainstEveryShapeButThePlane) {
  CollisionTable table = CollisionTable::Defaults();
  RegisterFclPairs(&table);
  for (ShapeType mesh : {ShapeType::kConvexHull, ShapeType::kRevolution}) {
    for (ShapeType other : kOthers) {
      EXPECT_EQ(table.Find(other, mesh), &CollideFcl) << ShapeTypeName(other);
      EXPECT_EQ(table.Find(mesh, other), &CollideFcl) << ShapeTypeName(other);
    }
    EXPECT_EQ(table.Find(mesh, ShapeType::kRevolution), &CollideFcl);
    EXPECT_NE(table.Find(ShapeType::kPlane, mesh), nullptr);
    EXPECT_NE(table.Find(ShapeType::kPlane, mesh), &CollideFcl);
  }
}

// A hull (a box of random half extents off its frame's origin) and a shape of `type`, B moved so
// that their support points along a random d are `offset` apart along d: PG(d) = offset, and for
// offset ≥ 0 the signed distance is exactly offset.
struct Sample {
  Shape a, b;
  Eigen::Isometry3d pose_a, pose_b;
};
Sample SampleNear(std::mt19937& rng, ShapeType type, double offset) {
  const Eigen::Vector3d h(Uniform(rng, 0.05, 0.3), Uniform(rng, 0.05, 0.3),
                          Uniform(rng, 0.05, 0.3));
  const Eigen::Vector3d c(Uniform(rng, -0.1, 0.1), Uniform(rng, -0.1, 0.1),
                          Uniform(rng, -0.1, 0.1));
  Sample s{Shape::Hull(BoxHull(h, c)),
           type == ShapeType::kConvexHull ? Shape::Hull(BoxHull(h.reverse(), -c))
                                          : RandomShape(type, rng),
           RandomPose(rng, 1.0), RandomPose(rng, 1.0)};
  const Eigen::Vector3d d = RandomRotation(rng).col(0);
  const Eigen::Vector3d p = Support(s.a, s.pose_a, d);
  const Eigen::Vector3d q = Support(s.b, s.pose_b, -d);
  s.pose_b.translation() += p + offset * d - q;
  return s;
}

double SmallestGap(const Sample& s, double margin, ContactGeometry* first) {
  ContactGeometry out[kMaxPairContacts];
  const int n = CollideFcl(s.a, s.pose_a, s.b, s.pose_b, margin, out);
  double gap = kInf;
  for (int i = 0; i < n; ++i) {
    if (out[i].gap < gap) gap = out[i].gap, *first = out[i];
  }
  return gap;
}

TEST(FclHull, GapsAreExactWhenSeparatedAndConsistentWhenPenetrating) {
  std::mt19937 rng(kSeed);
  for (ShapeType type : kOthers) {
    const std::string name(ShapeTypeName(type));
    double worst_separated = 0.0, worst_consistency = 0.0;
    for (int k = 0; k < 200; ++k) {
      // separated by up to 5 cm: the exact distance
      const double offset = Uniform(rng, 1e-3, 0.05);
      const Sample s = SampleNear(rng, type, offset);
      ContactGeometry c;
      const double gap = SmallestGap(s, 0.1, &c);
      worst_separated = std::max(worst_separated, std::abs(gap - offset));
      // penetrating by up to 2 mm
      const double depth = -Uniform(rng, 0.0, 2e-3);
      const Sample p = SampleNear(rng, type, depth);
      const double pen = SmallestGap(p, 0.0, &c);
      ASSERT_LT(pen, kInf) << name << " sample " << k;
      EXPECT_LE(pen, 1e-12) << name << " sample " << k;
      EXPECT_GE(pen, depth - 1e-9) << name << " sample " << k;
      const double along_normal = ProjectionGap(p.a, p.pose_a, p.b, p.pose_b, c.normal);
      worst_consistency = std::max(worst_consistency, std::abs(along_normal - pen));
    }
    ::testing::Test::RecordProperty(name + "_separated_error_m", Scientific(worst_separated));
    ::testing::Test::RecordProperty(name + "_consistency_m", Scientific(worst_consistency));
    EXPECT_LT(worst_separated, 1e-9) << name;
    EXPECT_LT(worst_consistency, 1e-9) << name;
  }
}

TEST(FclHull, ABoxAsAHullCollidesAsTheBox) {
  // against a sphere: the box's closed form (sphere_box.h), separated and penetrating
  std::mt19937 rng(kSeed);
  double worst_gap = 0.0, worst_normal = 0.0;
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d h(Uniform(rng, 0.05, 0.3), Uniform(rng, 0.05, 0.3),
                            Uniform(rng, 0.05, 0.3));
    const Shape sphere = Shape::Sphere(Uniform(rng, 0.05, 0.3));
    const Eigen::Isometry3d pose_box = RandomPose(rng, 1.0);
    const Eigen::Vector3d d = RandomRotation(rng).col(0);
    Eigen::Isometry3d pose_sphere = Eigen::Isometry3d::Identity();
    pose_sphere.translation() = Support(Shape::Box(h), pose_box, d) +
                                (sphere.radius + Uniform(rng, -2e-3, 0.02)) * d;
    ContactGeometry closed[kMaxPairContacts], fcl[kMaxPairContacts];
    const int n = CollideSphereBox(sphere, pose_sphere, Shape::Box(h), pose_box, 0.05, closed);
    const int m = CollideFcl(sphere, pose_sphere, Shape::Hull(BoxHull(h)), pose_box, 0.05, fcl);
    ASSERT_EQ(n, 1) << k;
    ASSERT_EQ(m, 1) << k;
    worst_gap = std::max(worst_gap, std::abs(closed[0].gap - fcl[0].gap));
    worst_normal = std::max(worst_normal, (closed[0].normal - fcl[0].normal).norm());
  }
  ::testing::Test::RecordProperty("worst_gap_m", Scientific(worst_gap));
  ::testing::Test::RecordProperty("worst_normal", Scientific(worst_normal));
  EXPECT_LT(worst_gap, 1e-8);
  EXPECT_LT(worst_normal, 1e-4);
}

TEST(FclHull, FacesTouchingFaceToFaceGiveTheCornersOfTheirOverlap) {
  // a 0.2 m square face on an equal one turned by 45° about the normal: their overlap is a
  // regular octagon, eight contacts at the same gap (here -1 mm), on both faces' planes
  const Eigen::Vector3d h(0.1, 0.1, 0.05);
  Eigen::Isometry3d below = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d above = Eigen::Isometry3d::Identity();
  above.linear() = Rotation(kPi / 4, Eigen::Vector3d::UnitZ());
  above.translation() = Eigen::Vector3d(0.0, 0.0, 0.1 - 1e-3);
  for (const Shape& table : {Shape::Box(h), Shape::Hull(BoxHull(h))}) {
    ContactGeometry out[kMaxPairContacts];
    const int n = CollideFcl(table, below, Shape::Hull(BoxHull(h)), above, 0.01, out);
    ASSERT_EQ(n, 8) << ShapeTypeName(table.type);
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(out[i].gap, -1e-3, 1e-12);
      EXPECT_LT((out[i].normal - Eigen::Vector3d::UnitZ()).norm(), 1e-9);
      EXPECT_NEAR(out[i].point_a.z(), 0.05, 1e-12);  // on the table's face
      // a corner of the octagon: on an edge of one square or the other, 0.1 from the axis
      const Eigen::Vector3d in_above = above.inverse() * out[i].point_b;
      EXPECT_NEAR(std::max(out[i].point_b.head<2>().cwiseAbs().maxCoeff(),
                           in_above.head<2>().cwiseAbs().maxCoeff()),
                  0.1, 1e-12);
    }
  }
}

TEST(FclHull, AHullDieRestsOnABoxOrHullTableAsTheBoxDie) {
  // one contact would let it rock about it (measured without the face contacts: tilted by
  // 0.1 rad after 2 s); with them it rests on four, like the box on the box
  const Eigen::Vector3d h(0.1, 0.07, 0.05);
  const Eigen::Vector3d slab(1.0, 1.0, 0.1);
  for (const Shape& table : {Shape::Box(slab), Shape::Hull(BoxHull(slab))}) {
    Scene scene =
        test::BoxBodyScene("die", h, Shape::Hull(BoxHull(h)), /*mass=*/0.5, /*mu=*/0.5);
    Collider top = scene.colliders[0];
    top.name = "table";
    top.body = kWorld;
    top.shape = table;
    top.pose.translation() = Eigen::Vector3d(0.0, 0.0, -0.1);
    scene.colliders.push_back(top);
    BodyState start;
    start.position = Eigen::Vector3d(0.05, 0.02, h.z());
    scene.initial_state = {start};
    RegisterFclPairs(&scene.collision_table);
    SimulatorOptions options;
    options.time_step = 1e-3;
    Simulator sim(scene, options);
    double worst_speed = 0.0;
    int contacts = 0;
    for (int k = 0; k < 2000; ++k) {
      contacts = sim.Step().closed_contacts;
      const BodyState& s = sim.state()[0];
      worst_speed = std::max(worst_speed, s.linear_velocity.norm() + s.angular_velocity.norm());
    }
    const std::string name(ShapeTypeName(table.type));
    ::testing::Test::RecordProperty(name + "_worst_speed", Scientific(worst_speed));
    EXPECT_EQ(contacts, 4) << name;
    EXPECT_LT(worst_speed, 1e-6) << name;  // measured: 3e-8
    EXPECT_LT(sim.state()[0].orientation.angularDistance(Eigen::Quaterniond::Identity()), 1e-9)
        << name;
    EXPECT_NEAR(sim.state()[0].position.z(), h.z(), 1e-6) << name;
  }
}

}  // namespace
}  // namespace nonsmooth_sim
