// The inclusion (17) of one contact whose friction set is a ball up to a diagonal map, solved
// directly: ContactSolver's fallback where the fixed-point iteration (46) does not settle.
//
// Where it is needed: at a drilling stick/slip transition of a mapped contact Ĝ_ττ is ~1e-6 of
// Ĝ_TT, the natural step of (46) along τ leaves the set and is rejected, and the step r̂_F moves
// Λ̂_τ so little per iteration that the iterate creeps (the rattleback's spin reversal: a few
// steps ended at max_iterations, docs/dev-notes.md). The direct solve does not depend on the
// conditioning of Ĝ_FF.
//
// Sets: {Λ_F : ||D⁻¹Λ_F|| ≤ μΛ_N} with D = diag(d_T1, d_T2, d_τ) over the friction components
// (T1, T2[, τ]): S_F in the mapped coordinates (`sphere`, D = I), E_F (55) (`ellipsoid`,
// D = diag(1, 1, R̄)), the Coulomb disk (3-component contacts, D = I on (T1, T2)).
//
// For a fixed normal percussion n = Λ_N the friction row of (17), -ξ_F ∈ N(Λ_F), is the optimality
// condition of
//   Λ_F(n) = argmin { ½ Λᵀ G_FF Λ + (c_F + G_FN n)ᵀ Λ : ||D⁻¹Λ|| ≤ μn }                      (a)
// a trust-region subproblem in x = D⁻¹Λ, solved exactly: the eigen-decomposition of D G_FF D and
// Newton's method on the secular equation 1/||x(λ)|| = 1/ρ from λ = 0 (Moré & Sorensen, 1983;
// monotone, as 1/||x(λ)|| is concave). The normal row of (17) is then the scalar equation
//   n = max(0, -(c_N + G_NF Λ_F(n)) / G_NN)                                                  (b)
// solved on a bracket [0, n_hi] (its right side minus n changes sign there) by the Illinois
// variant of regula falsi. A pair (n, Λ_F(n)) solving (b) solves (17) for the contact, and every
// solution of (17) is one.
#ifndef NONSMOOTH_SIM_CORE_BALL_CONTACT_SOLVE_H_
#define NONSMOOTH_SIM_CORE_BALL_CONTACT_SOLVE_H_

#include <Eigen/Core>

namespace nonsmooth_sim {

/// The direct solve for one contact whose G, dimension, μ and set stay while c changes (a block
/// Gauss-Seidel sweep over several contacts): the eigen-decomposition of D G_FF D once per Reset.
class BallContactSolver {
 public:
  /// G (4 × 4, symmetric positive definite on the first `dim` rows and columns; the rest is
  /// ignored) over (N, T1, T2, τ), `dim` ∈ {1, 3, 4} components, friction coefficient `mu`, the
  /// friction set's diagonal map `friction_metric` = (d_T1, d_T2, d_τ) (all > 0; d_τ unused for
  /// dim 3). False if G's blocks are not positive definite or the metric is not positive (Solve
  /// then fails).
  bool Reset(const Eigen::Matrix4d& G, int dim, double mu, const Eigen::Vector3d& friction_metric);
  /// (17) for this c: on success writes Λ (zero beyond `dim`) and returns true; returns false,
  /// leaving *lambda as it was, after a failed Reset or if no bracket of (b) is found within 2^64
  /// times the frictionless normal percussion (μ too large for the coupling G_NF: (b) then may
  /// have no solution). Deterministic, no allocation, never throws.
  bool Solve(const Eigen::Vector4d& c, Eigen::Vector4d* lambda) const;

 private:
  bool valid_ = false;
  int dim_ = 1;
  double mu_ = 0.0;
  double g_nn_ = 0.0;
  Eigen::Vector3d g_fn_ = Eigen::Vector3d::Zero();      // G_FN, zero-padded
  Eigen::Vector3d metric_ = Eigen::Vector3d::Ones();    // D, padded with 1
  Eigen::Matrix3d eigenvectors_ = Eigen::Matrix3d::Identity();  // of D G_FF D (padded: I)
  Eigen::Vector3d eigenvalues_ = Eigen::Vector3d::Ones();
};

/// Reset and Solve in one call, for one problem.
bool SolveBallContact(const Eigen::Matrix4d& G, const Eigen::Vector4d& c, int dim, double mu,
                      const Eigen::Vector3d& friction_metric, Eigen::Vector4d* lambda);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_BALL_CONTACT_SOLVE_H_
