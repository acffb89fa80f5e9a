// The Coulomb-Contensou set B_F (51)-(53): its boundary curve and the exact Euclidean projection.
//
// Units. Everything is done on the normalised boundary curve: b_T = s·β_T(u), b_τ = R̄·s·β_τ(u)
// with s = radius = μΛ_N, so that β_T(0) = 0, β_τ(0) = 1, β_T(∞) = 1, β_τ(∞) = 0, and the
// meridian plane (ρ, z) = (||Λ_T||, |Λ_τ|)/s. In that plane the curve is P(u) = (β_T, k·β_τ) with
// k = R̄ (the only shape parameter left).
//
// Facts used (checked by test/core/force_sets_coulomb_contensou_test.cpp):
//  - (51)-(52) join C¹ at u = 1, and with the contact radius R_c = 16R̄/(3π) (50)
//      db_τ/du = -u·R_c·db_T/du  on both branches,
//    so the outward normal of the meridian curve at u is n ∝ (u·R_c, 1).
//  - For u ≥ 2 the closed forms cancel catastrophically (b_T → s, b_τ → 0); with v = 1/u
//      β_T = 1 - Σ_{j≥1} a_j v^{2j},  a_1 = 1/10,  a_{j+1} = a_j (2j-1)(2j+1)/(2(j+1)(2j+5)),
//      π·β_τ = Σ_{j≥0} e_j v^{2j+1},  e_j = (32/3)(j+1) a_{j+1}/(2j+1)  (e_0 = 16/15),
//      u³·dβ_T/du = Σ_{j≥1} 2j·a_j v^{2j-2}  (→ 1/5)
//    (Taylor series of (51)-(52) in v, derived with sympy; they converge for v < 1). The series
//    are used for u ≥ 2, the closed forms as printed for 1 < u < 2; at the switch both are
//    accurate to ~5e-16 relative.
//
// Projection (one branch per region). Let x = (X, Z) be the scaled meridian point, X, Z ≥ 0.
//  - interior quick accept: B_F contains the diamond X + Z/k ≤ 1 and, by convexity, the polygon
//    through a few of its boundary points (shrunk by 1e-15 against rounding).
//  - otherwise the foot-point condition: p = P(u) with x - P(u) ∥ n(u), i.e.
//      H(u) = u R_c (Z - P_z(u)) - (X - P_ρ(u)) = 0,
//    and x is exterior exactly when Z > P_z(u) at a root (the distance along the normal is then
//    positive; for an interior point every root has Z ≤ P_z). H(0) = -X ≤ 0 and H(∞) = +∞, so
//    the sign of H(1) tells whether a root lies on the polynomial branch u ∈ [0, 1] or at u > 1:
//      u ≤ 1: safeguarded Newton on H (a polynomial), bracket [0, 1];
//      u > 1: with v = 1/u, F(v) = -v·H(1/v) = v(X - β_T) - R_c(Z - k β_τ) is convex on [0, 1]
//             (all series coefficients of -vβ_T and β_τ beyond the linear ones are ≥ 0), F(0) ≤ 0
//             < F(1), so its root is unique; Newton is started at an upper bound (the root of
//             the cubic minorant of F) and converges monotonically from the right; a bracket
//             [v_lo, v_hi] guards against rounding. v → 0 is u → ∞ without overflow.
//    The result is the curve point of the last Newton evaluation (its parameter within a few ulps
//    of the root) or, once a Newton step is below 1e-9 of the parameter, that point moved one
//    step on to first order (the neglected terms are O(step²) < 1e-18): most projections save
//    their last evaluation.
//  - on the axes: X = 0 projects to the pole (0, k), Z = 0 to the rim (1, 0).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/core/force_sets.h"

