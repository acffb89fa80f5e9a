// A block sliding on four sphere feet stops after the closed-form distance v0²/(2μg), for
// every friction set.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "dynamics_scenes.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"

namespace nonsmooth_sim {
namespace {

using test::AddGround;
using test::kGravity;
using test::Options;
using test::SphereCollider;

// A 1 kg block on four small spheres at its bottom corners (half base 0.1 m, centre of mass
// 0.06 m above the floor: it slides without tipping since μ·0.06 < 0.1).
Scene BlockScene(FrictionSet set, double mu, double speed) {
  Scene scene;
  RigidBody block;
  block.name = "block";
  block.mass = 1.0;
  block.inertia = Eigen::Vector3d(0.0042, 0.0042, 0.0067).asDiagonal();
  scene.bodies = {block};
  ContactLaw law;
  law.mu = mu;
  law.rbar = AverageFrictionRadius(5e-3);
  law.friction_set = set;
  for (double x : {-0.1, 0.1}) {
    for (double y : {-0.1, 0.1}) {
      const std::string name = "foot" + std::to_string(scene.colliders.size());
      scene.colliders.push_back(SphereCollider(name, 0, Eigen::Vector3d(x, y, -0.05), 0.01, law));
    }
  }
  AddGround(&scene);
  BodyState state;
  state.position = Eigen::Vector3d(0.0, 0.0, 0.06);
  state.linear_velocity = Eigen::Vector3d(speed, 0.0, 0.0);
  scene.initial_state = {state};
  return scene;
}

class SlidingBlock : public ::testing::TestWithParam<FrictionSet> {};

TEST_P(SlidingBlock, StopsAfterClosedFormDistance) {
  // v0 = 1 m/s, μ = 0.3: d = v0²/(2μg) = 0.16989 m, reached at t = v0/(μg) = 0.34 s. The block
  // rests on four contacts, a statically indeterminate normal problem: Gauss-Seidel converges on
  // it in stick, the Jacobi iterations need a relaxation α < 1 there (contact_solver.h).
  const double mu = 0.3;
  const double v0 = 1.0;
  SimulatorOptions options = Options(1e-3);
  options.solver.type = SolverType::kGaussSeidel;
  Simulator sim(BlockScene(GetParam(), mu, v0), options);
  const double x0 = sim.state()[0].position.x();
  double lowest = sim.state()[0].position.z();
  for (int k = 0; k < 500; ++k) {
    sim.Step();
    lowest = std::min(lowest, sim.state()[0].position.z());
  }
  const double distance = sim.state()[0].position.x() - x0;
  const double expected = v0 * v0 / (2.0 * mu * kGravity);
  // measured: relative error 1.6e-5 (coulomb, sphere) to 3.1e-5 (cylinder, ellipsoid, exact)
  EXPECT_NEAR(distance, expected, 5e-3 * expected) << FrictionSetName(GetParam());
  // at rest afterwards (measured |v| ≤ 4e-11 m/s, |ω| ≤ 1.2e-9 rad/s)
  EXPECT_LT(sim.state()[0].linear_velocity.norm(), 1e-9);
  EXPECT_LT(sim.state()[0].angular_velocity.norm(), 1e-8);
  // The strict index set (12) g(q_M) ≤ 0 sees feet at round-off gaps (+1e-17 m, from the
  // solver's tolerance-level rotation of the first step) as open, so the block rocks for a few
  // steps at the start and settles slightly lower: measured 3-4 μm (one lift of the gap
  // correction; 8-17 μm with gap_correction = false). Bounded, not drifting.
  EXPECT_GT(lowest, 0.06 - 5e-5);
}

INSTANTIATE_TEST_SUITE_P(AllFrictionSets, SlidingBlock, ::testing::ValuesIn(kAllFrictionSets),
                         [](const auto& info) { return std::string(FrictionSetName(info.param)); });

}  // namespace
}  // namespace nonsmooth_sim
