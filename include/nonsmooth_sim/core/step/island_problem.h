// The contact problem (17) of one island and the impulses (18) it gives: the paper's (16)-(18).
//   G_ij = W_iᵀ M⁻¹ W_j                                        DelassusBlock
//   c_i  = W_iᵀ M⁻¹ h Δt + (1 + ε_i) γ_i^B                     FreeContactVelocity
//   ξ_i ∈ N_{D_i}(-Λ_i), ξ = G Λ + c                           ContactSolver (contact_solver.h)
//   u_E  = u_B + M⁻¹ h Δt + M⁻¹ Σ W_i Λ_i                      AddContactImpulse, ApplyImpulses
// with the warm-start policy (WarmStart; RememberSolve keeps what the next step's start needs, see
// the header comment of simulator.h) and, for GyroscopicScheme::kImplicitMidpoint, the fixed-point
// passes of Euler's equations by the implicit midpoint rule around the solve.
#ifndef NONSMOOTH_SIM_CORE_STEP_ISLAND_PROBLEM_H_
#define NONSMOOTH_SIM_CORE_STEP_ISLAND_PROBLEM_H_

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "nonsmooth_sim/core/contact/contact_jacobian.h"
#include "nonsmooth_sim/core/contact_solver.h"
#include "nonsmooth_sim/core/model.h"
#include "nonsmooth_sim/core/rolling_contact_solver.h"
#include "nonsmooth_sim/core/simulator_options.h"
#include "nonsmooth_sim/core/step/islands.h"
#include "nonsmooth_sim/core/step/step_data.h"

