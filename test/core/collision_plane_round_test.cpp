// Plane against the round shapes (plane_sphere.h, plane_capsule.h, plane_ellipsoid.h).
//
// At 1000 random poses of plane and shape (seed 12345) each contact is compared with a brute-force
// reference: the minimum of the height above the plane over a parametrisation of the surface
// (zooming grid, collision_test_util.h), never the support formula of the code. Checked: the gap
// (the reference's own error is ~1e-15 m: the grid zooms to round-off), point_b on B's surface and
// at the reference's argmin (the argmin of a smooth minimum is only determined to ~√(1e-16) of the
// size, so 1e-6 m), point_a on the plane, the normal = the plane's normal, point_b − point_a =
// gap·n. Then: only contacts with gap ≤ margin, continuity along a rolling path.
#include <gtest/gtest.h>

#include <random>

#include "collision_test_util.h"
#include "nonsmooth_sim/core/collision/plane_capsule.h"
#include "nonsmooth_sim/core/collision/plane_ellipsoid.h"
#include "nonsmooth_sim/core/collision/plane_sphere.h"

namespace nonsmooth_sim {
namespace {

using namespace collision_test;  // NOLINT

constexpr double kGapTolerance = 1e-12;
constexpr double kSurfaceTolerance = 1e-12;
constexpr double kArgminTolerance = 1e-6;

const Shape kPlane = Shape::Plane();

double Height(const Eigen::Isometry3d& plane, const Eigen::Vector3d& x) {
  return (plane.inverse() * x).z();
}

// The plane's contact with B at a point of B: normal, point_a on the plane, point_b on B.
void ExpectPlaneContact(const ContactGeometry& c, const Eigen::Isometry3d& plane, const Shape& b,
                        const Eigen::Isometry3d& pose_b) {
  EXPECT_TRUE(WellFormed(c));
  EXPECT_LT((c.normal - plane.linear().col(2)).norm(), 1e-15);
  EXPECT_NEAR(Height(plane, c.point_a), 0.0, kSurfaceTolerance);
  EXPECT_NEAR(SurfaceResidual(b, pose_b, c.point_b), 0.0, kSurfaceTolerance);
  EXPECT_NEAR(c.gap, Height(plane, c.point_b), kGapTolerance);
  EXPECT_FALSE(c.face_point);
}

// Lowest point of the ellipsoid x = c + R S ω, |ω| = 1, by brute force over ω.
std::pair<double, Eigen::Vector3d> LowestPointOfEllipsoid(const Eigen::Isometry3d& plane,
                                                          const Shape& e,
                                                          const Eigen::Isometry3d& pose) {
  const auto point = [&](const Eigen::Vector3d& omega) {
    return Eigen::Vector3d(pose * e.half_extents.cwiseProduct(omega));
  };
  const auto [height, omega] =
      BruteMinimizeOverSphere([&](const Eigen::Vector3d& w) { return Height(plane, point(w)); });
  return {height, point(omega)};
}

TEST(PlaneSphere, MatchesBruteForceAtRandomPoses) {
  std::mt19937 rng(kSeed);
  for (int i = 0; i < kPoses; ++i) {
    const Eigen::Isometry3d plane = RandomPose(rng, 1.0);
    const Shape sphere = RandomShape(ShapeType::kSphere, rng);
    const Eigen::Isometry3d pose = RandomPose(rng, 1.0);
    ContactGeometry out[kMaxPairContacts];
    ASSERT_EQ(CollidePlaneSphere(kPlane, plane, sphere, pose, kInf, out), 1);
    ExpectPlaneContact(out[0], plane, sphere, pose);
    // reference: the sphere's surface c + r ω
    const auto [height, omega] = BruteMinimizeOverSphere([&](const Eigen::Vector3d& w) {
      return Height(plane, pose.translation() + sphere.radius * w);
    });
    EXPECT_NEAR(out[0].gap, height, kGapTolerance) << "pose " << i;
    EXPECT_LT((out[0].point_b - pose.translation() - sphere.radius * omega).norm(),
              kArgminTolerance);
    EXPECT_EQ(out[0].feature, 0);
  }
}

TEST(PlaneEllipsoid, MatchesBruteForceAtRandomPoses) {
  std::mt19937 rng(kSeed);
  for (int i = 0; i < kPoses; ++i) {
    const Eigen::Isometry3d plane = RandomPose(rng, 1.0);
    const Shape ellipsoid = RandomShape(ShapeType::kEllipsoid, rng);
    const Eigen::Isometry3d pose = RandomPose(rng, 1.0);
    ContactGeometry out[kMaxPairContacts];
    ASSERT_EQ(CollidePlaneEllipsoid(kPlane, plane, ellipsoid, pose, kInf, out), 1);
    ExpectPlaneContact(out[0], plane, ellipsoid, pose);
    const auto [height, lowest] = LowestPointOfEllipsoid(plane, ellipsoid, pose);
    EXPECT_NEAR(out[0].gap, height, kGapTolerance) << "pose " << i;
    EXPECT_LT((out[0].point_b - lowest).norm(), kArgminTolerance) << "pose " << i;
    EXPECT_EQ(out[0].feature, 0);
  }
}

TEST(PlaneCapsule, MatchesBruteForceAtRandomPoses) {
  std::mt19937 rng(kSeed);
  for (int i = 0; i < kPoses; ++i) {
    const Eigen::Isometry3d plane = RandomPose(rng, 1.0);
    const Shape capsule = RandomShape(ShapeType::kCapsule, rng);
    const Eigen::Isometry3d pose = RandomPose(rng, 1.0);
    ContactGeometry out[kMaxPairContacts];
    const int count = CollidePlaneCapsule(kPlane, plane, capsule, pose, kInf, out);
    ASSERT_EQ(count, capsule.half_length > 0.0 ? 2 : 1);
    // reference: the capsule as the union of balls of radius r on its core (shape.h)
    const auto [height, s] = BruteMinimize1(
        [&](double z) { return Height(plane, pose * Eigen::Vector3d(0, 0, z)) - capsule.radius; },
        -capsule.half_length, capsule.half_length);
    double lowest = kInf;
    int lower_end = 0;
    for (int k = 0; k < count; ++k) {
      ExpectPlaneContact(
          out[k], plane, Shape::Sphere(capsule.radius),
          pose * Eigen::Translation3d(0, 0, k == 0 ? -capsule.half_length : capsule.half_length));
      EXPECT_EQ(out[k].feature, k);
      // end k is the ball at z = ∓l
      const double z = k == 0 ? -capsule.half_length : capsule.half_length;
      EXPECT_NEAR((pose.inverse() * out[k].point_b - Eigen::Vector3d(0, 0, z)).norm(),
                  capsule.radius, kSurfaceTolerance);
      if (out[k].gap < lowest) lowest = out[k].gap, lower_end = k;
    }
    EXPECT_NEAR(lowest, height, kGapTolerance) << "pose " << i;
    // the lower end's point is the capsule's lowest point, on its surface (the upper end's lies
    // on its end sphere, inside the capsule unless it lies flat: plane_capsule.h)
    EXPECT_NEAR(SurfaceResidual(capsule, pose, out[lower_end].point_b), 0.0, kSurfaceTolerance);
    EXPECT_NEAR(Height(plane, pose * Eigen::Vector3d(0, 0, s)) - capsule.radius, lowest,
                kGapTolerance);
  }
}

// A contact is returned iff its gap ≤ margin: margins drawn around the gaps of the random poses.
TEST(PlaneRound, ReturnsExactlyTheContactsWithinMargin) {
  std::mt19937 rng(kSeed);
  for (int i = 0; i < kPoses; ++i) {
    const Eigen::Isometry3d plane = RandomPose(rng, 1.0);
    const Eigen::Isometry3d pose = RandomPose(rng, 1.0);
    const Shape capsule = RandomShape(ShapeType::kCapsule, rng);
    ContactGeometry all[kMaxPairContacts];
    const int count = CollidePlaneCapsule(kPlane, plane, capsule, pose, kInf, all);
    const double margin = Uniform(rng, -1.0, 1.0);
    int expected = 0;
    for (int k = 0; k < count; ++k) expected += all[k].gap <= margin ? 1 : 0;
    ContactGeometry out[kMaxPairContacts];
    const int within = CollidePlaneCapsule(kPlane, plane, capsule, pose, margin, out);
    ASSERT_EQ(within, expected);
    for (int k = 0; k < within; ++k) EXPECT_LE(out[k].gap, margin);
  }
}

TEST(PlaneCapsule, LyingFlatGivesBothEndsTiltedGivesTheLowerEnd) {
  const Shape capsule = Shape::Capsule(0.05, 0.2);
  const Eigen::Isometry3d ground = Eigen::Isometry3d::Identity();
  // lying along x, resting on z = 0 (margin 1e-12: cos(π/2) is 6e-17, not 0)
  const Eigen::Isometry3d flat = Pose(Rotation(kPi / 2, Eigen::Vector3d::UnitY()), {0, 0, 0.05});
  ContactGeometry out[kMaxPairContacts];
  ASSERT_EQ(CollidePlaneCapsule(kPlane, ground, capsule, flat, 1e-12, out), 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(out[k].gap, 0.0, 1e-15);
    EXPECT_NEAR(std::abs(out[k].point_b.x()), 0.2, 1e-15);
  }
  // raise the +z end (feature 1) by 1e-3 rad: only end 0 touches
  const Eigen::Isometry3d tilted =
      Pose(Rotation(kPi / 2 - 1e-3, Eigen::Vector3d::UnitY()), {0, 0, 0.05 + 0.2 * std::sin(1e-3)});
  ASSERT_EQ(CollidePlaneCapsule(kPlane, ground, capsule, tilted, 1e-6, out), 1);
  EXPECT_EQ(out[0].feature, 0);
  EXPECT_NEAR(out[0].gap, 0.0, 1e-15);
}

// Rolling: the contact point of an ellipsoid rotating about a tilted axis (its centre kept at
// height 0.2) moves by at most |Δc| + Δθ (a_max + a_max²/a_min) per step: the support point's
// rate is bounded by the largest radius of curvature a_max²/a_min. A jump to another point of
// the surface would be O(a_min) ≫ the bound.
TEST(PlaneEllipsoid, RollingContactPointIsContinuous) {
  const Shape ellipsoid = Shape::Ellipsoid({0.15, 0.1, 0.05});
  const double a_max = 0.15;
  const double a_min = 0.05;
  const Eigen::Isometry3d ground = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, 1.0, 0.2).normalized();
  constexpr int kSteps = 4000;
  constexpr double kStep = 2 * kPi / 1000;  // four turns
  ContactGeometry previous;
  Eigen::Isometry3d previous_pose = Eigen::Isometry3d::Identity();
  double largest_ratio = 0.0;
  for (int i = 0; i <= kSteps; ++i) {
    const double t = i * kStep;
    const Eigen::Isometry3d pose = Pose(Rotation(t, axis), {0.1 * t, 0.0, 0.2});
    ContactGeometry out[kMaxPairContacts];
    ASSERT_EQ(CollidePlaneEllipsoid(kPlane, ground, ellipsoid, pose, kInf, out), 1);
    EXPECT_EQ(out[0].feature, 0);
    if (i > 0) {
      const double bound =
          (pose.translation() - previous_pose.translation()).norm() +
          AngleBetween(previous_pose.linear(), pose.linear()) * (a_max + a_max * a_max / a_min);
      const double moved = (out[0].point_b - previous.point_b).norm();
      ASSERT_LE(moved, bound) << "step " << i;
      largest_ratio = std::max(largest_ratio, moved / bound);
    }
    previous = out[0];
    previous_pose = pose;
  }
  RecordProperty("largest_step_over_bound", std::to_string(largest_ratio));
}

}  // namespace
}  // namespace nonsmooth_sim
