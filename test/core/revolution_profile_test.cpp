// The body of revolution's profile (revolution_profile.h) and its plane contact
// (plane_revolution.h) against closed forms: a sphere sampled on its meridian becomes the
// concentric sphere of radius R cos(Δ/2) (Δ the samples' angle); a cylinder keeps its flat faces
// and its rims within the rounding τ; the Tippe-Top's two-sphere hull touches a plane where the
// two spheres do. Every property would fail with a wrong arc, angle or stretch.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "collision_test_util.h"
#include "nonsmooth_sim/core/collision/plane_revolution.h"
#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/core/revolution_profile.h"
#include "nonsmooth_sim/core/shape.h"

namespace nonsmooth_sim {
namespace {

using collision_test::RandomRotation;

// n + 1 points of the circle of radius r about (0, z0), from the top pole to the bottom one
std::vector<Eigen::Vector2d> Circle(double r, double z0, int n) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i <= n; ++i) {
    const double a = kPi * i / n;
    points.emplace_back(r * std::sin(a), z0 + r * std::cos(a));
  }
  return points;
}

Eigen::Vector3d RandomDirection(std::mt19937& rng) { return RandomRotation(rng).col(0); }

TEST(RevolutionProfile, SampledSphereIsTheConcentricSphereShortByTheSagitta) {
  constexpr double kR = 0.015, kZ0 = 0.003;
  constexpr int kN = 90;
  const auto profile = MakeRevolutionProfile(Circle(kR, kZ0, kN), 1e-4);
  const double inner = kR * std::cos(0.5 * kPi / kN);
  for (const RevolutionArc& arc : profile->arcs) {
    // (round-off: tan of the samples' small angles)
    EXPECT_NEAR(arc.centre.x(), 0.0, 1e-13);
    EXPECT_NEAR(arc.centre.y(), kZ0, 1e-13);
    EXPECT_NEAR(arc.radius, inner, 1e-13);
  }
  EXPECT_EQ(profile->top_disc_radius, 0.0);
  EXPECT_EQ(profile->bottom_disc_radius, 0.0);
  std::mt19937 rng(7);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d d = RandomDirection(rng);
    const Eigen::Vector3d expected = Eigen::Vector3d(0, 0, kZ0) + inner * d;
    EXPECT_LT((RevolutionSupport(*profile, d) - expected).norm(), 1e-13);
  }
  const double volume = 4.0 / 3.0 * kPi * std::pow(inner, 3);
  EXPECT_NEAR(RevolutionVolume(*profile) / volume, 1.0, 1e-6);
}

TEST(RevolutionProfile, CylinderKeepsItsFacesAndItsRimsWithinTheRounding) {
  constexpr double kR = 0.02, kL = 0.005, kTau = 1e-5;
  // the rims' points only (a cylinder mesh has no vertex on its axis)
  const auto profile = MakeRevolutionProfile({{kR, kL}, {kR, -kL}}, kTau);
  ASSERT_EQ(profile->arcs.size(), 2u);
  EXPECT_GT(profile->top_disc_radius, kR - 3 * kTau);
  EXPECT_GT(profile->bottom_disc_radius, kR - 3 * kTau);
  // the support of the exact cylinder, within τ
  std::mt19937 rng(8);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d d = RandomDirection(rng);
    const double rho = d.head<2>().norm();
    const double exact = kR * rho + kL * std::abs(d.z());
    const double h = d.dot(RevolutionSupport(*profile, d));
    EXPECT_LE(h, exact + 1e-15);
    EXPECT_GE(h, exact - kTau);
  }
  EXPECT_NEAR(RevolutionVolume(*profile) / (2 * kPi * kR * kR * kL), 1.0, 1e-3);
}

TEST(RevolutionProfile, ArcsJoinTangentiallyWithNormalsInOrder) {
  // the Tippe-Top's two-sphere hull: arcs, a straight cone between them
  std::vector<Eigen::Vector2d> points = Circle(0.015, 0.003, 120);
  for (const Eigen::Vector2d& p : Circle(0.005, 0.016, 60)) points.push_back(p);
  const auto profile = MakeRevolutionProfile(points, 1e-5);
  double previous = 0.0;
  for (int k = 0; k < static_cast<int>(profile->arcs.size()); ++k) {
    const RevolutionArc& arc = profile->arcs[k];
    EXPECT_GT(arc.theta_end, previous);
    EXPECT_GT(arc.radius, 0.0);
    if (k > 0) {
      // the stretch from the previous arc's end to this arc's start is perpendicular to the
      // shared normal (G1)
      const Eigen::Vector2d u(std::sin(previous), std::cos(previous));
      EXPECT_NEAR((ArcStart(*profile, k) - ArcEnd(*profile, k - 1)).dot(u), 0.0, 1e-15);
    }
    previous = arc.theta_end;
  }
  EXPECT_EQ(previous, kPi);
  // one straight stretch, the cone: √((a2 − a1)² − (R1 − R2)²) = 8.31 mm, give or take the
  // samples' spacing on each circle (0.26 and 0.39 mm) and the arcs' halves of the edges
  int stretches = 0;
  for (const RevolutionArc& arc : profile->arcs) {
    if (arc.stretch == 0.0) continue;
    ++stretches;
    EXPECT_NEAR(arc.stretch, std::sqrt(0.013 * 0.013 - 0.01 * 0.01), 1e-3);
  }
  EXPECT_EQ(stretches, 1);
  // the support's arc lookup against the best point of every arc
  const Shape shape = Shape::Revolution(profile);
  std::mt19937 rng(10);
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d d = RandomDirection(rng);
    EXPECT_NEAR(d.dot(RevolutionSupport(*profile, d)),
                d.dot(collision_test::Support(shape, Eigen::Isometry3d::Identity(), d)), 1e-16);
  }
}

