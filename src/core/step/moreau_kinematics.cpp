// The kinematic stages (13), (14)'s free velocities, (18) and (15), see moreau_kinematics.h.
#include "nonsmooth_sim/core/step/moreau_kinematics.h"

#include <algorithm>
#include <cmath>

#include "nonsmooth_sim/core/all_finite.h"

namespace nonsmooth_sim {
namespace {

// What (13) and the free velocities produced from one body's q_B, u_B.
bool MidpointIsFinite(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                      const Eigen::Vector3d& linear, const Eigen::Vector3d& angular) {
  return AllFinite(position) && AllFinite(orientation.coeffs()) && AllFinite(linear) &&
         AllFinite(angular);
}

}  // namespace

void ComputeMidpoints(const Model& model, const SimulatorOptions& options,
                      const std::vector<BodyState>& state, StepData* data, StepStatistics* stats,
                      bool* finite) {
  const double dt = options.time_step;
  const double half_dt = 0.5 * dt;
  // (13) q_M = q_B + Δt/2 F(q_B) u_B, and u_B + M⁻¹ h(q_M, u_B) Δt (14)
  double max_omega_sq = 0.0;  // max |ω|²: one square root per step, the same rounded maximum
  for (std::size_t b = 0; b < state.size(); ++b) {
    const BodyState& s = state[b];
    const BodyInertia& body = model.inertia[b];
    BodyStep& w = data->body[b];
    w.position_mid = s.position + half_dt * s.linear_velocity;
    w.orientation_mid = AdvanceOrientation(s.orientation, s.angular_velocity, half_dt).normalized();
    w.rotation_mid = w.orientation_mid.toRotationMatrix();
    w.linear_free = s.linear_velocity + dt * model.scene.gravity;
    w.gyroscopic_impulse = dt * GyroscopicTorque(body, s.angular_velocity);
    w.angular_free = s.angular_velocity + InverseInertiaTimes(body, w.gyroscopic_impulse);
    // the external wrench enters h(q_M, u_B) with gravity: v += Δt F/m, ω += Θ⁻¹ Δt A(p_M)ᵀτ
    // (A(p_B) would be first order in the torque's turning); skipped without one, so that a world
    // without wrenches steps exactly as before
    w.external = model.any_wrench && model.wrench[b].set;
    if (w.external) {
      w.linear_free += (dt * body.inverse_mass) * model.wrench[b].force;
      w.angular_external = dt * (w.rotation_mid.transpose() * model.wrench[b].torque);
      w.angular_free += InverseInertiaTimes(body, w.angular_external);
    }
    w.angular_end = w.angular_free;
    w.linear_contact.setZero();
    w.angular_contact.setZero();
    max_omega_sq = std::max(max_omega_sq, s.angular_velocity.squaredNorm());
    *finite = *finite &&
              MidpointIsFinite(w.position_mid, w.orientation_mid, w.linear_free, w.angular_free);
  }
  stats->max_dt_omega = std::max(stats->max_dt_omega, dt * std::sqrt(max_omega_sq));
  const bool beyond = stats->max_dt_omega > kExplicitGyroscopicMaxDtOmega;
  data->implicit = options.integrator == Integrator::kMoreau2 ||
                   options.gyroscopic == GyroscopicScheme::kImplicitMidpoint ||
                   (options.gyroscopic == GyroscopicScheme::kAuto && beyond);
  stats->explicit_gyroscopic_unsafe = !data->implicit && beyond;
}

bool ComputeEndState(const Model& model, const SimulatorOptions& options, StepData* data) {
  const double half_dt = 0.5 * options.time_step;
  bool finite = true;
  // (18) u_E, then (15) q_E = q_M + Δt/2 F(q_M) u_E with the quaternion renormalised
  for (std::size_t b = 0; b < data->body.size(); ++b) {
    BodyStep& w = data->body[b];
    w.linear_end = w.linear_free + model.inertia[b].inverse_mass * w.linear_contact;
    w.position_end = w.position_mid + half_dt * w.linear_end;
    w.orientation_end = AdvanceOrientation(w.orientation_mid, w.angular_end, half_dt).normalized();
    w.rotation_end = w.orientation_end.toRotationMatrix();
    // the squared norms too: a state whose energy overflows is as lost as one with an inf
    finite = finite && std::isfinite(w.linear_end.squaredNorm()) &&
             std::isfinite(w.angular_end.squaredNorm()) && AllFinite(w.position_end) &&
             AllFinite(w.orientation_end.coeffs());
  }
  return finite;
}

}  // namespace nonsmooth_sim
