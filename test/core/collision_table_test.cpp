// The collision table (collision_table.h): the defaults hold the closed forms in both orders and
// leave the pairs without one empty, registration replaces and is ordered, Collide() with the
// shapes swapped returns the flipped result (points swapped, normal negated) at 1000 random poses
// per registered pair (seed 12345), and two simulators with different tables do not affect each
// other.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "collision_test_util.h"
#include "dynamics_scenes.h"
#include "nonsmooth_sim/core/collision/capsule_capsule.h"
#include "nonsmooth_sim/core/collision/collision_table.h"
#include "nonsmooth_sim/core/collision/plane_box.h"
#include "nonsmooth_sim/core/collision/plane_capsule.h"
#include "nonsmooth_sim/core/collision/plane_cylinder.h"
#include "nonsmooth_sim/core/collision/plane_ellipsoid.h"
#include "nonsmooth_sim/core/collision/plane_hull.h"
#include "nonsmooth_sim/core/collision/plane_revolution.h"
#include "nonsmooth_sim/core/collision/plane_sphere.h"
#include "nonsmooth_sim/core/collision/sphere_box.h"
#include "nonsmooth_sim/core/collision/sphere_capsule.h"
#include "nonsmooth_sim/core/collision/sphere_sphere.h"
#include "nonsmooth_sim/core/simulator.h"
#include "scene_builders.h"

