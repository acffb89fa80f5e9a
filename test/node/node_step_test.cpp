// Paused: no TF and no clock change; ~step N advances the sim time by exactly N·Δt (also after
// a time step change) and publishes TF at the advertised rate, several stamps per message up to
// ~max_samples_per_message; ~step is refused while running and for N = 0.
#include <gtest/gtest.h>
#include <rosgraph_msgs/Clock.h>
#include <std_srvs/Empty.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>

#include "nonsmooth_sim/GetSolverProperties.h"
#include "nonsmooth_sim/SetSolverProperties.h"
#include "nonsmooth_sim/StepSimulation.h"
#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

// How long a negative check ("nothing arrives") waits [wall s]: 50 periods of the 100 Hz clock.
constexpr double kQuietWindow = 0.5;
constexpr double kTfRate = 1000.0;  // the node's default ~tf_rate [Hz of sim time]

StepSimulation Step(ros::NodeHandle& nh, std::uint32_t n) {
  StepSimulation srv;
  srv.request.steps = n;
  return Call(nh, kNode + "step", srv);
}

std::int64_t Nanoseconds(double seconds) { return std::llround(seconds * 1e9); }

class NodeStep : public testing::Test {
 protected:
  ros::NodeHandle nh_;
};

TEST_F(NodeStep, PausedMeansNoTransformAndNoClockChange) {
  Recorder<tf2_msgs::TFMessage> tf(nh_, "/tf");
  Recorder<rosgraph_msgs::Clock> clock(nh_, "/clock");
  ASSERT_TRUE(WaitFor([&] { return tf.Connected() && clock.Connected(); }, 20.0));
  // the latched clock tells the (never zero) time at once
  ASSERT_TRUE(clock.WaitForCount(1, 20.0));
  const ros::Time start = clock.Messages().front().clock;
  EXPECT_FALSE(start.isZero());
  // a bounded wait for something that must not happen
  EXPECT_FALSE(WaitFor([&] { return tf.Count() > 0; }, kQuietWindow)) << "TF while paused";
  for (const auto& c : clock.Messages()) EXPECT_EQ(c.clock, start) << "clock moved while paused";
}

