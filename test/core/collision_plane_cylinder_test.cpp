// Plane–cylinder (plane_cylinder.h).
//
// At 1000 random poses (seed 12345; never flat) the lowest returned gap is compared with the
// brute-force minimum of the height over the whole surface (lateral surface and both discs,
// zooming grid), and each rim contact with the minimum over its own rim. Then the flat-face
// face (a coin flat: four face points at 2r/3; tilted by 1e-3 rad: the rim point where it must be), the
// tolerance's threshold, a cylinder on its side, and a disc rolling on its rim (feature kept,
// contact point continuous).
#include <gtest/gtest.h>

#include <random>

#include "collision_test_util.h"
#include "nonsmooth_sim/core/collision/plane_cylinder.h"

namespace nonsmooth_sim {
namespace {

using namespace collision_test;  // NOLINT

constexpr double kGapTolerance = 1e-12;
constexpr double kSurfaceTolerance = 1e-12;

const Shape kPlane = Shape::Plane();
const Eigen::Isometry3d kGround = Eigen::Isometry3d::Identity();

double Height(const Eigen::Isometry3d& plane, const Eigen::Vector3d& x) {
  return (plane.inverse() * x).z();
}

// A point of the cylinder's surface in its frame: the lateral surface (φ, z) or face k's disc
// (ρ, φ); φ is searched as a periodic variable.
Eigen::Vector3d Lateral(const Shape& c, double phi, double z) {
  return {c.radius * std::cos(phi), c.radius * std::sin(phi), z};
}
Eigen::Vector3d Disc(const Shape& c, int k, double rho, double phi) {
  return {rho * std::cos(phi), rho * std::sin(phi), k == 0 ? -c.half_length : c.half_length};
}

TEST(PlaneCylinder, MatchesBruteForceAtRandomPoses) {
  std::mt19937 rng(kSeed);
  for (int i = 0; i < kPoses; ++i) {
    const Eigen::Isometry3d plane = RandomPose(rng, 1.0);
    const Shape cylinder = RandomShape(ShapeType::kCylinder, rng);
    const Eigen::Isometry3d pose = RandomPose(rng, 1.0);
    const auto height = [&](const Eigen::Vector3d& local) { return Height(plane, pose * local); };
    ContactGeometry out[kMaxPairContacts];
    ASSERT_EQ(CollidePlaneCylinder(kPlane, plane, cylinder, pose, kInf, out), 2) << "pose " << i;
    double lowest = kInf;
    for (int k = 0; k < 2; ++k) {
      const ContactGeometry& c = out[k];
      EXPECT_TRUE(WellFormed(c));
      EXPECT_EQ(c.feature, k);
      EXPECT_FALSE(c.face_point);
      EXPECT_LT((c.normal - plane.linear().col(2)).norm(), 1e-15);
      EXPECT_NEAR(Height(plane, c.point_a), 0.0, kSurfaceTolerance);
      EXPECT_NEAR(c.gap, Height(plane, c.point_b), kGapTolerance);
      // on face k's rim: |z| = l on the right side, ρ = r
      const Eigen::Vector3d local = pose.inverse() * c.point_b;
      EXPECT_NEAR(local.z(), k == 0 ? -cylinder.half_length : cylinder.half_length, 1e-12);
      EXPECT_NEAR(local.head<2>().norm(), cylinder.radius, 1e-12);
      // the lowest point of that rim
      const double rim_min =
          BruteMinimize1(
              [&](double phi) { return height(Disc(cylinder, k, cylinder.radius, phi)); }, 0.0,
              2 * kPi, /*periodic=*/true)
              .first;
      EXPECT_NEAR(c.gap, rim_min, kGapTolerance) << "pose " << i << " face " << k;
      lowest = std::min(lowest, c.gap);
    }
    // the lowest point of the whole surface
    double surface_min =
        BruteMinimize2(
            [&](const Eigen::Vector2d& p) { return height(Lateral(cylinder, p[0], p[1])); },
            Eigen::Vector2d(0.0, -cylinder.half_length),
            Eigen::Vector2d(2 * kPi, cylinder.half_length),
            /*periodic=*/{1, 0})
            .first;
    for (int k = 0; k < 2; ++k) {
      surface_min = std::min(
          surface_min,
          BruteMinimize2(
              [&](const Eigen::Vector2d& p) { return height(Disc(cylinder, k, p[0], p[1])); },
              Eigen::Vector2d(0, 0), Eigen::Vector2d(cylinder.radius, 2 * kPi), /*periodic=*/{0, 1})
              .first);
    }
    EXPECT_NEAR(lowest, surface_min, kGapTolerance) << "pose " << i;
  }
}

TEST(PlaneCylinder, CoinLyingFlatIsFourFacePointsAtTwoThirdsOfTheRadius) {
  const double r = 0.012;
  const Shape coin = Shape::Cylinder(r, 0.001);
  // resting on its −z face (features 2..5), 1e-4 above the ground
  ContactGeometry out[kMaxPairContacts];
  const Eigen::Isometry3d up = Pose(Eigen::Matrix3d::Identity(), {0.3, -0.2, 0.001 + 1e-4});
  ASSERT_EQ(CollidePlaneCylinder(kPlane, kGround, coin, up, 1e-3, out), 4);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int j = 0; j < 4; ++j) {
    EXPECT_TRUE(WellFormed(out[j]));
    EXPECT_TRUE(out[j].face_point);
    EXPECT_EQ(out[j].feature, 2 + j);
    EXPECT_NEAR(out[j].gap, 1e-4, 1e-15);
    // on the face, at the uniform pressure's drilling radius 2r/3 from its centre
    EXPECT_NEAR(out[j].point_b.z(), 1e-4, 1e-15);
    EXPECT_NEAR((out[j].point_b - Eigen::Vector3d(0.3, -0.2, 1e-4)).norm(), 2.0 * r / 3.0, 1e-15);
    centre += out[j].point_b / 4.0;
  }
  // spread symmetrically about the centre: no net moment of equal loads
  EXPECT_LT((centre - Eigen::Vector3d(0.3, -0.2, 1e-4)).norm(), 1e-15);
  // upside down: the +z face (features 6..9)
  const Eigen::Isometry3d down =
      Pose(Rotation(kPi, Eigen::Vector3d::UnitX()), {0.3, -0.2, 0.001 + 1e-4});
  ASSERT_EQ(CollidePlaneCylinder(kPlane, kGround, coin, down, 1e-3, out), 4);
  EXPECT_EQ(out[0].feature, 6);
  EXPECT_NEAR(out[0].gap, 1e-4, 1e-15);
  // a margin beyond the thickness still gives no points for the face facing up
  ASSERT_EQ(CollidePlaneCylinder(kPlane, kGround, coin, up, 1.0, out), 4);
}

TEST(PlaneCylinder, CoinTiltedBy1e3IsTheRimPoint) {
  const double r = 0.012;
  const double l = 0.001;
  const double tilt = 1e-3;
  const Shape coin = Shape::Cylinder(r, l);
  // tilted about x: local (0, y, −l) sits at height c_z + y sin(tilt) − l cos(tilt), lowest at
  // y = −r; the centre is placed so that this point touches the ground
  const Eigen::Isometry3d pose = Pose(Rotation(tilt, Eigen::Vector3d::UnitX()),
                                      {0.1, 0.2, l * std::cos(tilt) + r * std::sin(tilt)});
  ContactGeometry out[kMaxPairContacts];
  ASSERT_EQ(CollidePlaneCylinder(kPlane, kGround, coin, pose, 1e-9, out), 1);
  EXPECT_TRUE(WellFormed(out[0]));
  EXPECT_EQ(out[0].feature, 0);
  EXPECT_FALSE(out[0].face_point);
  EXPECT_NEAR(out[0].gap, 0.0, 1e-15);
  EXPECT_LT((out[0].point_b - pose * Eigen::Vector3d(0, -r, -l)).norm(), 1e-15);
}

// Flat iff the height difference across the face, 2r sin(tilt), is ≤ kFlatFaceTolerance.
TEST(PlaneCylinder, FlatThresholdIsTheHeightDifferenceAcrossTheFace) {
  const double r = 0.05;
  const Shape disc = Shape::Cylinder(r, 0.01);
  for (double factor : {0.5, 0.99, 1.01, 2.0}) {
    const double tilt = std::asin(factor * kFlatFaceTolerance / (2 * r));
    const Eigen::Isometry3d pose = Pose(Rotation(tilt, Eigen::Vector3d(1, 1, 0)), {0, 0, 0.01});
    ContactGeometry out[kMaxPairContacts];
    // flat: the four face points of the lower face (features 2..5); tilted: its rim point
    ASSERT_EQ(CollidePlaneCylinder(kPlane, kGround, disc, pose, 1e-3, out), factor < 1.0 ? 4 : 1);
    EXPECT_EQ(out[0].feature, factor < 1.0 ? 2 : 0) << "factor " << factor;
    EXPECT_EQ(out[0].face_point, factor < 1.0) << "factor " << factor;
  }
}

TEST(PlaneCylinder, LyingOnItsSideGivesTwoRimContacts) {
  const Shape roller = Shape::Cylinder(0.05, 0.2);
  // axis along y, resting on the ground (margin 1e-12: cos(π/2) is 6e-17, not 0)
  const Eigen::Isometry3d pose = Pose(Rotation(kPi / 2, Eigen::Vector3d::UnitX()), {0, 0, 0.05});
  ContactGeometry out[kMaxPairContacts];
  ASSERT_EQ(CollidePlaneCylinder(kPlane, kGround, roller, pose, 1e-12, out), 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(out[k].feature, k);
    EXPECT_NEAR(out[k].gap, 0.0, 1e-15);
    EXPECT_NEAR(out[k].point_b.x(), 0.0, 1e-15);
    EXPECT_NEAR(std::abs(out[k].point_b.y()), 0.2, 1e-15);
  }
  EXPECT_LT(out[0].point_b.y() * out[1].point_b.y(), 0.0);  // one at each end
}

// A disc rolling on its rim (its axis tilted by 1.2 rad from the ground's normal), heading and
// spin advancing, the lowest rim point kept at height 0. Along 3000 steps the
// feature stays 0 and the contact point moves by at most
//   |Δc| + Δθ (r + l) + r Δθ / sin(tilt)
// per step (the body turns by Δθ; the lowest rim point moves along the rim at the rate of the
// direction of n_⊥ in the face, ≤ Δθ / |n_⊥|). A jump to another rim point would be O(r).
TEST(PlaneCylinder, RollingOnItsRimKeepsFeatureAndContinuity) {
  const double r = 0.05;
  const double l = 0.005;
  const double tilt = 1.2;
  const Shape disc = Shape::Cylinder(r, l);
  constexpr int kSteps = 3000;
  constexpr double kStep = 1e-3;
  ContactGeometry previous;
  Eigen::Isometry3d previous_pose = Eigen::Isometry3d::Identity();
  for (int i = 0; i <= kSteps; ++i) {
    const double t = i * kStep;
    const double heading = 0.7 * t;
    const double spin = -5.0 * t;
    const Eigen::Matrix3d rotation = Rotation(heading, Eigen::Vector3d::UnitZ()) *
                                     Rotation(tilt, Eigen::Vector3d::UnitX()) *
                                     Rotation(spin, Eigen::Vector3d::UnitZ());
    // lowest rim point at height 0: centre height l cos(tilt) + r sin(tilt)
    const Eigen::Isometry3d pose =
        Pose(rotation, {r * spin, 0.1 * t, l * std::cos(tilt) + r * std::sin(tilt)});
    ContactGeometry out[kMaxPairContacts];
    ASSERT_EQ(CollidePlaneCylinder(kPlane, kGround, disc, pose, 1e-9, out), 1) << "step " << i;
    ASSERT_EQ(out[0].feature, 0) << "step " << i;
    EXPECT_NEAR(out[0].gap, 0.0, 1e-15);
    if (i > 0) {
      const double turned = AngleBetween(previous_pose.linear(), pose.linear());
      const double bound = (pose.translation() - previous_pose.translation()).norm() +
                           turned * (r + l) + r * turned / std::sin(tilt);
      ASSERT_LE((out[0].point_b - previous.point_b).norm(), bound) << "step " << i;
    }
    previous = out[0];
    previous_pose = pose;
  }
}

}  // namespace
}  // namespace nonsmooth_sim
