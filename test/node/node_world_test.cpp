// The world services (node_world_test.test: two 1 kg blocks at rest on the ground, "slider"
// frictionless, "sticker" with mu = 0.5; paused, stepped here):
// - get_world_properties / get_model_properties name the model, its bodies and collisions;
// - set_model_state then get_model_state returns what was set (1e-12);
// - bad requests (unknown model, body or frame, NaN, a zero quaternion) are refused with a reason
//   and ~get_state is bit-identical before and after;
// - apply_body_wrench on the frictionless block: its momentum grows by F times the requested
//   interval exactly (the steps it partly overlaps get the fraction), a = F/m while it acts, and
//   not at all after; on the block with friction a force below mu m g leaves it at rest.
#include <gtest/gtest.h>
#include <std_srvs/Empty.h>

#include <cmath>
#include <limits>

#include "nonsmooth_sim/ApplyBodyWrench.h"
#include "nonsmooth_sim/BodyRequest.h"
#include "nonsmooth_sim/GetModelProperties.h"
#include "nonsmooth_sim/GetModelState.h"
#include "nonsmooth_sim/GetSimulationState.h"
#include "nonsmooth_sim/GetWorldProperties.h"
#include "nonsmooth_sim/SetModelState.h"
#include "nonsmooth_sim/StepSimulation.h"
#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

const std::string kNode = "/nonsmooth_sim/";
constexpr double kMass = 1.0;     // two_blocks.urdf
constexpr double kDt = 1e-4;      // the node's default ~time_step
constexpr double kGravity = 9.81;

class World : public testing::Test {
 protected:
  SimulationState State() {
    return Call<GetSimulationState>(nh_, kNode + "get_state").response.state;
  }
  const BodyInfo& Body(const SimulationState& s, const std::string& name) {
    for (const BodyInfo& b : s.bodies) {
      if (b.name == name) return b;
    }
    ADD_FAILURE() << "no body " << name;
    return s.bodies.front();
  }
  void Step(std::uint32_t steps) {
    StepSimulation srv;
    srv.request.steps = steps;
    srv = Call<StepSimulation>(nh_, kNode + "step", srv);
    ASSERT_TRUE(srv.response.success) << srv.response.status_message;
  }
  ApplyBodyWrench::Response Apply(const std::string& body, double fx, double start,
                                  double duration) {
    ApplyBodyWrench srv;
    srv.request.body_name = body;
    srv.request.wrench.force.x = fx;
    srv.request.start_time = ros::Time(start);
    srv.request.duration = ros::Duration(duration);
    return Call<ApplyBodyWrench>(nh_, kNode + "apply_body_wrench", srv).response;
  }
  ros::NodeHandle nh_;
};

TEST_F(World, PropertiesNameTheModelItsBodiesAndCollisions) {
  const auto world = Call<GetWorldProperties>(nh_, kNode + "get_world_properties").response;
  EXPECT_TRUE(world.success);
  ASSERT_EQ(world.model_names, std::vector<std::string>{"blocks"});
  GetModelProperties srv;
  srv.request.model_name = "blocks";
  const auto model = Call<GetModelProperties>(nh_, kNode + "get_model_properties", srv).response;
  EXPECT_TRUE(model.success) << model.status_message;
  EXPECT_EQ(model.body_names, (std::vector<std::string>{"slider", "sticker"}));
  EXPECT_EQ(model.canonical_body_name, "slider");
  EXPECT_EQ(model.geom_names, (std::vector<std::string>{"slider_box", "sticker_box"}));
  EXPECT_FALSE(model.is_static);
  srv.request.model_name = "nope";
  const auto unknown = Call<GetModelProperties>(nh_, kNode + "get_model_properties", srv).response;
  EXPECT_FALSE(unknown.success);
  EXPECT_NE(unknown.status_message.find("blocks"), std::string::npos) << unknown.status_message;
}

