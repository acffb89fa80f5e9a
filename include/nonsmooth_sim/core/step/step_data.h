// The data of a step, as MuJoCo's mjData beside the Model: what the stages of Moreau's midpoint
// step (13)-(18) write and read. Per body the midpoint and end values (BodyStep), per collider its
// pose at q_M or q_E, the closed contacts of the index set (12) with their W, and the contacts'
// memory across steps. Sized for a model by Resize (after every change of the scene).
#ifndef NONSMOOTH_SIM_CORE_STEP_STEP_DATA_H_
#define NONSMOOTH_SIM_CORE_STEP_STEP_DATA_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "nonsmooth_sim/core/contact/contact_jacobian.h"
#include "nonsmooth_sim/core/model.h"
#include "nonsmooth_sim/core/step/contact_memory.h"
#include "nonsmooth_sim/core/step/step_report.h"

namespace nonsmooth_sim {

/// Per-body midpoint and end data of the current step.
struct BodyStep {
  Eigen::Vector3d position_mid;        ///< r_S(q_M) [m]
  Eigen::Quaterniond orientation_mid;  ///< p_M, normalised
  Eigen::Matrix3d rotation_mid;        ///< A(p_M)
  Eigen::Matrix3d rotation_end;        ///< A(p_E), for the gap correction
  Eigen::Vector3d linear_free;         ///< v_B + g Δt: linear part of u_B + M⁻¹hΔt [m/s]
  /// Δt·(-ω × Θω) at ω_B (explicit) or ω_M (implicit) [N m s]
  Eigen::Vector3d gyroscopic_impulse;
  Eigen::Vector3d angular_free;        ///< ω_B + Θ⁻¹·gyroscopic_impulse [rad/s]
  Eigen::Vector3d linear_contact;      ///< Σ linear parts of W_iΛ_i [N s]
  Eigen::Vector3d angular_contact;     ///< Σ J_iᵀΛ_i, in K [N m s]
  Eigen::Vector3d angular_end;         ///< ω_E [rad/s]
  Eigen::Vector3d linear_end;          ///< v_E [m/s]
  Eigen::Vector3d position_end;        ///< r_S(q_E) [m]
  Eigen::Quaterniond orientation_end;  ///< p_E, normalised
  /// Δt·A(p_M)ᵀτ: the external torque's impulse in K [N m s], valid if `external`
  Eigen::Vector3d angular_external;
  double kinetic_end = 0.0;  ///< ½m|v_E|² + ½ω_EᵀΘω_E [J] (the lift keeps the velocities)
  bool external = false;  ///< an external wrench acts on the body in this step
};

/// A contact of the index set (12) of the current step.
struct ClosedContact {
  ContactState report;          ///< geometry, frame, law at q_M; percussion and γ_E after solve
  ContactJacobian jacobian;     ///< W at q_M
  /// the rolling rows of W at q_M, set only where report.dimension == 6
  RollingJacobian rolling;
  /// γ^B = W(q_M)ᵀu_B (computed only where the law's ε ≠ 0 or for Integrator::kMoreau2, zero
  /// otherwise)
  Eigen::Vector4d gamma_begin = Eigen::Vector4d::Zero();
  /// kMoreau2: its friction acts against the midpoint velocity (it slid in the last step and
  /// slides on); false: against the end velocity
  bool friction_midpoint = false;
  std::uint64_t key = 0;        ///< (pair, feature) of the warm start and the tangent frame
  ContactMemory* memory = nullptr;  ///< memory[key] (node pointers stay valid on rehash)
};

struct StepData {
  std::vector<BodyStep> body;  ///< per body
  /// Per collider: its world pose; a static collider's is the model's, a body's is set at q_M
  /// by the contact pipeline and at q_E by the position projection (UpdateColliderPose).
  std::vector<Eigen::Isometry3d> collider_pose;
  /// closed[0, closed_count): the contacts of this step, ordered by collider pair and feature;
  /// the storage only grows (a contact is not cheap to construct, every field is written when it
  /// is reused).
  std::vector<ClosedContact> closed;
  std::size_t closed_count = 0;
  /// Warm starts and tangent frames by (pair, feature).
  ContactMemoryMap memory;
  long step = 0;          ///< steps taken: the clock of ContactMemory's closing steps
  bool implicit = false;  ///< this step uses the implicit midpoint rule (ComputeMidpoints)
  bool second_order = false;  ///< this step is Integrator::kMoreau2's
  /// a closed contact of this step has rolling components (dimension 6, HasRolling)
  bool any_rolling = false;
  /// Δt of the last step taken if it was kMoreau2's (its γ_E and end gaps are in the memory),
  /// else 0 [s]
  double previous_time_step = 0.0;

  /// Sizes the per-body and per-collider arrays for `model` (keeps the memory); no closed
  /// contact.
  void Resize(const Model& model);
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_STEP_STEP_DATA_H_