namespace nonsmooth_sim {
namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();
// Newton stops when its step is below this many ulps of the unknown.
constexpr double kStepTolerance = 4.0 * kEpsilon;
// A Newton step below this many units of the unknown is the last: its square is below 1e-18,
// so the curve point one step on is taken to first order (Advance) instead of evaluated.
constexpr double kLinearStepTolerance = 1e-9;
// R_c / R̄ = 16/(3π): db_τ/du = -u·R_c·db_T/du gives dβ_τ/du = -u·(16/(3π))·dβ_T/du.
constexpr double kRcPerRbar = 16.0 / (3.0 * kPi);
// Newton needs 2-5 evaluations typically and ≤ 16 on all tested inputs (R̄ from 1e-4 to 10); the
// cap only bounds a pathological input.
constexpr int kMaxIterations = 100;
// From u = 2 (v ≤ 1/2) on the series replace the closed forms (51)-(52): at u = 2 both are
// accurate to ~5e-16; the closed forms lose ~u² ulps, the series converge like v^{2j}.
constexpr double kSeriesMaxV = 0.5;
// Number of series terms for v ≤ 1/2, 1/3, 1/4, 1/8 and 1/128: the first neglected term is
// < 1e-17 relative there (tests: CoulombContensouBoundary.AgreesWithHighPrecision and
// .BranchesAndSeriesSwitchesAreContinuous). The intermediate tiers only save work: a sliding
// Tippe-Top's projections fall mostly on 1/8 < v ≤ 1/2.
constexpr int kTermsFull = 24;
constexpr int kTermsThird = 16;
constexpr double kThirdMaxV = 1.0 / 3.0;
constexpr int kTermsQuarter = 14;
constexpr double kQuarterMaxV = 0.25;
constexpr int kTermsMid = 10;
constexpr double kMidMaxV = 0.125;
constexpr int kTermsSmall = 5;
constexpr double kSmallMaxV = 1.0 / 128.0;

// ---------------------------------------------------------------------------------------------
// Series coefficients (see the file comment).

struct SeriesCoefficients {
  std::array<double, kTermsFull> a;  // a[i] = a_{i+1}: 1 - β_T = Σ a[i] v^{2i+2}
  std::array<double, kTermsFull> e;  // e[i] = e_i / π: β_τ = Σ e[i] v^{2i+1}
  std::array<double, kTermsFull> d;  // d[i] = 2(i+1) a_{i+1}: u³ dβ_T/du = Σ d[i] v^{2i}
};

constexpr SeriesCoefficients MakeSeriesCoefficients() {
  // a_j for j = 1 .. kTermsFull + 1 (e_j needs a_{j+1}); long double for the recurrence
  std::array<long double, kTermsFull + 1> a_j{};
  a_j[0] = 0.1L;
  for (int j = 1; j <= kTermsFull; ++j) {
    a_j[j] = a_j[j - 1] * static_cast<long double>((2 * j - 1) * (2 * j + 1)) /
             static_cast<long double>(2 * (j + 1) * (2 * j + 5));
  }
  SeriesCoefficients c{};
  for (int i = 0; i < kTermsFull; ++i) {
    c.a[i] = static_cast<double>(a_j[i]);
    c.e[i] = static_cast<double>(32.0L / 3.0L * static_cast<long double>(i + 1) * a_j[i] /
                                 static_cast<long double>(2 * i + 1) /
                                 3.14159265358979323846264338327950288L);
    c.d[i] = static_cast<double>(2.0L * static_cast<long double>(i + 1) * a_j[i]);
  }
  return c;
}

constexpr SeriesCoefficients kSeries = MakeSeriesCoefficients();

// ---------------------------------------------------------------------------------------------
// The normalised boundary curve.

// A point of the curve with u ≥ 1, parametrised by v = 1/u ∈ [0, 1].
struct RimPoint {
  double one_minus_bt;  // 1 - β_T(u)
  double btau;          // β_τ(u) = b_τ/(R̄ s)
  double slope;         // u³·dβ_T/du (tends to 1/5 as u → ∞)
};

// Each series p(w) = Σ c_i w^i is summed as p_even(w²) + w·p_odd(w²): two Horner chains of half
// the length, independent, so the evaluation waits on half as many dependent multiply-adds.
template <int kTerms>
constexpr RimPoint RimSeries(double v) {
  const double w = v * v;
  const double w2 = w * w;
  constexpr int kTopEven = (kTerms - 1) / 2 * 2;
  constexpr int kTopOdd = kTerms / 2 * 2 - 1;
  double a_even = 0.0, e_even = 0.0, d_even = 0.0;
  for (int i = kTopEven; i >= 0; i -= 2) {
    a_even = a_even * w2 + kSeries.a[i];
    e_even = e_even * w2 + kSeries.e[i];
    d_even = d_even * w2 + kSeries.d[i];
  }
  double a_odd = 0.0, e_odd = 0.0, d_odd = 0.0;
  for (int i = kTopOdd; i >= 1; i -= 2) {
    a_odd = a_odd * w2 + kSeries.a[i];
    e_odd = e_odd * w2 + kSeries.e[i];
    d_odd = d_odd * w2 + kSeries.d[i];
  }
  return {(a_even + w * a_odd) * w, (e_even + w * e_odd) * v, d_even + w * d_odd};
}

// (51)-(52) for u = 1/v ∈ [1, 2] as printed, with sqrt(u² - 1)/u = sqrt((1 - v)(1 + v)).
RimPoint RimClosedForm(double v) {
  const double u = 1.0 / v;
  const double u2 = u * u;
  const double arc = std::asin(v);
  const double root = std::sqrt((1.0 - v) * (1.0 + v));  // sqrt(u² - 1)/u
  // (51), u > 1
  const double bt = 3.0 / 16.0 * ((4.0 - u2) * u * arc + (u2 + 2.0) * root);
  // (52), u > 1
  const double btau =
      1.0 / (4.0 * kPi) * ((3.0 * u2 * u2 - 8.0 * u2 + 8.0) * arc + (6.0 - 3.0 * u2) * u * root);
  // d(51)/du = 3/16 ((4 - 3u²) asin(1/u) + (3 - 2/u²) sqrt(u² - 1))
  const double dbt = 3.0 / 16.0 * ((4.0 - 3.0 * u2) * arc + (3.0 - 2.0 * v * v) * u * root);
  return {1.0 - bt, btau, dbt * u2 * u};
}

RimPoint Rim(double v) {
  if (v <= kSmallMaxV) return RimSeries<kTermsSmall>(v);
  if (v <= kMidMaxV) return RimSeries<kTermsMid>(v);
  if (v <= kQuarterMaxV) return RimSeries<kTermsQuarter>(v);
  if (v <= kThirdMaxV) return RimSeries<kTermsThird>(v);
  if (v <= kSeriesMaxV) return RimSeries<kTermsFull>(v);
  return RimClosedForm(v);
}

// A point of the curve with u ∈ [0, 1]: (51)-(52) are polynomials there.
struct CapPoint {
  double bt;     // β_T(u)
  double btau;   // β_τ(u)
  double slope;  // dβ_T/du
};

constexpr CapPoint Cap(double u) {
  const double u2 = u * u;
  // (51), u ≤ 1: 3π/32 (-u³ + 4u)
  const double bt = 3.0 * kPi / 32.0 * u * (4.0 - u2);
  // (52), u ≤ 1: 1/8 (3u⁴ - 8u² + 8)
  const double btau = 1.0 - u2 * (1.0 - 0.375 * u2);
  const double slope = 3.0 * kPi / 32.0 * (4.0 - 3.0 * u2);
  return {bt, btau, slope};
}

// The curve point at v + dv to first order: d(1 - β_T)/dv = v·(u³ dβ_T/du), dβ_τ/dv =
// (16/(3π))·(u³ dβ_T/du).
RimPoint Advance(const RimPoint& p, double v, double dv) {
  return {p.one_minus_bt + dv * v * p.slope, p.btau + dv * kRcPerRbar * p.slope, p.slope};
}

// The curve point at u + du to first order: dβ_τ/du = -u·(16/(3π))·dβ_T/du.
CapPoint Advance(const CapPoint& p, double u, double du) {
  return {p.bt + du * p.slope, p.btau - du * u * kRcPerRbar * p.slope, p.slope};
}

// ---------------------------------------------------------------------------------------------
// Inscribed polygon (quick accept). In the coordinates (X, Y = Z/k) the cross-section does not
// depend on k; its chords between the curve points at these u lie inside (convexity). Chord
// gaps to the curve are ≤ 1% of the axes, so few interior points need the 1-D solve.

struct Vertex {
  double bt, btau;  // (β_T, β_τ)
};
constexpr Vertex CapVertex(double u) { return {Cap(u).bt, Cap(u).btau}; }
constexpr Vertex RimVertex(double v) {
  return {1.0 - RimSeries<kTermsFull>(v).one_minus_bt, RimSeries<kTermsFull>(v).btau};
}

struct Chord {
  double a, b, c;  // a X + b Y ≤ c on the inner side
};

// Curve points at u = 0, 0.2, ..., 1 (polynomials), u = 2, 3, 5, 10 (series) and ∞.
constexpr std::array<Vertex, 11> kPolygonVertices = {
    CapVertex(0.0),       CapVertex(0.2),        CapVertex(0.4),       CapVertex(0.6),
    CapVertex(0.8),       CapVertex(1.0),        RimVertex(1.0 / 2.0), RimVertex(1.0 / 3.0),
    RimVertex(1.0 / 5.0), RimVertex(1.0 / 10.0), Vertex{1.0, 0.0}};
// The vertices are rounded to ~1e-16; pull the chords in by this (relative) margin.
constexpr double kPolygonMargin = 1e-15;

constexpr std::array<Chord, kPolygonVertices.size() - 1> MakePolygonChords() {
  std::array<Chord, kPolygonVertices.size() - 1> chords{};
  for (std::size_t i = 0; i + 1 < kPolygonVertices.size(); ++i) {
    const Vertex& p = kPolygonVertices[i];
    const Vertex& q = kPolygonVertices[i + 1];
    // outward normal of the chord p → q (clockwise from the pole to the rim)
    const double a = p.btau - q.btau;
    const double b = q.bt - p.bt;
    chords[i] = {a, b, (a * p.bt + b * p.btau) * (1.0 - kPolygonMargin)};
  }
  return chords;
}
constexpr auto kPolygonChords = MakePolygonChords();

// (X, Z) inside the polygon, with kx = k·X (no division by k).
bool InPolygon(double kx, double Z, double k) {
  bool inside = true;
  for (const Chord& chord : kPolygonChords) inside &= chord.a * kx + chord.b * Z <= chord.c * k;
  return inside;
}

// ---------------------------------------------------------------------------------------------
// Root finding.

// One evaluation for Newton's method: the function, its slope and the curve point.
template <class Point>
struct NewtonEval {
  double value;
  double slope;
  Point point;
};

// Root of an increasing-through-its-root function fn on [lo, hi] (fn(lo) ≤ 0 ≤ fn(hi)) by
// Newton's method from x, falling back to bisection (geometric when the bracket spans more than
// a factor 2 and lo > 0) whenever a step leaves the bracket. Returns the curve point at (within a
// few ulps of) the root: evaluated there, or one step below kLinearStepTolerance on to first
// order.
template <class Fn>
auto SafeguardedNewton(Fn fn, double lo, double hi, double x) {
  for (int i = 0; i < kMaxIterations; ++i) {
    const auto f = fn(x);
    const double step = f.value / f.slope;
    // converged: the Newton step is below rounding of x (or x is a root)
    if (f.value == 0.0 || std::abs(step) <= kStepTolerance * x) return f.point;
    // the last step, to first order: Newton's error after it is O(step²), below rounding
    if (std::abs(step) <= kLinearStepTolerance * x && x - step > lo && x - step < hi) {
      return Advance(f.point, x, -step);
    }
    if (f.value < 0.0) {
      lo = x;
    } else {
      hi = x;
    }
    x -= step;
    // safeguard: bisect when the step leaves the bracket
    if (!(x > lo && x < hi)) x = (lo > 0.0 && hi > 2.0 * lo) ? std::sqrt(lo * hi) : 0.5 * (lo + hi);
    if (hi - lo <= kStepTolerance * hi) break;
  }
  return fn(x).point;
}

struct MeridianProjection {
  bool interior;
  double rho;  // projected ||Λ_T||/s
  double z;    // projected |Λ_τ|/s
};

// Foot point on the cap u ∈ [0, 1], given H(1) ≥ 0: root of H(u) = u R_c (Z - kβ_τ) - (X - β_T),
// H'(u) = R_c (Z - kβ_τ) + (1 + (u R_c)²) dβ_T/du.
MeridianProjection ProjectOnCap(double X, double Z, double k, double rc) {
  const auto h = [=](double u) {
    const CapPoint p = Cap(u);
    const double gap_z = Z - k * p.btau;
    const double wr = u * rc;
    return NewtonEval<CapPoint>{wr * gap_z - (X - p.bt), rc * gap_z + (1.0 + wr * wr) * p.slope, p};
  };
  // start: H(u) = -X + αu + βu³ - (3/8)R_c k u⁵ with α = R_c(Z - k) + 3π/8 (the slope at 0) and
  // β = R_c k - 3π/32; the tangent root X/α corrected once for the cubic term
  const double alpha = rc * (Z - k) + 3.0 * kPi / 8.0;
  const double beta = rc * k - 3.0 * kPi / 32.0;
  double u0 = 0.5;
  if (alpha > X) {
    const double tangent_root = X / alpha;
    const double corrected = alpha + beta * tangent_root * tangent_root;
    u0 = corrected > X ? X / corrected : tangent_root;
  }
  const CapPoint p = SafeguardedNewton(h, 0.0, 1.0, u0);
  return {Z <= k * p.btau, p.bt, k * p.btau};
}

// Foot point on the rim u ≥ 1, given H(1) < 0: root v = 1/u of the convex
// F(v) = v(X - 1 + (1 - β_T)) - R_c (Z - kβ_τ),  F'(v) = X - β_T + (v² + R_c²)·u³ dβ_T/du.
// `hint` (in/out, may be null): a start for Newton, then the root found.
MeridianProjection ProjectOnRim(double X, double Z, double k, double rc, double* hint) {
  const double xm1 = X - 1.0;
  double last_v = 0.0;
  const auto f = [=, &last_v](double v) {
    const RimPoint p = Rim(v);
    last_v = v;
    const double gap_rho = xm1 + p.one_minus_bt;
    return NewtonEval<RimPoint>{v * gap_rho - rc * (Z - k * p.btau),
                                gap_rho + (v * v + rc * rc) * p.slope, p};
  };
  const double gamma = rc * Z;
  // lower bound: β_τ ≤ (3/8) v and β_T ≥ 0 on [0, 1] give F(v) ≤ v(X + 3R_c k/8) - R_c Z
  const double v_lo = gamma / (X + 0.375 * rc * k);
  if (hint != nullptr && *hint > v_lo && *hint < 1.0) {
    // warm start inside the bracket [v_lo, 1] (F(1) > 0): from the right of the root Newton
    // descends monotonically (F convex); from the left its first step lands right of the root
    // (or is bisected back into the bracket)
    const RimPoint p = SafeguardedNewton(f, v_lo, 1.0, *hint);
    *hint = last_v;
    return {Z <= k * p.btau, 1.0 - p.one_minus_bt, k * p.btau};
  }
  // F ≥ F_m(v) = αv³ + βv - γ (first series terms), so the root of F_m is an upper bound
  const double alpha = kSeries.a[0] + rc * k * kSeries.e[1];
  const double beta = xm1 + rc * k * kSeries.e[0];
  double v_hi;
  if (beta > 0.0) {
    // F_m(γ/β) = α(γ/β)³ ≥ 0 and F_m(cbrt(γ/α)) = β cbrt(γ/α) ≥ 0
    v_hi = gamma / beta;
    if (v_hi > kSmallMaxV) v_hi = std::min(v_hi, std::cbrt(gamma / alpha));
  } else {
    // with b = sqrt(-β/α), c = cbrt(γ/α): α(b + c)³ ≥ α b²(b + c) + α c³ = -β(b + c) + γ
    v_hi = std::sqrt(-beta / alpha) + std::cbrt(gamma / alpha);
  }
  v_hi = std::min(v_hi, 1.0);
  const RimPoint p = SafeguardedNewton(f, v_lo, v_hi, v_hi);
  if (hint != nullptr) *hint = last_v;
  return {Z <= k * p.btau, 1.0 - p.one_minus_bt, k * p.btau};
}

// Projection of the meridian point (X, Z) ≥ 0 onto the normalised cross-section of B_F.
MeridianProjection ProjectMeridian(double X, double Z, double k, double* rim_hint) {
  const double kx = k * X;
  // interior, quick accept: the diamond with vertices (1, 0), (0, k) lies in B_F
  if (kx + Z <= k) return {true, X, Z};
  // boundary, on the drilling axis: the pole (u = 0)
  if (X == 0.0) return {false, 0.0, k};
  // boundary, in the tangential plane: the rim (u = ∞)
  if (Z == 0.0) return {false, 1.0, 0.0};
  // interior, quick accept: the inscribed polygon (inside the cylinder C_F only)
  if (X < 1.0 && Z < k && InPolygon(kx, Z, k)) return {true, X, Z};
  const double rc = k * (16.0 / (3.0 * kPi));
  // H(1) with β_T(1) = 9π/32, β_τ(1) = 3/8
  const double h1 = rc * (Z - 0.375 * k) - (X - 9.0 * kPi / 32.0);
  // interior (every root has Z ≤ P_z) or boundary (the unique root has Z > P_z)
  return h1 >= 0.0 ? ProjectOnCap(X, Z, k, rc) : ProjectOnRim(X, Z, k, rc, rim_hint);
}

}  // namespace

