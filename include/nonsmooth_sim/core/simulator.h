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
//  - The contact problem (17) is solved by ContactSolver, warm-started from the previous step's
//    percussions of the contacts that were closed then (zero for newly closed ones).
//  - GyroscopicScheme::kImplicitMidpoint replaces the gyroscopic part of h(q_M, u_B) by the
//    implicit midpoint rule Θ(ω_E - ω_B) = -Δt ω_M × Θω_M + Σ J_iᵀΛ_i, ω_M = (ω_B + ω_E)/2
//    (solved by Newton for fixed Λ), with a few fixed-point passes around the contact solve: the
//    gyroscopic impulse of the current ω_E enters c of the next pass (warm-started), until ω_E
//    changes by less than the solver's relative tolerance (or round-off), at most
//    kMaxGyroscopicPasses passes. Torque-free it conserves ½ωᵀΘω and |Θω| to round-off.
//
// Properties of the scheme worth knowing (measured on the Tippe-Top, see the README):
//  - It is velocity-level: (14) constrains γ_N at the end of the step, not g. A contact point that
//    moves over a curved surface (rolling, precessing) drifts into the floor by about
//    ½Δt²·(dW/dt)ᵀu per step, linearly in time: up to 0.22 mm on the peg after 8 s at Δt = 1e-4,
//    0.08 mm at 5e-5; a top rocking for 1 h at Δt = 1e-3 sinks 2.9 mm. A body at rest does not
//    drift. SimulatorOptions::gap_correction (on by default) bounds it by a position projection
//    after (15) that is not part of the paper's scheme (see there); off, the scheme is the paper's.
//  - A step that meets a non-finite value (the explicit gyroscopic term far outside its safe range
//    blows up) is not taken: StepStatistics::state_finite = false, state and time stay at the last
//    finite step, and the simulator stays stopped until SetState(). It never throws for that.
//  - The index set (12) uses g ≤ 0 exactly: a contact at a round-off-level positive gap (a box
//    resting on several feet after a tolerance-level rotation) is open for that step.
//  - With the explicit gyroscopic term, a step without contact gains ½Δt²·aᵀΘa; with contact,
//    friction dissipates far more. With kImplicitMidpoint the Tippe-Top's largest per-step energy
//    increase is round-off (3.5e-18 J).
//
// Step() allocates nothing once every problem size n it meets has been seen once (the contact
// problems are kept per size n; Eigen resizes would reallocate otherwise).
#ifndef NONSMOOTH_SIM_CORE_SIMULATOR_H_
#define NONSMOOTH_SIM_CORE_SIMULATOR_H_

#include <Eigen/Core>
#include <optional>
#include <string_view>
#include <vector>

#include "nonsmooth_sim/core/contact_solver.h"
#include "nonsmooth_sim/core/rigid_body_dynamics.h"
#include "nonsmooth_sim/core/scene.h"

