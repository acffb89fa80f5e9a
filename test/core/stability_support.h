// Shared by the stability tests (stability_*_test.cpp): stability at the extremes, the
// simulator stays finite, bounded and honest at the edges of every documented parameter range.
// Every case runs the Tippe-Top (tippe_top.h) or a smaller scene that isolates the point, and
// RunChecked checks after every step:
//  - no NaN or inf anywhere in the state, quaternions unit;
//  - penetration bounded (the smallest gap, with the measured value next to its bound);
//  - the solver is honest: `converged` agrees with its residual (≤ 1), every percussion lies in
//    its force set (Λ_N ≥ 0, friction inside μΛ_N, converged or not), and a step reported as
//    converged satisfies the normal law (γ_N ≥ 0 after the step, for ε = 0);
//  - energy: with the implicit-midpoint gyroscopic term no step gains more than round-off plus
//    the contact work Moreau's rule allows (kContactWorkPerStep), and E(t) ≤ E(0). These are
//    properties of the paper's scheme (13)-(18): the energy checks are net of the potential energy
//    the gap correction (SimulatorOptions::gap_correction, a position projection outside the
//    scheme, on by default) adds and reports per step (StepStatistics::gap_correction_energy).
//    GapCorrection.* (stability_long_test.cpp) checks the projection itself.
// Measured values are written next to each bound (Release build).
#ifndef NONSMOOTH_SIM_TEST_CORE_STABILITY_SUPPORT_H_
#define NONSMOOTH_SIM_TEST_CORE_STABILITY_SUPPORT_H_

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "scene_builders.h"

