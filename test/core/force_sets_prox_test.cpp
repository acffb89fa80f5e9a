// The projections onto the unilateral set, the Coulomb disk, the ball S_F, the cylinder C_F and
// the ellipsoid E_F (force_sets.h), by the properties of force_sets_support.h; E_F's axes, its
// flat limit, and why rescaling radially is not its projection.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "force_sets_support.h"

namespace nonsmooth_sim {
namespace {

using namespace force_sets_support;  // NOLINT(build/namespaces)

// ---------------------------------------------------------------------------------------------
// Unilateral set {x ≥ 0}.

TEST(ProxNonNegative, InteriorFixed) {
  for (const double x : {0.0, 1e-300, 1e-9, 1.0, 1e3, 1e300}) {
    EXPECT_EQ(ProxNonNegative(x).point, x);
    EXPECT_EQ(ProxNonNegative(x).region, ProxRegion::kInterior);
  }
}

TEST(ProxNonNegative, ExteriorToApex) {
  for (const double x : {-1e-300, -1e-9, -1.0, -1e3, -kInf}) {
    EXPECT_EQ(ProxNonNegative(x).point, 0.0);
    EXPECT_EQ(ProxNonNegative(x).region, ProxRegion::kApex);
  }
}

TEST(ProxNonNegative, AgreesWithBruteForceAndVariationalInequality) {
  std::mt19937_64 rng(kSeed + 10);
  for (int i = 0; i < kSamples; ++i) {
    const double x = RandomSign(rng) * LogUniform(rng, -9, 3);
    const double p = ProxNonNegative(x).point;
    EXPECT_NEAR(p, brute_force::ProjectNonNegative(x), 1e-9 * std::abs(x)) << x;
    for (const double z : {0.0, 1e-9, 1.0, 1e3}) EXPECT_LE((x - p) * (z - p), 0.0) << x;
    EXPECT_EQ(ProxNonNegative(p).point, p);
  }
}

// ---------------------------------------------------------------------------------------------
// Coulomb disk {||x|| ≤ radius} in the plane.

std::vector<std::pair<Eigen::Vector2d, double>> DiskSamples(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::pair<Eigen::Vector2d, double>> samples;
  for (int i = 0; i < kSamples; ++i) {
    const double radius = LogUniform(rng, -9, 3);
    const double psi = Uniform(rng, -kPi, kPi);
    double r;
    switch (i % 4) {
      case 0:
        r = Uniform(rng, 0.0, 3.0) * radius;
        break;  // near
      case 1:
        r = LogUniform(rng, -9, 3);
        break;  // any scale
      case 2:
        r = radius * (1.0 + RandomSign(rng) * LogUniform(rng, -15, -1));
        break;  // boundary
      default:
        r = i % 8 == 3 ? 0.0 : radius;
        break;  // centre, on circle
    }
    samples.push_back({Eigen::Vector2d(r * std::cos(psi), r * std::sin(psi)), radius});
  }
  return samples;
}

TEST(ProxDisk, InteriorFixed) {
  int checked = 0;
  for (const auto& [x, radius] : DiskSamples(kSeed + 11)) {
    if (x.norm() > radius * (1.0 - 1e-12)) continue;  // strictly inside, beyond rounding
    ++checked;
    EXPECT_EQ(ProxDisk(x, radius).point, x);
    EXPECT_EQ(ProxDisk(x, radius).region, ProxRegion::kInterior);
  }
  EXPECT_GE(checked, kSamples / 4);
}

TEST(ProxDisk, ExteriorOnBoundary) {
  int checked = 0;
  for (const auto& [x, radius] : DiskSamples(kSeed + 12)) {
    if (x.norm() <= radius * (1.0 + kBoundaryTolerance)) continue;
    ++checked;
    const Prox2 p = ProxDisk(x, radius);
    EXPECT_EQ(p.region, ProxRegion::kBoundary);
    EXPECT_NEAR(p.point.norm(), radius, 1e-15 * radius);
  }
  EXPECT_GE(checked, kSamples / 4);
}

TEST(ProxDisk, ApexAtZeroRadius) {
  for (const double radius : {0.0, -1.0, kNaN}) {
    const Prox2 p = ProxDisk(Eigen::Vector2d(0.3, -2.0), radius);
    EXPECT_EQ(p.region, ProxRegion::kApex);
    EXPECT_EQ(p.point, Eigen::Vector2d::Zero());
  }
}

TEST(ProxDisk, IdempotentVariationalInequalityNonExpansive) {
  const auto samples = DiskSamples(kSeed + 13);
  std::mt19937_64 rng(kSeed + 13);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const auto& [x, radius] = samples[i];
    const Eigen::Vector2d p = ProxDisk(x, radius).point;
    EXPECT_LE((ProxDisk(p, radius).point - p).norm(), 1e-15 * radius);
    for (int j = 0; j < 64; ++j) {
      const double psi = 2.0 * kPi * j / 64;
      const Eigen::Vector2d z =
          radius * Uniform(rng, 0.5, 1.0) * Eigen::Vector2d(std::cos(psi), std::sin(psi));
      EXPECT_LE((x - p).dot(z - p), 1e-12 * radius * (x - p).norm());
    }
    const Eigen::Vector2d y = samples[(i + 5) % samples.size()].first;
    EXPECT_LE((ProxDisk(y, radius).point - p).norm(), (y - x).norm() * (1.0 + 1e-12));
  }
}

TEST(ProxDisk, AgreesWithBruteForce) {
  for (const auto& [x, radius] : DiskSamples(kSeed + 14)) {
    const Eigen::Vector2d ref = brute_force::ProjectDisk(x, radius);
    EXPECT_LE((ProxDisk(x, radius).point - ref).norm(), kReferenceTolerance * radius)
        << x.transpose() << " radius=" << radius;
  }
}

// ---------------------------------------------------------------------------------------------
// Ball S_F (58), (59).

TEST(ProxBall, InteriorFixed) { CheckInteriorFixed(Ball()); }
TEST(ProxBall, ExteriorOnBoundary) { CheckExteriorOnBoundary(Ball()); }
TEST(ProxBall, ApexAtZeroRadius) { CheckApexAtZeroRadius(Ball()); }
TEST(ProxBall, Idempotent) { CheckIdempotent(Ball()); }
TEST(ProxBall, VariationalInequality) { CheckVariationalInequality(Ball()); }
TEST(ProxBall, NonExpansive) { CheckNonExpansive(Ball()); }
TEST(ProxBall, AgreesWithBruteForce) { CheckAgreesWithBruteForce(Ball()); }

// ---------------------------------------------------------------------------------------------
// Cylinder C_F (54).

TEST(ProxCylinder, InteriorFixed) { CheckInteriorFixed(Cylinder()); }
TEST(ProxCylinder, ExteriorOnBoundary) { CheckExteriorOnBoundary(Cylinder()); }
TEST(ProxCylinder, ApexAtZeroRadius) { CheckApexAtZeroRadius(Cylinder()); }
TEST(ProxCylinder, Idempotent) { CheckIdempotent(Cylinder()); }
TEST(ProxCylinder, VariationalInequality) { CheckVariationalInequality(Cylinder()); }
TEST(ProxCylinder, NonExpansive) { CheckNonExpansive(Cylinder()); }
TEST(ProxCylinder, AgreesWithBruteForce) { CheckAgreesWithBruteForce(Cylinder()); }

// ---------------------------------------------------------------------------------------------
// Ellipsoid E_F (55).

TEST(ProxEllipsoid, InteriorFixed) { CheckInteriorFixed(Ellipsoid()); }
TEST(ProxEllipsoid, ExteriorOnBoundary) { CheckExteriorOnBoundary(Ellipsoid()); }
TEST(ProxEllipsoid, ApexAtZeroRadius) { CheckApexAtZeroRadius(Ellipsoid()); }
TEST(ProxEllipsoid, Idempotent) { CheckIdempotent(Ellipsoid()); }
TEST(ProxEllipsoid, VariationalInequality) { CheckVariationalInequality(Ellipsoid()); }
TEST(ProxEllipsoid, NonExpansive) { CheckNonExpansive(Ellipsoid()); }
TEST(ProxEllipsoid, AgreesWithBruteForce) { CheckAgreesWithBruteForce(Ellipsoid()); }

TEST(ProxEllipsoid, AxisPointsProjectToPoleAndEquator) {
  const double radius = 2e-6, rbar = 2.945e-4;
  const Prox3 pole = ProxEllipsoid(Eigen::Vector3d(0.0, 0.0, -5.0 * rbar * radius), radius, rbar);
  EXPECT_EQ(pole.point, Eigen::Vector3d(0.0, 0.0, -rbar * radius));
  EXPECT_EQ(pole.region, ProxRegion::kBoundary);
  const Prox3 equator =
      ProxEllipsoid(Eigen::Vector3d(3.0 * radius, -4.0 * radius, 0.0), radius, rbar);
  EXPECT_NEAR((equator.point - Eigen::Vector3d(0.6 * radius, -0.8 * radius, 0.0)).norm(), 0.0,
              4e-16 * radius);
}

TEST(ProxEllipsoid, FlatLimitIsTheDisk) {
  std::mt19937_64 rng(kSeed + 20);
  for (int i = 0; i < 200; ++i) {
    Eigen::Vector3d x;
    for (int j = 0; j < 3; ++j) x[j] = RandomSign(rng) * LogUniform(rng, -9, 3);
    const double radius = LogUniform(rng, -9, 3);
    const Prox2 disk = ProxDisk(x.head<2>(), radius);
    const Prox3 p = ProxEllipsoid(x, radius, 0.0);
    EXPECT_EQ(p.point, Eigen::Vector3d(disk.point.x(), disk.point.y(), 0.0));
    EXPECT_EQ(p.region, ProxRegion::kBoundary);  // x_τ ≠ 0 is outside the flat disk
  }
}

// Radially rescaling onto the ellipsoid, x / sqrt((ρ/a)² + (z/c)²), is what an approximate
// implementation would do; it is the projection only for a ball. The checks above must reject it.
TEST(ProxEllipsoid, RadialRescalingIsNotTheProjection) {
  const auto radial = [](const Sample& s) -> Eigen::Vector3d {
    const double scale = std::hypot(s.x.head<2>().norm() / s.radius, s.x.z() / (s.rbar * s.radius));
    return scale > 1.0 ? Eigen::Vector3d(s.x / scale) : s.x;
  };
  const int samples = 300;
  const SetUnderTest ellipsoid = Ellipsoid();
  EXPECT_GT(CountVariationalInequalityViolations(radial, ellipsoid, kSeed + 21, samples),
            samples / 10);
  EXPECT_EQ(CountVariationalInequalityViolations(
                [&](const Sample& s) { return ProxEllipsoid(s.x, s.radius, s.rbar).point; },
                ellipsoid, kSeed + 21, samples),
            0);
  int disagreements = 0;
  for (const Sample& s : MakeSamples(ellipsoid, kSeed + 22)) {
    const Eigen::Vector3d ref = brute_force::ProjectEllipsoid(s.x, s.radius, s.rbar);
    if (AxisError(radial(s), ref, s.radius, s.rbar) > kReferenceTolerance) ++disagreements;
  }
  EXPECT_GT(disagreements, kSamples / 10);
  // for rbar = 1 (a ball) the rescaling is the projection and passes
  std::mt19937_64 rng(kSeed + 23);
  for (int i = 0; i < 200; ++i) {
    Sample s{Eigen::Vector3d::Zero(), LogUniform(rng, -9, 3), 1.0};
    for (int j = 0; j < 3; ++j) s.x[j] = RandomSign(rng) * LogUniform(rng, -9, 3);
    EXPECT_LE(AxisError(radial(s), ProxEllipsoid(s.x, s.radius, 1.0).point, s.radius, 1.0), 1e-14);
  }
}

}  // namespace
}  // namespace nonsmooth_sim