TEST_F(NodeStep, StepAdvancesByWholeTimeStepsAndPublishesTf) {
  Recorder<tf2_msgs::TFMessage> tf(nh_, "/tf");
  Recorder<rosgraph_msgs::Clock> clock(nh_, "/clock");
  ASSERT_TRUE(WaitFor([&] { return tf.Connected() && clock.Connected(); }, 20.0));
  const double dt = Call<GetSolverProperties>(nh_, kNode + "get_solver_properties").response.time_step;
  const std::int64_t tf_period = std::llround(1.0 / (kTfRate * dt));

  // a subscriber counts as connected before the node has its link: step until TF flows
  double warm_up = 0.0;
  ASSERT_TRUE(WaitFor(
      [&] {
        if (tf.Count() > 0) return true;
        warm_up = Step(nh_, static_cast<std::uint32_t>(tf_period)).response.sim_time;
        return WaitFor([&] { return tf.Count() > 0; }, 0.2);
      },
      20.0));
  // the last warm-up message has arrived (one connection keeps the order): nothing is pending
  ASSERT_TRUE(tf.WaitForMessage(
      [&](const tf2_msgs::TFMessage& m) {
        return std::llround(m.transforms[0].header.stamp.toSec() / dt) == std::llround(warm_up / dt);
      },
      20.0));
  tf.Clear();

  const StepSimulation first = Step(nh_, 250);
  ASSERT_TRUE(first.response.success) << first.response.status_message;
  const StepSimulation second = Step(nh_, 37);
  ASSERT_TRUE(second.response.success) << second.response.status_message;
  EXPECT_NEAR(first.response.sim_time - warm_up, 250 * dt, 1e-12);
  EXPECT_NEAR(second.response.sim_time - first.response.sim_time, 37 * dt, 1e-12);
  EXPECT_EQ((second.response.stamp - first.response.stamp).toNSec(), Nanoseconds(37 * dt));

  // the clock is flushed at the end of a step call
  ASSERT_TRUE(clock.WaitForMessage(
      [&](const rosgraph_msgs::Clock& c) { return c.clock == second.response.stamp; }, 20.0));
  // TF every tf_period steps, stamps strictly increasing, spaced by tf_period·Δt
  const std::int64_t steps_before = std::llround(warm_up / dt);
  const std::int64_t steps_after = std::llround(second.response.sim_time / dt);
  const auto expected =
      static_cast<std::size_t>(steps_after / tf_period - steps_before / tf_period);
  ASSERT_TRUE(tf.WaitForCount(expected, 20.0)) << tf.Count() << " of " << expected;
  const auto messages = tf.Messages();
  for (std::size_t i = 1; i < messages.size(); ++i) {
    const ros::Duration gap =
        messages[i].transforms[0].header.stamp - messages[i - 1].transforms[0].header.stamp;
    EXPECT_EQ(gap.toNSec(), Nanoseconds(tf_period * dt)) << i;
  }
  EXPECT_LE(messages.back().transforms[0].header.stamp, second.response.stamp);
  // batched: messages carry several stamps, never more than ~max_samples_per_message. A step call
  // runs in chunks of bounded wall time and sends what a chunk sampled at its end, so how full the
  // largest message is depends on the machine's speed (a sanitizer build fills fewer stamps)
  int max_samples = 0;
  ASSERT_TRUE(nh_.getParam(kNode + "max_samples_per_message", max_samples));
  ASSERT_GT(expected, static_cast<std::size_t>(max_samples));
  EXPECT_LE(tf.LargestMessage(), static_cast<std::size_t>(max_samples));
  EXPECT_GE(tf.LargestMessage(), 2u);
  EXPECT_LT(tf.MessageCount(), expected);
  EXPECT_GE(tf.MessageCount(), (expected + max_samples - 1) / max_samples);

  // paused again: nothing more
  const std::size_t tf_count = tf.Count();
  const std::size_t clock_count = clock.Count();
  EXPECT_FALSE(WaitFor([&] { return tf.Count() > tf_count || clock.Count() > clock_count; },
                       kQuietWindow));
  EXPECT_EQ(tf.Count(), expected);  // exactly the advertised rate, no more
}

TEST_F(NodeStep, ChangedTimeStepIsUsedByTheNextSteps) {
  SetSolverProperties set;
  set.request.time_step = {2e-4};
  set = Call(nh_, kNode + "set_solver_properties", set);
  ASSERT_TRUE(set.response.success) << set.response.status_message;
  const StepSimulation a = Step(nh_, 1);
  const StepSimulation b = Step(nh_, 10);
  EXPECT_EQ((b.response.stamp - a.response.stamp).toNSec(), Nanoseconds(10 * 2e-4));
  set.request.time_step = {1e-4};
  ASSERT_TRUE(Call(nh_, kNode + "set_solver_properties", set).response.success);
}

TEST_F(NodeStep, StepIsRefusedWhileRunningAndForZeroSteps) {
  const StepSimulation zero = Step(nh_, 0);
  EXPECT_FALSE(zero.response.success);
  EXPECT_NE(zero.response.status_message.find("steps"), std::string::npos);

  Call<std_srvs::Empty>(nh_, kNode + "unpause_physics");
  const StepSimulation running = Step(nh_, 5);
  EXPECT_FALSE(running.response.success);
  EXPECT_NE(running.response.status_message.find("pause_physics"), std::string::npos)
      << running.response.status_message;
  Call<std_srvs::Empty>(nh_, kNode + "pause_physics");
  EXPECT_TRUE(Step(nh_, 5).response.success);
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_step_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
