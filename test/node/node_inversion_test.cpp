// The Tippe-Top run through the node as fast as possible inverts exactly like the headless core
// simulator with the same scene and settings: every published state (one per step) equals the
// core's at that step, so the inversion times agree (to 1e-9 s, in fact exactly), and every
// ~contacts message lists exactly the core's closed contacts at its step: "big_sphere/ground" at
// the start (the peg open, so absent), "peg_sphere/ground" once the peg touches down. The node
// publishes every message it advertises: ~state at every step, ~contacts and /tf at 1 kHz, with
// consecutive sequence numbers and no gaps.
#include <gtest/gtest.h>
#include <std_srvs/Empty.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "nonsmooth_sim/ContactInfoArray.h"
#include "nonsmooth_sim/StepSimulation.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

constexpr double kDuration = 1.6;        // node_inversion_test.test: ~duration [s]
constexpr double kPegTouchdown = 2.4;    // θ > 2.4 rad: the peg touches down (inversion)
constexpr double kInverted = 2.9;        // θ > 2.9 rad: spinning on the peg
constexpr std::int64_t kContactsPeriod = 10;  // 1 kHz at Δt = 1e-4

// First time θ exceeds `level`, or -1.
template <typename Times, typename Thetas>
double FirstAbove(const Times& t, const Thetas& theta, double level) {
  for (std::size_t i = 0; i < theta.size(); ++i) {
    if (theta[i] > level) return t[i];
  }
  return -1.0;
}

