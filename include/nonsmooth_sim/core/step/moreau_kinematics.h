// The kinematic stages of Moreau's midpoint step, (13)-(15) and (18) of the paper:
//   q_M = q_B + Δt/2 F(q_B) u_B, and the free velocities u_B + M⁻¹ h(q_M, u_B) Δt      (13), (14)
//   u_E = u_B + M⁻¹ h Δt + M⁻¹ Σ W_i Λ_i                                               (18)
//   q_E = q_M + Δt/2 F(q_M) u_E, quaternion renormalised                               (15)
// The contact sums Σ W_iΛ_i and, with contact, ω_E come from the island problem in between.
#ifndef NONSMOOTH_SIM_CORE_STEP_MOREAU_KINEMATICS_H_
#define NONSMOOTH_SIM_CORE_STEP_MOREAU_KINEMATICS_H_

#include <vector>

#include "nonsmooth_sim/core/model.h"
#include "nonsmooth_sim/core/simulator_options.h"
#include "nonsmooth_sim/core/step/step_data.h"

namespace nonsmooth_sim {

/// (13) and the free velocities of (14) per body into data->body (gravity, the gyroscopic term at
/// ω_B, the external wrench at q_M; ω_E = the free ω, contact sums zero), from `state` = q_B, u_B.
/// Chooses the step's gyroscopic scheme (data->implicit; kAuto by Δt·|ω_B|); stats: max_dt_omega,
/// explicit_gyroscopic_unsafe. *finite becomes false if a midpoint value is not finite.
void ComputeMidpoints(const Model& model, const SimulatorOptions& options,
                      const std::vector<BodyState>& state, StepData* data, StepStatistics* stats,
                      bool* finite);

/// (18) v_E from the contact sums, then (15) r_S(q_E), p_E and A(p_E) per body into data->body
/// (ω_E is already there). false if an end value, |v_E|² or |ω_E|² is not finite.
bool ComputeEndState(const Model& model, const SimulatorOptions& options, StepData* data);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_STEP_MOREAU_KINEMATICS_H_