namespace nonsmooth_sim {

/// How the gyroscopic term -ω × Θω enters h in (14).
enum class GyroscopicScheme {
  kExplicit,         ///< "explicit": the paper's h(q_M, u_B); adds ½Δt²·aᵀΘa per step
  kImplicitMidpoint, ///< "implicit_midpoint": Euler's equations by the implicit midpoint rule,
                     ///< a few fixed-point passes around the contact solve; conserves ½ωᵀΘω, |L|
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

/// Δt·|ω| up to which the explicit gyroscopic term is considered safe (StepStatistics::
/// explicit_gyroscopic_unsafe). Measured on the Tippe-Top: runs with Δt·|ω| ≤ 0.18 never gained
/// energy, from 0.2 they gain, from 0.4-0.5 they blow up (non-finite state); 0.1 keeps a margin.
inline constexpr double kExplicitGyroscopicMaxDtOmega = 0.1;

struct SimulatorOptions {
  double time_step = 1e-4;  ///< Δt [s], in [1e-7, 1e-2]
  SolverOptions solver;
  GyroscopicScheme gyroscopic = GyroscopicScheme::kExplicit;
  /// After (15), each body whose closed contacts (12) all end below -kGapCorrectionSlop is
  /// translated along the ground normal +z until the highest of them is at -kGapCorrectionSlop
  /// (its penetration minus the slop; with one closed contact: the deepest penetration minus the
  /// slop). Velocities are kept. A lift never opens a contact that carried the body (lifting by
  /// the deepest of several would, and feed a rocking limit cycle). A position projection outside
  /// the paper's scheme that bounds the penetration drift of rolling contacts; false = the
  /// paper's scheme exactly. It adds m·g·Δz of potential energy, reported in
  /// StepStatistics::gap_correction_energy.
  bool gap_correction = true;
};
/// Throws std::invalid_argument naming the field and its allowed range.
void ValidateSimulatorOptions(const SimulatorOptions& options);

/// One sphere-ground contact after a step.
struct ContactState {
  bool closed = false;          ///< in the index set (12) of the last step
  double gap = 0.0;             ///< g at the end of the step [m]
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< lowest point of the sphere, world [m]
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ(); ///< ground normal, world
  /// Λ = (Λ_N, Λ_T1, Λ_T2, Λ_τ) of the last step [N s, N s, N s, N m s]; tangents along world x, y.
  /// Components the contact does not model are 0.
  Eigen::Vector4d percussion = Eigen::Vector4d::Zero();
  /// γ = (γ_N, γ_T1, γ_T2, γ_τ) = Wᵀu_E at the end of the step [m/s, m/s, m/s, rad/s]: with the
  /// W(q_M) the contact law constrained for a closed contact, with W(q_E) for an open one.
  Eigen::Vector4d relative_velocity = Eigen::Vector4d::Zero();
};

/// Most fixed-point passes of the implicit-midpoint gyroscopic scheme around the contact solve.
inline constexpr int kMaxGyroscopicPasses = 6;

struct StepStatistics {
  /// Of the (last) contact solve; with no closed contact iterations = 0 and converged = true. With
  /// kImplicitMidpoint, `iterations` is summed over the passes.
  SolverStatistics solver;
  int closed_contacts = 0;
  int gyroscopic_passes = 0;  ///< contact solves of this step (1 with kExplicit; 0 without contact)
  /// Largest Δt·|ω| over the bodies in this step: the explicit gyroscopic scheme's energy error
  /// per step grows like (Δt·|ω|)².
  double max_dt_omega = 0.0;
  /// gyroscopic == kExplicit and max_dt_omega > kExplicitGyroscopicMaxDtOmega: energy can grow by
  /// O((Δt·|ω|)²) per step and the run can diverge.
  bool explicit_gyroscopic_unsafe = false;
  /// Largest lift Δz of a body by SimulatorOptions::gap_correction in this step [m] (0: none).
  double gap_correction = 0.0;
  /// Potential energy the lifts added in this step, Σ -m g·ẑ Δz over the lifted bodies [J].
  double gap_correction_energy = 0.0;
  /// false: this step met a non-finite value (state, free velocities, contact problem, end state or
  /// the squared norms of the end velocities), i.e. the scheme diverged. The step was not taken:
  /// state, time and contact report stay at the last finite step, and every later Step() returns at
  /// once with state_finite = false (nothing advances) until SetState() replaces the state
  /// (Simulator::diverged()).
  bool state_finite = true;
};

class Simulator {
 public:
  /// Validates scene and options (std::invalid_argument); starts from scene.initial_state at t=0.
  Simulator(Scene scene, SimulatorOptions options);

  /// Advances by one time step (not after a non-finite step: see StepStatistics::state_finite).
  StepStatistics Step();
  /// The same, filling `stats` in place (all fields overwritten): with one StepStatistics reused
  /// across steps, a step allocates nothing once its problem sizes have been seen.
  void Step(StepStatistics* stats);

  double time() const { return time_; }
  /// A step met a non-finite value; Step() does nothing until SetState().
  bool diverged() const { return diverged_; }
  const Scene& scene() const { return scene_; }
  const SimulatorOptions& options() const { return options_; }
  const std::vector<BodyState>& state() const { return state_; }
  /// One per sphere of the scene, from the last step.
  const std::vector<ContactState>& contacts() const { return contacts_; }

