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
//    bodies (or a body and the static world), the pair function of the collision table
//    (collision.h) gives points, normals and gaps; those with g ≤ 0 form the index set. W_i
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
// Step() allocates nothing once every problem size n it meets has been seen once (the contact
// problems are kept per size n; Eigen resizes would reallocate otherwise).
#ifndef NONSMOOTH_SIM_CORE_SIMULATOR_H_
#define NONSMOOTH_SIM_CORE_SIMULATOR_H_

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <unordered_map>
#include <string_view>
#include <utility>
#include <vector>

#include "nonsmooth_sim/core/collision/broad_phase.h"
#include "nonsmooth_sim/core/collision/collision.h"
#include "nonsmooth_sim/core/contact/contact_jacobian.h"
#include "nonsmooth_sim/core/contact_solver.h"
#include "nonsmooth_sim/core/rigid_body_dynamics.h"
#include "nonsmooth_sim/core/scene.h"

namespace nonsmooth_sim {

/// How the gyroscopic term -ω × Θω enters h in (14).
enum class GyroscopicScheme {
  kExplicit,         ///< "explicit": the paper's h(q_M, u_B); adds ½Δt²·aᵀΘa per step
  kImplicitMidpoint, ///< "implicit_midpoint": Euler's equations by the implicit midpoint rule,
                     ///< a few fixed-point passes around the contact solve; conserves ½ωᵀΘω, |L|
  kAuto,             ///< "auto": per step, kExplicit while Δt·|ω_B| ≤ kExplicitGyroscopicMaxDtOmega
                     ///< for every body, kImplicitMidpoint for a step where a body exceeds it (a
                     ///< run that stays below is bit-identical to kExplicit)
};
std::string_view GyroscopicSchemeName(GyroscopicScheme scheme);
std::optional<GyroscopicScheme> GyroscopicSchemeFromName(std::string_view name);

/// Penetration a closed contact may keep before gap_correction lifts its body [m]. Far below every
/// geometric scale of the scenes (Tippe-Top: contact radius R = 0.5 mm, peg radius 5 mm; block
/// and disc feet 10 mm) and far above the per-step O(Δt²) drift of a rolling contact (measured at
/// most 1.6e-9 m per step for the top rocking at Δt = 1e-3, less at smaller Δt): a body at rest
/// never sinks to it and a short rolling phase rarely does (the rocking top needs ~1.3 s), while a
/// contact that keeps rolling is then held at -kGapCorrectionSlop by lifts of the size of that
/// per-step drift (nearly every step).
inline constexpr double kGapCorrectionSlop = 1e-6;

/// Projected Gauss-Seidel sweeps of the levelling of a body on several points of one static
/// collider (SimulatorOptions::gap_correction): at most 8 points with a diagonal-dominant
/// Delassus matrix; 30 sweeps bring a 10 µm tilt to the slop within 1e-12 m (measured on a box
/// on four corners and a capsule on its two ends).
inline constexpr int kLevellingSweeps = 30;

/// A contact closed in the last step stays in the index set (12) up to this positive gap [m]. A
/// body resting on a flat face or several corners sits at g = 0 up to round-off; without it the
/// contacts of such a face open for single steps at gaps of 1e-18 m and the body falls freely
/// for a step (a hop of g Δt). A contact that separates has Λ = 0 whether it is in the index set
/// or not (no adhesion; its friction bound μΛ_N is 0), so this changes nothing but the catching
/// of a body that comes back within 1 nm of where it left: far below every scale of the scenes.
/// The broad phase has no such margin: a sphere on a plane (its bounding sphere is the shape) keeps
/// g ≤ 0 exactly. Widening it by the hysteresis changed the Tippe-Top's θ(t) by up to 1.2e-5 rad
/// (a contact kept closed at a positive gap stops the gap correction's lift of the other sphere),
/// so the margin is left to the bodies with faces and corners, where it was needed.
inline constexpr double kContactHysteresis = 1e-9;

/// Δt·|ω| up to which the explicit gyroscopic term is considered safe (StepStatistics::
/// explicit_gyroscopic_unsafe). Measured on the Tippe-Top: runs with Δt·|ω| ≤ 0.18 never gained
/// energy, from 0.2 they gain, from 0.4-0.5 they blow up (non-finite state); 0.1 keeps a margin.
inline constexpr double kExplicitGyroscopicMaxDtOmega = 0.1;

/// Upper bound of SolverOptions::max_iterations in a simulation, where the cap multiplies the work
/// of every step (per island, and per gyroscopic pass with kImplicitMidpoint). It bounds a step at
/// 1e5 iterations of each island: 4.4 ms for the Tippe-Top on one contact (Gauss-Seidel, Release,
/// an idle core; 8-17 ms with the 2 cores shared; bounded_work_test prints it, 2026-12-02; the
/// contacts of an island cost O(n²) per iteration). 1e5 is the cap the converged references of the
/// trade study use (scripts/tradeoff, tolerance 1e-12, also on the slow `ellipsoid` set) and the
/// tightest Simulator tests (dynamics_test, tippe_top_test); the default is 1000.
/// ValidateSimulatorOptions checks it, and with it `simulate` and the node (parameters and
/// ~set_solver_properties).
inline constexpr int kMaxSimulatorIterations = 100000;

struct SimulatorOptions {
  double time_step = 1e-4;  ///< Δt [s], in [1e-7, 1e-2]
  /// solver.max_iterations in [1, kMaxSimulatorIterations], solver.relaxation in
  /// [kMinRelaxation, 2) (ValidateSolverOptions, contact_solver.h)
  SolverOptions solver;
  GyroscopicScheme gyroscopic = GyroscopicScheme::kExplicit;
  /// After (15), the closed contacts (12) are evaluated again at q_E (same pair, same feature).
  /// Per body and static collider it touches (a contact with the world), and per pair of bodies:
  /// if all closed contacts of that group end below -kGapCorrectionSlop, the body is translated
  /// along the group's normal until the highest of them is at -kGapCorrectionSlop (for a pair of
  /// bodies the two share the translation in inverse proportion to their masses, so that the
  /// centre of mass of the pair stays). Velocities are kept. A lift never opens a contact that
  /// carried the body (lifting by the deepest of several would, and feed a rocking limit cycle).
  /// A body resting on several points of one static collider (a face lying flat, box corners, a
  /// capsule on its side) is levelled instead: the smallest rigid displacement, translation and
  /// rotation about S in the metric of M, that brings every one of those points to ≥ -slop
  /// (LevelOnPoints; otherwise a multi-point rest keeps a corner microns deep for ever). A body
  /// buried there (its highest point deeper than its collider's bounding diameter, e.g. a die
  /// reset 10 m under the ground) is first lifted straight along the normal until that point is at
  /// -kGapCorrectionSlop, and only the rest is levelled: a level body stays level.
  /// A position projection outside the paper's scheme that bounds the penetration drift of
  /// rolling contacts; false = the paper's scheme exactly. It adds -m g·Δr of potential energy,
  /// reported in StepStatistics::gap_correction_energy. For the Tippe-Top on the ground this is a
  /// lift along +z by the highest closed contact's depth less the slop.
  bool gap_correction = true;
  /// The warm start of a contact's percussion: true = extrapolated from the last two steps where
  /// that is safe (see the header comment), false = the last step's percussion. Measured on the
  /// Tippe-Top (8 s, `sphere`): 3.6 → 2.1 solver iterations per step, θ(t) within 1e-6 rad.
  bool extrapolate_warm_start = true;
};
/// Throws std::invalid_argument naming the field and its allowed range.
void ValidateSimulatorOptions(const SimulatorOptions& options);

/// One contact of the index set (12) of the last step, at the midpoint q_M where it was found.
/// A and B are the two colliders, the normal points from A to B; a static collider is always A.
struct ContactState {
  int collider_a = 0;  ///< index into Scene::colliders
  int collider_b = 0;
  int body_a = kWorld;  ///< body of A (kWorld: static)
  int body_b = 0;       ///< body of B
  int feature = 0;      ///< ContactGeometry::feature of the pair function
  double gap = 0.0;     ///< g(q_M) ≤ 0 [m]
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< contact point on B, world [m]
  ContactFrame frame;   ///< n (A → B), t1, t2, world
  ContactLaw law;       ///< the pair's law (CombineLaws), R̄ of a face patch where it is one
  int dimension = 1;    ///< ContactDimension(law)
  /// Λ = (Λ_N, Λ_T1, Λ_T2, Λ_τ) on B [N s, N s, N s, N m s]; components the contact does not
  /// model are 0.
  Eigen::Vector4d percussion = Eigen::Vector4d::Zero();
  /// γ_E = W(q_M)ᵀu_E [m/s, m/s, m/s, rad/s]: velocity of B relative to A, the one the law
  /// constrained.
  Eigen::Vector4d relative_velocity = Eigen::Vector4d::Zero();
};

/// "<first>/<second>": the two colliders' names in Scene::colliders order (e.g.
/// "big_sphere/ground"). Stable while the scene does not change.
std::string ContactName(const Scene& scene, const ContactState& contact);

/// Most fixed-point passes of the implicit-midpoint gyroscopic scheme around the contact solve.
inline constexpr int kMaxGyroscopicPasses = 6;

struct StepStatistics {
  /// Over the islands' contact solves: iterations summed (and over the passes of
  /// kImplicitMidpoint), residual and max_change the largest, converged if every island did;
  /// friction_projected / normal_projected per contact of contacts(). With no closed contact
  /// iterations = 0 and converged = true.
  SolverStatistics solver;
  int closed_contacts = 0;
  int islands = 0;  ///< contact problems (17) solved: bodies linked by closed contacts
  /// Deepest penetration of a closed contact at the midpoint, max(0, -g(q_M)) [m].
  double max_penetration = 0.0;
  int gyroscopic_passes = 0;  ///< contact solves of this step (1 with kExplicit; 0 without contact)
  /// Largest Δt·|ω| over the bodies in this step: the explicit gyroscopic scheme's energy error
  /// per step grows like (Δt·|ω|)².
  double max_dt_omega = 0.0;
  /// gyroscopic == kExplicit and max_dt_omega > kExplicitGyroscopicMaxDtOmega: energy can grow by
  /// O((Δt·|ω|)²) per step and the run can diverge.
  bool explicit_gyroscopic_unsafe = false;
  /// Largest translation |Δr| of a body by SimulatorOptions::gap_correction in this step [m]
  /// (0: none).
  double gap_correction = 0.0;
  /// Potential energy the lifts added in this step, Σ -m g·Δr over the moved bodies [J].
  double gap_correction_energy = 0.0;
  /// Energy() of the state after this step, gap correction included [J]: the step sums it anyway
  /// (the state must not overflow it), so a caller need not sum it again. NaN if the step was not
  /// taken (state_finite false).
  double energy = 0.0;
  /// false: this step met a non-finite value (state, free velocities, contact problem, end state or
  /// the squared norms of the end velocities), i.e. the scheme diverged. The step was not taken:
  /// state, time and contact report stay at the last finite step, and every later Step() returns at
  /// once with state_finite = false (nothing advances) until SetState() replaces the state
  /// (Simulator::diverged()). The mechanical energy of the end state (Energy(), as MechanicalEnergy
  /// sums it) overflowing counts as non-finite too.
  bool state_finite = true;
  /// true: SimulatorOptions::gap_correction produced a non-finite value in this step (a position or
  /// orientation, the energy, or gap_correction / gap_correction_energy overflowing; only for
  /// bodies set through the core absurdly far into the ground, e.g. 1e300 m) and was undone: the
  /// state is the step's end state without the correction, as with gap_correction = false, and
  /// gap_correction = gap_correction_energy = 0. The step is taken (state_finite stays true).
  bool gap_correction_undone = false;
};

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
  const Scene& scene() const { return scene_; }
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
  /// Switches the friction set of every contact (name empty), of every contact of one collider
  /// (name = a collider's name) or of one contact (name = ContactName, "<first>/<second>"). The
  /// state is kept, the warm start of changed contacts dropped. Throws std::invalid_argument for an
  /// unknown name or set, changing nothing.
  void SetFrictionSet(FrictionSet set, const std::string& name = "");
  /// The friction set a contact named `name` ("<first>/<second>") would use.
  FrictionSet FrictionSetOf(const std::string& name) const;
  /// Replaces one collider's law (validated; throws std::invalid_argument / std::out_of_range).
  void SetContactLaw(int collider, const ContactLaw& law);

