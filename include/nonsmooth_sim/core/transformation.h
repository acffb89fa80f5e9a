// Linear maps of normal cone inclusions and of the contact problem.
//
// Möller, Leine, Glocker (ESMC 2009), sections 4 and 5. For a non-singular A ∈ ℝ^{n×n}:
//
//   A⁻¹C = { y | Ay ∈ C }                                                            (19)
//   N_C(x) = A⁻ᵀ N_{A⁻¹C}(A⁻¹x),  i.e.  y ∈ N_C(x) ⇔ Aᵀy ∈ N_{A⁻¹C}(A⁻¹x)          (20), (25)
//   prox^R_C(x) = A prox^{AᵀRA}_{A⁻¹C}(A⁻¹x)                                         (23)
//   prox^R_C(x + R⁻¹y) = A prox^{R̂}_{A⁻¹C}(A⁻¹x + R̂⁻¹Aᵀy)  for  R = A⁻ᵀR̂A⁻¹          (29), (31)
//
// so points map with A⁻¹, normal-cone elements (velocities) with Aᵀ, and norms with Aᵀ(·)A.
// On the contact problem (34) with one A_i per contact (A = diag(A_1, ..., A_m)):
//
//   ξ̂_i = A_iᵀξ_i,  Λ̂_i = A_i⁻¹Λ_i,  Ĝ_ij = A_iᵀ G_ij A_j,  ĉ_i = A_iᵀ c_i               (41)
//   Λ_i = A_iΛ̂_i                                                                     (47)
//
// For Coulomb-Contensou friction, A = diag(1, 1, R̄) (56) on (Λ_T1, Λ_T2, Λ_τ) maps the ball
// S_F (58) onto the ellipsoid E_F (55): A⁻¹E_F = S_F (57). The same A maps the Coulomb-Contensou
// set B_F (51)-(53) and the cylinder C_F (54) onto themselves with R̄ = 1 (both scale linearly
// along the drilling axis). On a whole contact (Λ_N, Λ_T1, Λ_T2, Λ_τ) it is diag(1, 1, 1, R̄): the
// normal component is not mapped.
//
// The dense functions take a general non-singular A (cost O(n³) where an inverse is needed); the
// *Diagonal functions take the diagonal of a diagonal A (cost O(n²)); TransformBlock is the
// unchecked fixed-size kernel the solver uses.
#ifndef NONSMOOTH_SIM_CORE_TRANSFORMATION_H_
#define NONSMOOTH_SIM_CORE_TRANSFORMATION_H_

#include <Eigen/Core>

#include "nonsmooth_sim/core/contact_solver.h"

