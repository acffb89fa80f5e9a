// The Coulomb-Contensou set B_F (51)-(53) (force_sets.h): its projection by the properties of
// force_sets_support.h, with and without a hint, and its boundary curve against an independent
// quad-precision reference (limits, asymptotics, continuity, derivatives, convexity).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "force_sets_support.h"

namespace nonsmooth_sim {
namespace {

using namespace force_sets_support;  // NOLINT(build/namespaces)

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