  double Energy() const { return MechanicalEnergy(scene_, state_); }

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
  // Per-body midpoint data of the current step.
  struct BodyStep {
    Eigen::Vector3d position_mid;        // r_S(q_M) [m]
    Eigen::Quaterniond orientation_mid;  // p_M, normalised
    Eigen::Matrix3d rotation_mid;        // A(p_M)
    Eigen::Matrix3d rotation_end;        // A(p_E), for the gap correction
    Eigen::Vector3d linear_free;         // v_B + g Δt: linear part of u_B + M⁻¹hΔt [m/s]
    Eigen::Vector3d gyroscopic_impulse;  // Δt·(-ω × Θω) at ω_B (explicit) or ω_M (implicit) [N m s]
    Eigen::Vector3d angular_free;        // ω_B + Θ⁻¹·gyroscopic_impulse [rad/s]
    Eigen::Vector3d linear_contact;      // Σ linear parts of W_iΛ_i [N s]
    Eigen::Vector3d angular_contact;     // Σ J_iᵀΛ_i, in K [N m s]
    Eigen::Vector3d angular_end;         // ω_E [rad/s]
    Eigen::Vector3d linear_end;          // v_E [m/s]
    Eigen::Vector3d position_end;        // r_S(q_E) [m]
    Eigen::Quaterniond orientation_end;  // p_E, normalised
    // Δt·A(p_M)ᵀτ: the external torque's impulse in K [N m s], valid if `external`
    Eigen::Vector3d angular_external;
    bool external = false;               // an external wrench acts on the body in this step
    int island = -1;                     // index into islands_ (-1: no closed contact)
  };
  // The external wrench of one body (SetExternalWrench), world axes.
  struct Wrench {
    Eigen::Vector3d force = Eigen::Vector3d::Zero();   // [N], through S
    Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // [N m]
    bool set = false;                                  // not both zero
  };
  // Memory of one (pair, feature) across steps.
  struct ContactMemory {
    Eigen::Vector3d tangent1 = Eigen::Vector3d::UnitX();
    Eigen::Vector4d percussion = Eigen::Vector4d::Zero();
    Eigen::Vector4d percussion_before = Eigen::Vector4d::Zero();  // of the step before that
    Eigen::Vector4d percussion_before2 = Eigen::Vector4d::Zero();  // and the one before that
    double rim_hint = 0.0;  // the warm start of B_F's exact prox (ContactWork::rim_hint)
    long closed_step = -2;  // the step it was last closed in
    long closed_before = -3;  // the step before that in which it was closed
    long closed_before2 = -4;  // and the one before that
    // the next warm start is extrapolated quadratically (SolveIsland), not linearly
    bool quadratic_served = false;
    bool sliding = false;    // its friction was projected in its last solve
    bool converged = false;  // its last solve converged
    // a warm start that no longer fits (another Δt, law or friction set): start from zero
    void DropWarmStart() {
      percussion.setZero();
      percussion_before.setZero();
      percussion_before2.setZero();
      quadratic_served = false;
    }
  };
  // A contact of the index set (12) of the current step.
  struct ClosedContact {
    ContactState report;         // geometry, frame, law at q_M; percussion and γ_E after solve
    ContactJacobian jacobian;    // W at q_M
    Eigen::Vector4d gamma_begin; // γ^B = W(q_M)ᵀu_B
    std::uint64_t key = 0;       // (pair, feature) of the warm start and the tangent frame
    ContactMemory* memory = nullptr;  // memory_[key] (node pointers stay valid on rehash)
  };
  // The closed contacts of one body with one static collider, or of two bodies, at q_E.
  struct GapGroup {
    int body_a = kWorld;        // kWorld for a static A
    int body_b = 0;
    int static_collider = -1;  // A's collider if it is static
    double highest_gap = 0.0;  // g(q_E) [m]
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  };
  // Bodies linked by closed contacts: one contact problem (17).
  struct Island {
    int first_contact = 0;  // into island_contacts_
    int contact_count = 0;
  };

