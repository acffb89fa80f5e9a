// A model of the user's own through the shipped launch files, with no start given
// (node_launch_model_test.test: scene.launch model:=coin.urdf; node_launch_model_tippe.test:
// tippe_top.launch model:=coin.urdf; both paused): the node starts and the body rests at its URDF
// pose, as the loader gives it. Neither the scene's start nor the Tippe-Top's tilt and spin reach
// it: before, scene.launch stopped with "bodies.tippe_top: not a free body of the scene" and
// tippe_top.launch spun the coin at 180 rad/s.
#include <gtest/gtest.h>

#include <string>

#include "nonsmooth_sim/GetSimulationState.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

TEST(LaunchModel, AModelOfYourOwnStartsAtItsUrdfPoseAtRest) {
  ros::NodeHandle nh;
  const SimulationState state =
      Call<GetSimulationState>(nh, kNode + "get_state").response.state;
  const scene_io::UrdfScene urdf =
      scene_io::LoadUrdfFile(std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/urdf/coin.urdf");
  ASSERT_EQ(state.bodies.size(), 1u);
  const BodyInfo& b = state.bodies.front();
  const BodyState& expected = urdf.scene.initial_state.front();
  EXPECT_EQ(b.name, "coin");
  EXPECT_EQ(state.sim_time, 0.0);
  EXPECT_EQ(b.center_of_mass.x, expected.position.x());
  EXPECT_EQ(b.center_of_mass.y, expected.position.y());
  EXPECT_EQ(b.center_of_mass.z, expected.position.z());
  EXPECT_EQ(b.pose.orientation.w, expected.orientation.w());
  EXPECT_EQ(b.pose.orientation.x, expected.orientation.x());
  EXPECT_EQ(b.pose.orientation.y, expected.orientation.y());
  EXPECT_EQ(b.pose.orientation.z, expected.orientation.z());
  EXPECT_EQ(b.angular_velocity_body.x, 0.0);
  EXPECT_EQ(b.angular_velocity_body.y, 0.0);
  EXPECT_EQ(b.angular_velocity_body.z, 0.0);
  EXPECT_EQ(b.twist.linear.x, 0.0);
  EXPECT_EQ(b.twist.linear.y, 0.0);
  EXPECT_EQ(b.twist.linear.z, 0.0);
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_launch_model_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