namespace nonsmooth_sim {
namespace {

using namespace collision_test;  // NOLINT

struct ClosedForm {
  ShapeType a;
  ShapeType b;
  CollideFunction function;
};

const std::vector<ClosedForm>& ClosedForms() {
  static const std::vector<ClosedForm> pairs = {
      {ShapeType::kPlane, ShapeType::kSphere, &CollidePlaneSphere},
      {ShapeType::kPlane, ShapeType::kCapsule, &CollidePlaneCapsule},
      {ShapeType::kPlane, ShapeType::kEllipsoid, &CollidePlaneEllipsoid},
      {ShapeType::kPlane, ShapeType::kCylinder, &CollidePlaneCylinder},
      {ShapeType::kPlane, ShapeType::kBox, &CollidePlaneBox},
      {ShapeType::kPlane, ShapeType::kConvexHull, &CollidePlaneHull},
      {ShapeType::kPlane, ShapeType::kRevolution, &CollidePlaneRevolution},
      {ShapeType::kSphere, ShapeType::kSphere, &CollideSphereSphere},
      {ShapeType::kSphere, ShapeType::kCapsule, &CollideSphereCapsule},
      {ShapeType::kSphere, ShapeType::kBox, &CollideSphereBox},
      {ShapeType::kCapsule, ShapeType::kCapsule, &CollideCapsuleCapsule},
  };
  return pairs;
}

bool IsClosedForm(ShapeType a, ShapeType b) {
  for (const ClosedForm& pair : ClosedForms()) {
    if ((pair.a == a && pair.b == b) || (pair.a == b && pair.b == a)) return true;
  }
  return false;
}

TEST(CollisionTable, HoldsTheClosedFormsInBothOrders) {
  const CollisionTable table = CollisionTable::Defaults();
  for (const ClosedForm& pair : ClosedForms()) {
    EXPECT_EQ(table.Find(pair.a, pair.b), pair.function);
    EXPECT_EQ(table.Find(pair.b, pair.a), pair.function);
  }
  // every other pair is empty (the FCL adapter fills the non-plane ones; plane–plane stays
  // empty), and an empty table has no pair at all
  const CollisionTable empty;
  for (int i = 0; i < kShapeTypeCount; ++i) {
    for (int j = 0; j < kShapeTypeCount; ++j) {
      const auto a = static_cast<ShapeType>(i);
      const auto b = static_cast<ShapeType>(j);
      if (!IsClosedForm(a, b)) {
        EXPECT_EQ(table.Find(a, b), nullptr) << i << ", " << j;
      }
      EXPECT_EQ(empty.Find(a, b), nullptr) << i << ", " << j;
    }
  }
}

TEST(CollisionTable, CollideReportsAMissingPair) {
  const CollisionTable table = CollisionTable::Defaults();
  ContactGeometry out[kMaxPairContacts];
  const Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  EXPECT_EQ(table.Collide(Shape::Plane(), origin, Shape::Plane(), origin, 1.0, out), -1);
  EXPECT_EQ(
      table.Collide(Shape::Box({1, 1, 1}), origin, Shape::Ellipsoid({1, 1, 1}), origin, 1.0, out),
      -1);
}

int CountingFunction(const Shape&, const Eigen::Isometry3d&, const Shape&, const Eigen::Isometry3d&,
                     double, ContactGeometry* out) {
  out[0] = ContactGeometry{};
  out[0].feature = 42;
  return 1;
}

TEST(CollisionTable, RegisterReplacesAndRequiresOrder) {
  CollisionTable table = CollisionTable::Defaults();
  table.Register(ShapeType::kEllipsoid, ShapeType::kBox, &CountingFunction);
  EXPECT_EQ(table.Find(ShapeType::kBox, ShapeType::kEllipsoid), &CountingFunction);
  ContactGeometry out[kMaxPairContacts];
  const Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  ASSERT_EQ(
      table.Collide(Shape::Box({1, 1, 1}), origin, Shape::Ellipsoid({1, 1, 1}), origin, 0.0, out),
      1);
  EXPECT_EQ(out[0].feature, 42);
  EXPECT_EQ(out[0].normal, -Eigen::Vector3d::UnitZ());  // called swapped: flipped back
  table.Register(ShapeType::kEllipsoid, ShapeType::kBox, nullptr);
  EXPECT_EQ(table.Find(ShapeType::kEllipsoid, ShapeType::kBox), nullptr);
  EXPECT_THROW(table.Register(ShapeType::kBox, ShapeType::kSphere, &CountingFunction),
               std::invalid_argument);
  EXPECT_EQ(table.Find(ShapeType::kSphere, ShapeType::kBox), &CollideSphereBox);
  // a copy is a table of its own
  CollisionTable copy = table;
  copy.Register(ShapeType::kSphere, ShapeType::kBox, &CountingFunction);
  EXPECT_EQ(table.Find(ShapeType::kSphere, ShapeType::kBox), &CollideSphereBox);
}

// Collide(b, a) = Collide(a, b) with point_a ↔ point_b and −normal: exactly for pairs of different
// types (the same computation), to round-off for the symmetric pairs of equal types (computed
// from the other side).
TEST(CollisionTable, SwappingTheShapesFlipsTheResult) {
  const CollisionTable table = CollisionTable::Defaults();
  std::mt19937 rng(kSeed);
  for (const ClosedForm& pair : ClosedForms()) {
    const double tolerance = pair.a == pair.b ? 1e-12 : 0.0;
    for (int i = 0; i < kPoses; ++i) {
      const Shape a = RandomShape(pair.a, rng);
      const Shape b = RandomShape(pair.b, rng);
      const Eigen::Isometry3d pose_a = RandomPose(rng, 0.5);
      const Eigen::Isometry3d pose_b = RandomPose(rng, 0.5);
      ContactGeometry forward[kMaxPairContacts];
      ContactGeometry backward[kMaxPairContacts];
      const int count = table.Collide(a, pose_a, b, pose_b, kInf, forward);
      ASSERT_GE(count, 1);
      ASSERT_EQ(table.Collide(b, pose_b, a, pose_a, kInf, backward), count);
      for (int k = 0; k < count; ++k) {
        EXPECT_NEAR(backward[k].gap, forward[k].gap, tolerance);
        EXPECT_LE((backward[k].point_a - forward[k].point_b).norm(), tolerance);
        EXPECT_LE((backward[k].point_b - forward[k].point_a).norm(), tolerance);
        EXPECT_LE((backward[k].normal + forward[k].normal).norm(), tolerance);
        EXPECT_EQ(backward[k].feature, forward[k].feature);
        EXPECT_EQ(backward[k].face_point, forward[k].face_point);
      }
    }
  }
}

// Collide() returns what the pair function returns, in ShapeType order.
TEST(CollisionTable, CollideCallsThePairFunction) {
  const CollisionTable table = CollisionTable::Defaults();
  std::mt19937 rng(kSeed);
  const Shape plane = Shape::Plane();
  const Shape box = RandomShape(ShapeType::kBox, rng);
  const Eigen::Isometry3d pose_plane = RandomPose(rng, 0.2);
  const Eigen::Isometry3d pose_box = RandomPose(rng, 0.2);
  ContactGeometry direct[kMaxPairContacts];
  ContactGeometry through_table[kMaxPairContacts];
  const int count = CollidePlaneBox(plane, pose_plane, box, pose_box, 0.1, direct);
  ASSERT_EQ(table.Collide(plane, pose_plane, box, pose_box, 0.1, through_table), count);
  for (int k = 0; k < count; ++k) {
    EXPECT_EQ(through_table[k].gap, direct[k].gap);
    EXPECT_EQ(through_table[k].point_b, direct[k].point_b);
  }
}

// Each scene carries its own table: a ball resting on the ground with the defaults keeps its
// contact, the same scene without the plane–sphere pair falls through, both stepped in turn in
// one process (a process-wide table would give both the same pairs).
TEST(CollisionTable, TwoSimulatorsWithDifferentTablesDoNotAffectEachOther) {
  constexpr double kRadius = 0.05;  // [m]
  const Scene with_pair = test::BallScene(kRadius, /*height=*/0.0, /*restitution=*/0.0, /*mu=*/0.3);
  Scene without_pair = with_pair;
  without_pair.collision_table.Register(ShapeType::kPlane, ShapeType::kSphere, nullptr);

  Simulator with(with_pair, SimulatorOptions{});
  Simulator without(without_pair, SimulatorOptions{});
  StepStatistics with_stats;
  StepStatistics without_stats;
  for (int step = 0; step < 1000; ++step) {  // 0.1 s at the default Δt = 1e-4 s
    with.Step(&with_stats);
    without.Step(&without_stats);
    ASSERT_EQ(with_stats.closed_contacts, 1) << "step " << step;
    ASSERT_EQ(without_stats.closed_contacts, 0) << "step " << step;
  }
  EXPECT_NEAR(with.state()[0].position.z(), kRadius, 1e-6);
  EXPECT_LT(without.state()[0].position.z(), kRadius - 0.01);  // fell ½gt² ≈ 0.05 m in 0.1 s
  EXPECT_EQ(with.scene().collision_table.Find(ShapeType::kPlane, ShapeType::kSphere),
            &CollidePlaneSphere);
  EXPECT_EQ(without.scene().collision_table.Find(ShapeType::kPlane, ShapeType::kSphere), nullptr);
}

}  // namespace
}  // namespace nonsmooth_sim
