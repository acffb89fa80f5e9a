// Fixed-point solver for the contact inclusion (17) of one time step.
//
// Möller, Leine, Glocker (ESMC 2009), sections 3-5. For every closed contact i the percussion
// Λ_i = (Λ_N, Λ_T1, Λ_T2, Λ_τ) (components present only where the contact models them) satisfies
//
//   ξ_i ∈ N_{D_i}(-Λ_i),   ξ_i = Σ_j G_ij Λ_j + c_i                                   (17)
//
// with the Delassus blocks G_ij = W_iᵀ M⁻¹ W_j and c_i of (16). D_i is the product of the
// unilateral normal set and the friction set of the contact's law, scaled by the current iterate
// of Λ_N (the usual fixed point for Coulomb friction).
//
// Iterations (all on percussions written with C = -D, see force_sets.h):
//  - kJacobi: projected Jacobi. On the original sets (37) for coulomb, cylinder, ellipsoid and
//    exact; on the transformed sets (42)-(43) with Λ̂ = A⁻¹Λ, Ĝ = AᵀGA, ĉ = Aᵀc (41),
//    A = diag(1, 1, 1, R̄) (56), for sphere; r_i = α / max_k G_iikk (43).
//  - kModifiedJacobi: (46): in the non-projecting case each component gets its own step
//    α / G_iikk, in the projecting case the step of (43).
//  - kGaussSeidel: the same equations as kModifiedJacobi, contact by contact, each contact using
//    the already updated percussions of the contacts before it.
//
// Stopping rule (per iteration ν, over all components k of all contacts):
//   converged  ⇔  |Λ_k^{ν+1} - Λ_k^ν| ≤ tolerance_abs + tolerance_rel · |Λ_k^{ν+1}|  for all k.
// The reported residual is max_k |Λ_k^{ν+1} - Λ_k^ν| / (tolerance_abs + tolerance_rel·|Λ_k^{ν+1}|)
// (≤ 1 means converged). Non-convergence is data: the solver returns after max_iterations with
// converged = false and never throws for it.
#ifndef NONSMOOTH_SIM_CORE_CONTACT_SOLVER_H_
#define NONSMOOTH_SIM_CORE_CONTACT_SOLVER_H_

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "nonsmooth_sim/core/force_sets.h"

namespace nonsmooth_sim {

/// The force law of one contact.
struct ContactLaw {
  double mu = 0.3;           ///< friction coefficient, ≥ 0; 0 = frictionless (no tangential part)
  double rbar = 0.0;         ///< average friction radius R̄ = 3πR/16 (50) [m], ≥ 0; 0 = no drilling
  double restitution = 0.0;  ///< Newton's ε (14), in [0, 1]
  FrictionSet friction_set = FrictionSet::kSphere;
};

/// Number of percussion components a contact with this law has: 1 (frictionless), 3 (normal and
/// two tangential: coulomb, or R̄ = 0) or 4 (with the drilling component).
int ContactDimension(const ContactLaw& law);

/// Solver iteration scheme.
enum class SolverType { kJacobi, kModifiedJacobi, kGaussSeidel };
/// "jacobi", "modified_jacobi", "gauss_seidel".
std::string_view SolverTypeName(SolverType type);
std::optional<SolverType> SolverTypeFromName(std::string_view name);
std::string SolverTypeNameList();

struct SolverOptions {
  SolverType type = SolverType::kModifiedJacobi;
  double tolerance_rel = 1e-8;  ///< relative tolerance on the change of Λ, ≥ 0
  double tolerance_abs = 1e-14; ///< absolute tolerance on the change of Λ [N s], ≥ 0
  int max_iterations = 1000;    ///< ≥ 1
  double relaxation = 1.0;      ///< α of (43), in (0, 2)
};

/// Throws std::invalid_argument naming the offending field and its allowed range.
void ValidateSolverOptions(const SolverOptions& options);

/// One closed contact in the problem: its law and where its components start in Λ, c and G.
struct ContactBlock {
  int offset = 0;  ///< index of Λ_N of this contact in the stacked vectors
  ContactLaw law;  ///< dimension = ContactDimension(law)
};

/// The inclusion (17) for the closed contacts of one step. Components of contact i occupy
/// [offset_i, offset_i + dim_i) in order (N, T1, T2, τ).
struct ContactProblem {
  Eigen::MatrixXd G;  ///< Delassus matrix, symmetric positive semi-definite, n × n
  Eigen::VectorXd c;  ///< n
  std::vector<ContactBlock> contacts;
};

struct SolverStatistics {
  int iterations = 0;
  double residual = 0.0;  ///< see the stopping rule above; ≤ 1 when converged
  bool converged = false;
  /// Per contact: whether the last iteration projected its friction components (sliding) and its
  /// normal component (separating, Λ_N clamped to 0).
  std::vector<bool> friction_projected;
  std::vector<bool> normal_projected;
};

/// Solves (17). `lambda` holds the warm start on entry (size n; zeros if unknown) and the
/// solution on return. Allocates only when the problem grows beyond what an earlier call saw:
/// keep one ContactSolver per simulation.
class ContactSolver {
 public:
  SolverStatistics Solve(const ContactProblem& problem, const SolverOptions& options,
                         Eigen::VectorXd* lambda);

 private:
  // workspace reused across calls (transformed Ĝ, ĉ, iterates)
  Eigen::MatrixXd g_hat_;
  Eigen::VectorXd c_hat_, lambda_hat_, lambda_next_, a_diag_;
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_CONTACT_SOLVER_H_