TEST_F(World, BadRequestsAreRefusedAndChangeNothing) {
  const SimulationState before = State();
  SetModelState set;
  set.request.model_state.model_name = "blocks";
  set.request.model_state.pose.orientation.w = 1.0;
  set.request.model_state.pose.position.z = 0.5;
  auto refused = [&](SetModelState srv, const std::string& why) {
    const auto res = Call<SetModelState>(nh_, kNode + "set_model_state", srv).response;
    EXPECT_FALSE(res.success) << why;
    EXPECT_NE(res.status_message.find("nothing changed"), std::string::npos) << why;
  };
  SetModelState s = set;
  s.request.model_state.model_name = "nope";
  refused(s, "unknown model");
  s = set;
  s.request.model_state.pose.position.x = std::numeric_limits<double>::quiet_NaN();
  refused(s, "NaN position");
  s = set;
  s.request.model_state.pose.orientation.w = 0.0;
  refused(s, "zero quaternion");
  s = set;
  s.request.model_state.pose.orientation.x = 1e300;  // finite, but |q| overflows
  refused(s, "overflowing quaternion");
  s = set;
  s.request.model_state.twist.angular.z = std::numeric_limits<double>::infinity();
  refused(s, "infinite spin");
  s = set;
  s.request.model_state.reference_frame = "nope::link";
  refused(s, "unknown frame");
  EXPECT_FALSE(Apply("nope", 1.0, 0.0, 1.0).success);
  EXPECT_FALSE(Apply("blocks::slider", std::numeric_limits<double>::quiet_NaN(), 0.0, 1.0).success);
  GetModelState get;
  get.request.model_name = "blocks";
  get.request.relative_entity_name = "nope";
  EXPECT_FALSE(Call<GetModelState>(nh_, kNode + "get_model_state", get).response.success);
  const SimulationState after = State();
  EXPECT_EQ(before.sim_time, after.sim_time);
  ASSERT_EQ(before.bodies.size(), after.bodies.size());
  for (std::size_t i = 0; i < before.bodies.size(); ++i) {  // (jellett_integral is NaN: no sphere)
    EXPECT_EQ(before.bodies[i].pose, after.bodies[i].pose);
    EXPECT_EQ(before.bodies[i].twist, after.bodies[i].twist);
    EXPECT_EQ(before.bodies[i].angular_velocity_body, after.bodies[i].angular_velocity_body);
  }
  EXPECT_EQ(before.energy, after.energy);
}

TEST_F(World, SetModelStateThenGetModelStateReturnsIt) {
  const SimulationState start = State();
  SetModelState set;
  ModelState& m = set.request.model_state;
  m.model_name = "blocks";
  m.pose.position.x = 0.25;
  m.pose.position.y = -0.5;
  m.pose.position.z = 0.3;
  const double half = 0.5 * 0.4;  // 0.4 rad about z
  m.pose.orientation.z = std::sin(half);
  m.pose.orientation.w = std::cos(half);
  m.twist.linear.x = 0.1;
  m.twist.angular.z = 2.0;
  const auto res = Call<SetModelState>(nh_, kNode + "set_model_state", set).response;
  ASSERT_TRUE(res.success) << res.status_message;
  GetModelState get;
  get.request.model_name = "blocks";
  const auto got = Call<GetModelState>(nh_, kNode + "get_model_state", get).response;
  ASSERT_TRUE(got.success) << got.status_message;
  EXPECT_NEAR(got.pose.position.x, 0.25, 1e-12);
  EXPECT_NEAR(got.pose.position.y, -0.5, 1e-12);
  EXPECT_NEAR(got.pose.position.z, 0.3, 1e-12);
  EXPECT_NEAR(got.pose.orientation.z, std::sin(half), 1e-12);
  EXPECT_NEAR(got.pose.orientation.w, std::cos(half), 1e-12);
  EXPECT_NEAR(got.twist.linear.x, 0.1, 1e-12);
  EXPECT_NEAR(got.twist.linear.y, 0.0, 1e-12);
  EXPECT_NEAR(got.twist.angular.z, 2.0, 1e-12);
  // the other body of the model moved rigidly with it: still 1 m from the slider, turned 0.4 rad
  const SimulationState now = State();
  const auto& slider = Body(now, "slider").pose.position;
  const auto& sticker = Body(now, "sticker").pose.position;
  EXPECT_NEAR(std::hypot(sticker.x - slider.x, sticker.y - slider.y), 1.0, 1e-12);
  EXPECT_NEAR(std::atan2(sticker.y - slider.y, sticker.x - slider.x), 0.4, 1e-12);
  // relative to the sticker the slider is 1 m behind it, at rest relative to it in rotation
  get.request.relative_entity_name = "blocks::sticker";
  const auto relative = Call<GetModelState>(nh_, kNode + "get_model_state", get).response;
  ASSERT_TRUE(relative.success) << relative.status_message;
  EXPECT_NEAR(relative.pose.position.x, -1.0, 1e-12);
  EXPECT_NEAR(relative.pose.position.y, 0.0, 1e-12);
  EXPECT_NEAR(relative.twist.angular.z, 0.0, 1e-12);

  // back to the start (rest on the ground), for the other tests
  m.pose.position.x = 0.0;
  m.pose.position.y = 0.0;
  m.pose.position.z = 0.01;
  m.pose.orientation.z = 0.0;
  m.pose.orientation.w = 1.0;
  m.twist = geometry_msgs::Twist();
  ASSERT_TRUE(Call<SetModelState>(nh_, kNode + "set_model_state", set).response.success);
  const SimulationState back = State();
  EXPECT_NEAR(Body(back, "sticker").pose.position.x, Body(start, "sticker").pose.position.x, 1e-12);
}

