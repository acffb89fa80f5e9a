// A solid ball with rolling resistance on the ground, through the Simulator's step (both
// integrators, both rolling sets), against the closed forms of docs/theory.md ("Rolling
// resistance"): rolling on a plane it decelerates at a = (5/7)μ_r g/r (rolling_decoupled exactly;
// rolling within 0.5 %, and exactly its own closed form with the slip of E_R's normal cone),
// stops at v₀/a and then stays at rest; on a
// slope it rests below tan θ* = μ_r/r (decoupled) or (μ_r/r)/√(1 + (μ_r/(μr))²) (coupled) and
// rolls above it. The same ball with μ_r = 0 rolls on at constant speed (no rolling component).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "dynamics_scenes.h"
#include "nonsmooth_sim/core/simulator.h"
#include "scene_builders.h"

namespace nonsmooth_sim {
namespace {

constexpr double kRadius = 0.05;     // r [m]
constexpr double kMass = 0.2;        // [kg]
constexpr double kMu = 0.5;
constexpr double kRbar = 1e-4;       // R̄ [m]
constexpr float kMuR = 1e-3f;        // μ_r [m]: μ_r/r = 0.02
constexpr double kDt = 1e-4;         // [s]
constexpr double kSpeed = 0.1;       // v₀ [m/s]

double MuR() { return static_cast<double>(kMuR); }

bool Coupled(FrictionSet set) { return set == FrictionSet::kRolling; }

// the closed forms (docs/theory.md): φ = F/M, the force over the rolling torque, (5/7)/r
// decoupled; coupled the root of ρ_r²rφ² + (Θ/m + r² - ρ_r²)φ - r = 0 (rolling with the slip
// γ_T = ρ_r²φγ_R of E_R's normal cone), ρ_r = μ_r/μ
double ForceOverTorque(FrictionSet set) {
  if (!Coupled(set)) return 5.0 / 7.0 / kRadius;
  const double rho_r = MuR() / kMu;
  const double a = rho_r * rho_r * kRadius;
  const double b = 0.4 * kRadius * kRadius + kRadius * kRadius - rho_r * rho_r;
  return 2.0 * kRadius / (b + std::sqrt(b * b + 4.0 * a * kRadius));
}
// v̇ = -φM/m with M on the set's boundary: μ_r mg decoupled, μ_r mg/√(1 + (φμ_r/μ)²) coupled
double Deceleration(FrictionSet set, double gravity) {
  const double phi = ForceOverTorque(set);
  const double a = phi * MuR() * gravity;
  if (!Coupled(set)) return a;
  return a / std::sqrt(1.0 + std::pow(phi * MuR() / kMu, 2));
}
double ThresholdTangent(FrictionSet set) {
  const double t = MuR() / kRadius;
  if (!Coupled(set)) return t;
  const double k = MuR() / (kMu * kRadius);
  return t / std::sqrt(1.0 + k * k);
}

// the ball touching the ground, gravity tilted by θ about y (the plane's downhill is +x)
Scene RollingBall(FrictionSet set, double theta, float mu_r = kMuR) {
  Scene scene;
  RigidBody ball;
  ball.name = "ball";
  ball.mass = kMass;
  ball.inertia = Eigen::Matrix3d::Identity() * (0.4 * kMass * kRadius * kRadius);
  scene.bodies = {ball};
  ContactLaw law;
  law.mu = kMu;
  law.rbar = kRbar;
  law.friction_set = set;
  law.rolling_resistance = mu_r;
  scene.colliders = {test::SphereCollider("ball", 0, Eigen::Vector3d::Zero(), kRadius, law)};
  test::AddGround(&scene);
  scene.gravity = test::kGravity * Eigen::Vector3d(std::sin(theta), 0.0, -std::cos(theta));
  BodyState state;
  state.position = Eigen::Vector3d(0.0, 0.0, kRadius);
  scene.initial_state = {state};
  return scene;
}

SimulatorOptions Options(Integrator integrator) {
  SimulatorOptions options = test::Options(kDt);
  options.integrator = integrator;
  return options;
}

// a rolling start: v = v₀ x̂, ω = v₀/r ŷ (K = world: the orientation stays the identity up to a
// rotation about ŷ, and the inertia is isotropic)
void StartRolling(Simulator* sim, double speed) {
  std::vector<BodyState> state = sim->state();
  state[0].linear_velocity = Eigen::Vector3d(speed, 0.0, 0.0);
  state[0].angular_velocity = Eigen::Vector3d(0.0, speed / kRadius, 0.0);
  sim->SetState(state);
}

double Speed(const Simulator& sim) { return sim.state()[0].linear_velocity.norm(); }
double Spin(const Simulator& sim) { return sim.state()[0].angular_velocity.norm(); }

class RollingBallStep : public ::testing::TestWithParam<std::tuple<FrictionSet, Integrator>> {
 protected:
  FrictionSet set() const { return std::get<0>(GetParam()); }
  Integrator integrator() const { return std::get<1>(GetParam()); }
};

TEST_P(RollingBallStep, DeceleratesStopsAndStaysAtRest) {
  Simulator sim(RollingBall(set(), 0.0), Options(integrator()));
  StartRolling(&sim, kSpeed);
  const double a = Deceleration(set(), test::kGravity);
  // it stops when the rolling torque M = mφ⁻¹a has used up its angular momentum about the contact
  // point, m v₀ r + Θ v₀/r (the friction force passes through the point): v₀/a for the decoupled
  // set; the coupled one starts without slip, off its steady ratio, at the same momentum
  const double inertia = 0.4 * kMass * kRadius * kRadius;
  const double torque = kMass * a / ForceOverTorque(set());
  const double stop = (kMass * kRadius + inertia / kRadius) * kSpeed / torque;  // ≈ 0.71 s
  // the contact has its rolling components
  sim.Step();
  ASSERT_EQ(sim.contacts().size(), 1u);
  EXPECT_EQ(sim.contacts()[0].dimension, 6);
  EXPECT_GT(sim.contacts()[0].rolling_percussion.norm(), 0.0);
  // the deceleration between 0.05 s and 0.25 s, from the speeds
  const auto run_to = [&](double t) {
    while (sim.time() < t - 0.5 * kDt) sim.Step();
    return sim.state()[0].linear_velocity.x();
  };
  const double v1 = run_to(0.05);
  const double v2 = run_to(0.25);
  const double measured = (v1 - v2) / 0.2;
  const double plain = 5.0 / 7.0 * MuR() * test::kGravity / kRadius;
  EXPECT_NEAR(measured / plain, 1.0, 5e-3) << "measured " << measured << ", (5/7)mu_r g/r " << plain;
  EXPECT_NEAR(measured / a, 1.0, 1e-6) << "measured " << measured << ", closed form " << a;
  // it rolls: the decoupled set without slip, the coupled one slips by γ_T/γ_R = ρ_r²φ (the
  // normal cone of E_R), i.e. v/(ωr) = 1 + ρ_r²φ/r
  const BodyState& s = sim.state()[0];
  const double rho_r = MuR() / kMu;
  const double ratio = Coupled(set()) ? 1.0 + rho_r * rho_r * ForceOverTorque(set()) / kRadius
                                      : 1.0;
  EXPECT_NEAR(s.linear_velocity.x() / (s.angular_velocity.y() * kRadius), ratio, 1e-6);
  // the stop: within two steps of v₀/a
  double stopped_at = -1.0;
  while (sim.time() < stop + 0.1) {
    sim.Step();
    if (stopped_at < 0.0 && sim.state()[0].linear_velocity.x() <= 1e-9) stopped_at = sim.time();
  }
  ASSERT_GT(stopped_at, 0.0) << "did not stop by " << stop + 0.1 << " s";
  EXPECT_NEAR(stopped_at, stop, 2.0 * kDt) << "closed form " << stop << " s";
  // and stays at rest for a second: no creep, no rocking
  const Eigen::Vector3d rest = sim.state()[0].position;
  double max_speed = 0.0;
  double max_spin = 0.0;
  while (sim.time() < stop + 1.1) {
    sim.Step();
    max_speed = std::max(max_speed, Speed(sim));
    max_spin = std::max(max_spin, Spin(sim));
  }
  EXPECT_LE(max_speed, 1e-12);
  EXPECT_LE(max_spin * kRadius, 1e-12);
  EXPECT_LE((sim.state()[0].position - rest).head<2>().norm(), 1e-12);
}

TEST_P(RollingBallStep, RestsBelowTheThresholdAngle) {
  const double theta = std::atan(0.99 * ThresholdTangent(set()));
  Simulator sim(RollingBall(set(), theta), Options(integrator()));
  // at rest: no creep over a second; the speed within what the solver's tolerance leaves
  // (tolerance_rel 1e-5 of Λ_T ~ m g sin θ Δt: ~1e-10 m/s, no drift)
  const Eigen::Vector3d rest = sim.state()[0].position;
  double max_speed = 0.0;
  while (sim.time() < 1.0) {
    sim.Step();
    max_speed = std::max(max_speed, Speed(sim));
  }
  EXPECT_LE(max_speed, 1e-9) << "tan theta = 0.99 tan theta* = " << std::tan(theta);
  EXPECT_LE((sim.state()[0].position - rest).norm(), 1e-12);
}

TEST_P(RollingBallStep, RollsAboveTheThresholdAngle) {
  const double theta = std::atan(1.01 * ThresholdTangent(set()));
  Simulator sim(RollingBall(set(), theta), Options(integrator()));
  while (sim.time() < 1.0) sim.Step();
  const double v = sim.state()[0].linear_velocity.x();
  // it rolls down: v grows (the decoupled set at (5/7)g(sin θ - (μ_r/r)cos θ))
  EXPECT_GT(v, 0.0);
  EXPECT_NEAR(sim.state()[0].angular_velocity.y() * kRadius / v, 1.0, 1e-2);
  if (!Coupled(set())) {
    const double a =
        5.0 / 7.0 * test::kGravity * (std::sin(theta) - MuR() / kRadius * std::cos(theta));
    EXPECT_NEAR(v / (a * sim.time()), 1.0, 5e-3) << "closed form " << a * sim.time();
  }
}

INSTANTIATE_TEST_SUITE_P(
    SetsAndIntegrators, RollingBallStep,
    ::testing::Combine(::testing::Values(FrictionSet::kRolling, FrictionSet::kRollingDecoupled),
                       ::testing::Values(Integrator::kMoreau, Integrator::kMoreau2)),
    [](const auto& info) {
      return std::string(FrictionSetName(std::get<0>(info.param))) + "_" +
             std::string(IntegratorName(std::get<1>(info.param)));
    });

TEST(RollingBallStepWithoutRolling, RollsOnAtConstantSpeed) {
  // μ_r = 0: the contact has no rolling components and nothing slows the ball
  Simulator sim(RollingBall(FrictionSet::kRolling, 0.0, 0.0f), Options(Integrator::kMoreau));
  StartRolling(&sim, kSpeed);
  while (sim.time() < 0.5) sim.Step();
  ASSERT_EQ(sim.contacts().size(), 1u);
  EXPECT_EQ(sim.contacts()[0].dimension, 4);
  EXPECT_EQ(sim.contacts()[0].rolling_percussion, Eigen::Vector2d::Zero());
  EXPECT_NEAR(sim.state()[0].linear_velocity.x(), kSpeed, 1e-12);
}

}  // namespace
}  // namespace nonsmooth_sim
