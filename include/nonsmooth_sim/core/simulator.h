// Moreau midpoint time-stepping of a Scene, (13)-(18) of Möller, Leine, Glocker (ESMC 2009).
//
//   q_M = q_B + Δt/2 F(q_B) u_B                                                        (13)
//   index set I = { i | g_i(q_M) ≤ 0 }                                                 (12)
//   M (u_E - u_B) - h(q_M, u_B) Δt - Σ_{i∈I} W_i Λ_i = 0,  ξ_i ∈ N_{D_i}(-Λ_i)         (14), (17)
//   G_ij = W_iᵀ M⁻¹ W_j,  c_i = W_iᵀ M⁻¹ h Δt + (1 + ε_i) γ_i^B                         (16)
//   u_E = u_B + M⁻¹ h Δt + M⁻¹ Σ W_i Λ_i                                              (18)
//   q_E = q_M + Δt/2 F(q_M) u_E, quaternion renormalised                              (15)
//
// Choices where the paper leaves room (all documented at the code that makes them):
//  - Kinematics (gap, W, contact point) use A(p_M) of the normalised midpoint quaternion p_M; the
//    end quaternion p_E = p_M ⊗ (1, Δt/4 K_ω_E) is normalised after the step (normalising p_M
//    first does not change the normalised p_E, the update is linear in p_M).
//  - Newton's restitution ε_i of a contact applies to all its components, as in (14): the
//    Tippe-Top's reference ε = 0 is "normal and tangential". A contact enters the solve only if it
//    is closed at the midpoint (12); open contacts cost nothing, μ = 0 gives no tangential
//    components, coulomb or R̄ = 0 no drilling component (ContactDimension).
//  - Contacts at q_M: the broad phase (broad_phase.h) proposes pairs of colliders on different
//    bodies (or a body and the static world), the pair function of the scene's collision table
//    (collision_table.h) gives points, normals and gaps; those with g ≤ 0 form the index set. W_i
//    spans one body (against the world) or two (contact_jacobian.h).
//  - Bodies linked by closed contacts form islands; each island is one contact problem (17),
//    solved by ContactSolver on its own (the G_ij of contacts on different islands are zero). A
//    body without a closed contact costs only its free step.
//  - Warm start and tangent frame of a contact are kept per (collider pair, feature): the
//    previous step's percussions of the contacts that were closed then (zero for newly closed
//    ones), the tangents carried over (contact_frame.h). With
//    SimulatorOptions::extrapolate_warm_start the start is extrapolated linearly instead,
//    2Λ^{n-1} - Λ^{n-2}, for a contact closed in the last two steps whose last solve converged
//    (an unconverged iterate's error would be extrapolated too), in an island of one contact or
//    of contacts that all slid in the last step; quadratically, 3(Λ^{n-1} - Λ^{n-2}) + Λ^{n-3},
//    for a contact alone in its island where that would have been the closer start of the last
//    solve, which converged within two iterations (a smooth stretch: the Tippe-Top's 8 s take
//    1.41 iterations per step instead of 2.05, with every event in the same step; without the
//    two-iteration condition the rattleback's reversal, where a slow drilling mode sets in, had
//    57 unconverged steps). Several contacts that stick can share their load in many ways (a
//    face on its points, a squeeze between two feet that roll); a start extrapolated along that
//    freedom is a solution as well, and the shares would drift step by step. The start only
//    chooses where the iteration begins: the result differs within the solver's tolerance.
//    (Falling back to Λ^{n-1} after steps where the extrapolation served worse, an impact, a
//    stick-slip switch, changed nothing measurable on the eight scenes.)
//  - GyroscopicScheme::kImplicitMidpoint replaces the gyroscopic part of h(q_M, u_B) by the
//    implicit midpoint rule Θ(ω_E - ω_B) = -Δt ω_M × Θω_M + Σ J_iᵀΛ_i, ω_M = (ω_B + ω_E)/2
//    (solved by Newton for fixed Λ), with a few fixed-point passes around the contact solve: the
//    gyroscopic impulse of the current ω_E enters c of the next pass (warm-started), until ω_E
//    changes by less than the solver's relative tolerance (or round-off), at most
//    kMaxGyroscopicPasses passes. Torque-free it conserves ½ωᵀΘω and |Θω| to round-off.
//    GyroscopicScheme::kAuto takes it for the steps in which some body has Δt·|ω_B| above
//    kExplicitGyroscopicMaxDtOmega, and the paper's explicit term for the others.
//
// Properties of the scheme worth knowing (measured on the Tippe-Top, see docs/simulate.md):
//  - It is velocity-level: (14) constrains γ_N at the end of the step, not g. A contact point that
//    moves over a curved surface (rolling, precessing) drifts into the floor by about
//    ½Δt²·(dW/dt)ᵀu per step, linearly in time: up to 0.22 mm on the peg after 8 s at Δt = 1e-4,
//    0.08 mm at 5e-5; a top rocking for 1 h at Δt = 1e-3 sinks 2.9 mm. A body at rest does not
//    drift. SimulatorOptions::gap_correction (on by default) bounds it by a position projection
//    after (15) that is not part of the paper's scheme (see there); off, the scheme is the paper's.
//  - A step that meets a non-finite value (the explicit gyroscopic term far outside its safe range
//    blows up) is not taken: StepStatistics::state_finite = false, state and time stay at the last
//    finite step, and the simulator stays stopped until SetState(). It never throws for that.
//    The end state's energy overflowing counts as non-finite; the gap correction, after that
//    check, is undone where it makes anything non-finite (StepStatistics::gap_correction_undone).
//  - The index set (12) uses g ≤ 0, and g ≤ kContactHysteresis (1 nm) for a contact that was
//    closed in the last step: a body resting at round-off-level positive gaps stays carried.
//  - With the explicit gyroscopic term, a step without contact gains ½Δt²·aᵀΘa; with contact,
//    friction dissipates far more. With kImplicitMidpoint the Tippe-Top's largest per-step energy
//    increase is round-off (3.5e-18 J).
//
// Step() allocates nothing once the largest problem it meets has been seen once (one contact
// problem whose storage only grows, BlockContactProblem::Resize).
//
// The step is an orchestration of stages over (Model, StepData), each in its own file pair under
// core/step/: moreau_kinematics (13), (14), (18), (15); contact_pipeline (12) and W; islands;
// island_problem (16), (17); position_projection (the gap correction after (15)).
#ifndef NONSMOOTH_SIM_CORE_SIMULATOR_H_
#define NONSMOOTH_SIM_CORE_SIMULATOR_H_

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "nonsmooth_sim/core/contact_solver.h"
#include "nonsmooth_sim/core/model.h"
#include "nonsmooth_sim/core/rigid_body_dynamics.h"
#include "nonsmooth_sim/core/scene.h"
#include "nonsmooth_sim/core/simulator_options.h"
#include "nonsmooth_sim/core/step/contact_pipeline.h"
#include "nonsmooth_sim/core/step/island_problem.h"
#include "nonsmooth_sim/core/step/islands.h"
#include "nonsmooth_sim/core/step/position_projection.h"
#include "nonsmooth_sim/core/step/step_data.h"
#include "nonsmooth_sim/core/step/step_report.h"

