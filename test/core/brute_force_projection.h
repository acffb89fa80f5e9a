// Independent reference projections for the force-set tests.
//
// Nothing here calls the code under test. Each set is described only by
//  - a membership test, and
//  - a parametrisation σ ↦ q(σ) of its boundary,
// both written from the defining formulas of the paper and evaluated in quadruple precision
// (GCC's __float128; sqrt, sin and cos by Newton's method and Taylor series, below). The
// projection of an exterior point is found by minimising the squared distance over the boundary:
// dense sampling of σ, then golden-section refinement around the best sample. For a convex set
// and an exterior point the distance restricted to the first-quadrant part of the boundary has a
// single local minimum, so the refinement finds the global one; it locates the minimum to
// sqrt(quad epsilon) ~ 1e-17 relative, far below the 1e-9 tolerance of the tests.
//
// Rotationally symmetric sets are handled in their meridian half-plane (ρ, z) = (||x_T||, |x_τ|)
// scaled by the radius; the result is lifted back along x_T and with the sign of x_τ.
#ifndef NONSMOOTH_SIM_TEST_CORE_BRUTE_FORCE_PROJECTION_H_
#define NONSMOOTH_SIM_TEST_CORE_BRUTE_FORCE_PROJECTION_H_

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>

namespace nonsmooth_sim::brute_force {

__extension__ typedef __float128 Quad;

// ---------------------------------------------------------------------------------------------
// Quadruple-precision elementary functions (no libquadmath needed).

// π as a double-double (error ~1e-32).
inline Quad QuadPi() { return Quad(3.141592653589793) + Quad(1.2246467991473532e-16); }

inline Quad QuadAbs(Quad x) { return x < 0 ? -x : x; }

inline Quad QuadSqrt(Quad x) {
  if (x <= 0) return 0;
  Quad y = std::sqrt(static_cast<double>(x));
  for (int i = 0; i < 3; ++i) y = 0.5 * (y + x / y);  // 3 Newton steps from 53 bits: > 113 bits
  return y;
}

// Σ_{k ≥ first} (-1)^(k - first) x^(2k+1)/(2k+1)!: first = 0 is sin x, first = 1 is x - sin x
// (without cancellation for small x). For |x| ≤ 4.
inline Quad QuadSinSeries(Quad x, int first) {
  const Quad x2 = x * x;
  Quad term = x;
  for (int k = 1; k <= first; ++k) term *= x2 / Quad((2 * k) * (2 * k + 1));
  Quad sum = 0;
  for (int k = first; k < first + 40; ++k) {
    sum += term;
    term *= -x2 / Quad((2 * k + 2) * (2 * k + 3));
    if (QuadAbs(term) <= Quad(1e-36) * QuadAbs(sum)) break;
  }
  return sum;
}
inline Quad QuadSin(Quad x) { return QuadSinSeries(x, 0); }
inline Quad QuadXMinusSin(Quad x) { return QuadSinSeries(x, 1); }
inline Quad QuadCos(Quad x) {
  const Quad x2 = x * x;
  Quad term = 1;
  Quad sum = 0;
  for (int k = 0; k < 40; ++k) {
    sum += term;
    term *= -x2 / Quad((2 * k + 1) * (2 * k + 2));
    if (QuadAbs(term) <= Quad(1e-36) * QuadAbs(sum)) break;
  }
  return sum;
}

// ---------------------------------------------------------------------------------------------
// Sets described by membership and a boundary parametrisation in the meridian half-plane.

struct QuadPoint {
  Quad rho;
  Quad z;
};

struct MeridianSet {
  std::function<bool(Quad rho, Quad z)> contains;   // membership, rho, z ≥ 0
  std::function<QuadPoint(double sigma)> boundary;  // first-quadrant boundary arc
  double sigma_min;
  double sigma_max;
  int samples;  // dense samples of σ before the golden-section refinement
};

// Minimiser of |q(σ)|² - 2 x·q(σ) (= |x - q|² - |x|², without the cancellation of |x|² for far
// points) over [sigma_min, sigma_max].
inline QuadPoint NearestBoundaryPoint(const MeridianSet& set, Quad rho, Quad z) {
  const auto objective = [&](double sigma) {
    const QuadPoint q = set.boundary(sigma);
    return q.rho * q.rho + q.z * q.z - 2 * (rho * q.rho + z * q.z);
  };
  const double step = (set.sigma_max - set.sigma_min) / set.samples;
  int best = 0;
  Quad best_value = objective(set.sigma_min);
  for (int i = 1; i <= set.samples; ++i) {
    const Quad value = objective(set.sigma_min + i * step);
    if (value < best_value) {
      best_value = value;
      best = i;
    }
  }
  // golden section on the two sample intervals around the best sample
  double a = set.sigma_min + std::max(best - 1, 0) * step;
  double b = set.sigma_min + std::min(best + 1, set.samples) * step;
  const double inv_phi = (std::sqrt(5.0) - 1.0) / 2.0;
  double c = b - inv_phi * (b - a);
  double d = a + inv_phi * (b - a);
  Quad fc = objective(c);
  Quad fd = objective(d);
  for (int i = 0; i < 120 && b - a > 0.0; ++i) {
    if (fc <= fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - inv_phi * (b - a);
      fc = objective(c);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + inv_phi * (b - a);
      fd = objective(d);
    }
  }
  return set.boundary(fc <= fd ? c : d);
}

// Projection of x = (x_T, x_τ) onto the rotationally symmetric set whose meridian cross-section,
// scaled by 1/radius, is `set`.
inline Eigen::Vector3d ProjectRotational(const Eigen::Vector3d& x, double radius,
                                         const MeridianSet& set) {
  const Quad scale = radius;
  const Quad x1 = x.x(), x2 = x.y(), x3 = x.z();
  const Quad rho = QuadSqrt(x1 * x1 + x2 * x2) / scale;
  const Quad z = QuadAbs(x3) / scale;
  if (set.contains(rho, z)) return x;
  const QuadPoint q = NearestBoundaryPoint(set, rho, z);
  const Quad ratio = rho > 0 ? q.rho / rho : Quad(0);
  const Quad z_out = x3 < 0 ? -q.z * scale : q.z * scale;
  return {static_cast<double>(x1 * ratio), static_cast<double>(x2 * ratio),
          static_cast<double>(z_out)};
}

// ---------------------------------------------------------------------------------------------
// The sets, from their definitions. `k` is the drilling half-axis over the tangential one (R̄).

// Ellipse ρ² + (z/k)² = 1 of E_F (55) (k = 1: the ball (58)); boundary (cos θ, k sin θ) with
// θ = (π/4)e^σ for σ ≤ 0 and π/2 - θ = (π/4)e^{-σ} for σ > 0 (both ends resolved on a log scale).
inline MeridianSet EllipseMeridian(double k) {
  const Quad kq = k;
  MeridianSet set;
  set.contains = [kq](Quad rho, Quad z) { return rho * rho + (z / kq) * (z / kq) <= 1; };
  set.boundary = [kq](double sigma) {
    if (sigma <= 0.0) {
      const Quad theta = std::ldexp(std::exp(sigma), -2) * 3.141592653589793;
      return QuadPoint{QuadCos(theta), kq * QuadSin(theta)};
    }
    const Quad phi = std::ldexp(std::exp(-sigma), -2) * 3.141592653589793;
    return QuadPoint{QuadSin(phi), kq * QuadCos(phi)};
  };
  set.sigma_min = -60.0;
  set.sigma_max = 60.0;
  set.samples = 240;
  return set;
}

// Rectangle ρ ≤ 1, z ≤ k of C_F (54): the top edge then the side edge, σ ∈ [0, 2].
inline MeridianSet CylinderMeridian(double k) {
  const Quad kq = k;
  MeridianSet set;
  set.contains = [kq](Quad rho, Quad z) { return rho <= 1 && z <= kq; };
  set.boundary = [kq](double sigma) {
    if (sigma <= 1.0) return QuadPoint{Quad(sigma), kq};
    return QuadPoint{Quad(1), kq * (2 - Quad(sigma))};
  };
  set.sigma_min = 0.0;
  set.sigma_max = 2.0;
  set.samples = 400;
  return set;
}

// The boundary curve (51)-(52) of B_F scaled by 1/(μΛ_N): (β_T(u), k β_τ(u)).
//  u ≤ 1, σ ≤ 0, u = e^σ: the polynomials of (51)-(52).
//  u > 1, σ > 0, θ = asin(1/u) = (π/2)e^{-σ}: with s = sin θ, c = cos θ, D = θ - s c
//    = (2θ - sin 2θ)/2, (51)-(52) read (multiply out to check)
//      β_T = 3/(16 s³) (-D + 4s²θ + 2s³c),
//      β_τ = 1/(4π s⁴) (3D - 8s²θ + 6s³c + 8s⁴θ),
//    and D comes without cancellation from the series of x - sin x. What cancellation remains
//    costs an absolute error ~ u·1e-34 in β_τ, so σ stops at 32 (u ≈ 5e13, error ~1e-20): a foot
//    point beyond it is (1, k·β_τ) with β_τ < 1e-14, represented by σ = 32 to within 1e-14·k.
inline QuadPoint ContensouBoundary(double sigma, Quad k) {
  if (sigma <= 0.0) {
    const Quad u = std::exp(sigma);
    const Quad u2 = u * u;
    const Quad bt = 3 * QuadPi() / 32 * (-u2 * u + 4 * u);
    const Quad btau = (3 * u2 * u2 - 8 * u2 + 8) / 8;
    return {bt, k * btau};
  }
  const Quad theta = std::exp(-sigma) * 1.5707963267948966;
  const Quad s = QuadSin(theta);
  const Quad c = QuadCos(theta);
  const Quad d = QuadXMinusSin(2 * theta) / 2;
  const Quad s2 = s * s;
  const Quad bt = 3 / (16 * s2 * s) * (-d + 4 * s2 * theta + 2 * s2 * s * c);
  const Quad btau = 1 / (4 * QuadPi() * s2 * s2) *
                    (3 * d - 8 * s2 * theta + 6 * s2 * s * c + 8 * s2 * s2 * theta);
  return {bt, k * btau};
}

inline constexpr double kContensouSigmaMin = -60.0;
inline constexpr double kContensouSigmaMax = 32.0;

// Membership in B_F (53): b_T is increasing in u, so for ρ < 1 find u with β_T(u) = ρ by
// bisection and compare z with k β_τ(u).
inline bool ContensouContains(Quad rho, Quad z, Quad k) {
  if (rho >= 1) return rho == 1 && z == 0;
  if (rho == 0) return z <= k;
  double lo = kContensouSigmaMin;
  double hi = kContensouSigmaMax;
  while (true) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    if (ContensouBoundary(mid, k).rho < rho) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  // z against the larger of the two bracketing heights (b_τ decreases with u)
  return z <= ContensouBoundary(lo, k).z;
}

inline MeridianSet ContensouMeridian(double k) {
  const Quad kq = k;
  MeridianSet set;
  set.contains = [kq](Quad rho, Quad z) { return ContensouContains(rho, z, kq); };
  set.boundary = [kq](double sigma) { return ContensouBoundary(sigma, kq); };
  set.sigma_min = kContensouSigmaMin;
  set.sigma_max = kContensouSigmaMax;
  set.samples = 184;
  return set;
}

// ---------------------------------------------------------------------------------------------
// The 3-D reference projections.

inline Eigen::Vector3d ProjectEllipsoid(const Eigen::Vector3d& x, double radius, double rbar) {
  return ProjectRotational(x, radius, EllipseMeridian(rbar));
}
inline Eigen::Vector3d ProjectBall(const Eigen::Vector3d& x, double radius) {
  return ProjectRotational(x, radius, EllipseMeridian(1.0));
}
inline Eigen::Vector3d ProjectCylinder(const Eigen::Vector3d& x, double radius, double rbar) {
  return ProjectRotational(x, radius, CylinderMeridian(rbar));
}
inline Eigen::Vector3d ProjectCoulombContensou(const Eigen::Vector3d& x, double radius,
                                               double rbar) {
  return ProjectRotational(x, radius, ContensouMeridian(rbar));
}

// The disk ||x|| ≤ radius in the plane, by minimising over its boundary circle directly (angle
// ψ ∈ [-π, π], no use of symmetry).
inline Eigen::Vector2d ProjectDisk(const Eigen::Vector2d& x, double radius) {
  const Quad r = radius;
  const Quad x1 = x.x(), x2 = x.y();
  if (x1 * x1 + x2 * x2 <= r * r) return x;
  const auto point = [r](double psi) {
    return QuadPoint{r * QuadCos(psi), r * QuadSin(psi)};  // (cos ψ, sin ψ) as (rho, z)
  };
  MeridianSet circle;
  circle.contains = [](Quad, Quad) { return false; };
  circle.boundary = point;
  circle.sigma_min = -3.141592653589793;
  circle.sigma_max = 3.141592653589793;
  circle.samples = 90;
  const QuadPoint q = NearestBoundaryPoint(circle, x1, x2);
  return {static_cast<double>(q.rho), static_cast<double>(q.z)};
}

// The half-line t ≥ 0, by minimising |x - t| over t ∈ [0, max(1, 2|x|)].
inline double ProjectNonNegative(double x) {
  MeridianSet half_line;
  half_line.contains = [](Quad rho, Quad) { return rho >= 0; };
  const double top = std::max(1.0, 2.0 * std::abs(x));
  half_line.boundary = [](double t) { return QuadPoint{Quad(t), Quad(0)}; };
  half_line.sigma_min = 0.0;
  half_line.sigma_max = top;
  half_line.samples = 100;
  if (x >= 0.0) return x;
  return static_cast<double>(NearestBoundaryPoint(half_line, x, 0).rho);
}

}  // namespace nonsmooth_sim::brute_force

#endif  // NONSMOOTH_SIM_TEST_CORE_BRUTE_FORCE_PROJECTION_H_