namespace nonsmooth_sim::stability {

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr int kBig = kBigSphere;  // collider indices of MakeTippeTopScene
inline constexpr int kPeg = kPegSphere;

using test::AddGround;
using test::SphereCollider;

// A percussion may leave its set by the round-off of the prox formulas only (relative to μΛ_N).
inline constexpr double kSetRoundOff = 1e-9;
// Energies are O(1e-2 J) for the Tippe-Top: round-off of E is ~1e-18 J; a step "gains no
// energy" if it gains less than this [J].
inline constexpr double kEnergyRoundOff = 1e-15;
// What Moreau's midpoint rule itself may add in one step even with the implicit-midpoint
// gyroscopic term: the contact percussions do the work ΔE = ½Λ·ξ + ½(1 - ε)Λ·γ_B with
// γ_B = W(q_M)ᵀu_B; ½Λ·ξ ≤ 0 (the normal cone), but for ε < 1 the second term has no sign
// where a contact persists (γ_B = O(Δt) from the change of W between midpoints). Rolling
// without sliding the Tippe-Top gains up to 1.8e-12 J in a step (1.5e-10 E0); sliding contacts
// and ε = 1 show round-off only [J].
inline constexpr double kContactWorkPerStep = 1e-11;
// A lifted contact ends at -kGapCorrectionSlop up to the round-off of z_S + A K_r_SM - ρ with
// lengths of O(1e-2 m) (~1e-18 m); 1e-12 m leaves room for the larger scenes [m].
inline constexpr double kLiftRoundOff = 1e-12;

// ---------------------------------------------------------------------------------------------
// What a run observed, step by step.

struct RunReport {
  long steps = 0;
  long contact_steps = 0;      // steps with at least one closed contact
  long unconverged_steps = 0;  // of those, reported unconverged
  long dishonest_steps = 0;  // converged ≠ (residual ≤ 1), or converged with γ_N < -tolerance
  long energy_report_wrong = 0;  // steps whose StepStatistics::energy is not Energy(), bit for bit
  bool finite = true;
  double max_quaternion_error = 0.0;      // max ||p| - 1|
  double min_gap = kInf;  // smallest gap of any collider above the ground after a step [m]
  // energies net of the gap correction's lifts, i.e. of the paper's scheme
  double max_step_energy_gain = -kInf;    // max E(t+Δt) - E(t) - ΔE_lift(t+Δt) [J]
  double max_energy_above_start = -kInf;  // max E(t) - E(0) - Σ ΔE_lift [J]
  double gap_correction_energy = 0.0;     // Σ ΔE_lift, the potential energy the lifts added [J]
  double max_gap_correction = 0.0;        // largest lift of one step [m]
  long gap_correction_steps = 0;          // steps with a lift
  double max_set_violation = 0.0;         // largest excess over its force set, / μΛ_N
  double theta_max = 0.0;                 // body 0 [rad]
  double min_normal_velocity = kInf;      // of converged closed contacts, ε = 0 [m/s]
};

inline bool StateIsFinite(const std::vector<BodyState>& state) {
  for (const BodyState& s : state) {
    if (!s.position.allFinite() || !s.orientation.coeffs().allFinite() ||
        !s.linear_velocity.allFinite() || !s.angular_velocity.allFinite()) {
      return false;
    }
  }
  return true;
}

// x, or the smallest positive double: a divisor for ratios that are 0/0 at the apex of a set.
inline double Positive(double x) { return std::max(x, std::numeric_limits<double>::min()); }

// Excess of Λ over the friction set of its law, relative to the radius μΛ_N (0 inside).
inline double SetViolation(const ContactLaw& law, const Eigen::Vector4d& lambda) {
  if (lambda[0] < 0.0) return kInf;
  const double radius = law.mu * lambda[0];
  const double tangential = lambda.segment<2>(1).norm();
  const double drilling = std::abs(lambda[3]);
  const int dimension = ContactDimension(law);
  if (dimension == 1) return tangential + drilling > 0.0 ? kInf : 0.0;
  const double scale = Positive(radius);
  if (dimension == 3) return drilling > 0.0 ? kInf : std::max(0.0, tangential - radius) / scale;
  const double torque_radius = law.rbar * radius;
  switch (law.friction_set) {
    case FrictionSet::kEllipsoid:
    case FrictionSet::kSphere: {
      // E_F (55): (|Λ_T|/μΛ_N)² + (Λ_τ/(R̄μΛ_N))² ≤ 1
      const double q = std::hypot(tangential / scale, drilling / Positive(torque_radius));
      return std::max(0.0, q - 1.0);
    }
    default:
      // C_F (54); B_F (51)-(53) lies inside it
      return std::max({0.0, (tangential - radius) / scale,
                       (drilling - torque_radius) / Positive(torque_radius)});
  }
}

// Runs `steps` steps and checks everything the header lists after each. `normal_tolerance`:
// the γ_N a converged ε = 0 contact may show after the step [m/s] (solver tolerance times G).
inline RunReport RunChecked(Simulator* sim, long steps, double normal_tolerance = 1e-6,
                     const std::function<void(long, const StepStatistics&)>& observe = {}) {
  RunReport r;
  const double e0 = sim->Energy();
  double previous = e0;
  StepStatistics stats;
  for (long k = 1; k <= steps; ++k) {
    sim->Step(&stats);
    ++r.steps;
    if (!StateIsFinite(sim->state())) {
      r.finite = false;
      break;
    }
    for (const BodyState& s : sim->state()) {
      r.max_quaternion_error =
          std::max(r.max_quaternion_error, std::abs(s.orientation.norm() - 1.0));
    }
    const double energy = sim->Energy();
    if (!(stats.energy == energy)) ++r.energy_report_wrong;
    r.gap_correction_energy += stats.gap_correction_energy;
    r.max_gap_correction = std::max(r.max_gap_correction, stats.gap_correction);
    if (stats.gap_correction > 0.0) ++r.gap_correction_steps;
    r.max_step_energy_gain =
        std::max(r.max_step_energy_gain, energy - previous - stats.gap_correction_energy);
    r.max_energy_above_start =
        std::max(r.max_energy_above_start, energy - e0 - r.gap_correction_energy);
    previous = energy;
    r.theta_max = std::max(r.theta_max, Inclination(sim->state()[0]));

    bool honest = stats.solver.converged == (stats.solver.residual <= 1.0);
    // the gap of every collider at the end of the step (q_E), closed or open
    r.min_gap = std::min(r.min_gap, test::MinGroundGap(sim->scene(), sim->state()));
    // contacts() holds the closed contacts (12) of the step, each with its pair's law
    const auto& contacts = sim->contacts();
    for (std::size_t i = 0; i < contacts.size(); ++i) {
      const ContactLaw& law = contacts[i].law;
      r.max_set_violation =
          std::max(r.max_set_violation, SetViolation(law, contacts[i].percussion));
      if (stats.solver.converged && law.restitution == 0.0) {
        const double gamma_n = contacts[i].relative_velocity[0];
        r.min_normal_velocity = std::min(r.min_normal_velocity, gamma_n);
        if (gamma_n < -normal_tolerance) honest = false;
      }
    }
    if (stats.closed_contacts > 0) {
      ++r.contact_steps;
      if (!stats.solver.converged) ++r.unconverged_steps;
    }
    if (!honest) ++r.dishonest_steps;
    if (observe) observe(k, stats);
  }
  return r;
}

// The invariants every case asserts.
inline void ExpectSane(const RunReport& r, double min_gap_bound, const std::string& what) {
  EXPECT_TRUE(r.finite) << what;
  EXPECT_LT(r.max_quaternion_error, 1e-14) << what;
  EXPECT_GT(r.min_gap, min_gap_bound) << what;
  EXPECT_LE(r.max_set_violation, kSetRoundOff) << what;
  EXPECT_EQ(r.energy_report_wrong, 0) << what;
  EXPECT_EQ(r.dishonest_steps, 0) << what << " (smallest γ_N of a converged step "
                                  << r.min_normal_velocity << " m/s)";
}

inline long Steps(double duration, double dt) { return std::lround(duration / dt); }

inline SimulatorOptions Options(double dt = 1e-4,
                         GyroscopicScheme scheme = GyroscopicScheme::kImplicitMidpoint) {
  SimulatorOptions options;
  options.time_step = dt;
  options.gyroscopic = scheme;
  return options;
}

struct TopSetup {
  double mu = 0.3;
  double contact_radius = 5e-4;  // R [m]
  double restitution = 0.0;
  FrictionSet set = FrictionSet::kSphere;
  double spin = 180.0;
  double inclination = 0.1;
};
inline Scene TippeTop(const TopSetup& setup) {
  TippeTopParameters parameters;
  parameters.mu = setup.mu;
  parameters.contact_radius = setup.contact_radius;
  parameters.restitution = setup.restitution;
  parameters.friction_set = setup.set;
  TippeTopInitialConditions initial;
  initial.spin = setup.spin;
  initial.inclination = setup.inclination;
  // a contact's μ is min(μ_top, μ_ground) (CombineLaws); GroundLaw() is neutral, so the top's μ
  // decides however large (the huge-μ test checks the contact's μ)
  return MakeTippeTopScene(parameters, initial);
}

inline double VerticalSpin(const Simulator& sim) {
  return (sim.state()[0].orientation * sim.state()[0].angular_velocity).z();
}

// A ball of 0.2 kg and 5 cm just touching the ground (gap exactly 0), under `gravity`.
inline Scene BallScene(const Eigen::Vector3d& gravity, FrictionSet set) {
  Scene scene;
  RigidBody ball;
  ball.name = "ball";
  ball.mass = 0.2;
  ball.inertia = Eigen::Matrix3d::Identity() * (0.4 * 0.2 * 0.05 * 0.05);
  scene.bodies = {ball};
  ContactLaw law;
  law.mu = 0.3;
  law.rbar = AverageFrictionRadius(5e-3);
  law.friction_set = set;
  scene.colliders = {SphereCollider("ball", 0, Eigen::Vector3d::Zero(), 0.05, law)};
  AddGround(&scene);
  scene.gravity = gravity;
  BodyState state;
  state.position = Eigen::Vector3d(0.0, 0.0, 0.05);  // touching: gap exactly 0
  scene.initial_state = {state};
  return scene;
}

}  // namespace nonsmooth_sim::stability

#endif  // NONSMOOTH_SIM_TEST_CORE_STABILITY_SUPPORT_H_
