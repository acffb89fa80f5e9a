// Tests of every projection in force_sets.h and of the boundary curve of B_F (51)-(53).
//
// Each prox is checked on ≥ 1000 fixed-seed samples spread over the regions of its set
// (interior, near the boundary on both sides, far away, on the axes) and over scales: radius
// and input components from 1e-9 to 1e3, and for the sets with a drilling axis
// R̄ ∈ {1e-4, 2.945e-4, 0.1, 1, 10}. Properties (each fails for a wrong projection):
//  - interior points are returned unchanged (region kInterior);
//  - results lie in the set; for exterior points on its boundary (region kBoundary);
//  - idempotence P(P(x)) = P(x);
//  - the variational inequality (x - p)·(z - p) ≤ tol for points z of the set (2), (7);
//  - non-expansiveness ||P(x) - P(y)|| ≤ ||x - y||;
//  - agreement with the independent brute-force minimisation of brute_force_projection.h.
// Normalisation of every tolerance: per axis, tangential components relative to s = radius, the
// drilling component relative to its own half-axis (R̄·s for C_F, E_F, B_F; s for the ball).
//
// Membership and points of the sets come from brute_force_projection.h (quad precision, from
// the definitions), never from the code under test.
#include "nonsmooth_sim/core/force_sets.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iomanip>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "brute_force_projection.h"

