// Force sets of the contact laws and their exact Euclidean proximal points.
//
// Möller, Leine, Glocker, "An efficient approximation of orthotropic set-valued force laws of
// normal cone type" (ESMC 2009), section 6. Every function here is the Euclidean projection
// prox_C(x) = argmin_{x* in C} ||x - x*|| (4), (6) onto one convex set C; each is a small pure
// function with one branch per region and reports which region the input was in.
//
// Conventions.
//  - Sets are written for the percussions Λ themselves (Λ_N ≥ 0), i.e. C = -D with the paper's
//    D of (11)/(14). The friction sets are symmetric (C = -C), so prox_D(-x) = -prox_D(x) and the
//    paper's "-Λ = prox_D(-Λ + r ξ)" (36) reads "Λ = prox_C(Λ - r ξ)".
//  - Friction sets are parametrised by `radius` = μ Λ_N ≥ 0 [N s] (the current normal
//    percussion times the friction coefficient). At radius = 0 the set is the point {0}.
//  - 3-D friction vectors are (Λ_T1, Λ_T2, Λ_τ): two tangential percussions [N s] and the
//    drilling percussion [N m s]. `rbar` = R̄ = 3πR/16 (50) is the average friction radius [m];
//    rbar ≤ 0 degenerates every 3-D set to the flat disk ||Λ_T|| ≤ radius, Λ_τ = 0.
//  - The prox functions never throw: radius ≤ 0 or NaN gives the apex.
#ifndef NONSMOOTH_SIM_CORE_FORCE_SETS_H_
#define NONSMOOTH_SIM_CORE_FORCE_SETS_H_

#include <Eigen/Core>
#include <cmath>

namespace nonsmooth_sim {

/// Which part of the set the projected point came from.
enum class ProxRegion {
  kInterior,  ///< x was in the set: prox(x) = x.
  kBoundary,  ///< x was outside: prox(x) lies on the boundary.
  kApex,      ///< the set is (or x maps to) its apex: the single point 0 (radius = 0 or Λ_N < 0).
};

struct Prox1 {
  double point;
  ProxRegion region;
};
struct Prox2 {
  Eigen::Vector2d point;
  ProxRegion region;
};
struct Prox3 {
  Eigen::Vector3d point;
  ProxRegion region;
};

/// Unilateral normal set {Λ_N ≥ 0}: max(x, 0).
Prox1 ProxNonNegative(double x);

/// Planar Coulomb disk {||Λ_T|| ≤ radius}, radius = μΛ_N ≥ 0.
Prox2 ProxDisk(const Eigen::Vector2d& x, double radius);

/// The flat limit R̄ = 0 of the 3-D friction sets: the disk ||Λ_T|| ≤ radius in the plane Λ_τ = 0.
Prox3 ProxFlatDisk(const Eigen::Vector3d& x, double radius);

/// Ball S_F (58): ||Λ_T||² + Λ_τ² ≤ radius², closed form (59).
Prox3 ProxBall(const Eigen::Vector3d& x, double radius);

/// Cylinder C_F (54): ||Λ_T|| ≤ radius, |Λ_τ| ≤ rbar·radius. The product of a disk and an interval,
/// so its projection is the pair of projections.
Prox3 ProxCylinder(const Eigen::Vector3d& x, double radius, double rbar);

/// Ellipsoid E_F (55): (||Λ_T||/radius)² + (Λ_τ/(rbar·radius))² ≤ 1. Exact Euclidean projection:
/// the rotational symmetry reduces it to an ellipse in (||Λ_T||, Λ_τ), whose Lagrange-multiplier
/// equation is solved by a safeguarded Newton iteration. (A radial rescaling is *not* this
/// projection unless rbar = 1.)
Prox3 ProxEllipsoid(const Eigen::Vector3d& x, double radius, double rbar);

/// Coulomb-Contensou set B_F (51)-(53) for a circular contact area with Hertz pressure. Exact
/// Euclidean projection: reduced to 2-D (||Λ_T||, Λ_τ) by rotational symmetry, the nearest point
/// of the boundary curve (b_T(u), b_τ(u)) is found by a safeguarded 1-D solve.
Prox3 ProxCoulombContensou(const Eigen::Vector3d& x, double radius, double rbar);
/// The same, warm-started for a sequence of nearby points (an iterative solver's iterates):
/// `rim_hint` (in/out, not null) holds v = 1/u of the last foot point this overload found on the
/// branch u > 1, or NaN for none. Any value is safe: it only chooses where the 1-D solve starts
/// (the result agrees with the overload above to a few ulps), and a good one saves most of it.
Prox3 ProxCoulombContensou(const Eigen::Vector3d& x, double radius, double rbar,
                           double* rim_hint);

/// A point (b_T(u), b_τ(u)) of the boundary curve of B_F, (51)-(52), u ∈ [0, ∞]; u = +inf gives
/// the limit (radius, 0). Accurate for all u (series expansions where the closed forms cancel).
struct CoulombContensouBoundaryPoint {
  double b_t;    ///< b_T(u) [N s]
  double b_tau;  ///< b_τ(u) [N m s]
};
CoulombContensouBoundaryPoint CoulombContensouBoundary(double u, double radius, double rbar);

// --- inline definitions
inline Prox1 ProxNonNegative(double x) {
  // interior: x ≥ 0 is kept
  if (x >= 0.0) return {x, ProxRegion::kInterior};
  // apex: the set's only boundary point 0
  return {0.0, ProxRegion::kApex};
}

inline Prox2 ProxDisk(const Eigen::Vector2d& x, double radius) {
  // apex: the disk has shrunk to the point 0
  if (!(radius > 0.0)) return {Eigen::Vector2d::Zero(), ProxRegion::kApex};
  const double norm_sq = x.squaredNorm();
  // interior: ||x|| ≤ radius
  if (norm_sq <= radius * radius) return {x, ProxRegion::kInterior};
  // boundary: radial projection (exact for a disk)
  return {x * (radius / std::sqrt(norm_sq)), ProxRegion::kBoundary};
}

inline Prox3 ProxBall(const Eigen::Vector3d& x, double radius) {
  // apex: the ball has shrunk to the point 0
  if (!(radius > 0.0)) return {Eigen::Vector3d::Zero(), ProxRegion::kApex};
  const double norm_sq = x.squaredNorm();
  // interior, first case of (59)
  if (norm_sq <= radius * radius) return {x, ProxRegion::kInterior};
  // boundary, second case of (59): μΛ_N x / ||x||
  return {x * (radius / std::sqrt(norm_sq)), ProxRegion::kBoundary};
}

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_FORCE_SETS_H_
