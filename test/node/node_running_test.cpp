// The node started from the launch file: TF world -> tippe_top arrives, /clock advances strictly
// and is never 0, ~contacts reports the contact "big_sphere/ground" carrying the weight (Λ_N =
// m g Δt per step) and no contact of the peg once the top rests upright, and so does
// ~wrench/big_sphere; diagnostics report the run.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/WrenchStamped.h>
#include <gtest/gtest.h>
#include <rosgraph_msgs/Clock.h>
#include <tf2_msgs/TFMessage.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <cmath>

#include "nonsmooth_sim/ContactInfoArray.h"
#include "nonsmooth_sim/GetSolverProperties.h"
#include "nonsmooth_sim/ResetState.h"
#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

constexpr double kMass = 6e-3;  // urdf/tippe_top.urdf
constexpr double kGravity = 9.81;

bool HasTippeTop(const tf2_msgs::TFMessage& m) {
  for (const auto& t : m.transforms) {
    if (t.header.frame_id == "world" && t.child_frame_id == "tippe_top") return true;
  }
  return false;
}

TEST(NodeRunning, TransformWorldToTippeTopArrives) {
  ros::NodeHandle nh;
  Recorder<tf2_msgs::TFMessage> tf(nh, "/tf");
  ASSERT_TRUE(tf.WaitForMessage(HasTippeTop, 20.0)) << "no world -> tippe_top on /tf";
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  ASSERT_TRUE(WaitFor([&] { return buffer.canTransform("world", "tippe_top", ros::Time(0)); }, 20.0));
  const auto t = buffer.lookupTransform("world", "tippe_top", ros::Time(0));
  EXPECT_GT(t.transform.translation.z, 0.0);   // the centre of mass is above the floor
  EXPECT_LT(t.transform.translation.z, 0.03);  // and below the inverted height 21 mm + margin
  // TF stamps only advance
  const auto messages = tf.Messages();
  for (std::size_t i = 1; i < messages.size(); ++i) {
    EXPECT_GT(messages[i].transforms[0].header.stamp, messages[i - 1].transforms[0].header.stamp);
  }
}

TEST(NodeRunning, ClockAdvancesMonotonicallyAndIsNeverZero) {
  ros::NodeHandle nh;
  Recorder<rosgraph_msgs::Clock> clock(nh, "/clock");
  ASSERT_TRUE(clock.WaitForCount(30, 20.0)) << "fewer than 30 /clock messages";
  const auto messages = clock.Messages();
  EXPECT_FALSE(messages[0].clock.isZero());
  for (std::size_t i = 1; i < messages.size(); ++i) {
    EXPECT_GT(messages[i].clock, messages[i - 1].clock) << i;
  }
}

TEST(NodeRunning, RestingTopCarriesItsWeightOnTheBigSphere) {
  ros::NodeHandle nh;
  const double dt = Call<GetSolverProperties>(nh, kNode + "get_solver_properties").response.time_step;
  Recorder<ContactSteps> contacts(nh, kNode + "contacts");
  Recorder<geometry_msgs::WrenchStamped> big_wrench(nh, kNode + "wrench/big_sphere");
  Recorder<geometry_msgs::WrenchStamped> peg_wrench(nh, kNode + "wrench/peg_sphere");
  // upright and at rest, resting on the big sphere
  ResetState reset;
  reset.request.inclination = {0.0};
  reset.request.spin = {0.0};
  reset = Call(nh, kNode + "reset", reset);
  ASSERT_TRUE(reset.response.success) << reset.response.status_message;
  const double after = reset.response.sim_time + 0.01;  // 100 steps later
  ASSERT_TRUE(contacts.WaitForMessage([&](const ContactInfoArray& m) { return m.sim_time > after; },
                                      20.0));
  int checked = 0;
  for (const ContactInfoArray& m : contacts.Messages()) {
    if (m.sim_time <= after) continue;
    // only the closed contact is listed: none of the peg
    ASSERT_EQ(m.contacts.size(), 1u) << "at t = " << m.sim_time;
    EXPECT_TRUE(ContactsOf(m, "peg_sphere").empty());
    const ContactInfo& big = m.contacts[0];
    EXPECT_EQ(big.name, "big_sphere/ground");
    EXPECT_EQ(big.collision, "big_sphere");
    EXPECT_EQ(big.body, "tippe_top");
    EXPECT_EQ(big.other_collision, "ground");
    EXPECT_EQ(big.other_body, "");
    EXPECT_EQ(big.frame, "big_sphere_contact");
    EXPECT_TRUE(big.closed);
    EXPECT_EQ(big.friction_set, "sphere");
    EXPECT_EQ(m.time_step, dt);
    EXPECT_EQ(m.header.frame_id, "world");
    // the normal from the ground up to the sphere
    EXPECT_NEAR(big.normal.z, 1.0, 1e-12);
    // Λ_N = m g Δt per step, to the solver tolerance
    EXPECT_NEAR(big.normal_percussion, kMass * kGravity * dt, 1e-6 * kMass * kGravity * dt);
    EXPECT_NEAR(big.normal_force, kMass * kGravity, 1e-6 * kMass * kGravity);
    EXPECT_NEAR(std::hypot(big.tangential_force[0], big.tangential_force[1]), 0.0, 1e-9);
    ++checked;
  }
  EXPECT_GT(checked, 0);

  // the same force on ~wrench/big_sphere, in the contact's frame (z along the normal)
  ASSERT_TRUE(big_wrench.WaitForMessage(
      [&](const geometry_msgs::WrenchStamped& w) { return w.header.stamp.toSec() > after; }, 20.0));
  int wrenches = 0;
  for (const geometry_msgs::WrenchStamped& w : big_wrench.Messages()) {
    if (w.header.stamp.toSec() <= after) continue;
    EXPECT_EQ(w.header.frame_id, "big_sphere_contact");
    EXPECT_NEAR(w.wrench.force.z, kMass * kGravity, 1e-6 * kMass * kGravity);
    EXPECT_NEAR(std::hypot(w.wrench.force.x, w.wrench.force.y), 0.0, 1e-9);
    ++wrenches;
  }
  EXPECT_GT(wrenches, 0);
  // the peg never touches after the reset (before it, the spinning top may have inverted): no
  // wrench but zero ones
  for (const geometry_msgs::WrenchStamped& w : peg_wrench.Messages()) {
    EXPECT_EQ(w.header.frame_id, "peg_sphere_contact");
    if (w.header.stamp.toSec() <= reset.response.sim_time) continue;
    EXPECT_EQ(w.wrench.force.x, 0.0);
    EXPECT_EQ(w.wrench.force.y, 0.0);
    EXPECT_EQ(w.wrench.force.z, 0.0);
    EXPECT_EQ(w.wrench.torque.z, 0.0);
  }
}

TEST(NodeRunning, DiagnosticsReportTheRun) {
  ros::NodeHandle nh;
  Recorder<diagnostic_msgs::DiagnosticArray> diagnostics(nh, "/diagnostics");
  const std::vector<std::string> keys = {
      "real-time factor", "step wall time [us]", "solver iterations (mean)",
      "solver residual (max, <= 1: converged)", "unconverged steps in total", "friction set",
      "closed contacts"};
  ASSERT_TRUE(diagnostics.WaitForMessage(
      [&](const diagnostic_msgs::DiagnosticArray& m) {
        for (const auto& status : m.status) {
          std::size_t found = 0;
          for (const auto& kv : status.values) {
            for (const auto& key : keys) found += kv.key == key;
          }
          if (found == keys.size()) return true;
        }
        return false;
      },
      20.0));
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_running_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
