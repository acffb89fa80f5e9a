// Plane–box (plane_box.h).
//
// The patch radius of a rectangle against numeric integration and the square's closed form; at
// 1000 random poses (seed 12345; never flat) the returned corners against the corners enumerated
// independently (Eigen::AlignedBox3d::corner) and against the brute-force lowest point of the
// surface; a box resting on each of its faces (four face points, features 8 + 4 face + j); tilted by 1e-3 rad
// (the two corners of the lower edge).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "collision_test_util.h"
#include "nonsmooth_sim/core/collision/plane_box.h"

namespace nonsmooth_sim {
namespace {

using namespace collision_test;  // NOLINT

constexpr double kGapTolerance = 1e-12;

const Shape kPlane = Shape::Plane();
const Eigen::Isometry3d kGround = Eigen::Isometry3d::Identity();

double Height(const Eigen::Isometry3d& plane, const Eigen::Vector3d& x) {
  return (plane.inverse() * x).z();
}

// Mean distance from the centre over [−a, a] × [−b, b] by the midpoint rule on an n × n grid of
// the quarter [0, a] × [0, b]. The integrand √(x² + y²) is smooth except at the corner (0, 0),
// where it is Lipschitz: the error is O(1/n²) up to a log factor, ~1e-8 relative at n = 2000.
double MeanDistanceNumeric(double a, double b, int n = 2000) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      sum += std::hypot((i + 0.5) * a / n, (j + 0.5) * b / n);
    }
  }
  return sum / (static_cast<double>(n) * n);
}

TEST(RectanglePatchRadius, MatchesNumericIntegration) {
  for (const auto& [a, b] : {std::pair{1.0, 1.0}, {0.3, 0.1}, {0.05, 0.5}, {2.0, 0.02}}) {
    const double numeric = MeanDistanceNumeric(a, b);
    EXPECT_NEAR(RectanglePatchRadius(a, b), numeric, 1e-7 * numeric) << a << " x " << b;
    EXPECT_DOUBLE_EQ(RectanglePatchRadius(a, b), RectanglePatchRadius(b, a));
  }
}

TEST(RectanglePatchRadius, SquareAndLimits) {
  // square of side s = 2a: s(√2 + ln(1 + √2))/6 ≈ 0.3826 s
  const double s = 0.4;
  EXPECT_NEAR(RectanglePatchRadius(s / 2, s / 2),
              s * (std::sqrt(2.0) + std::log(1.0 + std::sqrt(2.0))) / 6.0, 1e-16);
  EXPECT_NEAR(RectanglePatchRadius(s / 2, s / 2) / s, 0.3826, 1e-4);
  // a thin strip [−a, a] × ~0: the mean of |x|, a/2
  EXPECT_NEAR(RectanglePatchRadius(1.0, 1e-9), 0.5, 1e-8);
  // scales with the size
  EXPECT_NEAR(RectanglePatchRadius(3.0, 1.5), 3.0 * RectanglePatchRadius(1.0, 0.5), 1e-15);
}

TEST(PlaneBox, CornersMatchIndependentEnumerationAtRandomPoses) {
  std::mt19937 rng(kSeed);
  for (int i = 0; i < kPoses; ++i) {
    const Eigen::Isometry3d plane = RandomPose(rng, 1.0);
    const Shape box = RandomShape(ShapeType::kBox, rng);
    const Eigen::Isometry3d pose = RandomPose(rng, 1.0);
    const double margin = Uniform(rng, -1.0, 1.0);
    ContactGeometry out[kMaxPairContacts];
    const int count = CollidePlaneBox(kPlane, plane, box, pose, margin, out);
    // the corners within the margin, enumerated by Eigen
    const Eigen::AlignedBox3d aligned(-box.half_extents, box.half_extents);
    int expected = 0;
    double lowest_corner = kInf;
    for (int k = 0; k < 8; ++k) {
      const double h = Height(plane, pose * aligned.corner(Eigen::AlignedBox3d::CornerType(k)));
      expected += h <= margin ? 1 : 0;
      lowest_corner = std::min(lowest_corner, h);
    }
    ASSERT_EQ(count, expected) << "pose " << i;
    for (int k = 0; k < count; ++k) {
      const ContactGeometry& c = out[k];
      EXPECT_TRUE(WellFormed(c));
      EXPECT_LE(c.gap, margin);
      EXPECT_FALSE(c.face_point);
      EXPECT_LT((c.normal - plane.linear().col(2)).norm(), 1e-15);
      EXPECT_NEAR(Height(plane, c.point_a), 0.0, 1e-12);
      EXPECT_NEAR(c.gap, Height(plane, c.point_b), kGapTolerance);
      // point_b is the corner named by the feature: |local| = h componentwise, signs from bits
      ASSERT_GE(c.feature, 0);
      ASSERT_LT(c.feature, 8);
      const Eigen::Vector3d local = pose.inverse() * c.point_b;
      const Eigen::Vector3d corner = aligned.corner(Eigen::AlignedBox3d::CornerType(c.feature));
      EXPECT_LT((local - corner).norm(), 1e-12) << "feature " << c.feature;
      for (int m = 0; m < k; ++m) EXPECT_NE(out[m].feature, c.feature);
    }
    // the lowest corner is the lowest point of the surface (brute force over the six faces)
    double surface_min = kInf;
    for (int axis = 0; axis < 3; ++axis) {
      for (double side : {-1.0, 1.0}) {
        surface_min = std::min(
            surface_min, BruteMinimize2(
                             [&](const Eigen::Vector2d& uv) {
                               Eigen::Vector3d local;
                               local[axis] = side * box.half_extents[axis];
                               local[(axis + 1) % 3] = uv[0] * box.half_extents[(axis + 1) % 3];
                               local[(axis + 2) % 3] = uv[1] * box.half_extents[(axis + 2) % 3];
                               return Height(plane, pose * local);
                             },
                             Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1))
                             .first);
      }
    }
    EXPECT_NEAR(lowest_corner, surface_min, kGapTolerance);
  }
}

