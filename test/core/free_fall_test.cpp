// Free fall under the Moreau midpoint step against its closed form: exact positions and
// velocities, energy conserved to round-off.
#include <gtest/gtest.h>

#include <cmath>

#include "dynamics_scenes.h"
#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim {
namespace {

using test::BallScene;
using test::Options;

TEST(FreeFall, PositionAndVelocityAreExact) {
  // (13), (15), (18) integrate constant gravity exactly: r = r0 + v0 t + ½ g t², v = v0 + g t
  Scene scene = BallScene(0.05, 100.0, 0.0, 0.3);
  scene.initial_state[0].linear_velocity = Eigen::Vector3d(1.0, -2.0, 3.0);
  scene.initial_state[0].angular_velocity = Eigen::Vector3d(0.0, 0.0, 5.0);
  const BodyState start = scene.initial_state[0];
  Simulator sim(scene, Options(1e-3));
  const int steps = 2000;
  for (int k = 0; k < steps; ++k) {
    const StepStatistics stats = sim.Step();
    ASSERT_EQ(stats.closed_contacts, 0);
  }
  const double t = steps * 1e-3;
  const Eigen::Vector3d g = scene.gravity;
  const Eigen::Vector3d r = start.position + start.linear_velocity * t + 0.5 * g * t * t;
  const Eigen::Vector3d v = start.linear_velocity + g * t;
  // measured: 4e-13 m and 7e-14 m/s (round-off of 2000 additions)
  EXPECT_LT((sim.state()[0].position - r).norm(), 1e-11);
  EXPECT_LT((sim.state()[0].linear_velocity - v).norm(), 1e-11);
  EXPECT_NEAR(sim.time(), t, 1e-12);
  // a ball spinning about a principal axis keeps its spin exactly
  EXPECT_NEAR((sim.state()[0].angular_velocity - start.angular_velocity).norm(), 0.0, 1e-12);
}

TEST(FreeFall, EnergyIsConservedToRoundOff) {
  // ΔE = m v_M·g Δt - m g·Δt v_M = 0 per step
  Scene scene = BallScene(0.05, 100.0, 0.0, 0.3);
  scene.initial_state[0].linear_velocity = Eigen::Vector3d(0.5, 0.0, 4.0);
  Simulator sim(scene, Options(1e-3));
  const double e0 = sim.Energy();
  for (int k = 0; k < 2000; ++k) sim.Step();
  EXPECT_NEAR(sim.Energy(), e0, 1e-12 * std::abs(e0) + 1e-12);
}

}  // namespace
}  // namespace nonsmooth_sim