  void Initialize();
  // the per-body and per-collider arrays derived from scene_ (inertia_, planes_, needs_sweep_,
  // collider poses, radii, the step's workspace sizes): by Initialize and after AddBodies /
  // RemoveBodies; keeps the warm-start memory, the contact report and the wrenches
  void BuildCaches();
  void ComputeMidpoints(StepStatistics* stats, bool* finite);
  void FindContacts(StepStatistics* stats);
  void AddPairContacts(int first, int second);
  void BuildIslands(StepStatistics* stats);
  // false if an island's contact problem is not finite (nothing solved)
  bool SolveIsland(const Island& island, StepStatistics* stats);
  // (18), (15) into body_step_; false if any end value is not finite (state_ untouched)
  bool ComputeEndState();
  void CorrectGaps(StepStatistics* stats);
  // levels a body on the closed contacts [first, last) of closed_ (one pair with a static
  // collider, end geometry `end`); false if fewer than two of them are found at q_E
  bool LevelOnPoints(std::size_t first, std::size_t last, const ContactGeometry* end, int count,
                     StepStatistics* stats);
  // (18): the contact impulses M⁻¹ Σ W_iΛ_i of the island's contacts from lambda_
  void ApplyImpulses(const Island& island);
  // an island of one contact on an explicit step: SolveIsland's result without the block
  // problem (ContactSolver::SolveOnePrevalidated)
  bool SolveLoneContact(const Island& island, StepStatistics* stats);
  // SolveIsland's parts for one contact: its warm start (above), the block G_ij of (16) with a
  // contact of its island, its c_i (16), its impulse W_iΛ_i added to its bodies' sums, and what
  // the solve leaves in its report and memory (`alone`: the only contact of its island)
  Eigen::Vector4d WarmStart(const ContactMemory& memory, bool extrapolating) const;
  Eigen::Matrix4d DelassusBlock(const ClosedContact& a, const ClosedContact& b) const;
  Eigen::Vector4d FreeContactVelocity(const ClosedContact& c) const;
  void AddContactImpulse(const ClosedContact& c, const Eigen::Vector4d& percussion);
  void RememberSolve(ClosedContact* contact, const Eigen::Vector4d& percussion,
                     bool friction_projected, bool alone, double rim_hint);
  // the law of a pair with the overrides of SetFrictionSet
  ContactLaw PairLaw(int first, int second) const;
  // collider_pose_ of a collider on a body at q_M (end = false) or q_E (end = true).
  void UpdateColliderPose(int collider, bool end);

