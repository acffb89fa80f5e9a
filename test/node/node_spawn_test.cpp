// ~spawn_urdf_model and ~delete_model (node_spawn_test.test: the Tippe-Top, paused, stepped here):
// - a second Tippe-Top spawned next to the running one (its URDF from the file, then given the
//   first one's pose and twist by ~set_model_state) appears in TF as "top2/tippe_top", its
//   robot_description is set, and both tops invert;
// - deleting it: its frames stop, its robot_description is gone, get_world_properties lists one
//   model;
// - the first top's state equals, bit for bit, the headless core simulating it alone from t = 0,
//   before the spawn, while the second top is there and after it is deleted (islands are solved
//   separately: a world with the other top steps this one exactly as a world without it);
// - bad spawns (a malformed URDF, an existing name, NaN in the pose, an unknown reference frame,
//   a name that is not a graph name) and deleting an unknown model are refused with the reason
//   and change nothing (~get_state bit-identical);
// - a deleted model's ~wrench/ topic stays advertised, silent, and serves its next spawn.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/WrenchStamped.h>
#include <gtest/gtest.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>

#include "nonsmooth_sim/DeleteModel.h"
#include "nonsmooth_sim/GetModelState.h"
#include "nonsmooth_sim/GetSimulationState.h"
#include "nonsmooth_sim/GetWorldProperties.h"
#include "nonsmooth_sim/SetModelState.h"
#include "nonsmooth_sim/SpawnModel.h"
#include "nonsmooth_sim/StepSimulation.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

constexpr double kInverted = 2.9;  // θ > 2.9 rad: spinning on the peg
constexpr double kOffset = 0.5;    // the second top's distance from the first [m]
const std::string kTippeTopUrdf = std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/urdf/tippe_top.urdf";

class Spawn : public testing::Test {
 protected:
  SimulationState State() {
    return Call<GetSimulationState>(nh_, kNode + "get_state").response.state;
  }
  void Step(std::uint32_t steps) {
    StepSimulation srv;
    srv.request.steps = steps;
    srv = Call<StepSimulation>(nh_, kNode + "step", srv);
    ASSERT_TRUE(srv.response.success) << srv.response.status_message;
  }
  SpawnModel::Response SpawnTop(const std::string& name, const std::string& xml, double x) {
    SpawnModel srv;
    srv.request.model_name = name;
    srv.request.model_xml = xml;
    srv.request.initial_pose.position.x = x;
    srv.request.initial_pose.orientation.w = 1.0;
    return Call<SpawnModel>(nh_, kNode + "spawn_urdf_model", srv).response;
  }
  std::vector<std::string> Models() {
    return Call<GetWorldProperties>(nh_, kNode + "get_world_properties").response.model_names;
  }
  ros::NodeHandle nh_;
};

// The node's first body equals the headless top, bit for bit.
void ExpectSameAsHeadless(const SimulationState& node, const Simulator& headless,
                          const char* when) {
  ASSERT_FALSE(node.bodies.empty()) << when;
  const BodyInfo& b = node.bodies.front();
  const BodyState& s = headless.state()[0];
  EXPECT_EQ(node.sim_time, headless.time()) << when;
  EXPECT_EQ(b.center_of_mass.x, s.position.x()) << when;
  EXPECT_EQ(b.center_of_mass.y, s.position.y()) << when;
  EXPECT_EQ(b.center_of_mass.z, s.position.z()) << when;
  EXPECT_EQ(b.pose.orientation.w, s.orientation.w()) << when;
  EXPECT_EQ(b.pose.orientation.x, s.orientation.x()) << when;
  EXPECT_EQ(b.angular_velocity_body.x, s.angular_velocity.x()) << when;
  EXPECT_EQ(b.angular_velocity_body.z, s.angular_velocity.z()) << when;
  EXPECT_EQ(b.twist.linear.x, s.linear_velocity.x()) << when;
  EXPECT_EQ(b.inclination, Inclination(s)) << when;
}

// The value of key `key` in a /diagnostics message of the node, "" without it.
std::string DiagnosticValue(const diagnostic_msgs::DiagnosticArray& m, const std::string& key) {
  for (const auto& status : m.status) {
    for (const auto& kv : status.values) {
      if (kv.key == key) return kv.value;
    }
  }
  return "";
}

// Child frames of the /tf messages in `messages`.
std::set<std::string> ChildFrames(const std::vector<tf2_msgs::TFMessage>& messages) {
  std::set<std::string> frames;
  for (const auto& m : messages) {
    for (const auto& t : m.transforms) frames.insert(t.child_frame_id);
  }
  return frames;
}