namespace nonsmooth_sim {
namespace {

using brute_force::MeridianSet;
using brute_force::Quad;
using brute_force::QuadPoint;

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::uint64_t kSeed = 0x5eed2009;
constexpr int kSamples = 1200;
constexpr std::array<double, 5> kRbars = {1e-4, 2.945e-4, 0.1, 1.0, 10.0};

// Agreement with the brute-force reference, per axis. Measured worst (written to the test XML):
// ball 3e-16; B_F 1e-13 and E_F 3.5e-13, at points near the rim of the flattest sets, where the
// 1e-16 rounding of ||x_T|| alone moves the drilling component by up to ~1e-12 of its half-axis;
// C_F 2e-11, the reference's own resolution on the flat faces for inputs 1e12 radii away.
constexpr double kReferenceTolerance = 1e-9;
// Idempotence and "p is on the boundary", per axis (idempotence measured ≤ 1.5e-12).
constexpr double kBoundaryTolerance = 1e-9;

// ---------------------------------------------------------------------------------------------
// Sampling.

double LogUniform(std::mt19937_64& rng, double lo_exp, double hi_exp) {
  return std::pow(10.0, std::uniform_real_distribution<double>(lo_exp, hi_exp)(rng));
}
double Uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
double RandomSign(std::mt19937_64& rng) { return Uniform(rng, 0.0, 1.0) < 0.5 ? -1.0 : 1.0; }

// Lift a meridian point (ρ, z) ≥ 0, in units of radius, to 3-D with a random tangential
// direction and sign of the drilling component.
Eigen::Vector3d Lift(double rho, double z, double radius, std::mt19937_64& rng) {
  const double psi = Uniform(rng, -kPi, kPi);
  return {radius * rho * std::cos(psi), radius * rho * std::sin(psi), RandomSign(rng) * radius * z};
}

// A rotationally symmetric set under test: its prox, and its reference description.
struct SetUnderTest {
  std::string name;
  std::function<Prox3(const Eigen::Vector3d&, double radius, double rbar)> prox;
  std::function<MeridianSet(double rbar)> meridian;  // reference, in units of radius
  std::function<double(double rbar)> drilling_axis;  // drilling half-axis / radius
};

SetUnderTest Ball() {
  return {"ball", [](const Eigen::Vector3d& x, double r, double) { return ProxBall(x, r); },
          [](double) { return brute_force::EllipseMeridian(1.0); }, [](double) { return 1.0; }};
}
SetUnderTest Cylinder() {
  return {"cylinder", ProxCylinder, brute_force::CylinderMeridian,
          [](double rbar) { return rbar; }};
}
SetUnderTest Ellipsoid() {
  return {"ellipsoid", ProxEllipsoid, brute_force::EllipseMeridian,
          [](double rbar) { return rbar; }};
}
SetUnderTest CoulombContensou() {
  return {"coulomb_contensou",
          [](const Eigen::Vector3d& x, double r, double rbar) {
            return ProxCoulombContensou(x, r, rbar);
          },
          brute_force::ContensouMeridian, [](double rbar) { return rbar; }};
}
// The warm-started overload, its hint carried from each call to the next (the samples are
// unrelated points, so mostly a poor start): it must pass every check the cold one does.
SetUnderTest CoulombContensouHinted() {
  auto hint = std::make_shared<double>(std::numeric_limits<double>::quiet_NaN());
  return {"coulomb_contensou_hinted",
          [hint](const Eigen::Vector3d& x, double r, double rbar) {
            return ProxCoulombContensou(x, r, rbar, hint.get());
          },
          brute_force::ContensouMeridian, [](double rbar) { return rbar; }};
}

struct Sample {
  Eigen::Vector3d x;
  double radius;
  double rbar;
};

// Meridian coordinates of x in units of radius, in quad precision.
QuadPoint Meridian(const Eigen::Vector3d& x, double radius) {
  const Quad x1 = x.x(), x2 = x.y(), x3 = x.z(), r = radius;
  return {brute_force::QuadSqrt(x1 * x1 + x2 * x2) / r, brute_force::QuadAbs(x3) / r};
}

bool Contains(const MeridianSet& set, const Eigen::Vector3d& x, double radius) {
  const QuadPoint m = Meridian(x, radius);
  return set.contains(m.rho, m.z);
}

// Reference boundary point at σ and its outward unit normal (from a central difference of the
// parametrisation, oriented away from the origin).
struct BoundarySample {
  double rho, z, n_rho, n_z;
};
BoundarySample BoundaryWithNormal(const MeridianSet& set, double sigma) {
  const double h = 1e-6 * (set.sigma_max - set.sigma_min);
  const QuadPoint q = set.boundary(sigma);
  const QuadPoint a = set.boundary(std::max(sigma - h, set.sigma_min));
  const QuadPoint b = set.boundary(std::min(sigma + h, set.sigma_max));
  double n_rho = -static_cast<double>(b.z - a.z);
  double n_z = static_cast<double>(b.rho - a.rho);
  const double norm = std::hypot(n_rho, n_z);
  n_rho /= norm;
  n_z /= norm;
  if (n_rho * static_cast<double>(q.rho) + n_z * static_cast<double>(q.z) < 0.0) {
    n_rho = -n_rho;
    n_z = -n_z;
  }
  return {static_cast<double>(q.rho), static_cast<double>(q.z), n_rho, n_z};
}

// A point of the set: a boundary point scaled towards the origin (the sets are convex and
// contain 0): on the boundary (unless strictly_inside), just inside (by 1e-12 .. 1e-1
// relative), or anywhere inside.
Eigen::Vector3d PointInSet(const MeridianSet& set, double radius, std::mt19937_64& rng,
                           bool strictly_inside = false) {
  const QuadPoint q = set.boundary(Uniform(rng, set.sigma_min, set.sigma_max));
  const double kind = Uniform(rng, strictly_inside ? 0.3 : 0.0, 1.0);
  const double lambda = kind < 0.3    ? 1.0
                        : kind < 0.65 ? 1.0 - LogUniform(rng, -12, -1)
                                      : Uniform(rng, 0.0, 1.0);
  return Lift(lambda * static_cast<double>(q.rho), lambda * static_cast<double>(q.z), radius, rng);
}

// Samples over all regions and scales (see the file comment).
std::vector<Sample> MakeSamples(const SetUnderTest& set, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Sample> samples;
  samples.reserve(kSamples);
  for (int i = 0; i < kSamples; ++i) {
    const double rbar = kRbars[i % kRbars.size()];
    const double radius = LogUniform(rng, -9, 3);
    const double k = set.drilling_axis(rbar);
    const MeridianSet meridian = set.meridian(rbar);
    Eigen::Vector3d x;
    switch (i % 7) {
      case 0:
      case 1: {  // near the set: scaled meridian radius in [0, 3]
        const double r = Uniform(rng, 0.0, 3.0);
        const double alpha = Uniform(rng, 0.0, kPi / 2);
        x = Lift(r * std::cos(alpha), r * k * std::sin(alpha), radius, rng);
        break;
      }
      case 2: {  // components log-uniform over 1e-9 .. 1e3, independent of the radius
        for (int j = 0; j < 3; ++j) x[j] = RandomSign(rng) * LogUniform(rng, -9, 3);
        break;
      }
      case 3:
      case 4: {  // within 1e-13 .. 1 (in units of the smaller axis) of the boundary, either side
        const BoundarySample b =
            BoundaryWithNormal(meridian, Uniform(rng, meridian.sigma_min, meridian.sigma_max));
        const double d = RandomSign(rng) * LogUniform(rng, -13, 0) * std::min(1.0, k);
        x = Lift(std::max(0.0, b.rho + d * b.n_rho), std::max(0.0, b.z + d * b.n_z), radius, rng);
        break;
      }
      case 5: {  // inside, from the reference
        x = PointInSet(meridian, radius, rng);
        break;
      }
      default: {  // on the drilling axis, in the tangential plane, or 0
        const double which = Uniform(rng, 0.0, 1.0);
        const double r = LogUniform(rng, -3, 3);
        if (which < 0.45) {
          x = Eigen::Vector3d(0.0, 0.0, RandomSign(rng) * r * k * radius);
        } else if (which < 0.9) {
          x = Lift(r, 0.0, radius, rng);
          x.z() = 0.0;
        } else {
          x = Eigen::Vector3d::Zero();
        }
        break;
      }
    }
    samples.push_back({x, radius, rbar});
  }
  return samples;
}

// For RecordProperty: the measured worst errors end up in the test XML.
std::string Scientific(double value) {
  std::ostringstream out;
  out << std::scientific << std::setprecision(2) << value;
  return out.str();
}

// Per-axis distance of two results: max(tangential / s, drilling / (k s)).
double AxisError(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius, double k) {
  return std::max((a - b).head<2>().norm() / radius, std::abs(a.z() - b.z()) / (k * radius));
}

// ---------------------------------------------------------------------------------------------
// The property checks, shared by all rotationally symmetric sets.

void CheckInteriorFixed(const SetUnderTest& set) {
  std::mt19937_64 rng(kSeed + 1);
  int checked = 0;
  for (int i = 0; i < kSamples; ++i) {
    const double rbar = kRbars[i % kRbars.size()];
    const double radius = LogUniform(rng, -9, 3);
    const MeridianSet meridian = set.meridian(rbar);
    const Eigen::Vector3d x = PointInSet(meridian, radius, rng, /*strictly_inside=*/true);
    ++checked;
    const Prox3 p = set.prox(x, radius, rbar);
    EXPECT_EQ(p.region, ProxRegion::kInterior) << set.name << " x=" << x.transpose();
    EXPECT_EQ(p.point, x) << set.name << " radius=" << radius << " rbar=" << rbar;
  }
  EXPECT_EQ(checked, kSamples);
}

void CheckExteriorOnBoundary(const SetUnderTest& set) {
  int checked = 0;
  for (const Sample& s : MakeSamples(set, kSeed + 2)) {
    const MeridianSet meridian = set.meridian(s.rbar);
    // clearly exterior: still outside when pulled in by the boundary tolerance
    if (Contains(meridian, s.x * (1.0 - kBoundaryTolerance), s.radius)) continue;
    ++checked;
    const Prox3 p = set.prox(s.x, s.radius, s.rbar);
    EXPECT_EQ(p.region, ProxRegion::kBoundary) << set.name << " x=" << s.x.transpose();
    EXPECT_TRUE(Contains(meridian, p.point * (1.0 - kBoundaryTolerance), s.radius))
        << set.name << " result not in the set: x=" << s.x.transpose() << " radius=" << s.radius
        << " rbar=" << s.rbar;
    EXPECT_FALSE(Contains(meridian, p.point * (1.0 + kBoundaryTolerance), s.radius))
        << set.name << " result inside, not on the boundary: x=" << s.x.transpose()
        << " radius=" << s.radius << " rbar=" << s.rbar;
  }
  EXPECT_GE(checked, kSamples / 3);
}

void CheckApexAtZeroRadius(const SetUnderTest& set) {
  std::mt19937_64 rng(kSeed + 3);
  for (const double radius : {0.0, -0.0, -1e-6, -kInf, kNaN}) {
    for (int i = 0; i < 50; ++i) {
      Eigen::Vector3d x;
      for (int j = 0; j < 3; ++j) x[j] = RandomSign(rng) * LogUniform(rng, -9, 3);
      if (i == 0) x.setZero();
      const Prox3 p = set.prox(x, radius, kRbars[i % kRbars.size()]);
      EXPECT_EQ(p.region, ProxRegion::kApex) << set.name << " radius=" << radius;
      EXPECT_EQ(p.point, Eigen::Vector3d::Zero()) << set.name << " radius=" << radius;
    }
  }
}

void CheckIdempotent(const SetUnderTest& set) {
  double worst = 0.0;
  for (const Sample& s : MakeSamples(set, kSeed + 4)) {
    const Eigen::Vector3d p = set.prox(s.x, s.radius, s.rbar).point;
    const Eigen::Vector3d pp = set.prox(p, s.radius, s.rbar).point;
    const double error = AxisError(p, pp, s.radius, set.drilling_axis(s.rbar));
    worst = std::max(worst, error);
    EXPECT_LE(error, kBoundaryTolerance)
        << set.name << " x=" << s.x.transpose() << " radius=" << s.radius << " rbar=" << s.rbar;
  }
  ::testing::Test::RecordProperty("worst_idempotence_error", Scientific(worst));
}

// (x - p)·(z - p) ≤ tol for z on a grid of boundary points and at random points of the set. A
// position error δ of p changes the left side by at most δ(|x - p| + |z - p|); the tolerance
// allows δ = kReferenceTolerance times the smaller half-axis. Returns the number of samples with
// a violation (the test expects none; the radial-rescaling test expects many).
int CountVariationalInequalityViolations(const std::function<Eigen::Vector3d(const Sample&)>& prox,
                                         const SetUnderTest& set, std::uint64_t seed, int samples) {
  std::mt19937_64 rng(seed);
  int violations = 0;
  const std::vector<Sample> all = MakeSamples(set, seed);
  for (int i = 0; i < samples; ++i) {
    const Sample& s = all[i];
    const MeridianSet meridian = set.meridian(s.rbar);
    const double k = set.drilling_axis(s.rbar);
    const Eigen::Vector3d p = prox(s);
    const Eigen::Vector3d gap = s.x - p;
    const double delta = kReferenceTolerance * std::min(1.0, k) * s.radius;
    const auto violates = [&](const Eigen::Vector3d& z) {
      return gap.dot(z - p) > delta * (gap.norm() + (z - p).norm());
    };
    // z in the meridian plane of p (where a wrong foot point shows most) and elsewhere
    const double rho_p = p.head<2>().norm();
    const Eigen::Vector2d dir =
        rho_p > 0.0 ? Eigen::Vector2d(p.head<2>() / rho_p) : Eigen::Vector2d(1.0, 0.0);
    const double sign = p.z() < 0.0 ? -1.0 : 1.0;
    bool violated = false;
    constexpr int kGrid = 160;
    for (int j = 0; j <= kGrid && !violated; ++j) {
      const double sigma =
          meridian.sigma_min + (meridian.sigma_max - meridian.sigma_min) * j / kGrid;
      const QuadPoint q = meridian.boundary(sigma);
      const double zr = s.radius * static_cast<double>(q.rho);
      const Eigen::Vector3d z(zr * dir.x(), zr * dir.y(),
                              sign * s.radius * static_cast<double>(q.z));
      if (violates(z)) violated = true;
    }
    for (int j = 0; j < 40 && !violated; ++j) {
      const Eigen::Vector3d z = PointInSet(meridian, s.radius, rng);
      if (violates(z)) violated = true;
    }
    if (violated) ++violations;
  }
  return violations;
}

void CheckVariationalInequality(const SetUnderTest& set) {
  const int violations = CountVariationalInequalityViolations(
      [&](const Sample& s) { return set.prox(s.x, s.radius, s.rbar).point; }, set, kSeed + 5,
      kSamples);
  EXPECT_EQ(violations, 0) << set.name;
}

void CheckNonExpansive(const SetUnderTest& set) {
  std::mt19937_64 rng(kSeed + 6);
  const std::vector<Sample> samples = MakeSamples(set, kSeed + 6);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Sample& s = samples[i];
    // a close neighbour (relative distance 1e-12 .. 1) and, every other time, a second sample
    // with the same radius and R̄
    Eigen::Vector3d y;
    if (i % 2 == 0) {
      const double scale = LogUniform(rng, -12, 0) * std::max(s.x.norm(), s.radius);
      y = s.x + scale * Eigen::Vector3d(Uniform(rng, -1, 1), Uniform(rng, -1, 1),
                                        Uniform(rng, -1, 1) * set.drilling_axis(s.rbar));
    } else {
      y = samples[(i + 7) % samples.size()].x;
    }
    const Eigen::Vector3d px = set.prox(s.x, s.radius, s.rbar).point;
    const Eigen::Vector3d py = set.prox(y, s.radius, s.rbar).point;
    const double slack = 1e-11 * std::min(1.0, set.drilling_axis(s.rbar)) * s.radius;
    EXPECT_LE((px - py).norm(), (s.x - y).norm() * (1.0 + 1e-9) + slack)
        << set.name << " x=" << s.x.transpose() << " y=" << y.transpose() << " radius=" << s.radius
        << " rbar=" << s.rbar;
  }
}

void CheckAgreesWithBruteForce(const SetUnderTest& set) {
  double worst = 0.0;
  for (const Sample& s : MakeSamples(set, kSeed + 7)) {
    const Eigen::Vector3d p = set.prox(s.x, s.radius, s.rbar).point;
    const Eigen::Vector3d ref = brute_force::ProjectRotational(s.x, s.radius, set.meridian(s.rbar));
    const double error = AxisError(p, ref, s.radius, set.drilling_axis(s.rbar));
    worst = std::max(worst, error);
    EXPECT_LE(error, kReferenceTolerance)
        << set.name << " x=" << s.x.transpose() << " radius=" << s.radius << " rbar=" << s.rbar
        << "\n prox=" << p.transpose() << "\n ref =" << ref.transpose();
  }
  ::testing::Test::RecordProperty("worst_reference_error", Scientific(worst));
}

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

// ---------------------------------------------------------------------------------------------
// Coulomb-Contensou set B_F (51)-(53): the projection.

TEST(ProxCoulombContensou, InteriorFixed) { CheckInteriorFixed(CoulombContensou()); }
TEST(ProxCoulombContensou, ExteriorOnBoundary) { CheckExteriorOnBoundary(CoulombContensou()); }
TEST(ProxCoulombContensou, ApexAtZeroRadius) { CheckApexAtZeroRadius(CoulombContensou()); }
TEST(ProxCoulombContensou, Idempotent) { CheckIdempotent(CoulombContensou()); }
TEST(ProxCoulombContensou, VariationalInequality) {
  CheckVariationalInequality(CoulombContensou());
}
TEST(ProxCoulombContensou, NonExpansive) { CheckNonExpansive(CoulombContensou()); }
TEST(ProxCoulombContensou, AgreesWithBruteForce) { CheckAgreesWithBruteForce(CoulombContensou()); }

TEST(ProxCoulombContensou, HintedPassesTheSameChecks) {
  const SetUnderTest set = CoulombContensouHinted();
  CheckInteriorFixed(set);
  CheckExteriorOnBoundary(set);
  CheckIdempotent(set);
  CheckVariationalInequality(set);
  CheckNonExpansive(set);
  CheckAgreesWithBruteForce(set);
}

// Any hint, good or absurd, gives the cold projection to a few ulps, and the hint returned is
// the foot point's v = 1/u: started from it, the same point again.
TEST(ProxCoulombContensou, AnyHintGivesTheSameProjection) {
  std::mt19937_64 rng(kSeed + 31);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  int rim_projections = 0;
  for (int i = 0; i < 2000; ++i) {
    const double radius = LogUniform(rng, -6, 1);
    const double rbar = LogUniform(rng, -4, 1);
    // meridian points around the boundary, most of them outside (the branch u > 1 is X large)
    const Eigen::Vector3d x =
        Lift(LogUniform(rng, -1, 1.5), rbar * LogUniform(rng, -3, 1), radius, rng);
    const Prox3 cold = ProxCoulombContensou(x, radius, rbar);
    double found = nan;
    ProxCoulombContensou(x, radius, rbar, &found);
    if (found == found) ++rim_projections;
    for (const double start : {nan, -1.0, 0.0, 1e-300, Uniform(rng, 0.0, 1.0), 1.0, 2.0, inf,
                               found, found * (1.0 + 1e-3), found * (1.0 - 1e-3)}) {
      double hint = start;
      const Prox3 warm = ProxCoulombContensou(x, radius, rbar, &hint);
      ASSERT_EQ(warm.region, cold.region) << "hint " << start;
      EXPECT_LE((warm.point - cold.point).norm(), 4e-16 * radius * (1.0 + rbar))
          << "x " << x.transpose() << " radius " << radius << " rbar " << rbar << " hint "
          << start;
    }
  }
  // the branch u > 1 was exercised
  EXPECT_GT(rim_projections, 200);
}

TEST(ProxCoulombContensou, AxisPointsProjectToPoleAndRim) {
  const double radius = 1.8e-6, rbar = 2.945e-4;
  const Prox3 pole =
      ProxCoulombContensou(Eigen::Vector3d(0.0, 0.0, 7.0 * rbar * radius), radius, rbar);
  EXPECT_EQ(pole.point, Eigen::Vector3d(0.0, 0.0, rbar * radius));  // b_τ(0) = R̄μΛ_N
  EXPECT_EQ(pole.region, ProxRegion::kBoundary);
  const Prox3 rim =
      ProxCoulombContensou(Eigen::Vector3d(-3.0 * radius, 4.0 * radius, 0.0), radius, rbar);
  EXPECT_NEAR((rim.point - Eigen::Vector3d(-0.6 * radius, 0.8 * radius, 0.0)).norm(), 0.0,
              4e-16 * radius);  // b_T(∞) = μΛ_N
  EXPECT_EQ(rim.region, ProxRegion::kBoundary);
}

TEST(ProxCoulombContensou, FlatLimitIsTheDisk) {
  std::mt19937_64 rng(kSeed + 30);
  for (int i = 0; i < 200; ++i) {
    Eigen::Vector3d x;
    for (int j = 0; j < 3; ++j) x[j] = RandomSign(rng) * LogUniform(rng, -9, 3);
    const double radius = LogUniform(rng, -9, 3);
    const Prox2 disk = ProxDisk(x.head<2>(), radius);
    EXPECT_EQ(ProxCoulombContensou(x, radius, 0.0).point,
              Eigen::Vector3d(disk.point.x(), disk.point.y(), 0.0));
  }
}

// ---------------------------------------------------------------------------------------------
// Coulomb-Contensou set B_F (51)-(53): the boundary curve.

// Reference β_T(u) = b_T/s, β_τ(u) = b_τ/(R̄ s) at a double u, in quad precision: the
// polynomials for u ≤ 1; for u > 1 the θ-form of brute_force::ContensouBoundary with
// θ = asin(1/u) (Newton on sin from the double asin). Accurate to ~u²·1e-34 relative.
struct QuadCurvePoint {
  Quad bt, btau;
};
Quad QuadAsin(Quad y) {
  Quad theta = std::asin(static_cast<double>(y));
  // Newton on sin θ = y: 53 → 106 → 212 bits
  for (int i = 0; i < 3; ++i)
    theta -= (brute_force::QuadSin(theta) - y) / brute_force::QuadCos(theta);
  return theta;
}

QuadCurvePoint ReferenceCurve(Quad u) {
  if (u <= 1) {
    const Quad u2 = u * u;
    return {3 * brute_force::QuadPi() / 32 * (4 * u - u2 * u), (3 * u2 * u2 - 8 * u2 + 8) / 8};
  }
  const Quad y = 1 / u;
  const Quad theta = QuadAsin(y);
  const Quad s = y, c = brute_force::QuadSqrt((1 - y) * (1 + y));
  const Quad d = brute_force::QuadXMinusSin(2 * theta) / 2;
  const Quad s2 = s * s;
  const Quad bt = 3 / (16 * s2 * s) * (-d + 4 * s2 * theta + 2 * s2 * s * c);
  const Quad btau = 1 / (4 * brute_force::QuadPi() * s2 * s2) *
                    (3 * d - 8 * s2 * theta + 6 * s2 * s * c + 8 * s2 * s2 * theta);
  return {bt, btau};
}

// u from 0 to 1e9, log-spaced, plus the switch points of the implementation and their neighbours.
std::vector<double> CurveParameters() {
  std::vector<double> us = {0.0, 1e-300, 1e-12};
  for (double e = -6.0; e <= 9.0; e += 0.01) us.push_back(std::pow(10.0, e));
  for (const double u : {1.0, 2.0, 8.0, 128.0}) {
    for (const double f : {1.0 - 1e-9, 1.0 - 1e-15, 1.0, 1.0 + 1e-15, 1.0 + 1e-9})
      us.push_back(u * f);
  }
  return us;
}

TEST(CoulombContensouBoundary, AgreesWithHighPrecision) {
  // measured worst: 4e-16 (b_T), 1.1e-15 (b_τ)
  constexpr double kTolerance = 4e-15;
  for (const double rbar : kRbars) {
    for (const double radius : {1e-9, 1.8e-6, 1e3}) {
      for (const double u : CurveParameters()) {
        const CoulombContensouBoundaryPoint b = CoulombContensouBoundary(u, radius, rbar);
        const QuadCurvePoint ref = ReferenceCurve(u);
        EXPECT_NEAR(b.b_t / radius, static_cast<double>(ref.bt),
                    kTolerance * static_cast<double>(ref.bt) + 1e-300)
            << "u=" << u;
        EXPECT_NEAR(b.b_tau / (rbar * radius), static_cast<double>(ref.btau),
                    kTolerance * static_cast<double>(ref.btau))
            << "u=" << u;
      }
    }
  }
}

// Above u = 1e9 the quad reference itself loses digits; there the leading terms of the
// expansion, s - b_T ≈ s/(10u²) and b_τ ≈ 16R̄s/(15πu), are exact to double precision (next
// terms are u⁻² smaller). The two constants are first confirmed on the quad reference.
TEST(CoulombContensouBoundary, LargeUAsymptotics) {
  const Quad u_ref = 1e8;
  const QuadCurvePoint ref = ReferenceCurve(u_ref);
  EXPECT_NEAR(static_cast<double>((1 - ref.bt) * u_ref * u_ref), 0.1, 1e-15);
  EXPECT_NEAR(static_cast<double>(ref.btau * u_ref), 16.0 / (15.0 * kPi), 1e-15);
  for (const double u : {1e10, 1e12, 1e15, 1e50, 1e150, 1e300}) {
    const CoulombContensouBoundaryPoint b = CoulombContensouBoundary(u, 1.0, 1.0);
    EXPECT_NEAR(b.b_tau * u, 16.0 / (15.0 * kPi), 1e-15) << "u=" << u;
    EXPECT_EQ(b.b_t, 1.0) << "u=" << u;  // 1 - 1/(10u²) rounds to 1
  }
  const CoulombContensouBoundaryPoint b = CoulombContensouBoundary(1e7, 1.0, 1.0);
  EXPECT_NEAR((1.0 - b.b_t) * 1e14, 0.1, 0.1 * 1e-1);  // 1 - b_T = 1e-15: a few ulps of 1
}

TEST(CoulombContensouBoundary, Limits) {
  for (const double rbar : kRbars) {
    for (const double radius : {1e-9, 1.8e-6, 1e3}) {
      const CoulombContensouBoundaryPoint top = CoulombContensouBoundary(0.0, radius, rbar);
      EXPECT_EQ(top.b_t, 0.0);              // b_T(0) = 0
      EXPECT_EQ(top.b_tau, rbar * radius);  // b_τ(0) = R̄μΛ_N
      const CoulombContensouBoundaryPoint rim = CoulombContensouBoundary(kInf, radius, rbar);
      EXPECT_EQ(rim.b_t, radius);  // b_T(∞) = μΛ_N
      EXPECT_EQ(rim.b_tau, 0.0);   // b_τ(∞) = 0
      const CoulombContensouBoundaryPoint one = CoulombContensouBoundary(1.0, radius, rbar);
      EXPECT_NEAR(one.b_t, 9.0 * kPi / 32.0 * radius, 1e-16 * radius);  // both branches of (51)
      EXPECT_NEAR(one.b_tau, 3.0 / 8.0 * rbar * radius, 1e-16 * rbar * radius);  // and (52)
    }
  }
}

// Both branches meet at u = 1 (value and slope: fact (a)), and the implementation's switches
// (closed form | series at u = 2, series truncations at u = 8 and u = 128) are continuous.
TEST(CoulombContensouBoundary, BranchesAndSeriesSwitchesAreContinuous) {
  for (const double u : {1.0, 2.0, 8.0, 128.0}) {
    const double below = std::nextafter(u, 0.0), above = std::nextafter(u, kInf);
    const CoulombContensouBoundaryPoint a = CoulombContensouBoundary(below, 1.0, 1.0);
    const CoulombContensouBoundaryPoint b = CoulombContensouBoundary(above, 1.0, 1.0);
    EXPECT_NEAR(a.b_t, b.b_t, 2e-15 * b.b_t) << "u=" << u;
    EXPECT_NEAR(a.b_tau, b.b_tau, 2e-15 * b.b_tau) << "u=" << u;
  }
  // slopes db_T/du from both sides of u = 1, (quad reference, one-sided differences) against
  // fact (a): 3π/32 (4 - 3u²) = 3π/32 at u = 1
  const Quad h = 1e-12;
  const Quad left = (ReferenceCurve(1).bt - ReferenceCurve(1 - h).bt) / h;
  const Quad right = (ReferenceCurve(1 + h).bt - ReferenceCurve(1).bt) / h;
  EXPECT_NEAR(static_cast<double>(left), 3.0 * kPi / 32.0, 1e-10);
  EXPECT_NEAR(static_cast<double>(right), 3.0 * kPi / 32.0, 1e-10);
}

// Fact (a): for u > 1, db_T/du = 3/16 ((4 - 3u²) asin(1/u) + (3 - 2/u²) sqrt(u² - 1)); fact (b):
// db_τ/du = -u R db_T/du with R = 16R̄/(3π) on both branches, i.e. the outward normal is
// ∝ (uR, 1). Central differences of the quad reference (h = 1e-9 u, error ~h² ≈ 1e-18 u²).
TEST(CoulombContensouBoundary, DerivativeAndNormalFacts) {
  for (const double u : {0.05, 0.3, 0.7, 0.95, 1.05, 1.5, 3.0, 10.0, 100.0, 1e3}) {
    const Quad uq = u, h = Quad(1e-9) * uq;
    const QuadCurvePoint a = ReferenceCurve(uq - h), b = ReferenceCurve(uq + h);
    const double dbt = static_cast<double>((b.bt - a.bt) / (2 * h));
    const double dbtau = static_cast<double>((b.btau - a.btau) / (2 * h));  // per R̄s
    // fact (a), evaluated in quad (the closed form cancels like u⁴ ulps)
    const Quad expected_dbt = u <= 1.0
                                  ? 3 * brute_force::QuadPi() / 32 * (4 - 3 * uq * uq)
                                  : Quad(3) / 16 *
                                        ((4 - 3 * uq * uq) * QuadAsin(1 / uq) +
                                         (3 - 2 / (uq * uq)) * brute_force::QuadSqrt(uq * uq - 1));
    EXPECT_NEAR(dbt / static_cast<double>(expected_dbt), 1.0, 1e-12) << "u=" << u;
    // fact (b) with rbar = 1: db_τ/du / (R̄ s) = -u (16/(3π)) db_T/du / s
    EXPECT_NEAR(dbtau, -u * 16.0 / (3.0 * kPi) * dbt, 1e-12 * std::abs(dbtau)) << "u=" << u;
  }
  // the implementation's curve has the same normal: double-precision central differences
  for (const double rbar : {2.945e-4, 1.0}) {
    const double rc = 16.0 * rbar / (3.0 * kPi);
    for (const double u : {0.05, 0.5, 0.9, 1.3, 1.7, 3.0, 5.0, 20.0, 60.0}) {
      const double h = 1e-5 * u;
      const CoulombContensouBoundaryPoint a = CoulombContensouBoundary(u - h, 1.0, rbar);
      const CoulombContensouBoundaryPoint b = CoulombContensouBoundary(u + h, 1.0, rbar);
      const double slope = (b.b_tau - a.b_tau) / (b.b_t - a.b_t);  // dz/dρ = -u R
      EXPECT_NEAR(slope / (-u * rc), 1.0, 1e-6) << "u=" << u << " rbar=" << rbar;
    }
  }
}

// Convex: successive chords of the (scaled) curve turn one way; midpoints of boundary points lie
// in B_F; B_F lies between the diamond ρ/s + |z|/(R̄s) ≤ 1 and the cylinder C_F.
TEST(CoulombContensouBoundary, ConvexBetweenDiamondAndCylinder) {
  std::vector<double> us = {0.0};
  for (double e = -4.0; e <= 4.0; e += 0.005) us.push_back(std::pow(10.0, e));
  std::vector<Eigen::Vector2d> points;
  for (const double u : us) {
    const CoulombContensouBoundaryPoint b = CoulombContensouBoundary(u, 1.0, 1.0);
    points.emplace_back(b.b_t, b.b_tau);
    EXPECT_LE(b.b_t, 1.0) << u;
    EXPECT_LE(b.b_tau, 1.0) << u;
    EXPECT_GE(b.b_t + b.b_tau, 1.0 - 1e-15) << u;
  }
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    const Eigen::Vector2d c1 = points[i] - points[i - 1], c2 = points[i + 1] - points[i];
    const double cross = c1.x() * c2.y() - c1.y() * c2.x();
    // clockwise (≤ 0) up to rounding of the chords (ε·|c1|·|c2|/min(|c1|,|c2|))
    EXPECT_LE(cross, 1e-14 * std::max(c1.norm(), c2.norm())) << "u=" << us[i];
  }
  std::mt19937_64 rng(kSeed + 40);
  for (const double rbar : kRbars) {
    const MeridianSet set = brute_force::ContensouMeridian(rbar);
    for (int i = 0; i < 100; ++i) {
      const double u1 = LogUniform(rng, -4, 6), u2 = LogUniform(rng, -4, 6);
      const CoulombContensouBoundaryPoint a = CoulombContensouBoundary(u1, 1.0, rbar);
      const CoulombContensouBoundaryPoint b = CoulombContensouBoundary(u2, 1.0, rbar);
      // the midpoint, pulled in by 1e-12, is in B_F (membership from the reference)
      const Quad scale = 0.5 * (1.0 - 1e-12);
      EXPECT_TRUE(set.contains(scale * (Quad(a.b_t) + Quad(b.b_t)),
                               scale * (Quad(a.b_tau) + Quad(b.b_tau))))
          << "u1=" << u1 << " u2=" << u2;
    }
  }
}

TEST(CoulombContensouBoundary, RejectsInvalidArguments) {
  EXPECT_THROW(CoulombContensouBoundary(-1.0, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(CoulombContensouBoundary(kNaN, 1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(CoulombContensouBoundary(1.0, -1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(CoulombContensouBoundary(1.0, kInf, 1.0), std::invalid_argument);
  EXPECT_THROW(CoulombContensouBoundary(1.0, 1.0, -1.0), std::invalid_argument);
  EXPECT_THROW(CoulombContensouBoundary(1.0, 1.0, kNaN), std::invalid_argument);
  try {
    CoulombContensouBoundary(-1.0, 1.0, 1.0);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("u must be"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace nonsmooth_sim
