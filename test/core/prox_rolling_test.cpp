// Tests of the rolling-resistance sets' prox (prox_rolling.h): the coupled 5-ball and the
// decoupled product S_F × disk, in the mapped coordinates Λ̂ = A⁻¹Λ.
//
// Each prox is checked on fixed-seed samples over every region (interior, near the boundary on
// both sides, far away, one factor inside and the other outside) and radii 1e-9 … 1e3 against:
//  - an independent brute-force minimisation of ||x - p||² over the set's boundary in quad
//    precision (brute_force_projection.h): the best of random boundary points refined by a (1+1) evolution strategy over the
//    boundary (no radial formula; for the product set each factor on its own, the squared
//    distance being a sum over the factors);
//  - interior points unchanged, idempotence, the variational inequality (x - p)·(z - p) ≤ 0 for
//    points z of the set, non-expansiveness;
//  - the map: A maps the ball onto the ellipsoid E_R of (55) extended by the rolling semi-axes.
#include "nonsmooth_sim/core/prox_rolling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "brute_force_projection.h"
#include "../measured_value.h"

namespace nonsmooth_sim {
namespace {

using test::Scientific;

constexpr std::uint64_t kSeed = 0x7011ed;
constexpr int kSamples = 300;
// agreement with the brute-force reference, relative to max(radius, ||x||)
constexpr double kReferenceTolerance = 1e-12;  // measured 1.7e-16 (2026-12-06)

using brute_force::Quad;
using VectorL = std::vector<Quad>;

Quad DistanceSquared(const VectorL& a, const VectorL& b) {
  Quad sum = 0;
  for (std::size_t k = 0; k < a.size(); ++k) sum += (a[k] - b[k]) * (a[k] - b[k]);
  return sum;
}

// r·u for a nonzero u: a point of the sphere of radius r.
VectorL OnSphere(VectorL u, Quad r) {
  Quad norm = 0;
  for (Quad v : u) norm += v * v;
  norm = brute_force::QuadSqrt(norm);
  for (Quad& v : u) v *= r / norm;
  return u;
}

// argmin over the sphere ||p|| = r of ||z - p||², searched over its points alone: the best of
// random points, then a (1+1) evolution strategy (a random step of size σ on the sphere, kept
// if nearer; σ doubled after a success, shrunk after a failure, the 1/5 rule) until σ ~ 1e-17.
VectorL NearestOnSphere(const VectorL& z, Quad r, std::mt19937_64& rng) {
  const std::size_t n = z.size();
  std::normal_distribution<double> normal;
  VectorL best(n);
  Quad best_value = 1e300;
  for (int s = 0; s < 200; ++s) {
    VectorL u(n);
    for (Quad& v : u) v = normal(rng);
    const VectorL p = OnSphere(u, r);
    const Quad value = DistanceSquared(p, z);
    if (value < best_value) {
      best_value = value;
      best = p;
    }
  }
  Quad sigma = Quad(0.5) * r;
  for (int it = 0; it < 20000 && sigma > Quad(1e-20) * r; ++it) {
    VectorL u = best;
    for (Quad& v : u) v += sigma * normal(rng);
    const VectorL p = OnSphere(u, r);
    const Quad value = DistanceSquared(p, z);
    if (value < best_value) {
      best_value = value;
      best = p;
      sigma *= 2;
    } else {
      sigma *= Quad(0.84);  // 2^(-1/4): the step holds where a fifth of the proposals succeed
    }
  }
  return best;
}

// The projection onto the ball ||p|| ≤ r of z: z if inside, else the nearest boundary point.
VectorL BruteBall(const VectorL& z, Quad r, std::mt19937_64& rng) {
  Quad norm_sq = 0;
  for (Quad v : z) norm_sq += v * v;
  if (norm_sq <= r * r) return z;
  return NearestOnSphere(z, r, rng);
}

VectorL ToLong(const Vector5d& x, int first, int count) {
  VectorL v(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) v[static_cast<std::size_t>(k)] = x[first + k];
  return v;
}

Vector5d BruteCoupled(const Vector5d& x, double radius, std::mt19937_64& rng) {
  const VectorL p = BruteBall(ToLong(x, 0, 5), radius, rng);
  Vector5d result;
  for (int k = 0; k < 5; ++k) result[k] = static_cast<double>(p[static_cast<std::size_t>(k)]);
  return result;
}

Vector5d BruteDecoupled(const Vector5d& x, double radius, std::mt19937_64& rng) {
  const VectorL friction = BruteBall(ToLong(x, 0, 3), radius, rng);
  const VectorL rolling = BruteBall(ToLong(x, 3, 2), radius, rng);
  Vector5d result;
  for (int k = 0; k < 3; ++k) result[k] = static_cast<double>(friction[static_cast<std::size_t>(k)]);
  for (int k = 0; k < 2; ++k) result[3 + k] = static_cast<double>(rolling[static_cast<std::size_t>(k)]);
  return result;
}

bool InCoupled(const Vector5d& x, double radius) { return x.norm() <= radius * (1 + 1e-12); }
bool InDecoupled(const Vector5d& x, double radius) {
  return x.head<3>().norm() <= radius * (1 + 1e-12) && x.tail<2>().norm() <= radius * (1 + 1e-12);
}

// A sample around the set: a random direction per factor, each factor's size in [0, 3]·radius,
// sometimes one factor exactly on an axis or zero.
Vector5d RandomSample(std::mt19937_64& rng, double radius, int k) {
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> size(0.0, 3.0);
  Vector5d x;
  for (int i = 0; i < 5; ++i) x[i] = normal(rng);
  x.head<3>() *= size(rng) * radius / x.head<3>().norm();
  x.tail<2>() *= size(rng) * radius / x.tail<2>().norm();
  if (k % 7 == 0) x.tail<2>().setZero();
  if (k % 11 == 0) x.head<3>().setZero();
  if (k % 13 == 0) x = x.cwiseProduct(Vector5d(1, 0, 0, 1, 0));
  return x;
}

// A point of the set: a random point scaled inside both factors.
Vector5d RandomSetPoint(std::mt19937_64& rng, double radius, bool coupled) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vector5d z;
  for (int i = 0; i < 5; ++i) z[i] = u(rng) * radius;
  if (coupled) {
    if (z.norm() > radius) z *= radius / z.norm();
  } else {
    if (z.head<3>().norm() > radius) z.head<3>() *= radius / z.head<3>().norm();
    if (z.tail<2>().norm() > radius) z.tail<2>() *= radius / z.tail<2>().norm();
  }
  return z;
}

struct Case {
  const char* name;
  Prox5 (*prox)(const Vector5d&, double);
  Vector5d (*brute)(const Vector5d&, double, std::mt19937_64&);
  bool (*contains)(const Vector5d&, double);
  bool coupled;
};

const Case kCases[] = {
    {"coupled", &ProxRollingBall, &BruteCoupled, &InCoupled, true},
    {"decoupled", &ProxRollingDecoupled, &BruteDecoupled, &InDecoupled, false},
};

TEST(ProxRolling, AgreesWithBruteForceOverEveryRegionAndScale) {
  for (const Case& c : kCases) {
    std::mt19937_64 rng(kSeed);
    double worst = 0.0;
    int inside = 0;
    int outside = 0;
    for (int k = 0; k < kSamples; ++k) {
      const double radius = std::pow(10.0, -9.0 + 12.0 * (k % 25) / 24.0);
      const Vector5d x = RandomSample(rng, radius, k);
      const Prox5 p = c.prox(x, radius);
      const Vector5d reference = c.brute(x, radius, rng);
      const double scale = std::max(radius, x.norm());
      const double error = (p.point - reference).cwiseAbs().maxCoeff() / scale;
      worst = std::max(worst, error);
      ASSERT_LE(error, kReferenceTolerance) << c.name << " x = " << x.transpose()
                                            << " radius = " << radius;
      ASSERT_TRUE(c.contains(p.point, radius)) << c.name;
      if (c.contains(x, radius) && p.region == ProxRegion::kInterior) {
        ASSERT_EQ(p.point, x) << c.name;  // the interior is kept bit for bit
        ++inside;
      } else {
        ASSERT_EQ(p.region, ProxRegion::kBoundary) << c.name << " x = " << x.transpose();
        ++outside;
      }
    }
    EXPECT_GT(inside, kSamples / 10) << c.name;
    EXPECT_GT(outside, kSamples / 3) << c.name;
    RecordProperty(std::string("worst_reference_error_") + c.name, Scientific(worst));
  }
}

TEST(ProxRolling, IdempotentNonExpansiveAndVariationalInequality) {
  for (const Case& c : kCases) {
    std::mt19937_64 rng(kSeed + 1);
    for (int k = 0; k < kSamples; ++k) {
      const double radius = std::pow(10.0, -6.0 + 9.0 * (k % 10) / 9.0);
      const Vector5d x = RandomSample(rng, radius, k);
      const Vector5d y = RandomSample(rng, radius, k + 1);
      const Prox5 px = c.prox(x, radius);
      const Prox5 py = c.prox(y, radius);
      // idempotence
      const Prox5 again = c.prox(px.point, radius);
      ASSERT_LE((again.point - px.point).cwiseAbs().maxCoeff(), 1e-15 * radius) << c.name;
      // non-expansiveness
      ASSERT_LE((px.point - py.point).norm(), (x - y).norm() * (1 + 1e-14) + 1e-300) << c.name;
      // (x - p)·(z - p) ≤ 0 for every z of the set, (2), (7)
      for (int j = 0; j < 20; ++j) {
        const Vector5d z = RandomSetPoint(rng, radius, c.coupled);
        ASSERT_LE((x - px.point).dot(z - px.point), 1e-13 * radius * std::max(radius, x.norm()))
            << c.name << " x = " << x.transpose() << " z = " << z.transpose();
      }
    }
  }
}

TEST(ProxRolling, ApexAtZeroOrNanRadius) {
  const Vector5d x(1, 2, 3, 4, 5);
  for (const Case& c : kCases) {
    for (double radius : {0.0, -1.0, std::nan("")}) {
      const Prox5 p = c.prox(x, radius);
      EXPECT_EQ(p.region, ProxRegion::kApex) << c.name;
      EXPECT_EQ(p.point, Vector5d::Zero()) << c.name;
    }
  }
}

// The decoupled set: the rolling factor does not change the friction factor's projection (and
// conversely), so a contact pressed to roll keeps its sliding friction; the coupled set trades
// one for the other along the ball.
TEST(ProxRolling, DecoupledFactorsAreIndependentCoupledOnesShareTheRadius) {
  const double radius = 2.0;
  const Vector5d sticking_rolling_saturated(0.6, 0.0, 0.0, 5.0, 0.0);
  const Prox5 d = ProxRollingDecoupled(sticking_rolling_saturated, radius);
  EXPECT_EQ(d.point.head<3>(), Vector5d(sticking_rolling_saturated).head<3>());
  EXPECT_NEAR(d.point[3], radius, 1e-15);
  const Prox5 b = ProxRollingBall(sticking_rolling_saturated, radius);
  EXPECT_LT(b.point[0], 0.6 * 0.99);  // the rolling torque took part of the radius
  EXPECT_NEAR(b.point.norm(), radius, 1e-15);
}

// A = diag(1, 1, R̄, ρ_r, ρ_r) on the friction components (ρ_r = μ_r/μ) maps the coupled ball
// ||Λ̂_F|| ≤ μΛ_N onto E_R: ||Λ_T||² + (Λ_τ/R̄)² + (||Λ_R||/ρ_r)² ≤ (μΛ_N)², i.e. ||Λ_R|| ≤ μ_rΛ_N
// where Λ_T = Λ_τ = 0, and the decoupled product onto E_F × {||Λ_R|| ≤ μ_rΛ_N}.
TEST(ProxRolling, TheMapTakesTheBallToTheEllipsoidWithRollingSemiAxes) {
  const double mu = 0.3;
  const double lambda_n = 2.0;
  const double rbar = 3e-4;
  const double mu_r = 5e-5;
  const double rho_r = mu_r / mu;
  const Vector5d a(1.0, 1.0, rbar, rho_r, rho_r);
  const double radius = mu * lambda_n;
  std::mt19937_64 rng(kSeed + 2);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  int checked = 0;
  for (int k = 0; k < kSamples; ++k) {
    Vector5d lambda(u(rng) * radius, u(rng) * radius, u(rng) * rbar * radius,
                    u(rng) * mu_r * lambda_n, u(rng) * mu_r * lambda_n);
    const double e_r = std::sqrt(lambda.head<2>().squaredNorm() +
                                 std::pow(lambda[2] / rbar, 2) +
                                 lambda.tail<2>().squaredNorm() / (rho_r * rho_r));
    if (std::abs(e_r - radius) < 1e-9 * radius) continue;
    const Vector5d hat = lambda.cwiseQuotient(a);
    EXPECT_EQ(ProxRollingBall(hat, radius).region == ProxRegion::kInterior, e_r < radius);
    const bool in_product = std::hypot(lambda[0], lambda[1], lambda[2] / rbar) <= radius &&
                            lambda.tail<2>().norm() <= mu_r * lambda_n;
    EXPECT_EQ(ProxRollingDecoupled(hat, radius).region == ProxRegion::kInterior, in_product);
    ++checked;
  }
  EXPECT_GT(checked, kSamples / 2);
  // the pure rolling bound: the ball's pole along R1 is μ_rΛ_N in the original coordinates
  const Vector5d pole = a.cwiseProduct(ProxRollingBall(Vector5d(0, 0, 0, 1e3, 0), radius).point);
  EXPECT_NEAR(pole[3], mu_r * lambda_n, 1e-15);
}

}  // namespace
}  // namespace nonsmooth_sim
