// The extrapolated warm start (SimulatorOptions::extrapolate_warm_start, simulator.h): against the
// plain one (the last step's percussion) it must give the same motion within the solver's
// tolerance, save iterations where the percussions change smoothly, and cost none where the
// solution is not unique (two feet that roll and stick can squeeze each other in any amount).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "scene_builders.h"

namespace nonsmooth_sim {
namespace {

struct Trajectory {
  std::vector<BodyState> states;  // after every step
  long iterations = 0;            // summed over the steps
};

Trajectory Simulate(const Scene& scene, bool extrapolate, int steps) {
  SimulatorOptions options;
  options.extrapolate_warm_start = extrapolate;
  Simulator sim(scene, options);
  Trajectory run;
  StepStatistics stats;
  for (int k = 0; k < steps; ++k) {
    sim.Step(&stats);
    EXPECT_TRUE(stats.state_finite);
    run.iterations += stats.solver.iterations;
    run.states.push_back(sim.state()[0]);
  }
  return run;
}

class TippeTopWarmStart : public ::testing::TestWithParam<FrictionSet> {};

TEST_P(TippeTopWarmStart, ExtrapolatedKeepsTheMotionAndSavesIterations) {
  TippeTopParameters parameters;
  parameters.friction_set = GetParam();
  const Scene scene = MakeTippeTopScene(parameters);
  // through the inversion and the peg's touchdown (θ > 2.4 rad at 1.32 s, peg at 1.37 s)
  constexpr int kSteps = 16000;
  const Trajectory plain = Simulate(scene, false, kSteps);
  const Trajectory extrapolated = Simulate(scene, true, kSteps);
  double largest = 0.0;
  int inverted_plain = -1;
  int inverted_extrapolated = -1;
  for (int k = 0; k < kSteps; ++k) {
    const double a = Inclination(plain.states[static_cast<std::size_t>(k)]);
    const double b = Inclination(extrapolated.states[static_cast<std::size_t>(k)]);
    largest = std::max(largest, std::abs(a - b));
    if (inverted_plain < 0 && a > 2.4) inverted_plain = k;
    if (inverted_extrapolated < 0 && b > 2.4) inverted_extrapolated = k;
  }
  // the start only decides where the iteration begins: θ(t) agrees within the solver's
  // tolerance (1e-5 relative on the percussions), the inversion in the same step
  EXPECT_LT(largest, 1e-6);
  ASSERT_GT(inverted_plain, 0);
  EXPECT_EQ(inverted_extrapolated, inverted_plain);
  // the top slides smoothly on one contact most of the time: far fewer iterations
  // (measured 0.70 of the plain start's over these 1.6 s with sphere and exact, 0.57 over 8 s)
  EXPECT_LT(static_cast<double>(extrapolated.iterations), 0.75 * plain.iterations)
      << "plain " << plain.iterations << ", extrapolated " << extrapolated.iterations;
}

INSTANTIATE_TEST_SUITE_P(Sets, TippeTopWarmStart,
                         ::testing::Values(FrictionSet::kSphere, FrictionSet::kExact),
                         [](const auto& info) { return std::string(FrictionSetName(info.param)); });

// A dumbbell (two spheres on one body) launched sliding and turning: it soon rolls on both feet,
// sticking. Then a squeeze along its axis (equal and opposite tangential percussions at the two
// feet) moves nothing, so any amount of it solves the contact problem; a start extrapolated along
// it would be accepted, and the squeeze would grow step after step until the friction cones stop
// it, costing iterations there. Islands of sticking contacts are therefore not extrapolated.
TEST(WarmStart, TwoStickingFeetDoNotDrift) {
  Scene scene;
  RigidBody body;
  body.name = "dumbbell";
  body.mass = 1.0;
  body.inertia = Eigen::Vector3d(2e-4, 1e-2, 1e-2).asDiagonal();
  scene.bodies.push_back(body);
  ContactLaw law;
  law.mu = 0.3;
  law.rbar = AverageFrictionRadius(2e-4);
  scene.colliders.push_back(test::SphereCollider("a", 0, Eigen::Vector3d(0.1, 0, 0), 0.02, law));
  scene.colliders.push_back(test::SphereCollider("b", 0, Eigen::Vector3d(-0.1, 0, 0), 0.02, law));
  test::AddGround(&scene);
  BodyState start;
  start.position = Eigen::Vector3d(0, 0, 0.02);
  start.linear_velocity = Eigen::Vector3d(0.3, 0.2, 0);
  start.angular_velocity = Eigen::Vector3d(0, 0, 3);
  scene.initial_state = {start};

  constexpr int kSteps = 20000;  // 2 s: sliding, then rolling on both feet
  const Trajectory plain = Simulate(scene, false, kSteps);
  const Trajectory extrapolated = Simulate(scene, true, kSteps);
  // the same motion within the tolerance
  double largest = 0.0;
  for (int k = 0; k < kSteps; ++k) {
    const BodyState& a = plain.states[static_cast<std::size_t>(k)];
    const BodyState& b = extrapolated.states[static_cast<std::size_t>(k)];
    largest = std::max(largest, (a.position - b.position).norm());
  }
  EXPECT_LT(largest, 1e-6);
  // still rolling at the end (the phase the test is about)
  EXPECT_GT(plain.states.back().linear_velocity.head<2>().norm(), 0.05);
  // no more iterations than the plain start (measured 0.90 of them; extrapolating these islands
  // too took 2.7 times as many: the squeeze drifted)
  EXPECT_LE(static_cast<double>(extrapolated.iterations), 1.05 * plain.iterations)
      << "plain " << plain.iterations << ", extrapolated " << extrapolated.iterations;
}

}  // namespace
}  // namespace nonsmooth_sim
