// Sphere–box (sphere_box.h).
//
// At 1000 random poses (seed 12345) with the sphere's centre outside, near, and inside the box,
// each contact is checked against a brute-force signed distance of the centre from the box's
// surface: the minimum of |c − x| over each face sampled by a zooming grid, negative when the
// centre is inside (membership from the definition |y_j| ≤ h_j); gap = that − r. Also: the
// projection gap along the normal equals the gap (the normal is optimal), point_a on the sphere,
// point_b on the box surface and at the reference's closest point, point_b − point_a = gap·n.
#include <gtest/gtest.h>

#include <random>

#include "collision_test_util.h"
#include "nonsmooth_sim/core/collision/sphere_box.h"

namespace nonsmooth_sim {
namespace {

using namespace collision_test;  // NOLINT

constexpr double kGapTolerance = 1e-12;
constexpr double kSurfaceTolerance = 1e-12;
// The closest point of a face is found to ~1e-9 m by the grid (a distance minimum is quadratic).
constexpr double kPointTolerance = 1e-7;

// (signed distance of the world point c from the box's surface, the closest surface point)
std::pair<double, Eigen::Vector3d> SignedDistanceFromBox(const Shape& box,
                                                         const Eigen::Isometry3d& pose,
                                                         const Eigen::Vector3d& c) {
  const Eigen::Vector3d& h = box.half_extents;
  double best = kInf;
  Eigen::Vector3d closest = Eigen::Vector3d::Zero();
  for (int axis = 0; axis < 3; ++axis) {
    for (double side : {-1.0, 1.0}) {
      const auto face_point = [&](const Eigen::Vector2d& uv) {
        Eigen::Vector3d local;
        local[axis] = side * h[axis];
        local[(axis + 1) % 3] = uv[0] * h[(axis + 1) % 3];
        local[(axis + 2) % 3] = uv[1] * h[(axis + 2) % 3];
        return Eigen::Vector3d(pose * local);
      };
      const auto [distance, uv] =
          BruteMinimize2([&](const Eigen::Vector2d& p) { return (face_point(p) - c).norm(); },
                         Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
      if (distance < best) best = distance, closest = face_point(uv);
    }
  }
  const Eigen::Vector3d y = pose.inverse() * c;
  const bool inside = (y.cwiseAbs() - h).maxCoeff() <= 0.0;
  return {inside ? -best : best, closest};
}

TEST(SphereBox, MatchesBruteForceAtRandomPoses) {
  std::mt19937 rng(kSeed);
  int inside = 0;
  int outside_overlapping = 0;
  for (int i = 0; i < kPoses; ++i) {
    const Shape sphere = RandomShape(ShapeType::kSphere, rng, 0.02, 0.3);
    const Shape box = RandomShape(ShapeType::kBox, rng);
    const Eigen::Isometry3d pose_box = RandomPose(rng, 1.0);
    // the centre in the box's frame within 1.5 × its half-extents plus the radius
    const Eigen::Vector3d reach = 1.5 * box.half_extents + Eigen::Vector3d::Constant(sphere.radius);
    const Eigen::Vector3d local(Uniform(rng, -reach.x(), reach.x()),
                                Uniform(rng, -reach.y(), reach.y()),
                                Uniform(rng, -reach.z(), reach.z()));
    const Eigen::Isometry3d pose_sphere = Pose(RandomRotation(rng), pose_box * local);
    ContactGeometry out[kMaxPairContacts];
    ASSERT_EQ(CollideSphereBox(sphere, pose_sphere, box, pose_box, kInf, out), 1);
    const ContactGeometry& c = out[0];
    const auto [distance, closest] =
        SignedDistanceFromBox(box, pose_box, pose_sphere.translation());
    EXPECT_TRUE(WellFormed(c));
    EXPECT_EQ(c.feature, 0);
    EXPECT_NEAR(c.gap, distance - sphere.radius, kGapTolerance) << "pose " << i;
    EXPECT_NEAR(ProjectionGap(sphere, pose_sphere, box, pose_box, c.normal), c.gap, kGapTolerance);
    EXPECT_NEAR(SurfaceResidual(sphere, pose_sphere, c.point_a), 0.0, kSurfaceTolerance);
    EXPECT_NEAR(SurfaceResidual(box, pose_box, c.point_b), 0.0, kSurfaceTolerance);
    // the closest surface point is unique unless the centre is equidistant from two faces
    EXPECT_LT((c.point_b - closest).norm(), kPointTolerance) << "pose " << i;
    inside += distance < 0.0 ? 1 : 0;
    outside_overlapping += distance >= 0.0 && c.gap < 0.0 ? 1 : 0;
  }
  // every region is sampled
  EXPECT_GT(inside, kPoses / 10);
  EXPECT_GT(outside_overlapping, kPoses / 20);
}

// The centre inside, nearest the +y face: n = −e_y (from the sphere into the box, out through
// +y), gap = −(depth + r).
TEST(SphereBox, CentreInsideExitsThroughTheNearestFace) {
  const Shape box = Shape::Box({0.3, 0.2, 0.25});
  const Shape sphere = Shape::Sphere(0.05);
  const Eigen::Isometry3d pose_box = Pose(Rotation(0.4, Eigen::Vector3d(1, 2, 3)), {0.1, 0.2, 0.3});
  const Eigen::Isometry3d pose_sphere =
      Pose(Eigen::Matrix3d::Identity(), pose_box * Eigen::Vector3d(0.05, 0.17, -0.1));
  ContactGeometry out[kMaxPairContacts];
  ASSERT_EQ(CollideSphereBox(sphere, pose_sphere, box, pose_box, 0.0, out), 1);
  EXPECT_TRUE(WellFormed(out[0]));
  EXPECT_LT((out[0].normal + pose_box.linear().col(1)).norm(), 1e-15);
  EXPECT_NEAR(out[0].gap, -(0.03 + 0.05), 1e-15);
  EXPECT_LT((out[0].point_b - pose_box * Eigen::Vector3d(0.05, 0.2, -0.1)).norm(), 1e-15);
}

// Continuity as the centre crosses a face: the gap and normal move by O(step).
TEST(SphereBox, CrossingTheSurfaceIsContinuous) {
  const Shape box = Shape::Box({0.3, 0.2, 0.25});
  const Shape sphere = Shape::Sphere(0.05);
  const Eigen::Isometry3d pose_box = Pose(Rotation(0.4, Eigen::Vector3d(1, 2, 3)), {0.1, 0.2, 0.3});
  ContactGeometry previous;
  constexpr double kStep = 1e-5;
  for (int i = 0; i <= 2000; ++i) {
    // along x through the +x face at x = 0.3
    const Eigen::Vector3d local(0.29 + i * kStep, 0.05, 0.02);
    ContactGeometry out[kMaxPairContacts];
    ASSERT_EQ(CollideSphereBox(sphere, Pose(Eigen::Matrix3d::Identity(), pose_box * local), box,
                               pose_box, kInf, out),
              1);
    if (i > 0) {
      ASSERT_NEAR(out[0].gap, previous.gap, kStep * (1 + 1e-9)) << "step " << i;
      ASSERT_LT((out[0].normal - previous.normal).norm(), 1e-12) << "step " << i;
    }
    previous = out[0];
  }
}

TEST(SphereBox, CentreAtTheBoxCentreIsDefined) {
  const Shape cube = Shape::Box({0.2, 0.2, 0.2});
  ContactGeometry out[kMaxPairContacts];
  ASSERT_EQ(CollideSphereBox(Shape::Sphere(0.1), Eigen::Isometry3d::Identity(), cube,
                             Eigen::Isometry3d::Identity(), 0.0, out),
            1);
  EXPECT_TRUE(WellFormed(out[0]));
  EXPECT_NEAR(out[0].gap, -0.3, 1e-15);
  // the first axis on ties, + side at 0: out through +x
  EXPECT_EQ(out[0].normal, -Eigen::Vector3d::UnitX());
}

}  // namespace
}  // namespace nonsmooth_sim