TEST_F(Spawn, ASecondTopInvertsAndItsDeletionLeavesTheFirstExactlyAsAlone) {
  Recorder<tf2_msgs::TFMessage> tf(nh_, "/tf", 1000000);
  Recorder<diagnostic_msgs::DiagnosticArray> diagnostics(nh_, "/diagnostics");
  Simulator headless = HeadlessTippeTop(nh_);
  const std::string xml = ReadFile(kTippeTopUrdf);
  ASSERT_FALSE(xml.empty());

  // connected: step (paused) 10 at a time until /tf flows, then to 0.1 s alone
  std::uint32_t steps = 0;
  ASSERT_TRUE(WaitFor(
      [&] {
        if (tf.Count() > 0) return true;
        Step(10);
        steps += 10;
        return WaitFor([&] { return tf.Count() > 0; }, 0.2);
      },
      20.0));
  ASSERT_LT(steps, 1000u);
  Step(1000 - steps);
  for (int k = 0; k < 1000; ++k) headless.Step();
  ExpectSameAsHeadless(State(), headless, "before the spawn");

  const SpawnModel::Response spawned = SpawnTop("top2", xml, kOffset);
  ASSERT_TRUE(spawned.success) << spawned.status_message;
  EXPECT_EQ(Models(), (std::vector<std::string>{"tippe_top", "top2"}));
  std::string description;
  EXPECT_TRUE(nh_.getParam("/top2/robot_description", description));
  EXPECT_EQ(description, xml);

  // the second top: the first one's pose and twist, kOffset along x
  GetModelState get;
  get.request.model_name = "tippe_top";
  const GetModelState::Response first =
      Call<GetModelState>(nh_, kNode + "get_model_state", get).response;
  ASSERT_TRUE(first.success) << first.status_message;
  SetModelState set;
  set.request.model_state.model_name = "top2";
  set.request.model_state.pose = first.pose;
  set.request.model_state.pose.position.x += kOffset;
  set.request.model_state.twist = first.twist;
  const auto moved = Call<SetModelState>(nh_, kNode + "set_model_state", set).response;
  ASSERT_TRUE(moved.success) << moved.status_message;

  // both invert (2.9 s more: the Tippe-Top is spinning on its peg by 3 s)
  for (int chunk = 0; chunk < 29; ++chunk) Step(1000);
  for (int k = 0; k < 29000; ++k) headless.Step();
  const SimulationState both = State();
  ASSERT_EQ(both.bodies.size(), 2u);
  EXPECT_EQ(both.bodies[1].name, "top2/tippe_top");
  EXPECT_GT(both.bodies[0].inclination, kInverted);
  EXPECT_GT(both.bodies[1].inclination, kInverted);
  ExpectSameAsHeadless(both, headless, "with the second top");
  // both in TF (the tf channel publishes every 10 steps)
  ASSERT_TRUE(tf.WaitForMessage(
      [](const tf2_msgs::TFMessage& m) {
        return m.transforms.front().header.stamp.toSec() > 3.0 - 1e-6;
      },
      20.0));
  const std::set<std::string> with = ChildFrames(tf.Messages());
  EXPECT_EQ(with.count("tippe_top"), 1u);
  EXPECT_EQ(with.count("top2/tippe_top"), 1u);
  // /diagnostics (1 Hz of wall time) counts both: each top on the ground is its own island
  EXPECT_TRUE(diagnostics.WaitForMessage(
      [](const diagnostic_msgs::DiagnosticArray& m) {
        return DiagnosticValue(m, "models") == "2" && DiagnosticValue(m, "bodies") == "2" &&
               DiagnosticValue(m, "contact islands (problems solved in the last step)") == "2";
      },
      20.0));

  DeleteModel remove;
  remove.request.model_name = "top2";
  const auto deleted = Call<DeleteModel>(nh_, kNode + "delete_model", remove).response;
  ASSERT_TRUE(deleted.success) << deleted.status_message;
  EXPECT_EQ(Models(), std::vector<std::string>{"tippe_top"});
  EXPECT_FALSE(nh_.hasParam("/top2/robot_description"));
  tf.Clear();

  Step(1000);
  for (int k = 0; k < 1000; ++k) headless.Step();
  const SimulationState alone = State();
  ASSERT_EQ(alone.bodies.size(), 1u);
  ExpectSameAsHeadless(alone, headless, "after the deletion");
  ASSERT_TRUE(tf.WaitForMessage(
      [](const tf2_msgs::TFMessage& m) {
        return m.transforms.front().header.stamp.toSec() > 3.1 - 1e-6;
      },
      20.0));
  const std::set<std::string> after = ChildFrames(tf.Messages());
  EXPECT_EQ(after.count("tippe_top"), 1u);
  for (const std::string& frame : after) {
    EXPECT_NE(frame.rfind("top2", 0), 0u) << frame << " still published";
  }
}

