// Exact Euclidean projection onto the ellipsoid E_F (55).
//
// E_F has the semi-axes a = radius (twice, tangential) and c = R̄·radius (drilling). With
// rotational symmetry the problem is the projection of (ρ, z) = (||x_T||, x_τ) onto an ellipse.
// The Lagrange condition of argmin ||x - p||² s.t. (p_ρ/a)² + (p_z/c)² = 1 gives
//   p_ρ = ρ a²/(a² + t),  p_z = z c²/(c² + t),
// with the multiplier t ≥ 0 the root of
//   f(t) = (ρ a/(a² + t))² + (z c/(c² + t))² - 1,
// which is convex and decreasing for t > -min(a², c²). Everything below is written in units of
// a (X = ρ/a, Z = |z|/a, semi-axes 1 and k = R̄, multiplier t/a²), because c/a = R̄ ~ 3e-4 makes
// the raw problem badly scaled. The root is found by Newton's method on the equivalent
//   h(t) = (f(t) + 1)^(-1/2) - 1 = 0,
// which is increasing and concave (h'' = -3(XZk)²(1 - k²)²(1+t)²(k²+t)²/(...) ≤ 0, checked with
// sympy) and exactly linear when one of the two terms dominates; f itself behaves like 1/t² there
// and Newton on it would crawl. Started left of the root (h ≤ 0), Newton on a concave increasing
// function increases monotonically to the root; started right of it, its first step lands left.
// A bracket of rigorous bounds guards against rounding. Since p = (I + t·diag(1, 1, 1/k²))⁻¹ x in
// these units, the tangential direction needs no division by ρ.
#include <algorithm>
#include <cmath>
#include <limits>

#include "nonsmooth_sim/core/force_sets.h"

namespace nonsmooth_sim {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
// Newton stops when its step is below this many ulps of t (the root is then exact to rounding)
constexpr double kStepTolerance = 4.0 * kEpsilon;
// ... or when h is within its own rounding error (a few ulps of 1) of zero (needed when t ≪ 1:
// the root is then only determined to ~ε absolute).
constexpr double kResidualTolerance = 4.0 * kEpsilon;
// Monotone Newton needs few (≤ 6 observed) iterations; the cap only bounds a pathological input.
constexpr int kMaxIterations = 100;

// The multiplier t ≥ 0 (in units of a²) of the projection of the exterior point (X, Z) > 0 onto
// the ellipse (p_ρ)² + (p_z/k)² = 1.
double EllipseMultiplier(double X, double Z, double k) {
  const double k2 = k * k;
  const double kz = k * Z;
  // lower bound (f ≥ 0, h ≤ 0): one term of f alone is 1 at t = X - 1 or t = kZ - k², and
  // f ≥ 0 wherever (X² + (kZ)²)/(max(1, k²) + t)² ≥ 1
  // (squares do not overflow: X, kZ ≤ 1e12 for inputs and radius in 1e-9 .. 1e3)
  const double norm = std::sqrt(X * X + kz * kz);
  double lo = std::max({0.0, X - 1.0, kz - k2, norm - std::max(1.0, k2)});
  // upper bound (f ≤ 0): f(t) ≤ (X² + (kZ)²)/(min(1, k²) + t)² - 1
  double hi = std::max(lo, norm - std::min(1.0, k2));
  // Start: when one term of f is nearly constant near the root (e.g. X ≲ 1 and the root close
  // to the rim), the other behaves like 1/t² and Newton from `lo` would crawl; use the range of
  // the nearly constant term. At the root a + b = 1 with a = (X/(1+t))², b = (kZ/(k²+t))²: a ≤ X²
  // gives b ≥ 1 - X², i.e. t ≤ t_up = kZ/sqrt(1 - X²) - k², and then a ≥ (X/(1 + t_up))² gives
  // t ≥ kZ/sqrt(1 - (X/(1 + t_up))²) - k²; the same with a and b swapped. Rounding can put these
  // estimates on the wrong side of a root near 0, so they only choose the start; the bracket
  // stays [lo, hi] (Newton from the right of the root of a concave h lands left of it).
  double t_up = hi;
  if (X < 1.0) t_up = std::min(t_up, kz / std::sqrt((1.0 - X) * (1.0 + X)) - k2);
  if (kz < k2) t_up = std::min(t_up, X / std::sqrt((1.0 - kz / k2) * (1.0 + kz / k2)) - 1.0);
  double t = lo;
  const double gap_rho = (1.0 + t_up - X) * (1.0 + t_up + X);  // (1 + t_up)² - X²
  if (gap_rho > 0.0) t = std::max(t, kz * (1.0 + t_up) / std::sqrt(gap_rho) - k2);
  const double gap_z = (k2 + t_up - kz) * (k2 + t_up + kz);  // (k² + t_up)² - (kZ)²
  if (gap_z > 0.0) t = std::max(t, X * (k2 + t_up) / std::sqrt(gap_z) - 1.0);
  t = std::min(t, hi);
  for (int i = 0; i < kMaxIterations; ++i) {
    const double q_rho = X / (1.0 + t);  // p_ρ
    const double q_z = kz / (k2 + t);    // p_z / k
    const double a = q_rho * q_rho;
    const double b = q_z * q_z;
    const double inv_norm = 1.0 / std::sqrt(a + b);
    const double h = inv_norm - 1.0;
    if (h == 0.0) return t;
    if (h < 0.0) {
      lo = t;
    } else {
      hi = t;  // passed the root by rounding
    }
    // h' = (a + b)^(-3/2) (a/(1 + t) + b/(k² + t))
    const double dh = inv_norm * inv_norm * inv_norm * (a / (1.0 + t) + b / (k2 + t));
    const double step = h / dh;
    // converged: the Newton step is below rounding of t, or h is zero to rounding
    if (std::abs(step) <= kStepTolerance * t || std::abs(h) <= kResidualTolerance) return t - step;
    t -= step;
    // safeguard: Newton from the left stays in [lo, hi]; bisect if rounding says otherwise
    if (!(t >= lo && t <= hi)) t = 0.5 * (lo + hi);
    if (hi - lo <= kStepTolerance * hi) return t;
  }
  return t;
}

}  // namespace