CoulombContensouBoundaryPoint CoulombContensouBoundary(double u, double radius, double rbar) {
  if (!(u >= 0.0)) {
    throw std::invalid_argument("CoulombContensouBoundary: u must be in [0, inf], got " +
                                std::to_string(u));
  }
  if (!(radius >= 0.0) || std::isinf(radius)) {
    throw std::invalid_argument("CoulombContensouBoundary: radius must be finite and >= 0, got " +
                                std::to_string(radius));
  }
  if (!(rbar >= 0.0) || std::isinf(rbar)) {
    throw std::invalid_argument("CoulombContensouBoundary: rbar must be finite and >= 0, got " +
                                std::to_string(rbar));
  }
  if (u <= 1.0) {
    // (51)-(52), u ≤ 1
    const CapPoint p = Cap(u);
    return {radius * p.bt, rbar * radius * p.btau};
  }
  // (51)-(52), u > 1 (series for u ≥ 2; v = 0 at u = ∞)
  const RimPoint p = Rim(1.0 / u);
  return {radius * (1.0 - p.one_minus_bt), rbar * radius * p.btau};
}

Prox3 ProxCoulombContensou(const Eigen::Vector3d& x, double radius, double rbar) {
  return ProxCoulombContensou(x, radius, rbar, nullptr);
}