namespace nonsmooth_sim {

class Simulator {
 public:
  /// Validates scene and options (std::invalid_argument; also a start whose energy overflows, as
  /// SetState); starts from scene.initial_state at t=0.
  Simulator(Scene scene, SimulatorOptions options);

  /// Advances by one time step (not after a non-finite step: see StepStatistics::state_finite).
  StepStatistics Step();
  /// The same, filling `stats` in place (all fields overwritten): with one StepStatistics reused
  /// across steps, a step allocates nothing once its problem sizes and pairs have been seen.
  void Step(StepStatistics* stats);

  double time() const { return time_; }
  /// A step met a non-finite value; Step() does nothing until SetState().
  bool diverged() const { return diverged_; }
  const Scene& scene() const { return model_.scene; }
  const SimulatorOptions& options() const { return options_; }
  const std::vector<BodyState>& state() const { return state_; }
  /// The closed contacts of the last step, ordered by collider pair and feature.
  const std::vector<ContactState>& contacts() const { return contacts_; }
  /// The first closed contact of the last step that involves collider `collider`, or nullptr.
  const ContactState* FindContact(int collider) const;
  /// Whether collider `collider` had a closed contact in the last step.
  bool InContact(int collider) const { return FindContact(collider) != nullptr; }

  /// Replaces the state (validated; quaternions normalised) and clears the warm start, the contact
  /// report and diverged(). Throws std::invalid_argument and leaves everything unchanged on bad
  /// input: a non-finite value, a zero quaternion, or a state whose Energy() would overflow (a
  /// term ½m|v_S|², ½ωᵀΘω, -m g·r_S, their sum, |v_S|² or |ω|²; the message names the field and
  /// its bound). Any other finite state is accepted, far beyond the starts' bounds too.
  void SetState(const std::vector<BodyState>& state);
  /// Replaces the states of the bodies `bodies` (no repeats) by `states` (one each; validated,
  /// quaternions normalised, energy bounded as in SetState) and forgets only their contacts (warm
  /// starts, tangent frames, report): every other body steps on exactly as if nothing had been
  /// set. Clears diverged().
  /// Throws std::out_of_range or std::invalid_argument and changes nothing on bad input.
  void SetBodyStates(const std::vector<int>& bodies, const std::vector<BodyState>& states);
  void SetTime(double time);
  /// Validated like the constructor; throws and changes nothing on bad input.
  void SetOptions(const SimulatorOptions& options);
  /// The time step alone (validated as in SetOptions), between two steps. Unlike SetOptions, the
  /// contacts' warm starts are kept, scaled by the ratio (a percussion is a force times Δt): for
  /// a stepper that changes Δt every step (AdaptiveStepper).
  void SetTimeStep(double time_step);