// Resting on face f (f = 2j + side) at height 1e-4: four face points on its diagonals, features
// 8 + 4f + j, at the rectangle's drilling radius; with a margin beyond the box, also the four
// corners of the opposite face.
TEST(PlaneBox, RestingOnEachFaceIsFourFacePoints) {
  const Eigen::Vector3d h(0.1, 0.2, 0.3);
  const Shape box = Shape::Box(h);
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const int face = 2 * axis + side;
      // rotate the face's outward normal (±e_axis) onto −z
      const Eigen::Vector3d outward = (side == 1 ? 1.0 : -1.0) * Eigen::Vector3d::Unit(axis);
      const Eigen::Matrix3d rotation =
          Eigen::Quaterniond::FromTwoVectors(outward, -Eigen::Vector3d::UnitZ()).toRotationMatrix();
      const Eigen::Isometry3d pose = Pose(rotation, {0.5, 0.5, h[axis] + 1e-4});
      ContactGeometry out[kMaxPairContacts];
      ASSERT_EQ(CollidePlaneBox(kPlane, kGround, box, pose, 1e-3, out), 4) << "face " << face;
      const Eigen::Vector3d face_centre = pose * (h[axis] * outward);
      const double rbar = RectanglePatchRadius(h[(axis + 1) % 3], h[(axis + 2) % 3]);
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (int j = 0; j < 4; ++j) {
        EXPECT_TRUE(WellFormed(out[j]));
        EXPECT_TRUE(out[j].face_point);
        EXPECT_EQ(out[j].feature, 8 + 4 * face + j);
        EXPECT_NEAR(out[j].gap, 1e-4, 1e-15);
        // on the face's diagonals at the uniform pressure's drilling radius from its centre
        EXPECT_NEAR((out[j].point_b - face_centre).norm(), rbar, 1e-14);
        mean += out[j].point_b / 4.0;
      }
      EXPECT_LT((mean - face_centre).norm(), 1e-14);
      ASSERT_EQ(CollidePlaneBox(kPlane, kGround, box, pose, 1.0, out), 8);
      for (int k = 4; k < 8; ++k) EXPECT_NEAR(out[k].gap, 2 * h[axis] + 1e-4, 1e-15);
    }
  }
}

TEST(PlaneBox, TiltedBy1e3GivesTheLowerEdgesCorners) {
  const Eigen::Vector3d h(0.1, 0.2, 0.3);
  const Shape box = Shape::Box(h);
  const double tilt = 1e-3;
  // about x: local (x, y, −c) at height c_z + y sin(tilt) − c cos(tilt): lowest at y = −b
  const Eigen::Isometry3d pose = Pose(Rotation(tilt, Eigen::Vector3d::UnitX()),
                                      {0, 0, h.z() * std::cos(tilt) + h.y() * std::sin(tilt)});
  ContactGeometry out[kMaxPairContacts];
  ASSERT_EQ(CollidePlaneBox(kPlane, kGround, box, pose, 1e-9, out), 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_FALSE(out[k].face_point);
    EXPECT_NEAR(out[k].gap, 0.0, 1e-15);
    const Eigen::Vector3d local = pose.inverse() * out[k].point_b;
    EXPECT_NEAR(local.y(), -h.y(), 1e-15);
    EXPECT_NEAR(local.z(), -h.z(), 1e-15);
  }
  // corners 0 (−,−,−) and 1 (+,−,−)
  EXPECT_EQ(out[0].feature, 0);
  EXPECT_EQ(out[1].feature, 1);
}

// Flat iff the corners' heights differ by ≤ kFlatFaceTolerance across the face.
TEST(PlaneBox, FlatThresholdIsTheHeightDifferenceAcrossTheFace) {
  const Eigen::Vector3d h(0.1, 0.2, 0.3);
  const Shape box = Shape::Box(h);
  for (double factor : {0.5, 0.99, 1.01, 2.0}) {
    // about x the bottom face's corners differ by 2b sin(tilt)
    const double tilt = std::asin(factor * kFlatFaceTolerance / (2 * h.y()));
    const Eigen::Isometry3d pose = Pose(Rotation(tilt, Eigen::Vector3d::UnitX()), {0, 0, h.z()});
    ContactGeometry out[kMaxPairContacts];
    const int count = CollidePlaneBox(kPlane, kGround, box, pose, 1e-3, out);
    // flat: the four face points of the bottom face (face 4: −z); tilted: its four corners
    EXPECT_EQ(count, 4) << "factor " << factor;
    EXPECT_EQ(out[0].feature, factor < 1.0 ? 8 + 4 * 4 : 0) << "factor " << factor;
    EXPECT_EQ(out[0].face_point, factor < 1.0) << "factor " << factor;
  }
}

}  // namespace
}  // namespace nonsmooth_sim
