// The node with ~accuracy (node_accuracy_test.test: the Tippe-Top, paused, ~accuracy 1e-4):
// ~step N advances the sim time by exactly N ticks (~time_step) and the samples stay at the fixed
// sample times, while the error estimate chooses steps larger than the tick; the peg touches down
// when the node's own fine fixed-step run (Δt = 2e-5) says, within 10·TOL of the time plus one
// ~contacts sample; /diagnostics reports the steps; out-of-range settings are refused and change
// nothing, and ~accuracy 0 gives the fixed steps back.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <std_srvs/Empty.h>

#include <cmath>
#include <optional>
#include <string>

#include "nonsmooth_sim/ContactSteps.h"
#include "nonsmooth_sim/GetSimulationState.h"
#include "nonsmooth_sim/GetSolverProperties.h"
#include "nonsmooth_sim/SetSolverProperties.h"
#include "nonsmooth_sim/StepSimulation.h"
#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

constexpr double kTolerance = 1e-4;  // node_accuracy_test.test
constexpr double kTick = 1e-4;       // tippe_top.launch's time_step [s]
constexpr double kSample = 1e-3;     // ~contacts_rate 1000 Hz [s]
constexpr double kRun = 1.45;        // past the peg's touchdown (≈ 1.371 s) [s]
constexpr double kFineTick = 2e-5;  // the fixed-step reference (its touchdown error ≈ 1e-5 s)

double SimTime(ros::NodeHandle& nh) {
  return Call<GetSimulationState>(nh, kNode + "get_state").response.state.sim_time;
}

StepSimulation Step(ros::NodeHandle& nh, std::uint32_t n) {
  StepSimulation srv;
  srv.request.steps = n;
  return Call(nh, kNode + "step", srv);
}

SetSolverProperties SetAccuracy(ros::NodeHandle& nh, std::vector<double> accuracy,
                                std::vector<double> time_step = {},
                                std::vector<double> min_dt = {}) {
  SetSolverProperties srv;
  srv.request.accuracy = std::move(accuracy);
  srv.request.time_step = std::move(time_step);
  srv.request.min_dt = std::move(min_dt);
  return Call(nh, kNode + "set_solver_properties", srv);
}

// Steps `ticks` from `start` and returns the time after start of the first ~contacts sample with
// the peg in contact; every sample must lie on the sample grid start + k·kSample.
std::optional<double> PegTouchdown(ros::NodeHandle& nh, Recorder<ContactSteps>* contacts,
                                   double start, std::uint32_t ticks, double tick) {
  contacts->Clear();
  const StepSimulation step = Step(nh, ticks);
  EXPECT_TRUE(step.response.success) << step.response.status_message;
  EXPECT_NEAR(step.response.sim_time - start, ticks * tick, 1e-9);
  // the last sample arrives (one connection keeps the order)
  EXPECT_TRUE(contacts->WaitForMessage(
      [&](const ContactInfoArray& s) { return s.sim_time > step.response.sim_time - kSample; },
      20.0));
  std::optional<double> touchdown;
  for (const ContactInfoArray& s : contacts->Messages()) {
    const double k = (s.sim_time - start) / kSample;
    EXPECT_NEAR(k, std::round(k), 1e-6) << "a sample off the grid at " << s.sim_time;
    for (const ContactInfo& c : s.contacts) {
      if (!touchdown && c.collision == "peg_sphere") touchdown = s.sim_time - start;
    }
  }
  return touchdown;
}

TEST(NodeAccuracy, SettingsAreReportedAndOutOfRangeIsRefused) {
  ros::NodeHandle nh;
  GetSolverProperties get = Call<GetSolverProperties>(nh, kNode + "get_solver_properties");
  EXPECT_EQ(get.response.accuracy, kTolerance);
  EXPECT_EQ(get.response.time_step, kTick);
  EXPECT_GT(get.response.max_dt, get.response.min_dt);
  for (const SetSolverProperties& refused :
       {SetAccuracy(nh, {5.0}), SetAccuracy(nh, {-1e-3}), SetAccuracy(nh, {1e-3}, {}, {1.0})}) {
    EXPECT_FALSE(refused.response.success);
    EXPECT_NE(refused.response.status_message.find("nothing changed"), std::string::npos)
        << refused.response.status_message;
  }
  get = Call<GetSolverProperties>(nh, kNode + "get_solver_properties");
  EXPECT_EQ(get.response.accuracy, kTolerance);
}

TEST(NodeAccuracy, TouchesDownWithTheFineFixedStepAndSamplesOnTheTicks) {
  ros::NodeHandle nh;
  Recorder<ContactSteps> contacts(nh, kNode + "contacts");
  Recorder<diagnostic_msgs::DiagnosticArray> diagnostics(nh, "/diagnostics");
  ASSERT_TRUE(WaitFor([&] { return contacts.Connected() && diagnostics.Connected(); }, 20.0));
  const auto ticks = static_cast<std::uint32_t>(std::lround(kRun / kTick));

  // the knob: steps larger than the tick, landing on it
  const double start = SimTime(nh);
  const std::optional<double> knob = PegTouchdown(nh, &contacts, start, ticks, kTick);
  ASSERT_TRUE(knob);
  double accepted = 0.0, largest = 0.0;
  ASSERT_TRUE(diagnostics.WaitForMessage(
      [&](const diagnostic_msgs::DiagnosticArray& m) {
        for (const auto& status : m.status) {
          if (DiagnosticValue(status, "accepted steps (accuracy, in total)", &accepted) &&
              DiagnosticValue(status, "largest step [s] (accuracy)", &largest) && accepted > 0.0) {
            return true;
          }
        }
        return false;
      },
      20.0));
  EXPECT_LT(accepted, static_cast<double>(ticks));
  EXPECT_GT(largest, kTick);

  // the node's own fine fixed-step run from the same start
  Call<std_srvs::Empty>(nh, kNode + "reset_simulation");
  const SetSolverProperties fixed = SetAccuracy(nh, {0.0}, {kFineTick});
  ASSERT_TRUE(fixed.response.success) << fixed.response.status_message;
  const double restart = SimTime(nh);
  const std::optional<double> reference =
      PegTouchdown(nh, &contacts, restart, static_cast<std::uint32_t>(std::lround(kRun / kFineTick)),
                   kFineTick);
  ASSERT_TRUE(reference);
  std::printf("peg touchdown: ~accuracy %g %.4f s, fixed 2e-5 s %.4f s; %.0f accepted steps for "
              "%u ticks, the largest %.3g s\n",
              kTolerance, *knob, *reference, accepted, ticks, largest);
  EXPECT_NEAR(*knob, *reference, 10.0 * kTolerance * *reference + kSample + 1e-9);
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_accuracy_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
