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
// The solver's A is diagonal per contact: ContactMapDiagonal gives its diagonal, TransformBlock is
// the unchecked fixed-size kernel of (41). (The dense maps of (20)-(31) for a general A, which the
// tests check these equations with, are in test/core/dense_transformation.h.)
#ifndef NONSMOOTH_SIM_CORE_TRANSFORMATION_H_
#define NONSMOOTH_SIM_CORE_TRANSFORMATION_H_

#include <Eigen/Core>

#include "nonsmooth_sim/core/friction_law.h"

namespace nonsmooth_sim {

/// Diagonal of A_i over (Λ_N, Λ_T1, Λ_T2, Λ_τ) the solver uses for a contact with this law
/// (the coordinates of its row in the laws table, friction_law.h): (1, 1, 1, R̄), i.e.
/// diag(1, (56)), for a contact with a drilling component (ContactDimension = 4) whose law is
/// mapped (`sphere`: A⁻¹E_F = S_F (57)), or mapped by option and `map_drilling_sets`
/// (SolverOptions; `exact`, `cylinder`: A⁻¹B_F, A⁻¹C_F = the sets with R̄ = 1); all ones
/// otherwise (iterated on the original set, (37)). Entries beyond the contact's dimension are 1.
/// No validation (see ValidateContactProblem). Inline: the solver asks it per contact per step.
inline Eigen::Vector4d ContactMapDiagonal(const ContactLaw& law, bool map_drilling_sets) {
  // without a drilling component every law is the coulomb disk: nothing to map
  if (ContactDimension(law) != 4) return Eigen::Vector4d::Ones();
  const Eigen::Vector4d mapped(1.0, 1.0, 1.0, law.rbar);  // diag(1, A) with A of (56)
  if (LawIs<&FrictionLaw::coordinates, LawCoordinates::kMapped>(law.friction_set)) return mapped;
  if (LawIs<&FrictionLaw::coordinates, LawCoordinates::kMappedByOption>(law.friction_set)) {
    return map_drilling_sets ? mapped : Eigen::Vector4d::Ones();
  }
  return Eigen::Vector4d::Ones();  // LawCoordinates::kOriginal
}

/// One padded block Ĝ_ij = A_iᵀ G_ij A_j for diagonal A_i = diag(a_i), A_j = diag(a_j) (41).
/// Unchecked: the solver's inner kernel.
inline Eigen::Matrix4d TransformBlock(const Eigen::Matrix4d& g_ij, const Eigen::Vector4d& a_i,
                                      const Eigen::Vector4d& a_j) {
  return a_i.asDiagonal() * g_ij * a_j.asDiagonal();
}

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_TRANSFORMATION_H_