TEST(NodeInversion, InvertsExactlyLikeTheHeadlessSimulatorWithoutDroppingMessages) {
  ros::NodeHandle nh;
  Recorder<SimulationState> states(nh, kNode + "state", 1000000);
  Recorder<ContactSteps> contacts(nh, kNode + "contacts", 1000000);
  Recorder<tf2_msgs::TFMessage> tf(nh, "/tf", 1000000);

  // the headless reference with the node's settings
  Simulator reference = HeadlessTippeTop(nh);
  const double dt = reference.options().time_step;
  ASSERT_EQ(dt, 1e-4);

  // One persistent connection per service for every call: no socket is opened or closed in
  // either process while the streams connect and run (see below).
  ros::ServiceClient step_client =
      nh.serviceClient<StepSimulation>(kNode + "step", /*persistent=*/true);
  ros::ServiceClient unpause_client =
      nh.serviceClient<std_srvs::Empty>(kNode + "unpause_physics", /*persistent=*/true);
  ASSERT_TRUE(step_client.waitForExistence(ros::Duration(20.0)));
  ASSERT_TRUE(unpause_client.waitForExistence(ros::Duration(20.0)));

  // Live streams before the run. A subscriber counts as connected before the node has its link,
  // and roscpp retries a dropped link only after 0.1 s: the whole run (16 000 steps, 20 ms when
  // ~state has no subscriber) can fall into that gap. Seen once in CI: the node's publishing cost
  // per step was that of a run without a ~state subscriber, and no state of the run arrived,
  // after an earlier state had. So step (paused) 10 steps at a time until one round's
  // samples all arrive: its 10 states, consecutive, and its ~contacts and /tf sample. Every
  // link delivers in order, so nothing older is in flight then; the recorders start empty.
  auto step_of = [&](double sim_time) { return std::llround(sim_time / dt); };
  bool live = false;
  std::string last_round;
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(30.0);
  while (!live && ros::WallTime::now() < give_up) {
    states.Clear();
    contacts.Clear();
    tf.Clear();
    StepSimulation step;
    step.request.steps = kContactsPeriod;
    ASSERT_TRUE(step_client.call(step) && step.response.success) << step.response.status_message;
    const std::int64_t end = step_of(step.response.sim_time);
    const bool arrived =
        states.WaitForMessage([&](const SimulationState& m) { return step_of(m.sim_time) == end; },
                              0.5) &&
        contacts.WaitForMessage(
            [&](const ContactInfoArray& m) { return step_of(m.sim_time) == end; }, 0.5) &&
        tf.WaitForMessage(
            [&](const tf2_msgs::TFMessage& m) {
              return step_of(m.transforms[0].header.stamp.toSec()) == end;
            },
            0.5);
    const std::vector<SimulationState> round = states.Messages();
    live = arrived && round.size() >= static_cast<std::size_t>(kContactsPeriod);
    for (std::int64_t i = 0; live && i < kContactsPeriod; ++i) {
      live = step_of(round[round.size() - kContactsPeriod + i].sim_time) ==
             end - kContactsPeriod + 1 + i;
    }
    last_round = "step " + std::to_string(end) + ": " + std::to_string(round.size()) +
                 " states, " + std::to_string(contacts.Count()) + " ~contacts and " +
                 std::to_string(tf.Count()) + " /tf samples";
  }
  ASSERT_TRUE(live) << "the streams did not all deliver one round of 10 steps in 30 s; last "
                    << last_round;
  states.Clear();
  contacts.Clear();
  tf.Clear();

  // as fast as possible until the node pauses itself at ~duration
  std_srvs::Empty unpause;
  ASSERT_TRUE(unpause_client.call(unpause));
  ASSERT_TRUE(states.WaitForMessage(
      [&](const SimulationState& m) { return m.sim_time >= kDuration - 0.5 * dt; }, 45.0))
      << "the node did not reach t = " << kDuration << " s, or ~state lost its last message: "
      << states.Count() << " states received, the last at t = "
      << (states.Count() > 0 ? states.Messages().back().sim_time : -1.0) << " s";
  const std::vector<SimulationState> received = states.Messages();
  const std::int64_t total_steps = std::llround(received.back().sim_time / dt);
  // the last ~contacts and /tf of the run (at the last multiple of 10 steps) arrive too
  const std::int64_t last_publish = total_steps / kContactsPeriod * kContactsPeriod;
  ASSERT_TRUE(contacts.WaitForMessage(
      [&](const ContactInfoArray& m) {
        return std::llround(m.sim_time / dt) == last_publish;
      },
      20.0));
  ASSERT_TRUE(tf.WaitForMessage(
      [&](const tf2_msgs::TFMessage& m) {
        return std::llround(m.transforms[0].header.stamp.toSec() / dt) == last_publish;
      },
      20.0));

  // Nothing dropped: roscpp numbers the messages of ~state (header.seq), and the sim times step
  // on by the advertised period (~state every step; the samples of ~contacts and /tf, several per
  // message, every 10 steps).
  for (std::size_t i = 1; i < received.size(); ++i) {
    ASSERT_EQ(received[i].header.seq, received[i - 1].header.seq + 1) << "gap at " << i;
    ASSERT_EQ(step_of(received[i].sim_time), step_of(received[i - 1].sim_time) + 1) << i;
  }
  const std::vector<ContactInfoArray> contact_messages = contacts.Messages();
  for (std::size_t i = 1; i < contact_messages.size(); ++i) {
    ASSERT_EQ(step_of(contact_messages[i].sim_time),
              step_of(contact_messages[i - 1].sim_time) + kContactsPeriod) << i;
  }
  const std::vector<tf2_msgs::TFMessage> transforms = tf.Messages();
  for (std::size_t i = 1; i < transforms.size(); ++i) {
    ASSERT_EQ(step_of(transforms[i].transforms[0].header.stamp.toSec()),
              step_of(transforms[i - 1].transforms[0].header.stamp.toSec()) + kContactsPeriod)
        << i;
  }
  EXPECT_GT(received.size(), 15000u);  // 1.6 s at one state per step

  // the headless core, step by step
  std::vector<double> ref_time(total_steps + 1, 0.0), ref_theta(total_steps + 1, 0.0);
  std::map<std::int64_t, std::vector<std::string>> ref_contacts;  // at the ~contacts steps
  ref_theta[0] = Inclination(reference.state()[0]);
  for (std::int64_t k = 1; k <= total_steps; ++k) {
    reference.Step();
    ref_time[k] = reference.time();
    ref_theta[k] = Inclination(reference.state()[0]);
    if (k % kContactsPeriod == 0) {
      std::vector<std::string>& names = ref_contacts[k];
      for (const ContactState& c : reference.contacts()) {
        names.push_back(ContactName(reference.scene(), c));
      }
    }
  }
  int mismatches = 0;
  std::vector<double> node_time, node_theta;
  for (const SimulationState& m : received) {
    const std::int64_t k = step_of(m.sim_time);
    mismatches += m.sim_time != ref_time[k] || m.bodies[0].inclination != ref_theta[k];
    node_time.push_back(m.sim_time);
    node_theta.push_back(m.bodies[0].inclination);
  }
  EXPECT_EQ(mismatches, 0) << "of " << received.size() << " states";

  // ~contacts lists the core's closed contacts, by name, and no open one
  int contact_mismatches = 0;
  std::size_t peg_listed = 0;
  for (const ContactInfoArray& m : contact_messages) {
    std::vector<std::string> names;
    for (const ContactInfo& c : m.contacts) {
      names.push_back(c.name);
      EXPECT_TRUE(c.closed) << c.name << " at t = " << m.sim_time;
      peg_listed += c.name == "peg_sphere/ground";
    }
    const auto ref = ref_contacts.find(step_of(m.sim_time));
    if (ref == ref_contacts.end() || ref->second != names) {
      if (++contact_mismatches <= 5) {
        ADD_FAILURE() << "contacts at t = " << m.sim_time << ": " << testing::PrintToString(names)
                      << ", the core: "
                      << (ref == ref_contacts.end() ? std::string("no such step")
                                                    : testing::PrintToString(ref->second));
      }
    }
  }
  EXPECT_EQ(contact_mismatches, 0) << "of " << contact_messages.size() << " ~contacts messages";
  // at the start the top spins on its big sphere, the peg open (absent)
  const ContactInfoArray& start = contact_messages.front();
  ASSERT_EQ(start.contacts.size(), 1u);
  EXPECT_EQ(start.contacts[0].name, "big_sphere/ground");
  EXPECT_EQ(start.contacts[0].other_collision, "ground");
  EXPECT_TRUE(ContactsOf(start, "peg_sphere").empty());
  // the peg touches down during the inversion
  EXPECT_GT(peg_listed, 0u) << "no peg_sphere/ground contact in " << kDuration << " s";

  // the same inversion, judged over the steps the node published
  const std::int64_t first = step_of(received.front().sim_time);
  const std::vector<double> ref_t(ref_time.begin() + first, ref_time.end());
  const std::vector<double> ref_th(ref_theta.begin() + first, ref_theta.end());
  const double t_node = FirstAbove(node_time, node_theta, kPegTouchdown);
  const double t_ref = FirstAbove(ref_t, ref_th, kPegTouchdown);
  ASSERT_GT(t_ref, 0.0) << "the headless Tippe-Top did not invert within " << kDuration << " s";
  EXPECT_NEAR(t_node, t_ref, 1e-9);
  EXPECT_NEAR(FirstAbove(node_time, node_theta, kInverted), FirstAbove(ref_t, ref_th, kInverted),
              1e-9);
  RecordProperty("inversion_time_s", std::to_string(t_node));
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_inversion_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