  /// Replaces the state (validated; quaternions normalised) and clears the warm start, the contact
  /// report and diverged(). Throws std::invalid_argument and leaves everything unchanged on bad
  /// input.
  void SetState(const std::vector<BodyState>& state);
  void SetTime(double time);
  /// Validated like the constructor; throws and changes nothing on bad input.
  void SetOptions(const SimulatorOptions& options);
  /// Switches the friction law of one sphere's contact (or all with std::nullopt); the state is
  /// kept, the warm start of changed contacts dropped. Throws std::out_of_range for a bad index.
  void SetFrictionSet(FrictionSet set, std::optional<int> sphere = std::nullopt);
  /// Replaces one sphere's law (validated; throws std::invalid_argument / std::out_of_range).
  void SetContactLaw(int sphere, const ContactLaw& law);

  double Energy() const { return MechanicalEnergy(scene_, state_); }

 private:
  // Per-body midpoint data of the current step.
  struct BodyStep {
    Eigen::Vector3d position_mid;        // r_S(q_M) [m]
    Eigen::Quaterniond orientation_mid;  // p_M, normalised
    Eigen::Matrix3d rotation_mid;        // A(p_M)
    Eigen::Matrix3d rotation_end;        // A(p_E), for the gap correction and contact report
    Eigen::Vector3d linear_free;         // v_B + g Δt: linear part of u_B + M⁻¹hΔt [m/s]
    Eigen::Vector3d gyroscopic_impulse;  // Δt·(-ω × Θω) at ω_B (explicit) or ω_M (implicit) [N m s]
    Eigen::Vector3d angular_free;        // ω_B + Θ⁻¹·gyroscopic_impulse [rad/s]
    Eigen::Vector3d linear_contact;      // Σ linear parts of W_iΛ_i [N s]
    Eigen::Vector3d angular_contact;     // Σ J_iᵀΛ_i, in K [N m s]
    Eigen::Vector3d angular_end;         // ω_E [rad/s]
    Eigen::Vector3d linear_end;          // v_E [m/s]
    Eigen::Vector3d position_end;        // r_S(q_E) [m]
    Eigen::Quaterniond orientation_end;  // p_E, normalised
    double highest_closed_gap = 0.0;     // largest g(q_E) of its closed contacts [m]
    bool has_contact = false;
  };
  // A contact of the index set (12) of the current step.
  struct ClosedContact {
    int sphere = 0;
    int body = 0;
    int offset = 0;     // first component in the stacked Λ, c, G
    int dimension = 0;  // ContactDimension of its law
    GroundContactKinematics kinematics;  // at q_M
    Eigen::Vector4d gamma_begin;         // γ^B = W(q_M)ᵀu_B
  };

  void Initialize();
  // false if the contact problem is not finite (nothing solved)
  bool SolveContacts(int size, StepStatistics* stats);
  // (18), (15) into body_step_; false if any end value is not finite (state_ untouched)
  bool ComputeEndState();
  void CorrectGaps(StepStatistics* stats);
  void ReportContacts();
  ContactProblem& ProblemOfSize(int size);

  Scene scene_;
  SimulatorOptions options_;
  std::vector<BodyState> state_;
  double time_ = 0.0;
  bool diverged_ = false;
  std::vector<ContactState> contacts_;
  ContactSolver solver_;
  // per sphere: last step's percussion, for the warm start
  std::vector<Eigen::Vector4d> warm_start_;
  // per body: M⁻¹ (10), computed once
  std::vector<BodyInertia> inertia_;
  // per sphere: ContactDimension of its law
  std::vector<int> dimension_;
  // workspace of Step(), sized once
  std::vector<BodyStep> body_step_;
  std::vector<ClosedContact> closed_;
  // contact problem and percussions per stacked size n (index n), sized on first use
  std::vector<ContactProblem> problems_;
  std::vector<Eigen::VectorXd> lambdas_;
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_SIMULATOR_H_
