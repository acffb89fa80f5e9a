// What a contact remembers across steps, per (collider pair, feature) (ContactKey): the tangent
// frame carried over (contact_frame.h) and the percussions and closing steps its warm start is
// extrapolated from (island_problem.h: WarmStart, and the header comment of simulator.h). A plain
// struct: a stepper that needs more history adds a field here.
#ifndef NONSMOOTH_SIM_CORE_STEP_CONTACT_MEMORY_H_
#define NONSMOOTH_SIM_CORE_STEP_CONTACT_MEMORY_H_

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace nonsmooth_sim {

struct ContactMemory {
  Eigen::Vector3d tangent1 = Eigen::Vector3d::UnitX();  ///< t1 of its last frame, world
  /// Λ^{n-1}, Λ^{n-2}, Λ^{n-3} of its last three solves [N s, N s, N s, N m s]
  Eigen::Vector4d percussion = Eigen::Vector4d::Zero();
  Eigen::Vector4d percussion_before = Eigen::Vector4d::Zero();
  Eigen::Vector4d percussion_before2 = Eigen::Vector4d::Zero();
  double rim_hint = 0.0;     ///< the warm start of B_F's exact prox (ContactWork::rim_hint)
  /// Λ_R of its last solve where it had rolling components [N m s] (its warm start)
  Eigen::Vector2d rolling_percussion = Eigen::Vector2d::Zero();
  long closed_step = -2;     ///< the step it was last closed in
  long closed_before = -3;   ///< the step before that in which it was closed
  long closed_before2 = -4;  ///< and the one before that
  /// The next warm start is extrapolated quadratically, not linearly (RememberSolve).
  bool quadratic_served = false;
  bool sliding = false;    ///< its friction was projected in its last solve
  bool converged = false;  ///< its last solve converged
  /// Integrator::kMoreau2: γ_E = W(q_M)ᵀu_E of the step it was last closed in [m/s, m/s, m/s,
  /// rad/s], and its gap g(q_E) at the end of that step (before the gap correction; +∞ where the
  /// feature was gone) [m]
  Eigen::Vector4d gamma_end = Eigen::Vector4d::Zero();
  double gap_end = std::numeric_limits<double>::infinity();

  /// The warm start of a step `ratio` times as long (a percussion is a force times Δt).
  void ScaleWarmStart(double ratio) {
    percussion *= ratio;
    percussion_before *= ratio;
    percussion_before2 *= ratio;
    rolling_percussion *= ratio;
  }
  /// A warm start that no longer fits (another Δt, law or friction set): start from zero.
  void DropWarmStart() {
    percussion.setZero();
    percussion_before.setZero();
    percussion_before2.setZero();
    rolling_percussion.setZero();
    quadratic_served = false;
  }
};

/// The memories by ContactKey(first, second, feature); a pair's own entry (feature kPairFeature,
/// contact_pipeline.h) records the step the pair last had a closed contact.
using ContactMemoryMap = std::unordered_map<std::uint64_t, ContactMemory>;

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_STEP_CONTACT_MEMORY_H_
