// Moreau midpoint time-stepping of a Scene, (13)-(18) of Möller, Leine, Glocker (ESMC 2009).
//
//   q_M = q_B + Δt/2 F(q_B) u_B                                                        (13)
//   index set I = { i | g_i(q_M) ≤ 0 }                                                 (12)
//   M (u_E - u_B) - h(q_M, u_B) Δt - Σ_{i∈I} W_i Λ_i = 0,  ξ_i ∈ N_{D_i}(-Λ_i)         (14), (17)
//   u_E = u_B + M⁻¹ h Δt + M⁻¹ Σ W_i Λ_i                                              (18)
//   q_E = q_M + Δt/2 F(q_M) u_E, quaternion renormalised                              (15)
//
// The contact problem is solved by ContactSolver, warm-started from the previous step.
#ifndef NONSMOOTH_SIM_CORE_SIMULATOR_H_
#define NONSMOOTH_SIM_CORE_SIMULATOR_H_

#include <Eigen/Core>
#include <optional>
#include <string_view>
#include <vector>

#include "nonsmooth_sim/core/contact_solver.h"
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

struct SimulatorOptions {
  double time_step = 1e-4;  ///< Δt [s], in [1e-7, 1e-2]
  SolverOptions solver;
  GyroscopicScheme gyroscopic = GyroscopicScheme::kExplicit;
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
  /// γ = (γ_N, γ_T1, γ_T2, γ_τ) at the end of the step [m/s, m/s, m/s, rad/s].
  Eigen::Vector4d relative_velocity = Eigen::Vector4d::Zero();
};

struct StepStatistics {
  SolverStatistics solver;   ///< of the (last) contact solve; iterations = 0 with no closed contact
  int closed_contacts = 0;
  /// Largest Δt·|ω| over the bodies in this step: the explicit gyroscopic scheme's energy error
  /// per step grows like (Δt·|ω|)².
  double max_dt_omega = 0.0;
};

class Simulator {
 public:
  /// Validates scene and options (std::invalid_argument) and starts from scene.initial_state at t=0.
  Simulator(Scene scene, SimulatorOptions options);

  /// Advances by one time step.
  StepStatistics Step();

  double time() const { return time_; }
  const Scene& scene() const { return scene_; }
  const SimulatorOptions& options() const { return options_; }
  const std::vector<BodyState>& state() const { return state_; }
  /// One per sphere of the scene, from the last step.
  const std::vector<ContactState>& contacts() const { return contacts_; }

  /// Replaces the state (validated; quaternions normalised) and clears the warm start and the
  /// contact report. Throws std::invalid_argument and leaves everything unchanged on bad input.
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
  Scene scene_;
  SimulatorOptions options_;
  std::vector<BodyState> state_;
  double time_ = 0.0;
  std::vector<ContactState> contacts_;
  ContactSolver solver_;
  // per sphere: last step's percussion, for the warm start
  std::vector<Eigen::Vector4d> warm_start_;
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_SIMULATOR_H_
