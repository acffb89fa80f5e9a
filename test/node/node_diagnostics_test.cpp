// /diagnostics and the end-of-run log line of a run that is shorter than one diagnostics period
// and has no contact (node_diagnostics_test.test): the real-time factor is measured over the wall
// time the integrator ran, not over the paused rest of the period (it read 0.05 here before:
// 0.05 s of sim time over a 1 s wall period); the end-of-run line counts the wall time of the
// chunk that reached ~duration (its "us/step stepping" was negative before).
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <rosgraph_msgs/Log.h>

#include <std_srvs/Empty.h>

#include <cstdio>
#include <string>

#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

constexpr double kDuration = 0.05;  // node_diagnostics_test.test [s]

TEST(NodeDiagnostics, RealTimeFactorAndEndOfRunLineCoverTheRunOnly) {
  ros::NodeHandle nh;
  Recorder<diagnostic_msgs::DiagnosticArray> diagnostics(nh, "/diagnostics");
  Recorder<rosgraph_msgs::Log> log(nh, "/rosout");  // the node publishes its log lines here
  // /rosout's publishers: this test node itself and the node under test; wait for both, or the
  // end-of-run line may go out before the node's connection (seen under ThreadSanitizer)
  ASSERT_TRUE(WaitFor([&] { return log.Publishers() >= 2 && diagnostics.Connected(); }, 20.0));
  Call<std_srvs::Empty>(nh, "/nonsmooth_sim/unpause_physics");

  // until a period after the run (at ~duration, paused, nothing ran in it)
  const auto after_the_run = [&](const diagnostic_msgs::DiagnosticArray& m) {
    double running = 0.0, sim_time = 0.0;
    for (const auto& status : m.status) {
      if (DiagnosticValue(status, "running wall time in period [s]", &running) &&
          DiagnosticValue(status, "sim time [s]", &sim_time) && running == 0.0 &&
          sim_time > kDuration - 1e-9) {
        return true;
      }
    }
    return false;
  };
  ASSERT_TRUE(diagnostics.WaitForMessage(after_the_run, 20.0));
  // factor × running wall time of each period that ran adds up to the run's sim time (a factor
  // averaged over the paused rest of the period falls short by the period's paused share; no bound
  // on the factor itself: that is the machine's speed, and under AddressSanitizer it is below 1)
  double advanced = 0.0;
  int periods_that_ran = 0;
  for (const auto& m : diagnostics.Messages()) {
    for (const auto& status : m.status) {
      double factor = 0.0, running = 0.0;
      if (DiagnosticValue(status, "running wall time in period [s]", &running) && running > 0.0 &&
          DiagnosticValue(status, "real-time factor", &factor)) {
        ++periods_that_ran;
        EXPECT_GT(factor, 0.0);
        advanced += factor * running;
      }
    }
  }
  EXPECT_GE(periods_that_ran, 1);
  EXPECT_NEAR(advanced, kDuration, 1e-4 * kDuration);  // values are printed with 6 digits

  std::string line;
  ASSERT_TRUE(log.WaitForMessage(
      [&](const rosgraph_msgs::Log& m) {
        if (m.msg.find("reached t =") == std::string::npos) return false;
        line = m.msg;
        return true;
      },
      20.0))
      << "no end-of-run line";
  double t = 0.0, wall = 0.0, summary_factor = 0.0, stepping = -1.0, publishing = -1.0;
  long long steps = 0;
  ASSERT_EQ(std::sscanf(line.c_str(),
                        "nonsmooth_sim: reached t = %lf s after %lld steps: %lf s wall running "
                        "(real-time factor %lf), %lf us/step stepping + %lf us/step publishing",
                        &t, &steps, &wall, &summary_factor, &stepping, &publishing),
            6)
      << line;
  EXPECT_NEAR(t, kDuration, 1e-9);
  EXPECT_EQ(steps, 500);  // 0.05 s / 1e-4 s
  EXPECT_GT(stepping, 0.0) << line;
  EXPECT_GE(publishing, 0.0) << line;
  EXPECT_GT(wall, 0.0) << line;
  // the line's factor is its sim time over its running wall time (printed with 2 decimals, wall
  // with 4 digits)
  EXPECT_NEAR(summary_factor, t / wall, 0.005 + 1e-3 * t / wall) << line;
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_diagnostics_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
