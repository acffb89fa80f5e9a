// The contact inclusion (17) of an island with a rolling contact, in padded 6-blocks.
//
// A contact with rolling components (HasRolling, friction_law.h) has the percussion
// Λ = (Λ_N, Λ_T1, Λ_T2, Λ_τ, Λ_R1, Λ_R2) (prox_rolling.h); the other contacts of its island keep
// their 1, 3 or 4 components, padded to 6. The problem is ContactSolver's (contact_solver.h) with
// 6 × 6 blocks G_ij and it is iterated the same way, in the coordinates Λ̂ = A⁻¹Λ (40)-(47):
// A = diag(1, 1, 1, R̄, μ_r/μ, μ_r/μ) for a rolling contact, ContactMapDiagonal padded with ones
// for the others. Each contact's update is (46): the normal block
//   Λ̂_N ← max(0, Λ̂_N - (α/Ĝ_NN) ξ̂_N),
// then the friction block F (T1, T2[, τ[, R1, R2]]) with the radius μΛ_N of the new Λ_N:
//   z = Λ̂_F - r̂_F ξ̂_F, r̂_F = α / max_{k∈F} Ĝ_kk;   y = Λ̂_F - (α/Ĝ_kk) ξ̂_k per component;
//   Λ̂_F ← y if z and y are in the set, z if z is, prox(z) otherwise,
// with the law's 5-D prox (FrictionLaw::prox5) on a rolling contact and its 3-D prox
// (ProxFrictionLaw) on the others. kGaussSeidel sweeps contact by contact with the updated
// percussions, the Jacobi schemes with the last sweep's (both take (46) per contact).
// Stopping rule: ContactSolver's, in the iterated coordinates,
//   d̂_k ≤ tolerance_abs / a_k + tolerance_rel |Λ̂_k|,  d̂_k = max(|ΔΛ̂_k|, min(s_k|ΔΛ̂_k|, 2ê_k)),
// s_k = 1 for the normal block and an accepted y, σ_k = (α/Ĝ_kk)/r̂_F for a z step, capped by
// q/(1 - q) where the prox acted (q the friction block's contraction estimate); ê_k the set's
// half-width μΛ̂_N (R̄ of the iterated set times that along τ). Without the scaled distance the
// iteration stops while the split between sliding force and rolling torque still creeps along
// the boundary (the coupled sphere: 3e-4 off its deceleration). No direct solve. Residual and
// max_change in the original coordinates as there. This path runs only for islands that hold a
// rolling contact: every other island is ContactSolver's, unchanged.
#ifndef NONSMOOTH_SIM_CORE_ROLLING_CONTACT_SOLVER_H_
#define NONSMOOTH_SIM_CORE_ROLLING_CONTACT_SOLVER_H_

#include <Eigen/Core>
#include <vector>

#include "nonsmooth_sim/core/contact_solver.h"

namespace nonsmooth_sim {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// BlockContactProblem in 6-blocks: contact i has the law `laws[i]` (its dimension
/// ContactDimensionWithRolling), c_i = c[i] and G_ij = G[i·m + j]; entries beyond a contact's
/// dimension are ignored.
struct RollingBlockProblem {
  std::vector<ContactLaw> laws;
  std::vector<Matrix6d> G;  ///< m × m blocks, symmetric
  std::vector<Vector6d> c;
  int size() const { return static_cast<int>(laws.size()); }
  /// m contacts; allocates only when m exceeds every earlier size
  void Resize(int m);
};

/// Diagonal of A_i over (N, T1, T2, τ, R1, R2): (1, 1, 1, R̄, μ_r/μ, μ_r/μ) for a rolling
/// contact, ContactMapDiagonal and ones for the others.
Vector6d RollingMapDiagonal(const ContactLaw& law, bool map_drilling_sets);

class RollingContactSolver {
 public:
  /// Solves (17) for `problem` (valid as ContactSolver::SolvePrevalidated's: G_ii > 0 within the
  /// dimensions, finite). `lambda`: one padded Λ_i per contact, the warm start on entry and the
  /// solution on return. `rim_hints` (optional, size m, in/out) as ContactSolver's.
  void SolvePrevalidated(const RollingBlockProblem& problem, const SolverOptions& options,
                         std::vector<Vector6d>* lambda, SolverStatistics* statistics,
                         std::vector<double>* rim_hints = nullptr);

 private:
  struct Work {
    Vector6d scale = Vector6d::Ones();  // diag(A_i)
    Vector6d step = Vector6d::Zero();   // α / Ĝ_iikk
    Vector6d tolerance_abs_hat = Vector6d::Zero();
    double r_friction = 0.0;  // α / max_{k∈F} Ĝ_iikk
    double mu = 0.0;
    double set_rbar = 0.0;  // R̄ of the iterated 3-D set (ContactWork::set_rbar)
    double rim_hint = 0.0;
    int dim = 1;
    FrictionSet set = kPlanarFrictionSet;
    Vector6d change = Vector6d::Zero();           // |ΔΛ̂| of the last update
    Vector6d previous_change = Vector6d::Zero();  // and of the one before
    bool normal_projected = false;
    bool friction_projected = false;
    bool natural_step = false;  // the last update accepted y
  };
  // d̂_k of the stopping rule for contact `w` at Λ̂ = `lambda` after its last update
  static Vector6d Distance(const Work& w, const Vector6d& lambda);
  // (46) on contact i for ξ̂ = xi from `current`; the new Λ̂_i
  Vector6d Update(Work* w, const Vector6d& current, const Vector6d& xi) const;

  std::vector<Work> work_;
  std::vector<Matrix6d> g_hat_;
  std::vector<Vector6d> c_hat_;
  std::vector<Vector6d> lambda_hat_;
  std::vector<Vector6d> lambda_next_;
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_ROLLING_CONTACT_SOLVER_H_
