// The friction sets with rolling resistance and their exact Euclidean proximal points.
//
// Möller, Leine, Glocker (ESMC 2009), section 6, extended by two components: the rolling
// percussion Λ_R = (Λ_R1, Λ_R2) [N m s], the torque about the tangents t1, t2 of the contact
// frame, bounded by μ_r Λ_N with μ_r the rolling-resistance length [m]. The friction vector is
// 5-D, (Λ_T1, Λ_T2, Λ_τ, Λ_R1, Λ_R2). Both sets are iterated in the coordinates Λ̂ = A⁻¹Λ of
// (40)-(47) with A = diag(1, 1, 1, R̄, ρ_r, ρ_r) on (N, T1, T2, τ, R1, R2), ρ_r = μ_r/μ [m]:
//
//   coupled    E_R: (||Λ_T||/ρ)² + (Λ_τ/(R̄ρ))² + (||Λ_R||/(ρ_rρ))² ≤ 1,  ρ = μΛ_N,
//              the 5-D ellipsoid of (55) with two more semi-axes μ_rΛ_N; A⁻¹E_R is the
//              5-ball ||Λ̂_F|| ≤ ρ (as S_F (57)-(58) in 3-D), whose prox is (59) in 5-D.
//   decoupled  E_F × D_R: (55) for (T1, T2, τ) and, on its own, ||Λ_R|| ≤ μ_rΛ_N (the rolling
//              disk of ODE's and Bullet's rolling friction); A⁻¹ maps it onto S_F × the disk
//              ||Λ̂_R|| ≤ ρ, a product whose prox is the pair of prox (59) and the disk's.
//
// Conventions as in force_sets.h: radius = μΛ_N ≥ 0 [N s]; radius ≤ 0 or NaN gives the apex.
#ifndef NONSMOOTH_SIM_CORE_PROX_ROLLING_H_
#define NONSMOOTH_SIM_CORE_PROX_ROLLING_H_

#include <Eigen/Core>

#include "nonsmooth_sim/core/force_sets.h"

namespace nonsmooth_sim {

using Vector5d = Eigen::Matrix<double, 5, 1>;

struct Prox5 {
  Vector5d point;
  ProxRegion region;
};

/// The coupled set in the mapped coordinates: the 5-ball ||x|| ≤ radius, (59) in five dimensions.
Prox5 ProxRollingBall(const Vector5d& x, double radius);

/// The decoupled set in the mapped coordinates: the 3-ball ||(x_T1, x_T2, x_τ)|| ≤ radius (S_F,
/// (58)-(59)) times the disk ||(x_R1, x_R2)|| ≤ radius. Region: kInterior if x is in the set,
/// kApex at radius ≤ 0, kBoundary otherwise (either factor projected).
Prox5 ProxRollingDecoupled(const Vector5d& x, double radius);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_PROX_ROLLING_H_