Prox3 ProxEllipsoid(const Eigen::Vector3d& x, double radius, double rbar) {
  // apex: the ellipsoid has shrunk to the point 0
  if (!(radius > 0.0)) return {Eigen::Vector3d::Zero(), ProxRegion::kApex};
  const Eigen::Vector2d x_t = x.head<2>();
  const double rho = x_t.norm();
  // flat limit R̄ = 0: the disk ||Λ_T|| ≤ radius in the plane Λ_τ = 0
  if (!(rbar > 0.0)) return ProxFlatDisk(x, radius);
  const double inv_radius = 1.0 / radius;
  const double X = rho * inv_radius;
  const double Z = std::abs(x.z()) * inv_radius;
  // interior: (55), (ρ/a)² + (z/c)² ≤ 1 multiplied by k²
  const double kx = rbar * X;
  if (kx * kx + Z * Z <= rbar * rbar) return {x, ProxRegion::kInterior};
  // boundary, on the drilling axis: the pole (0, 0, ±R̄·radius)
  if (rho == 0.0) {
    return {Eigen::Vector3d(0.0, 0.0, std::copysign(rbar * radius, x.z())), ProxRegion::kBoundary};
  }
  // boundary, in the tangential plane: the equator, radially
  if (x.z() == 0.0) {
    const Eigen::Vector2d p_t = x_t * (radius / rho);
    return {Eigen::Vector3d(p_t.x(), p_t.y(), 0.0), ProxRegion::kBoundary};
  }
  // boundary, general: p = (x_T/(1 + t), x_τ/(1 + t/k²)) with the root t of f
  const double t = EllipseMultiplier(X, Z, rbar);
  const Eigen::Vector2d p_t = x_t / (1.0 + t);
  return {Eigen::Vector3d(p_t.x(), p_t.y(), x.z() / (1.0 + t / (rbar * rbar))),
          ProxRegion::kBoundary};
}

}  // namespace nonsmooth_sim
