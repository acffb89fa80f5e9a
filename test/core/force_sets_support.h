// Shared by the tests of every projection in force_sets.h (force_sets_*_test.cpp).
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
#ifndef NONSMOOTH_SIM_TEST_CORE_FORCE_SETS_SUPPORT_H_
#define NONSMOOTH_SIM_TEST_CORE_FORCE_SETS_SUPPORT_H_

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
#include <string>
#include <vector>

#include "brute_force_projection.h"
#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/core/force_sets.h"
#include "../measured_value.h"

namespace nonsmooth_sim::force_sets_support {

using brute_force::MeridianSet;
using brute_force::Quad;
using brute_force::QuadPoint;

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr std::uint64_t kSeed = 0x5eed2009;
inline constexpr int kSamples = 1200;
inline constexpr std::array<double, 5> kRbars = {1e-4, 2.945e-4, 0.1, 1.0, 10.0};

// Agreement with the brute-force reference, per axis. Measured worst (written to the test XML):
// ball 3e-16; B_F 1e-13 and E_F 3.5e-13, at points near the rim of the flattest sets, where the
// 1e-16 rounding of ||x_T|| alone moves the drilling component by up to ~1e-12 of its half-axis;
// C_F 2e-11, the reference's own resolution on the flat faces for inputs 1e12 radii away.
inline constexpr double kReferenceTolerance = 1e-9;
// Idempotence and "p is on the boundary", per axis (idempotence measured ≤ 1.5e-12).
inline constexpr double kBoundaryTolerance = 1e-9;

// ---------------------------------------------------------------------------------------------
// Sampling.

inline double LogUniform(std::mt19937_64& rng, double lo_exp, double hi_exp) {
  return std::pow(10.0, std::uniform_real_distribution<double>(lo_exp, hi_exp)(rng));
}
inline double Uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
inline double RandomSign(std::mt19937_64& rng) { return Uniform(rng, 0.0, 1.0) < 0.5 ? -1.0 : 1.0; }

// Lift a meridian point (ρ, z) ≥ 0, in units of radius, to 3-D with a random tangential
// direction and sign of the drilling component.
inline Eigen::Vector3d Lift(double rho, double z, double radius, std::mt19937_64& rng) {
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

inline SetUnderTest Ball() {
  return {"ball", [](const Eigen::Vector3d& x, double r, double) { return ProxBall(x, r); },
          [](double) { return brute_force::EllipseMeridian(1.0); }, [](double) { return 1.0; }};
}
inline SetUnderTest Cylinder() {
  return {"cylinder", ProxCylinder, brute_force::CylinderMeridian,
          [](double rbar) { return rbar; }};
}
inline SetUnderTest Ellipsoid() {
  return {"ellipsoid", ProxEllipsoid, brute_force::EllipseMeridian,
          [](double rbar) { return rbar; }};
}
inline SetUnderTest CoulombContensou() {
  return {"coulomb_contensou",
          [](const Eigen::Vector3d& x, double r, double rbar) {
            return ProxCoulombContensou(x, r, rbar);
          },
          brute_force::ContensouMeridian, [](double rbar) { return rbar; }};
}
// The warm-started overload, its hint carried from each call to the next (the samples are
// unrelated points, so mostly a poor start): it must pass every check the cold one does.
inline SetUnderTest CoulombContensouHinted() {
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
inline QuadPoint Meridian(const Eigen::Vector3d& x, double radius) {
  const Quad x1 = x.x(), x2 = x.y(), x3 = x.z(), r = radius;
  return {brute_force::QuadSqrt(x1 * x1 + x2 * x2) / r, brute_force::QuadAbs(x3) / r};
}

inline bool Contains(const MeridianSet& set, const Eigen::Vector3d& x, double radius) {
  const QuadPoint m = Meridian(x, radius);
  return set.contains(m.rho, m.z);
}

// Reference boundary point at σ and its outward unit normal (from a central difference of the
// parametrisation, oriented away from the origin).
struct BoundarySample {
  double rho, z, n_rho, n_z;
};
inline BoundarySample BoundaryWithNormal(const MeridianSet& set, double sigma) {
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
inline Eigen::Vector3d PointInSet(const MeridianSet& set, double radius, std::mt19937_64& rng,
                                  bool strictly_inside = false) {
  const QuadPoint q = set.boundary(Uniform(rng, set.sigma_min, set.sigma_max));
  const double kind = Uniform(rng, strictly_inside ? 0.3 : 0.0, 1.0);
  const double lambda = kind < 0.3    ? 1.0
                        : kind < 0.65 ? 1.0 - LogUniform(rng, -12, -1)
                                      : Uniform(rng, 0.0, 1.0);
  return Lift(lambda * static_cast<double>(q.rho), lambda * static_cast<double>(q.z), radius, rng);
}

// Samples over all regions and scales (see the file comment).
inline std::vector<Sample> MakeSamples(const SetUnderTest& set, std::uint64_t seed) {
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
using test::Scientific;

// Per-axis distance of two results: max(tangential / s, drilling / (k s)).
inline double AxisError(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius,
                        double k) {
  return std::max((a - b).head<2>().norm() / radius, std::abs(a.z() - b.z()) / (k * radius));
}

// ---------------------------------------------------------------------------------------------
// The property checks, shared by all rotationally symmetric sets.

inline void CheckInteriorFixed(const SetUnderTest& set) {
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

inline void CheckExteriorOnBoundary(const SetUnderTest& set) {
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

inline void CheckApexAtZeroRadius(const SetUnderTest& set) {
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

inline void CheckIdempotent(const SetUnderTest& set) {
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
inline int CountVariationalInequalityViolations(
    const std::function<Eigen::Vector3d(const Sample&)>& prox, const SetUnderTest& set,
    std::uint64_t seed, int samples) {
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

inline void CheckVariationalInequality(const SetUnderTest& set) {
  const int violations = CountVariationalInequalityViolations(
      [&](const Sample& s) { return set.prox(s.x, s.radius, s.rbar).point; }, set, kSeed + 5,
      kSamples);
  EXPECT_EQ(violations, 0) << set.name;
}

inline void CheckNonExpansive(const SetUnderTest& set) {
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

inline void CheckAgreesWithBruteForce(const SetUnderTest& set) {
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

}  // namespace nonsmooth_sim::force_sets_support

#endif  // NONSMOOTH_SIM_TEST_CORE_FORCE_SETS_SUPPORT_H_