Prox3 ProxCoulombContensou(const Eigen::Vector3d& x, double radius, double rbar,
                           double* rim_hint) {
  // apex: B_F has shrunk to the point 0
  if (!(radius > 0.0)) return {Eigen::Vector3d::Zero(), ProxRegion::kApex};
  const Eigen::Vector2d x_t = x.head<2>();
  const double rho = x_t.norm();
  // flat limit R̄ = 0: the disk ||Λ_T|| ≤ radius in the plane Λ_τ = 0
  if (!(rbar > 0.0)) return ProxFlatDisk(x, radius);
  // reduce to the meridian plane, scaled by radius
  const double inv_radius = 1.0 / radius;
  const MeridianProjection m =
      ProjectMeridian(rho * inv_radius, std::abs(x.z()) * inv_radius, rbar, rim_hint);
  // interior: x ∈ B_F (53)
  if (m.interior) return {x, ProxRegion::kInterior};
  // boundary: restore the tangential direction (0 on the axis) and the sign of Λ_τ
  const Eigen::Vector2d p_t =
      rho > 0.0 ? Eigen::Vector2d(x_t * (radius * m.rho / rho)) : Eigen::Vector2d::Zero();
  return {Eigen::Vector3d(p_t.x(), p_t.y(), std::copysign(radius * m.z, x.z())),
          ProxRegion::kBoundary};
}

}  // namespace nonsmooth_sim