  Scene scene_;
  SimulatorOptions options_;
  std::vector<BodyState> state_;
  double time_ = 0.0;
  long step_count_ = 0;
  bool diverged_ = false;
  bool implicit_step_ = false;  // this step uses the implicit midpoint rule (ComputeMidpoints)
  std::vector<ContactState> contacts_;
  ContactSolver solver_;
  // per body: M⁻¹ (10), computed once
  std::vector<BodyInertia> inertia_;
  // friction sets set per contact name by SetFrictionSet: (first, second) collider → set
  std::vector<std::pair<std::pair<int, int>, FrictionSet>> pair_sets_;
  std::vector<int> planes_;  // static plane colliders
  // whether two colliders that are not planes can meet (two bodies with colliders, or a body and
  // a static collider that is not a plane): without, the sweep is skipped
  bool needs_sweep_ = false;
  std::vector<Eigen::Isometry3d> collider_pose_;  // per collider, at q_M during FindContacts
  // per collider: its pose has a rotation (not identity); bytes, not std::vector<bool>: it is read
  // per collider and step
  std::vector<std::uint8_t> collider_rotated_;
  std::vector<double> bounding_radius_;  // per collider: BoundingRadius of its shape [m]
  // warm starts and tangent frames by (pair, feature)
  std::unordered_map<std::uint64_t, ContactMemory> memory_;
  // per body: the external wrench (SetExternalWrench); any_wrench_: one of them is set (a world
  // without one skips the work in ComputeMidpoints)
  std::vector<Wrench> wrench_;
  bool any_wrench_ = false;
  // workspace of Step(), sized once
  std::vector<BodyStep> body_step_;
  // the colliders that are not planes in the sweep order of the last step (emptied by
  // BuildCaches): nearly sorted for the next step's sweep
  std::vector<BoundingSphere> spheres_;
  std::vector<std::pair<int, int>> pairs_;
  std::vector<std::pair<int, int>> merged_pairs_;  // FindContacts' merge of plane and sweep pairs
  // closed_[0, closed_count_): the contacts of this step; the storage only grows (a contact is
  // not cheap to construct, every field is written when it is reused)
  std::vector<ClosedContact> closed_;
  std::size_t closed_count_ = 0;
  std::vector<Island> islands_;
  std::vector<int> island_contacts_;  // contact indices grouped by island
  std::vector<int> union_find_;       // per body
  std::vector<int> island_bodies_;    // body indices grouped by island (same order as contacts)
  std::vector<int> island_body_start_;
  std::vector<GapGroup> gap_groups_;
  // the pair function's output (a member: eight ContactGeometry are not free to construct)
  std::array<ContactGeometry, kMaxPairContacts> geometry_;
  // the contact problem of the island being solved, in blocks (contact k of the island is block
  // k), and its percussions; they only grow
  BlockContactProblem problem_;
  std::vector<Eigen::Vector4d> lambda_;
  std::vector<double> rim_hints_;  // with lambda_: the solver's warm start of B_F's prox
  SolverStatistics island_stats_;
  // Throws std::invalid_argument (naming the body, the field and its allowed range) unless the
  // mechanical energy of `state` in `scene` (MechanicalEnergy) and each of its terms are finite:
  // the constructor, AddBodies, SetState and SetBodyStates, after ValidateState.
  static void RequireFiniteEnergy(const Scene& scene, const std::vector<BodyState>& state);
  // CorrectGaps moved a body in this step (then Step checks what it did)
  bool gap_moved_ = false;
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_SIMULATOR_H_