namespace nonsmooth_sim {

/// Most fixed-point passes of the implicit-midpoint gyroscopic scheme around the contact solve.
inline constexpr int kMaxGyroscopicPasses = 6;

// Warm starts extrapolated from a contact's last percussions Λ^{n-1}, Λ^{n-2}, Λ^{n-3}:
// linear 2Λ^{n-1} - Λ^{n-2}, quadratic 3(Λ^{n-1} - Λ^{n-2}) + Λ^{n-3}.
inline Eigen::Vector4d LinearStart(const ContactMemory& m) {
  return 2.0 * m.percussion - m.percussion_before;
}
inline Eigen::Vector4d QuadraticStart(const ContactMemory& m) {
  return 3.0 * (m.percussion - m.percussion_before) + m.percussion_before2;
}

/// The warm start of a contact in step `step`: the previous step's percussion (zero if the contact
/// was open then; the memory is zero beyond the contact's dimension), or, `extrapolating`,
/// extrapolated from the last two or three where its last solve converged.
[[gnu::always_inline]] inline Eigen::Vector4d WarmStart(const ContactMemory& memory, long step,
                                                        bool extrapolating) {
  if (memory.closed_step != step - 1) return Eigen::Vector4d::Zero();
  if (extrapolating && memory.converged && memory.closed_before == step - 2) {
    return memory.quadratic_served ? QuadraticStart(memory) : LinearStart(memory);
  }
  return memory.percussion;
}

/// (16) G_ij = W_iᵀ M⁻¹ W_j over the sides the two contacts share a body on.
[[gnu::always_inline]] inline Eigen::Matrix4d DelassusBlock(const std::vector<BodyInertia>& inertia,
                                                            const ClosedContact& a,
                                                            const ClosedContact& b) {
  Eigen::Matrix4d block = Eigen::Matrix4d::Zero();
  for (const ContactSide& s : a.jacobian.side) {
    if (s.body < 0) continue;
    const BodyInertia& body = inertia[static_cast<std::size_t>(s.body)];
    for (const ContactSide& t : b.jacobian.side) {
      if (t.body != s.body) continue;
      block += &s == &t ? OwnDelassusBlock(body, s)
                        : SideDelassusBlock(body, a.jacobian, s, b.jacobian, t);
    }
  }
  return block;
}

/// (16) G_ij in 6-blocks for an island with rolling contacts (rolling_contact_solver.h):
/// DelassusBlock's 4 × 4 and the rolling rows' parts (RollingDelassusParts) of the contacts with
/// dimension 6; zero where neither has rolling rows.
inline Matrix6d RollingDelassusBlock(const std::vector<BodyInertia>& inertia,
                                     const ClosedContact& a, const ClosedContact& b) {
  Matrix6d block = Matrix6d::Zero();
  block.topLeftCorner<4, 4>() = DelassusBlock(inertia, a, b);
  const bool rolling_a = a.report.dimension == 6;
  const bool rolling_b = b.report.dimension == 6;
  if (!rolling_a && !rolling_b) return block;
  const RollingSide none;
  for (int s = 0; s < 2; ++s) {
    const ContactSide& sa = a.jacobian.side[s];
    if (sa.body < 0) continue;
    for (int t = 0; t < 2; ++t) {
      const ContactSide& tb = b.jacobian.side[t];
      if (tb.body != sa.body) continue;
      RollingDelassusParts(sa, rolling_a ? a.rolling.side[s] : none, tb,
                           rolling_b ? b.rolling.side[t] : none, &block);
    }
  }
  return block;
}

/// γ_R = Σ_sides sign J_R K_ω of a contact with rolling components for the free angular
/// velocities (BodyStep::angular_free) [rad/s]: the rolling rows' part of c_i (16). Restitution
/// does not act on them. kMoreau2 (`state` = u_B, else null): where the contact's friction acts
/// against the midpoint velocity (ClosedContact::friction_midpoint) so does its rolling torque,
/// ξ_R = γ_R,E + γ_R^B, as the sliding components (one normal cone for the coupled set).
inline Eigen::Vector2d RollingFreeVelocity(const std::vector<BodyStep>& body,
                                           const ClosedContact& c,
                                           const std::vector<BodyState>* state = nullptr) {
  const bool midpoint = state != nullptr && c.friction_midpoint;
  Eigen::Vector2d gamma = Eigen::Vector2d::Zero();
  for (int s = 0; s < 2; ++s) {
    const ContactSide& side = c.jacobian.side[s];
    if (side.body < 0) continue;
    const std::size_t b = static_cast<std::size_t>(side.body);
    gamma += side.sign * (c.rolling.side[s].rows * body[b].angular_free);
    if (midpoint) gamma += side.sign * (c.rolling.side[s].rows * (*state)[b].angular_velocity);
  }
  return gamma;
}

/// (18) for the rolling rows: the torque Λ_R1 t1 + Λ_R2 t2 on B and its opposite on A, added
/// to the sides' angular contact sums (in K).
inline void AddRollingImpulse(const ClosedContact& c, const Eigen::Vector2d& rolling,
                              std::vector<BodyStep>* body) {
  for (int s = 0; s < 2; ++s) {
    const ContactSide& side = c.jacobian.side[s];
    if (side.body < 0) continue;
    (*body)[static_cast<std::size_t>(side.body)].angular_contact +=
        side.sign * (c.rolling.side[s].rows.transpose() * rolling);
  }
}

/// (16) c_i = W_iᵀ M⁻¹ h Δt + (1 + ε_i) γ_i^B = W_iᵀ(u_B + M⁻¹hΔt) + ε_i γ_i^B: the contact's
/// velocity without its percussion, from the free velocities of its bodies (BodyStep::linear_free,
/// angular_free) [m/s, m/s, m/s, rad/s].
[[gnu::always_inline]] inline Eigen::Vector4d FreeContactVelocity(const std::vector<BodyStep>& body,
                                                                  const ClosedContact& c) {
  Eigen::Vector4d gamma_free = Eigen::Vector4d::Zero();
  for (const ContactSide& side : c.jacobian.side) {
    if (side.body < 0) continue;
    const BodyStep& w = body[static_cast<std::size_t>(side.body)];
    gamma_free += SideVelocity(c.jacobian, side, w.linear_free, w.angular_free);
  }
  return gamma_free + c.report.law.restitution * c.gamma_begin;
}

/// Integrator::kMoreau2 holds a persistent contact on position level: its normal law acts on
/// γ_N(q_E) + max(g(q_B), -d)/τ, τ = max(kPositionTimeConstant, Δt), so that a gap or a shallow
/// penetration g(q_B) left by the last step decays at the rate 1/τ instead of drifting (the
/// drift is O(Δt²) per unit time, so the term stays O(Δt²) in the velocity). A rate, not a
/// fraction per step: steps of Δt and Δt/2 hold a contact alike (AdaptiveStepper compares them).
/// docs/theory.md.
inline constexpr double kPositionTimeConstant = 2e-3;  // [s]
/// d [m]: the deepest penetration the position term pushes out at its full rate. An impact leaves
/// its contact up to |γ_N|Δt/2 deep; pushed out at g/τ, that would be a bounce; deeper than d,
/// the term pushes at d/τ (5e-6 m/s) and the gap correction lifts what is below its slop (1 µm).
inline constexpr double kPositionHoldDepth = 1e-8;

/// c_i of Integrator::kMoreau2 (docs/theory.md, "The second-order integrator"). A contact that
/// closes in this step (an impact) is Moreau's, FreeContactVelocity. A contact closed in the last
/// step imposes its law on the end velocity W(q_E)ᵀu_E ≈ γ_E + γ^B - γ_B, where W(q_B)ᵀu_B = γ_B
/// is interpolated between this step's W(q_M) (γ^B = W(q_M)ᵀu_B, Δt/2 after q_B) and the last
/// step's (γ_E^{n-1} = W(q_M^{n-1})ᵀu_B, Δt_{n-1}/2 before q_B):
///   γ^B - γ_B = Δt/(Δt + Δt_{n-1}) (γ^B - γ_E^{n-1})            ((γ^B - γ_E^{n-1})/2 for equal steps)
/// plus the position term β g(q_B)/Δt on the normal; a contact whose friction slid in the last
/// step and slides on (ClosedContact::friction_midpoint) has its friction act against the
/// midpoint velocity, ξ_F = γ_E + γ^B (twice (γ_B + γ_E)/2 at q_M). Restitution does not enter a
/// persistent contact.
[[gnu::always_inline]] inline Eigen::Vector4d SecondOrderContactVelocity(
    const std::vector<BodyStep>& body, const ClosedContact& c, double dt, double previous_dt,
    long step) {
  const ContactMemory& memory = *c.memory;
  // closed in the last step, and that step recorded γ_E and g(q_E) (a kMoreau2 step)
  if (memory.closed_step != step - 1 || !(previous_dt > 0.0)) return FreeContactVelocity(body, c);
  Eigen::Vector4d velocity = Eigen::Vector4d::Zero();
  for (const ContactSide& side : c.jacobian.side) {
    if (side.body < 0) continue;
    const BodyStep& w = body[static_cast<std::size_t>(side.body)];
    velocity += SideVelocity(c.jacobian, side, w.linear_free, w.angular_free);
  }
  Eigen::Vector4d shift = (dt / (dt + previous_dt)) * (c.gamma_begin - memory.gamma_end);
  if (c.friction_midpoint) shift.tail<3>() = c.gamma_begin.tail<3>();
  if (std::isfinite(memory.gap_end)) {
    shift(kNormal) += std::max(memory.gap_end, -kPositionHoldDepth) /
                      std::max(kPositionTimeConstant, dt);
  }
  return velocity + shift;
}

/// (18) W_iΛ_i added to the contact sums of its bodies: on a side sign (LᵀΛ, JᵀΛ); Λ is zero
/// beyond the contact's dimension.
[[gnu::always_inline]] inline void AddContactImpulse(const ClosedContact& c,
                                                     const Eigen::Vector4d& percussion,
                                                     std::vector<BodyStep>* body) {
  const Eigen::Vector3d linear = c.jacobian.linear.transpose() * percussion;
  for (const ContactSide& side : c.jacobian.side) {
    if (side.body < 0) continue;
    BodyStep& w = (*body)[static_cast<std::size_t>(side.body)];
    w.linear_contact += side.sign * linear;
    w.angular_contact += side.sign * (side.angular.transpose() * percussion);
  }
}

/// Solves the contact problems of a step's islands, one at a time, and keeps what the next step's
/// warm start needs in the contacts' memories. Holds the solver and the problem's storage (they
/// only grow: a step allocates nothing once every problem size has been seen).
class IslandProblem {
 public:
  /// Island `index` of `islands` (built on data->closed): G, c, the solve (17), ω_E of its bodies
  /// and their impulse sums (18) in data->body, percussions in the contacts' reports and memories;
  /// with data->implicit the implicit-midpoint passes. `state` is q_B, u_B. false if the problem
  /// is not finite (nothing solved).
  bool Solve(const Model& model, const SimulatorOptions& options,
             const std::vector<BodyState>& state, const Islands& islands, std::size_t index,
             StepData* data, StepStatistics* stats) {
    // one contact (a top on the ground) on an explicit step: without the block problem
    const Island& island = islands.islands()[index];
    // an island with a rolling contact: in 6-blocks (rolling_contact_solver.h)
    if (data->any_rolling && HasRollingContact(islands, index, *data)) {
      return SolveBlocks<true>(model, options, state, islands, index, data, stats);
    }
    if (island.contact_count == 1 && !data->implicit) {
      return SolveLoneContact(model, options, static_cast<std::size_t>(islands.contact(island, 0)),
                              data, stats);
    }
    return SolveBlocks<false>(model, options, state, islands, index, data, stats);
  }