// The Tippe-Top's hull on a plane: its lowest point as the two spheres' (the hull's support is
// the larger of theirs), within the samples' sagitta; a second contact at the cone's far end when
// it lies within the margin.
TEST(PlaneRevolution, TippeTopHullTouchesWhereItsSpheresDo) {
  constexpr double kR1 = 0.015, kA1 = 0.003, kR2 = 0.005, kA2 = 0.016;
  std::vector<Eigen::Vector2d> points = Circle(kR1, kA1, 180);
  for (const Eigen::Vector2d& p : Circle(kR2, kA2, 60)) points.push_back(p);
  const Shape top = Shape::Revolution(MakeRevolutionProfile(points, 1e-5));
  const double sagitta = std::max(kR1 * (1.0 - std::cos(0.5 * kPi / 180)),
                                  kR2 * (1.0 - std::cos(0.5 * kPi / 60)));
  const Eigen::Isometry3d plane = Eigen::Isometry3d::Identity();
  std::mt19937 rng(9);
  int two = 0;
  for (int i = 0; i < 2000; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = RandomRotation(rng);
    pose.translation() = Eigen::Vector3d(0.01, -0.02, 0.015);
    const Eigen::Vector3d down = pose.linear().transpose() * -Eigen::Vector3d::UnitZ();
    const double lowest = std::min(
        pose.translation().z() - kR1 + pose.linear().col(2).z() * kA1,
        pose.translation().z() - kR2 + pose.linear().col(2).z() * kA2);
    ContactGeometry out[kMaxPairContacts];
    const int n = CollidePlaneRevolution(Shape::Plane(), plane, top, pose, 1.0, out);
    ASSERT_GE(n, 1);
    EXPECT_NEAR(out[0].gap, lowest, sagitta + 1e-12) << down.transpose();
    EXPECT_NEAR(out[0].point_b.z(), out[0].gap, 1e-15);
    for (int j = 1; j < n; ++j) EXPECT_GE(out[j].gap, out[0].gap - 1e-12);
    two += n > 1;
  }
  EXPECT_GT(two, 0);  // the cone's far end is reported where it lies within the margin
}

TEST(PlaneRevolution, UprightCylinderRestsOnFourFacePointsAndOnItsSideOnTwo) {
  constexpr double kR = 0.02, kL = 0.005;
  const Shape disc = Shape::Revolution(MakeRevolutionProfile({{kR, kL}, {kR, -kL}}, 1e-6));
  const double rho = 2.0 * disc.revolution->bottom_disc_radius / 3.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation().z() = kL - 1e-4;
  ContactGeometry out[kMaxPairContacts];
  ASSERT_EQ(CollidePlaneRevolution(Shape::Plane(), Eigen::Isometry3d::Identity(), disc, pose,
                                   1e-3, out),
            4);
  for (int j = 0; j < 4; ++j) {
    EXPECT_TRUE(out[j].face_point);
    EXPECT_NEAR(out[j].gap, -1e-4, 1e-15);
    EXPECT_NEAR(out[j].point_b.head<2>().norm(), rho, 1e-15);
  }
  // on its side: both rims (the support, the straight side's far end) at the same gap
  pose.linear() = Eigen::AngleAxisd(0.5 * kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  pose.translation().z() = kR - 1e-4;
  const int n = CollidePlaneRevolution(Shape::Plane(), Eigen::Isometry3d::Identity(), disc, pose,
                                       1e-3, out);
  ASSERT_EQ(n, 2);
  EXPECT_NEAR(out[0].gap, out[1].gap, 1e-15);
  EXPECT_NEAR(std::abs(out[0].point_b.y() - out[1].point_b.y()), 2 * kL, 1e-5);
}

TEST(RevolutionProfile, RefusesWhatSpansNoArea) {
  EXPECT_THROW(MakeRevolutionProfile({{0.0, 0.0}, {0.0, 1.0}}, 1e-3), std::invalid_argument);
  EXPECT_THROW(MakeRevolutionProfile({{1.0, 0.0}}, 1e-3), std::invalid_argument);
  EXPECT_THROW(MakeRevolutionProfile({{1.0, 0.0}, {1.0, 1.0}}, 0.0), std::invalid_argument);
  EXPECT_THROW(MakeRevolutionProfile({{NAN, 0.0}, {1.0, 1.0}}, 1e-3), std::invalid_argument);
}

}  // namespace
}  // namespace nonsmooth_sim