  /// Everything a step changes, and the time step: state, time, diverged(), the contacts' memory
  /// (its warm starts are for that time step) and report. Restore
  /// needs the same world (no AddBodies / RemoveBodies in between). Once a checkpoint has held as
  /// many contacts as the simulator has, Save allocates nothing (the copies reuse its storage).
  struct Checkpoint {
    std::vector<BodyState> state;
    double time = 0.0;
    bool diverged = false;
    std::vector<ContactState> contacts;
    ContactMemoryMap memory;
    long step = 0;
    double previous_time_step = 0.0;
    double time_step = 0.0;
  };
  void Save(Checkpoint* checkpoint) const;
  /// Back to a saved checkpoint; throws std::invalid_argument (nothing changed) if it is of a
  /// world with another number of bodies.
  void Restore(const Checkpoint& checkpoint);
  /// Switches the friction set of every contact (name empty), of every contact of one collider
  /// (name = a collider's name) or of one contact (name = ContactName, "<first>/<second>"). The
  /// state is kept, every contact's warm start dropped (a changed one would start outside its
  /// set). Throws std::invalid_argument for an unknown name or set, changing nothing.
  void SetFrictionSet(FrictionSet set, const std::string& name = "");
  /// The friction set a contact named `name` ("<first>/<second>") would use.
  FrictionSet FrictionSetOf(const std::string& name) const;
  /// Replaces one collider's law (validated; throws std::invalid_argument / std::out_of_range).
  void SetContactLaw(int collider, const ContactLaw& law);

  double Energy() const { return MechanicalEnergy(model_.scene, state_); }

  // --- the world changed between two steps (simulator_world.cpp)

  /// Appends the bodies and colliders of `model` (its colliders' `body` index model.bodies, or
  /// kWorld for static ones) with the start states `state` (one per model body), between two
  /// steps. The bodies already there keep their state, warm starts and tangent frames. The merged
  /// scene is validated like the constructor's (unique names, ranges; also a non-empty body name
  /// must not be in use; a state whose energy overflows, as SetState): throws
  /// std::invalid_argument and changes nothing on bad input. The
  /// model's initial_state and gravity are not used. Returns the index of the first new body (the
  /// new bodies are scene().bodies[first ...], the new colliders appended in order).
  int AddBodies(const Scene& model, const std::vector<BodyState>& state);
  /// Removes the bodies `bodies` (indices into scene(), any order, no repeats) and the colliders
  /// on them, and `colliders` (indices of static colliders, e.g. a model's fixed links), between
  /// two steps. The rest keep their state, their contacts' warm starts, tangent frames and friction
  /// sets (re-indexed, the order of the remaining bodies and colliders kept): from this step on
  /// they move exactly as in a world that never had what was removed. Throws std::out_of_range and
  /// changes nothing for a bad index (std::invalid_argument for a repeated index or a collider in
  /// `colliders` that is on a body). Removing every body is allowed (an empty world steps).
  void RemoveBodies(const std::vector<int>& bodies, const std::vector<int>& colliders = {});
  /// An external force (world axes, through the centre of mass) [N] and torque (world axes) [N m]
  /// on body `body`, constant over every following step until changed: it enters h in (14)
  /// with gravity (the torque turned into body axes by A(p_M), at the midpoint q_M where (14)
  /// evaluates h: second order with kImplicitMidpoint, where A(p_B) is first order). Zero by
  /// default; a zero wrench is none (the step is the one without). Throws std::out_of_range for
  /// a bad body, std::invalid_argument for a non-finite value (nothing changed).
  void SetExternalWrench(int body, const Eigen::Vector3d& force, const Eigen::Vector3d& torque);
  /// The external wrench of `body`: (force, torque), world axes.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> ExternalWrench(int body) const;

 private:
  void Initialize();
  // the arrays derived from the scene (Model::BuildCaches) and the step's workspace sizes: by
  // Initialize and after AddBodies / RemoveBodies; keeps the warm-start memory, the contact
  // report and the wrenches
  void BuildCaches();
  // Throws std::invalid_argument (naming the body, the field and its allowed range) unless the
  // mechanical energy of `state` in `scene` (MechanicalEnergy) and each of its terms are finite:
  // the constructor, AddBodies, SetState and SetBodyStates, after ValidateState.
  static void RequireFiniteEnergy(const Scene& scene, const std::vector<BodyState>& state);

  Model model_;  // changed only by the setters and world changes, between two steps
  SimulatorOptions options_;
  std::vector<BodyState> state_;
  double time_ = 0.0;
  bool diverged_ = false;
  std::vector<ContactState> contacts_;  // the report of the last step
  StepData data_;
  // the stages and their workspaces
  ContactPipeline contact_pipeline_;
  Islands islands_;
  IslandProblem island_problem_;
  PositionProjection position_projection_;
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_SIMULATOR_H_