TEST_F(Spawn, BadRequestsAreRefusedAndChangeNothing) {
  const std::string xml = ReadFile(kTippeTopUrdf);
  const SimulationState before = State();
  const std::vector<std::string> models = Models();
  auto refused = [&](const SpawnModel::Response& res, const std::string& expected) {
    EXPECT_FALSE(res.success) << expected;
    EXPECT_NE(res.status_message.find(expected), std::string::npos) << res.status_message;
    EXPECT_NE(res.status_message.find("nothing changed"), std::string::npos) << res.status_message;
  };
  refused(SpawnTop("bad", "<robot name='x'><link", 1.0), "urdf:");
  refused(SpawnTop("tippe_top", xml, 1.0), "exists already");
  refused(SpawnTop("a/b", xml, 1.0), "model_name");
  refused(SpawnTop("nan", xml, std::numeric_limits<double>::quiet_NaN()), "initial_pose.position");
  refused(SpawnTop("far", xml, 1e9), "initial_pose.position");
  SpawnModel frame;
  frame.request.model_name = "framed";
  frame.request.model_xml = xml;
  frame.request.initial_pose.orientation.w = 1.0;
  frame.request.reference_frame = "nope::link";
  refused(Call<SpawnModel>(nh_, kNode + "spawn_urdf_model", frame).response, "reference_frame");
  frame.request.reference_frame.clear();
  frame.request.initial_pose.orientation.w = 0.0;
  refused(Call<SpawnModel>(nh_, kNode + "spawn_urdf_model", frame).response, "orientation");
  DeleteModel remove;
  remove.request.model_name = "nope";
  const auto deleted = Call<DeleteModel>(nh_, kNode + "delete_model", remove).response;
  EXPECT_FALSE(deleted.success);
  EXPECT_NE(deleted.status_message.find("tippe_top"), std::string::npos) << deleted.status_message;

  EXPECT_EQ(Models(), models);
  ExpectSameBodies(before, State());
  EXPECT_EQ(before.sim_time, State().sim_time);
}

// A deleted model's ~wrench/ topic sends a last zero wrench, stays advertised without messages
// (unadvertising would call the master under roscpp's publication lock, which the stepping takes:
// node_master_test) and serves the next model that has that collision name.
TEST_F(Spawn, ADeletedModelsWrenchTopicIsKeptForItsNextSpawn) {
  const std::string xml = ReadFile(kTippeTopUrdf);
  const std::string topic = kNode + "wrench/w1/big_sphere";
  Recorder<geometry_msgs::WrenchStamped> wrench(nh_, topic);
  const auto is_load = [](const geometry_msgs::WrenchStamped& m) {
    return m.header.frame_id == "w1/big_sphere_contact" && m.wrench.force.z > 0.0;
  };
  const auto is_zero = [](const geometry_msgs::WrenchStamped& m) {
    return m.wrench.force.x == 0.0 && m.wrench.force.y == 0.0 && m.wrench.force.z == 0.0 &&
           m.wrench.torque.x == 0.0 && m.wrench.torque.y == 0.0 && m.wrench.torque.z == 0.0;
  };
  // step (paused) until the top on the ground sends its load: the subscriber is connected
  const auto loaded = [&] {
    return WaitFor(
        [&] {
          Step(100);
          return wrench.WaitForMessage(is_load, 0.1);
        },
        30.0);
  };
  for (int round = 0; round < 2; ++round) {
    const SpawnModel::Response spawned = SpawnTop("w1", xml, -kOffset);
    ASSERT_TRUE(spawned.success) << spawned.status_message;
    ASSERT_TRUE(loaded()) << "round " << round << ": no load on " << topic;
    DeleteModel remove;
    remove.request.model_name = "w1";
    const auto deleted = Call<DeleteModel>(nh_, kNode + "delete_model", remove).response;
    ASSERT_TRUE(deleted.success) << deleted.status_message;
    ASSERT_TRUE(wrench.WaitForMessage(is_zero, 10.0)) << "no last zero wrench";
    std::vector<std::string> publishers;
    XmlRpc::XmlRpcValue request, response, state;
    request[0] = ros::this_node::getName();
    ASSERT_TRUE(ros::master::execute("getSystemState", request, response, state, true));
    for (int i = 0; i < state[0].size(); ++i) {
      if (static_cast<std::string>(state[0][i][0]) != topic) continue;
      for (int k = 0; k < state[0][i][1].size(); ++k) {
        publishers.push_back(static_cast<std::string>(state[0][i][1][k]));
      }
    }
    EXPECT_EQ(publishers, std::vector<std::string>{"/nonsmooth_sim"}) << "kept advertised";
    wrench.Clear();
    Step(500);
    ros::WallDuration(0.2).sleep();
    EXPECT_EQ(wrench.Count(), 0u) << "a deleted model's topic is silent";
  }
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_spawn_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
