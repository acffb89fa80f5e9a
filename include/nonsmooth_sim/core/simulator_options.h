// Options of a simulation: the scheme's step size, solver, gyroscopic scheme and the two choices
// outside the paper's scheme (gap correction, extrapolated warm starts); see simulator.h.
#ifndef NONSMOOTH_SIM_CORE_SIMULATOR_OPTIONS_H_
#define NONSMOOTH_SIM_CORE_SIMULATOR_OPTIONS_H_

#include <array>
#include <optional>
#include <string_view>

#include "nonsmooth_sim/core/contact_solver.h"

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
inline constexpr std::array<GyroscopicScheme, 3> kAllGyroscopicSchemes = {
    GyroscopicScheme::kExplicit, GyroscopicScheme::kImplicitMidpoint, GyroscopicScheme::kAuto};
/// "explicit", "implicit_midpoint", "auto"; "" for a value not in kAllGyroscopicSchemes.
std::string_view GyroscopicSchemeName(GyroscopicScheme scheme);
std::optional<GyroscopicScheme> GyroscopicSchemeFromName(std::string_view name);

/// The time-stepping scheme (docs/theory.md, "The second-order integrator"). Both are built from
/// the same stages (core/step/) and solve the same normal-cone inclusion per contact.
enum class Integrator {
  kMoreau,   ///< "moreau": the paper's midpoint rule (13)-(18), bit for bit; first order
  kMoreau2,  ///< "moreau2": second order without impacts: a contact closed in the last step
             ///< imposes its law on the end velocity W(q_E)ᵀu_E (W(q_E) estimated from this
             ///< step's and the last step's W(q_M)) and is held on position level, a sliding
             ///< one acts against the midpoint velocity; the gyroscopic term by the implicit
             ///< midpoint rule; a contact that closes (an impact) as in kMoreau
};
inline constexpr std::array<Integrator, 2> kAllIntegrators = {Integrator::kMoreau,
                                                              Integrator::kMoreau2};
/// "moreau", "moreau2"; "" for a value not in kAllIntegrators.
std::string_view IntegratorName(Integrator integrator);
std::optional<Integrator> IntegratorFromName(std::string_view name);

/// Δt·|ω| up to which the explicit gyroscopic term is considered safe (StepStatistics::
/// explicit_gyroscopic_unsafe). Measured on the Tippe-Top: runs with Δt·|ω| ≤ 0.18 never gained
/// energy, from 0.2 they gain, from 0.4-0.5 they blow up (non-finite state); 0.1 keeps a margin.
inline constexpr double kExplicitGyroscopicMaxDtOmega = 0.1;

/// Upper bound of SolverOptions::max_iterations in a simulation, where the cap multiplies the work
/// of every step (per island, and per gyroscopic pass with kImplicitMidpoint). It bounds a step at
/// 1e5 iterations of each island: 4.4 ms for the Tippe-Top on one contact (Gauss-Seidel, Release,
/// an idle core; 8-17 ms with the 2 cores shared; bounded_work_test prints it, 2026-12-02; the
/// contacts of an island cost O(n²) per iteration). 1e5 is the cap the converged references of the
/// trade study use (scripts/dev/tradeoff, tolerance 1e-12, also on the slow `ellipsoid` set) and the
/// tightest Simulator tests (multi_body_test, tippe_top_test); the default is 1000.
/// ValidateSimulatorOptions checks it, and with it `simulate` and the node (parameters and
/// ~set_solver_properties).
inline constexpr int kMaxSimulatorIterations = 100000;

struct SimulatorOptions {
  double time_step = 1e-4;  ///< Δt [s], in [1e-7, 1e-2]
  /// solver.max_iterations in [1, kMaxSimulatorIterations], solver.relaxation in
  /// [kMinRelaxation, 2) (ValidateSolverOptions, contact_solver.h)
  SolverOptions solver;
  GyroscopicScheme gyroscopic = GyroscopicScheme::kExplicit;
  /// kMoreau is the library's default (the paper's scheme, the reference); `simulate` and the
  /// node default to kMoreau2. kMoreau2 takes the implicit midpoint rule whatever `gyroscopic`.
  Integrator integrator = Integrator::kMoreau;
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

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_SIMULATOR_OPTIONS_H_
