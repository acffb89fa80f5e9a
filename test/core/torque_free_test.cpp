// Torque-free rotation and the gyroscopic term: the explicit scheme keeps the world angular
// momentum and gains energy by ½Δt²·(its closed form), the implicit midpoint keeps energy and
// |L| and solves its equation, and the diagonal-inertia products equal the full ones.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "dynamics_scenes.h"
#include "nonsmooth_sim/core/rigid_body_dynamics.h"
#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim {
namespace {

using test::Options;

// An asymmetric body without contacts.
Scene FreeBodyScene(const Eigen::Vector3d& omega) {
  Scene scene;
  RigidBody body;
  body.name = "brick";
  body.mass = 0.5;
  body.inertia = Eigen::Vector3d(2e-3, 3e-3, 4e-3).asDiagonal();
  scene.bodies = {body};
  BodyState state;
  state.orientation =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  state.angular_velocity = omega;
  scene.initial_state = {state};
  return scene;
}

double RotationalEnergy(const Simulator& sim) {
  const BodyState& s = sim.state()[0];
  return 0.5 * s.angular_velocity.dot(sim.scene().bodies[0].inertia * s.angular_velocity);
}
Eigen::Vector3d BodyAngularMomentum(const Simulator& sim) {
  return sim.scene().bodies[0].inertia * sim.state()[0].angular_velocity;
}
Eigen::Vector3d WorldAngularMomentum(const Simulator& sim) {
  return sim.state()[0].orientation * BodyAngularMomentum(sim);
}

TEST(TorqueFree, ExplicitSchemeKeepsWorldAngularMomentum) {
  // spin near the major axis: L = AΘω is constant in the world frame. The explicit scheme's
  // error is first order: measured relative drift 7.5e-6 at Δt = 1e-4, 1.5e-5 at 2e-4 over 1 s.
  double drift[2];
  const double dts[2] = {1e-4, 2e-4};
  for (int run = 0; run < 2; ++run) {
    Simulator sim(FreeBodyScene(Eigen::Vector3d(0.3, -0.2, 10.0)), Options(dts[run]));
    const Eigen::Vector3d l0 = WorldAngularMomentum(sim);
    const int steps = static_cast<int>(std::lround(1.0 / dts[run]));
    drift[run] = 0.0;
    for (int k = 0; k < steps; ++k) {
      sim.Step();
      drift[run] = std::max(drift[run], (WorldAngularMomentum(sim) - l0).norm() / l0.norm());
    }
  }
  EXPECT_LT(drift[0], 1e-3);
  // and it converges: halving Δt at least roughly halves the drift
  EXPECT_LT(drift[0], 0.7 * drift[1]);
}

TEST(TorqueFree, ImplicitMidpointKeepsEnergyAndAngularMomentumMagnitude) {
  // a tumbling asymmetric body (ω with components on all axes), 1e5 steps: the implicit midpoint
  // rule conserves ½ωᵀΘω and |Θω| exactly, up to round-off
  const Eigen::Vector3d omega0(3.0, 2.0, 5.0);
  Simulator sim(FreeBodyScene(omega0), Options(1e-3, GyroscopicScheme::kImplicitMidpoint));
  const double t0 = RotationalEnergy(sim);
  const double l0 = BodyAngularMomentum(sim).norm();
  double energy_error = 0.0;
  double momentum_error = 0.0;
  for (int k = 0; k < 100000; ++k) {
    sim.Step();
    energy_error = std::max(energy_error, std::abs(RotationalEnergy(sim) - t0) / t0);
    momentum_error = std::max(momentum_error, std::abs(BodyAngularMomentum(sim).norm() - l0) / l0);
  }
  // measured: 2.6e-14 and 1.3e-14 (the world-frame vector L drifts by 1.2e-6: the orientation
  // update (15) is not part of the conserving scheme)
  EXPECT_LT(energy_error, 1e-12);
  EXPECT_LT(momentum_error, 1e-12);
  // it really moved: the body tumbles, ω is far from its start
  EXPECT_GT((sim.state()[0].angular_velocity - omega0).norm(), 0.1);

  // control: the explicit scheme fails the same bound by orders of magnitude
  Simulator explicit_sim(FreeBodyScene(omega0), Options(1e-3));
  for (int k = 0; k < 1000; ++k) explicit_sim.Step();
  EXPECT_GT(std::abs(RotationalEnergy(explicit_sim) - t0) / t0, 1e-6);
}

TEST(TorqueFree, ExplicitEnergyGainIsHalfDtSquaredATimesThetaA) {
  // one explicit step: ω_E = ω_B + Δt a, a = Θ⁻¹(-ω×Θω), so ΔT = ω_BᵀΘ(Δt a) + ½Δt² aᵀΘa and the
  // first term vanishes (ω·(ω×Θω) = 0)
  const Eigen::Vector3d omega(3.0, 2.0, 5.0);
  Simulator sim(FreeBodyScene(omega), Options(1e-3));
  const Eigen::Matrix3d theta = sim.scene().bodies[0].inertia;
  const Eigen::Vector3d a = theta.inverse() * GyroscopicTorque(theta, omega);
  const double expected = 0.5 * 1e-6 * a.dot(theta * a);
  const double before = RotationalEnergy(sim);
  sim.Step();
  EXPECT_NEAR(RotationalEnergy(sim) - before, expected, 1e-6 * expected);
  EXPECT_GT(expected, 0.0);
}

TEST(TorqueFree, ExplicitEnergyGainPerStepScalesWithDtSquared) {
  // largest per-step energy increase over the same 0.2 s at Δt and Δt/2: theory 4, required ≥ 3
  double largest[2];
  const double dts[2] = {1e-3, 5e-4};
  for (int run = 0; run < 2; ++run) {
    Simulator sim(FreeBodyScene(Eigen::Vector3d(3.0, 2.0, 5.0)), Options(dts[run]));
    largest[run] = 0.0;
    double previous = sim.Energy();
    const int steps = static_cast<int>(std::lround(0.2 / dts[run]));
    for (int k = 0; k < steps; ++k) {
      sim.Step();
      largest[run] = std::max(largest[run], sim.Energy() - previous);
      previous = sim.Energy();
    }
  }
  ASSERT_GT(largest[1], 0.0);
  // measured ratio 4.000
  EXPECT_GE(largest[0] / largest[1], 3.0);
  EXPECT_LE(largest[0] / largest[1], 5.0);
}

TEST(TorqueFree, ImplicitMidpointSolvesItsEquation) {
  // the returned ω_E satisfies Θ(ω_E - ω_B) = -Δt ω_M×Θω_M + impulse to round-off
  const BodyInertia body = MakeBodyInertia(0.5, Eigen::Vector3d(2e-3, 3e-3, 4e-3).asDiagonal());
  const Eigen::Vector3d omega_b(30.0, -20.0, 50.0);
  const Eigen::Vector3d impulse(1e-4, 2e-4, -3e-4);
  const double dt = 1e-3;
  const Eigen::Vector3d omega_e = ImplicitMidpointEuler(body, omega_b, impulse, dt, omega_b);
  const Eigen::Vector3d mid = 0.5 * (omega_b + omega_e);
  const Eigen::Vector3d residual =
      body.inertia * (omega_e - omega_b) + dt * mid.cross(body.inertia * mid) - impulse;
  EXPECT_LT(residual.norm(), 1e-15);
}

TEST(TorqueFree, DiagonalInertiaProductsEqualTheFullProducts) {
  // InverseInertiaTimes and GyroscopicTorque(BodyInertia) take three products where Θ is diagonal
  // (the step's path for principal bodies): the full 3 × 3 products' values exactly, and the full
  // products themselves for a body whose Θ is not diagonal
  std::mt19937 random(20261203);
  std::uniform_real_distribution<double> uniform(-200.0, 200.0);
  std::uniform_real_distribution<double> moment(1e-5, 1e-1);
  const Eigen::Matrix3d off_diagonal =
      (Eigen::Matrix3d() << 0.0, 1.0, -2.0, 1.0, 0.0, 0.5, -2.0, 0.5, 0.0).finished();
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d diagonal(moment(random), moment(random), moment(random));
    const BodyInertia principal = MakeBodyInertia(0.3, diagonal.asDiagonal());
    // diagonally dominant: positive definite
    const Eigen::Matrix3d full_inertia =
        Eigen::Matrix3d(diagonal.asDiagonal()) + 0.01 * diagonal.minCoeff() * off_diagonal;
    const BodyInertia general = MakeBodyInertia(0.3, full_inertia);
    ASSERT_TRUE(principal.principal);
    ASSERT_FALSE(general.principal);
    const Eigen::Vector3d x(uniform(random), uniform(random), uniform(random));
    for (const BodyInertia* body : {&principal, &general}) {
      const Eigen::Vector3d inverse_full = body->inverse_inertia * x;
      const Eigen::Vector3d gyroscopic_full = GyroscopicTorque(body->inertia, x);
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(InverseInertiaTimes(*body, x)[k], inverse_full[k]);
        EXPECT_EQ(GyroscopicTorque(*body, x)[k], gyroscopic_full[k]);
      }
    }
  }
}

}  // namespace
}  // namespace nonsmooth_sim