 private:
  // an island of one contact on an explicit step: Solve's result without the block problem
  // (ContactSolver::SolveOnePrevalidated)
  bool SolveLoneContact(const Model& model, const SimulatorOptions& options, std::size_t i,
                        StepData* data, StepStatistics* stats);
  // whether island `index` has a contact with rolling components (dimension 6)
  static bool HasRollingContact(const Islands& islands, std::size_t index, const StepData& data);
  // the block problem of the island's m contacts (m × m blocks G_ij), and the implicit passes;
  // kRolling: in 6-blocks, by RollingContactSolver (the island has a rolling contact)
  template <bool kRolling>
  bool SolveBlocks(const Model& model, const SimulatorOptions& options,
                   const std::vector<BodyState>& state, const Islands& islands, std::size_t index,
                   StepData* data, StepStatistics* stats);
  // (18): the contact impulses Σ W_iΛ_i of the island's contacts from lambda_ (kRolling: from
  // rolling_lambda_, the rolling torques too)
  template <bool kRolling>
  void ApplyImpulses(const Islands& islands, std::size_t index, StepData* data) const;
  // what the solve leaves in the contact's report and memory (`alone`: the only contact of its
  // island)
  void RememberSolve(ClosedContact* contact, const Eigen::Vector4d& percussion,
                     bool friction_projected, bool alone, double rim_hint, long step) const;

  ContactSolver solver_;
  // the contact problem of the island being solved, in blocks (contact k of the island is block
  // k), and its percussions; they only grow
  BlockContactProblem problem_;
  std::vector<Eigen::Vector4d> lambda_;
  std::vector<double> rim_hints_;  // with lambda_: the solver's warm start of B_F's prox
  SolverStatistics island_stats_;
  // the same for an island with a rolling contact, in 6-blocks
  RollingContactSolver rolling_solver_;
  RollingBlockProblem rolling_problem_;
  std::vector<Vector6d> rolling_lambda_;
};

/// The bodies without a closed contact on an implicit step: ω_E by the implicit midpoint rule
/// alone, torque-free unless an external torque acts.
void SolveFreeBodiesImplicit(const Model& model, const SimulatorOptions& options,
                             const std::vector<BodyState>& state, const Islands& islands,
                             StepData* data);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_STEP_ISLAND_PROBLEM_H_