namespace nonsmooth_sim {

/// A of (56) on (Λ_T1, Λ_T2, Λ_τ): diag(1, 1, R̄), with A⁻¹E_F = S_F (57).
/// Throws std::invalid_argument unless rbar is finite and > 0 [m].
Eigen::Matrix3d ContensouMap(double rbar);

/// Diagonal of A_i over (Λ_N, Λ_T1, Λ_T2, Λ_τ) the solver uses for a contact with this law and
/// these options (contact_solver.h, table of the iterated sets): (1, 1, 1, R̄), i.e. diag(1, (56)),
/// for a contact with a drilling component (ContactDimension = 4) whose law is `sphere`
/// (A⁻¹E_F = S_F (57)), or `exact` / `cylinder` with options.map_drilling_sets (A⁻¹B_F, A⁻¹C_F
/// = the sets with R̄ = 1); all ones otherwise (iterated on the original set, (37)). Entries
/// beyond the contact's dimension are 1. No validation (see ValidateContactProblem). Inline: the
/// solver asks it per contact per step.
inline Eigen::Vector4d ContactMapDiagonal(const ContactLaw& law, const SolverOptions& options) {
  // without a drilling component every law is the coulomb disk: nothing to map
  if (ContactDimension(law) != 4) return Eigen::Vector4d::Ones();
  const Eigen::Vector4d mapped(1.0, 1.0, 1.0, law.rbar);  // diag(1, A) with A of (56)
  switch (law.friction_set) {
    case FrictionSet::kSphere: return mapped;  // A⁻¹E_F = S_F (57)
    case FrictionSet::kExact:                  // A⁻¹B_F = B_F with R̄ = 1, (40)-(47)
    case FrictionSet::kCylinder:               // A⁻¹C_F = C_F with R̄ = 1, (40)-(47)
      return options.map_drilling_sets ? mapped : Eigen::Vector4d::Ones();
    case FrictionSet::kEllipsoid:  // E_F itself, the paper's untransformed reference (37)
    case FrictionSet::kCoulomb: break;
  }
  return Eigen::Vector4d::Ones();
}

/// The paper's choice, section 6: only the `sphere` law is mapped, every other law is iterated on
/// its original set. The same as ContactMapDiagonal(law, options) with
/// options.map_drilling_sets = false; NOT what the solver does with the default SolverOptions.
Eigen::Vector4d ContactMapDiagonal(const ContactLaw& law);

/// Stacked diagonal (size n) of the block-diagonal A = diag(A_1, ..., A_m) of a problem, each
/// block from ContactMapDiagonal(law, options). Throws std::invalid_argument for an invalid
/// problem.
Eigen::VectorXd ProblemMapDiagonal(const ContactProblem& problem, const SolverOptions& options);

/// The same with the one-argument ContactMapDiagonal (only `sphere` mapped).
Eigen::VectorXd ProblemMapDiagonal(const ContactProblem& problem);

// ---- general non-singular A (n × n) -------------------------------------------------------------
// All throw std::invalid_argument naming the argument for mismatched sizes, and for a singular A
// where A⁻¹ is needed.

/// Ĝ = AᵀGA (41); blockwise Ĝ_ij = A_iᵀ G_ij A_j for a block-diagonal A.
Eigen::MatrixXd TransformDelassus(const Eigen::MatrixXd& g, const Eigen::MatrixXd& a);
/// ξ̂ = Aᵀξ, ĉ = Aᵀc (41): the map of normal-cone elements y ↦ Aᵀy of (25).
Eigen::VectorXd TransformVelocity(const Eigen::MatrixXd& a, const Eigen::VectorXd& xi);
/// Λ̂ = A⁻¹Λ (41): the map of points x ↦ A⁻¹x of (20), (25).
Eigen::VectorXd TransformPercussion(const Eigen::MatrixXd& a, const Eigen::VectorXd& lambda);
/// Λ = AΛ̂ (47).
Eigen::VectorXd RestorePercussion(const Eigen::MatrixXd& a, const Eigen::VectorXd& lambda_hat);
/// R = A⁻ᵀR̂A⁻¹ (29): with it, (31) holds.
Eigen::MatrixXd MetricOnOriginal(const Eigen::MatrixXd& a, const Eigen::MatrixXd& r_hat);
/// AᵀRA: the norm of the prox on A⁻¹C in (23), (28) and (38).
Eigen::MatrixXd MetricOnTransformed(const Eigen::MatrixXd& a, const Eigen::MatrixXd& r);

// ---- diagonal A, given by its diagonal `a` (entries finite and non-zero) --------------------------

/// Ĝ = diag(a) G diag(a) (41).
Eigen::MatrixXd TransformDelassusDiagonal(const Eigen::MatrixXd& g, const Eigen::VectorXd& a);
/// ξ̂ = diag(a) ξ (41).
Eigen::VectorXd TransformVelocityDiagonal(const Eigen::VectorXd& a, const Eigen::VectorXd& xi);
/// Λ̂ = diag(a)⁻¹ Λ (41).
Eigen::VectorXd TransformPercussionDiagonal(const Eigen::VectorXd& a,
                                            const Eigen::VectorXd& lambda);
/// Λ = diag(a) Λ̂ (47).
Eigen::VectorXd RestorePercussionDiagonal(const Eigen::VectorXd& a,
                                          const Eigen::VectorXd& lambda_hat);

/// One padded block Ĝ_ij = A_iᵀ G_ij A_j for diagonal A_i = diag(a_i), A_j = diag(a_j) (41).
/// Unchecked: the solver's inner kernel.
inline Eigen::Matrix4d TransformBlock(const Eigen::Matrix4d& g_ij, const Eigen::Vector4d& a_i,
                                      const Eigen::Vector4d& a_j) {
  return a_i.asDiagonal() * g_ij * a_j.asDiagonal();
}

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_TRANSFORMATION_H_
