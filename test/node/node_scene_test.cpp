// A shipped scene through launch/scene.launch: the coin of config/coin.yaml (its start loaded
// as ~initial_state rosparams) spins flat on its face. Its face touches the ground at four face
// points named "coin/ground", 2r/3 from its axis (the drilling radius of uniform pressure) and
// without drilling components of their own, and the spin decays through the node as the core
// computes it: dω/dt = -(4/3) μ g / r.
#include <gtest/gtest.h>

#include <cmath>

#include "nonsmooth_sim/GetSimulationState.h"
#include "nonsmooth_sim/StepSimulation.h"
#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

// urdf/coin.urdf and config/coin.yaml
constexpr double kRadius = 0.012;
constexpr double kMu = 0.3;
constexpr double kGravity = 9.81;
constexpr double kSpin = 50.0;

double VerticalSpin(const SimulationState& state) { return state.bodies.at(0).twist.angular.z; }

TEST(NodeScene, CoinStartsFromItsYamlAndSpinsDownOnAFacePatch) {
  ros::NodeHandle nh;
  Recorder<ContactSteps> contacts(nh, kNode + "contacts");
  ASSERT_TRUE(WaitFor([&] { return contacts.Connected(); }, 20.0));

  // the start is the YAML's, not the URDF pose at rest
  const auto start = Call<GetSimulationState>(nh, kNode + "get_state");
  ASSERT_EQ(start.response.state.bodies.size(), 1u);
  EXPECT_EQ(start.response.state.bodies[0].name, "coin");
  EXPECT_NEAR(VerticalSpin(start.response.state), kSpin, 1e-12);
  EXPECT_NEAR(start.response.state.bodies[0].pose.position.z, 0.001, 1e-12);

  // 0.05 s of spinning (paused node, ~step)
  StepSimulation step;
  step.request.steps = 500;
  step = Call<StepSimulation>(nh, kNode + "step", step);
  ASSERT_TRUE(step.response.success) << step.response.status_message;
  const auto after = Call<GetSimulationState>(nh, kNode + "get_state");
  const double t = after.response.state.sim_time - start.response.state.sim_time;
  ASSERT_NEAR(t, 0.05, 1e-9);
  const double rate = (VerticalSpin(after.response.state) - kSpin) / t;
  // (4/3) μ g / r = 327 rad/s²; the patch law gives it to the solver tolerance
  EXPECT_NEAR(rate, -4.0 / 3.0 * kMu * kGravity / kRadius, 0.02 * 327.0);

  // the face lies flat: four face points, 2r/3 from the axis
  ASSERT_TRUE(contacts.WaitForMessage(
      [](const ContactInfoArray& m) { return !m.contacts.empty(); }, 20.0));
  const ContactInfoArray last = contacts.Messages().back();
  ASSERT_EQ(last.contacts.size(), 4u);
  const auto& centre = after.response.state.bodies[0].center_of_mass;
  for (const ContactInfo& c : last.contacts) {
    EXPECT_EQ(c.name, "coin/ground");
    EXPECT_EQ(c.collision, "coin");
    EXPECT_EQ(c.other_collision, "ground");
    EXPECT_EQ(c.average_friction_radius, 0.0);  // the spread carries the drilling torque
    // (points at the step's midpoint, the centre at its end: they differ by the drift, ~1e-8 m)
    EXPECT_NEAR(std::hypot(c.position.x - centre.x, c.position.y - centre.y), 2.0 * kRadius / 3.0,
                1e-6);
  }
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_scene_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
