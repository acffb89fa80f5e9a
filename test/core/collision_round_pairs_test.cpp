// Sphere–sphere, sphere–capsule, capsule–capsule (sphere_sphere.h, sphere_capsule.h,
// capsule_capsule.h).
//
// At 1000 random poses (seed 12345), half of them overlapping, each contact is checked against
//  - the brute-force distance between the cores (a point for a sphere, the segment of a
//    capsule) minimised over their parameters (zooming grid): gap = that distance − r_a − r_b,
//    since a sphere and a capsule are balls swept along their cores (shape.h);
//  - the projection gap along its normal, min_B n·x − max_A n·y from the shapes' support
//    functions: equal to the gap only for the optimal normal (collision_test_util.h);
//  - point_a on A's surface, point_b on B's, point_b − point_a = gap·n.
// Then the parallel capsules (two contacts at the ends of the overlap) and degenerate inputs.
#include <gtest/gtest.h>

#include <random>

#include "collision_test_util.h"
#include "nonsmooth_sim/core/collision/capsule_capsule.h"
#include "nonsmooth_sim/core/collision/sphere_capsule.h"
#include "nonsmooth_sim/core/collision/sphere_sphere.h"

namespace nonsmooth_sim {
namespace {

using namespace collision_test;  // NOLINT

// The reference minimises to round-off (~1e-16 m) and the closed forms are exact: both the
// gap and the projection gap agree to round-off of the poses' arithmetic.
constexpr double kGapTolerance = 1e-12;
constexpr double kSurfaceTolerance = 1e-12;

// Core point of a sphere or capsule at parameter s (0 for a sphere).
Eigen::Vector3d Core(const Eigen::Isometry3d& pose, double s) {
  return pose * Eigen::Vector3d(0, 0, s);
}

// Random pose of B near A: centres within ~ the sum of the sizes, so that about half overlap.
Eigen::Isometry3d NearbyPose(std::mt19937& rng, const Eigen::Isometry3d& pose_a, double reach) {
  Eigen::Isometry3d pose = RandomPose(rng, reach);
  pose.translation() += pose_a.translation();
  return pose;
}

void ExpectContactOfRoundShapes(const ContactGeometry& c, const Shape& a,
                                const Eigen::Isometry3d& pose_a, const Shape& b,
                                const Eigen::Isometry3d& pose_b, double reference_gap) {
  EXPECT_TRUE(WellFormed(c));
  EXPECT_NEAR(c.gap, reference_gap, kGapTolerance);
  EXPECT_NEAR(ProjectionGap(a, pose_a, b, pose_b, c.normal), c.gap, kGapTolerance);
  EXPECT_NEAR(SurfaceResidual(a, pose_a, c.point_a), 0.0, kSurfaceTolerance);
  EXPECT_NEAR(SurfaceResidual(b, pose_b, c.point_b), 0.0, kSurfaceTolerance);
  EXPECT_FALSE(c.face_point);
}

TEST(SphereSphere, MatchesDefinitionAtRandomPoses) {
  std::mt19937 rng(kSeed);
  int overlapping = 0;
  for (int i = 0; i < kPoses; ++i) {
    const Shape a = RandomShape(ShapeType::kSphere, rng);
    const Shape b = RandomShape(ShapeType::kSphere, rng);
    const Eigen::Isometry3d pose_a = RandomPose(rng, 1.0);
    const Eigen::Isometry3d pose_b = NearbyPose(rng, pose_a, 0.6);
    ContactGeometry out[kMaxPairContacts];
    ASSERT_EQ(CollideSphereSphere(a, pose_a, b, pose_b, kInf, out), 1);
    const double reference =
        (pose_b.translation() - pose_a.translation()).norm() - a.radius - b.radius;
    ExpectContactOfRoundShapes(out[0], a, pose_a, b, pose_b, reference);
    EXPECT_EQ(out[0].feature, 0);
    overlapping += reference < 0.0 ? 1 : 0;
  }
  EXPECT_GT(overlapping, kPoses / 5);  // the sample covers penetration
}

TEST(SphereCapsule, MatchesBruteForceAtRandomPoses) {
  std::mt19937 rng(kSeed);
  int overlapping = 0;
  for (int i = 0; i < kPoses; ++i) {
    const Shape a = RandomShape(ShapeType::kSphere, rng);
    const Shape b = RandomShape(ShapeType::kCapsule, rng);
    const Eigen::Isometry3d pose_a = RandomPose(rng, 1.0);
    const Eigen::Isometry3d pose_b = NearbyPose(rng, pose_a, 0.6);
    ContactGeometry out[kMaxPairContacts];
    ASSERT_EQ(CollideSphereCapsule(a, pose_a, b, pose_b, kInf, out), 1);
    const double distance =
        BruteMinimize1([&](double t) { return (Core(pose_b, t) - pose_a.translation()).norm(); },
                       -b.half_length, b.half_length)
            .first;
    const double reference = distance - a.radius - b.radius;
    ExpectContactOfRoundShapes(out[0], a, pose_a, b, pose_b, reference);
    EXPECT_EQ(out[0].feature, 0);
    overlapping += reference < 0.0 ? 1 : 0;
  }
  EXPECT_GT(overlapping, kPoses / 5);
}

TEST(CapsuleCapsule, MatchesBruteForceAtRandomPoses) {
  std::mt19937 rng(kSeed);
  int overlapping = 0;
  for (int i = 0; i < kPoses; ++i) {
    const Shape a = RandomShape(ShapeType::kCapsule, rng);
    const Shape b = RandomShape(ShapeType::kCapsule, rng);
    const Eigen::Isometry3d pose_a = RandomPose(rng, 1.0);
    const Eigen::Isometry3d pose_b = NearbyPose(rng, pose_a, 0.8);
    ContactGeometry out[kMaxPairContacts];
    ASSERT_EQ(CollideCapsuleCapsule(a, pose_a, b, pose_b, kInf, out), 1) << "pose " << i;
    // the distance between the cores is convex in (s, t), and so is its minimum over t as a
    // function of s: nested 1-D zooming grids find the minimum of a convex function
    const auto distance_from_b = [&](double s) {
      return BruteMinimize1([&](double t) { return (Core(pose_b, t) - Core(pose_a, s)).norm(); },
                            -b.half_length, b.half_length, false, 50, 9)
          .first;
    };
    const double distance =
        BruteMinimize1(distance_from_b, -a.half_length, a.half_length, false, 50, 9).first;
    const double reference = distance - a.radius - b.radius;
    ExpectContactOfRoundShapes(out[0], a, pose_a, b, pose_b, reference);
    EXPECT_EQ(out[0].feature, 0);
    overlapping += reference < 0.0 ? 1 : 0;
  }
  EXPECT_GT(overlapping, kPoses / 5);
}

// Capsule B (r 0.03, l 0.15) lying along capsule A (r 0.05, l 0.2), both along x, B shifted by
// 0.1 in x: the cores overlap over x ∈ [−0.05, 0.2].
struct Stack {
  Shape a = Shape::Capsule(0.05, 0.2);
  Shape b = Shape::Capsule(0.03, 0.15);
  Eigen::Isometry3d pose_a = Pose(Rotation(kPi / 2, Eigen::Vector3d::UnitY()), {0, 0, 0});
  Eigen::Isometry3d PoseB(double tilt) const {
    // tilted about y through the overlap's start x = −0.05, which stays touching
    const Eigen::Vector3d pivot(-0.05, 0.0, 0.08);
    const Eigen::Matrix3d tilt_rotation = Rotation(-tilt, Eigen::Vector3d::UnitY());
    return Pose(tilt_rotation * Rotation(kPi / 2, Eigen::Vector3d::UnitY()),
                pivot + tilt_rotation * Eigen::Vector3d(0.15, 0.0, 0.0));
  }
};

TEST(CapsuleCapsule, ParallelOverlapGivesTwoContactsAtItsEnds) {
  const Stack stack;
  ContactGeometry out[kMaxPairContacts];
  ASSERT_EQ(CollideCapsuleCapsule(stack.a, stack.pose_a, stack.b, stack.PoseB(0.0), 1e-9, out), 2);
  const double ends[2] = {-0.05, 0.2};
  for (int k = 0; k < 2; ++k) {
    EXPECT_TRUE(WellFormed(out[k]));
    EXPECT_EQ(out[k].feature, 1 + k);
    EXPECT_NEAR(out[k].gap, 0.0, 1e-15);
    EXPECT_LT((out[k].normal - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
    EXPECT_LT((out[k].point_a - Eigen::Vector3d(ends[k], 0, 0.05)).norm(), 1e-15);
    EXPECT_LT((out[k].point_b - Eigen::Vector3d(ends[k], 0, 0.05)).norm(), 1e-15);
  }
  // still parallel within the tolerance: the height difference along the overlap (0.25 long)
  // is half of it
  ASSERT_EQ(CollideCapsuleCapsule(stack.a, stack.pose_a, stack.b,
                                  stack.PoseB(0.5 * kFlatFaceTolerance / 0.25), 1e-3, out),
            2);
  EXPECT_NEAR(out[1].gap - out[0].gap, 0.5 * kFlatFaceTolerance, 1e-12);
  // no longer parallel at twice the tolerance: the closest points, one contact
  ASSERT_EQ(CollideCapsuleCapsule(stack.a, stack.pose_a, stack.b,
                                  stack.PoseB(2.0 * kFlatFaceTolerance / 0.25), 1e-3, out),
            1);
  EXPECT_EQ(out[0].feature, 0);
}

TEST(CapsuleCapsule, TiltedAlongTheOtherGivesTheLowerEnd) {
  const Stack stack;
  ContactGeometry out[kMaxPairContacts];
  // the +x end of B raised by 1e-3 rad: only the pivot end touches
  ASSERT_EQ(CollideCapsuleCapsule(stack.a, stack.pose_a, stack.b, stack.PoseB(1e-3), 1e-9, out), 1);
  EXPECT_EQ(out[0].feature, 0);
  EXPECT_NEAR(out[0].gap, 0.0, 1e-15);
  EXPECT_NEAR(out[0].point_a.x(), -0.05, 1e-12);
}

TEST(CapsuleCapsule, CollinearEndToEndIsOneContact) {
  const Shape a = Shape::Capsule(0.05, 0.2);
  const Shape b = Shape::Capsule(0.03, 0.2);
  const Eigen::Matrix3d along_x = Rotation(kPi / 2, Eigen::Vector3d::UnitY());
  ContactGeometry out[kMaxPairContacts];
  ASSERT_EQ(
      CollideCapsuleCapsule(a, Pose(along_x, {0, 0, 0}), b, Pose(along_x, {0.5, 0, 0}), kInf, out),
      1);
  EXPECT_EQ(out[0].feature, 0);
  EXPECT_NEAR(out[0].gap, 0.5 - 0.4 - 0.08, 1e-15);
  EXPECT_LT((out[0].normal - Eigen::Vector3d::UnitX()).norm(), 1e-15);
}

// Coincident centres and crossing cores: a defined normal (world +z), finite output.
TEST(RoundPairs, DegenerateInputsGiveTheDefaultNormal) {
  ContactGeometry out[kMaxPairContacts];
  const Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  ASSERT_EQ(CollideSphereSphere(Shape::Sphere(0.1), origin, Shape::Sphere(0.2), origin, 0.0, out),
            1);
  EXPECT_TRUE(WellFormed(out[0]));
  EXPECT_EQ(out[0].normal, Eigen::Vector3d::UnitZ());
  EXPECT_NEAR(out[0].gap, -0.3, 1e-15);
  ASSERT_EQ(
      CollideSphereCapsule(Shape::Sphere(0.1), Pose(Eigen::Matrix3d::Identity(), {0, 0, 0.05}),
                           Shape::Capsule(0.1, 0.3), origin, 0.0, out),
      1);
  EXPECT_TRUE(WellFormed(out[0]));
  EXPECT_EQ(out[0].normal, Eigen::Vector3d::UnitZ());
  const Eigen::Isometry3d crossing = Pose(Rotation(kPi / 2, Eigen::Vector3d::UnitX()), {0, 0, 0});
  ASSERT_EQ(CollideCapsuleCapsule(Shape::Capsule(0.1, 0.3), origin, Shape::Capsule(0.1, 0.3),
                                  crossing, 0.0, out),
            1);
  EXPECT_TRUE(WellFormed(out[0]));
  EXPECT_NEAR(out[0].gap, -0.2, 1e-15);
  // identical capsules: two contacts at the overlap's ends, finite
  ASSERT_EQ(CollideCapsuleCapsule(Shape::Capsule(0.1, 0.3), origin, Shape::Capsule(0.1, 0.3),
                                  origin, 0.0, out),
            2);
  for (int k = 0; k < 2; ++k) EXPECT_TRUE(WellFormed(out[k]));
}

TEST(RoundPairs, NothingBeyondTheMargin) {
  ContactGeometry out[kMaxPairContacts];
  const Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  const Eigen::Isometry3d apart = Pose(Eigen::Matrix3d::Identity(), {0, 0, 1.0});
  EXPECT_EQ(CollideSphereSphere(Shape::Sphere(0.2), origin, Shape::Sphere(0.3), apart, 0.49, out),
            0);
  EXPECT_EQ(CollideSphereSphere(Shape::Sphere(0.2), origin, Shape::Sphere(0.3), apart, 0.51, out),
            1);
  EXPECT_EQ(
      CollideSphereCapsule(Shape::Sphere(0.2), origin, Shape::Capsule(0.1, 0.2), apart, 0.49, out),
      0);
  EXPECT_EQ(
      CollideSphereCapsule(Shape::Sphere(0.2), origin, Shape::Capsule(0.1, 0.2), apart, 0.51, out),
      1);
  EXPECT_EQ(CollideCapsuleCapsule(Shape::Capsule(0.1, 0.2), origin, Shape::Capsule(0.1, 0.2), apart,
                                  0.39, out),
            0);
  EXPECT_EQ(CollideCapsuleCapsule(Shape::Capsule(0.1, 0.2), origin, Shape::Capsule(0.1, 0.2), apart,
                                  0.41, out),
            1);
}

}  // namespace
}  // namespace nonsmooth_sim