TEST_F(World, AWrenchGivesExactlyItsImpulseOnAFrictionlessPlane) {
  Step(100);  // settle on the ground
  const SimulationState before = State();
  const double t0 = before.sim_time;
  const double vx0 = Body(before, "slider").twist.linear.x;
  // F = 2 N from a start and for a duration that are not multiples of the step
  const double force = 2.0, start = t0 + 0.00123, duration = 0.01234;
  const auto res = Apply("blocks::slider", force, start, duration);
  ASSERT_TRUE(res.success) << res.status_message;
  Step(10);  // before the start: nothing
  EXPECT_EQ(Body(State(), "slider").twist.linear.x, vx0);
  Step(100);  // inside the interval: a = F/m over whole steps inside it
  const SimulationState mid = State();
  const double v_mid = Body(mid, "slider").twist.linear.x;
  Step(1);
  const double a = (Body(State(), "slider").twist.linear.x - v_mid) / kDt;
  EXPECT_NEAR(a, force / kMass, 1e-6 * force / kMass);
  Step(200);  // past the end
  const SimulationState end = State();
  const double v_end = Body(end, "slider").twist.linear.x;
  EXPECT_NEAR(v_end - vx0, force * duration / kMass, 1e-6 * force * duration / kMass);
  Step(100);  // and nothing after it
  EXPECT_NEAR(Body(State(), "slider").twist.linear.x, v_end, 1e-12);
  EXPECT_NEAR(Body(State(), "slider").twist.linear.z, 0.0, 1e-9);
}

TEST_F(World, AForceBelowTheFrictionLimitLeavesABlockAtRest) {
  Step(100);
  const double x0 = Body(State(), "sticker").pose.position.x;
  const auto res = Apply("blocks::sticker", 0.8 * 0.5 * kMass * kGravity, 0.0, -1.0);  // until cleared
  ASSERT_TRUE(res.success) << res.status_message;
  Step(2000);
  const SimulationState s = State();
  EXPECT_NEAR(Body(s, "sticker").twist.linear.x, 0.0, 1e-9);
  EXPECT_NEAR(Body(s, "sticker").pose.position.x, x0, 1e-9);
  BodyRequest clear;
  clear.request.body_name = "blocks::sticker";
  Call<BodyRequest>(nh_, kNode + "clear_body_wrenches", clear);
  // above the limit it slides: (F - mu m g)/m
  const double pushed = 1.5 * 0.5 * kMass * kGravity;
  ASSERT_TRUE(Apply("sticker", pushed, 0.0, -1.0).success);
  Step(1000);
  const double v1 = Body(State(), "sticker").twist.linear.x;
  Step(1000);
  const double v2 = Body(State(), "sticker").twist.linear.x;
  EXPECT_NEAR((v2 - v1) / (1000 * kDt), (pushed - 0.5 * kMass * kGravity) / kMass, 1e-6);
  Call<BodyRequest>(nh_, kNode + "clear_body_wrenches", clear);
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_world_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
