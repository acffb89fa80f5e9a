// A convex hull against every other shape through FCL's convex type (fcl_pairs.h): registered for
// each pair; at 200 random samples per pair (seed 12345) near contact along a known direction
// (SamplePair below): separated, the gap is the exact distance; penetrating by up to 2 mm, the
// gap lies between the sampled depth and 0 and equals the projection gap along its own normal;
// and a box as a hull gives the box's gap (its closed form against a sphere), for 500 hulls made
// and freed one after the other (new hulls at the addresses of freed ones: CollideFcl's cache of
// fcl::Convex per hull must not mistake one for another).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>

#include "../core/collision_test_util.h"
#include "nonsmooth_sim/collision_fcl/fcl_pairs.h"
#include "nonsmooth_sim/core/collision/sphere_box.h"

namespace nonsmooth_sim {
namespace {

// "1.23e-10": a measured value for RecordProperty.
std::string Scientific(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}

using namespace collision_test;  // NOLINT

constexpr ShapeType kOthers[] = {ShapeType::kSphere, ShapeType::kCapsule, ShapeType::kEllipsoid,
                                 ShapeType::kCylinder, ShapeType::kBox, ShapeType::kConvexHull};

TEST(FclHull, RegisteredAgainstEveryShapeButThePlane) {
  CollisionTable table = CollisionTable::Defaults();
  RegisterFclPairs(&table);
  for (ShapeType other : kOthers) {
    EXPECT_EQ(table.Find(other, ShapeType::kConvexHull), &CollideFcl);
    EXPECT_EQ(table.Find(ShapeType::kConvexHull, other), &CollideFcl);
  }
  EXPECT_NE(table.Find(ShapeType::kPlane, ShapeType::kConvexHull), &CollideFcl);
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

}  // namespace
}  // namespace nonsmooth_sim
