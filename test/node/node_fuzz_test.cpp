// 2 000 random requests to every service of the node (fixed seed), a mix of valid values and
// hostile ones (NaN, ±Inf, 1e300, denormals, huge counts, unknown names, wrong array lengths),
// while it runs as fast as possible: every call is answered (a failed exchange is tried once more,
// at most 3 times in the run), each within a bounded wall time; afterwards the node is alive, its state finite and /clock never
// went backwards. (issue 11: "no input crashes or freezes the node")
#include <gtest/gtest.h>
#include <rosgraph_msgs/Clock.h>
#include <std_srvs/Empty.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "nonsmooth_sim/ApplyBodyWrench.h"
#include "nonsmooth_sim/GetFrictionSet.h"
#include "nonsmooth_sim/GetModelState.h"
#include "nonsmooth_sim/GetSimulationState.h"
#include "nonsmooth_sim/GetSolverProperties.h"
#include "nonsmooth_sim/ResetState.h"
#include "nonsmooth_sim/SetFrictionSet.h"
#include "nonsmooth_sim/SetModelState.h"
#include "nonsmooth_sim/SetSolverProperties.h"
#include "nonsmooth_sim/StepSimulation.h"
#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

const std::string kNode = "/nonsmooth_sim/";
constexpr int kRequests = 2000;
constexpr double kMaxAnswerWall = 30.0;  // [s] the longest a call may take (a ~step of 1e5 steps
                                         // at the slowest accepted settings, on a shared machine)

class Fuzzer {
 public:
  explicit Fuzzer(unsigned seed) : rng_(seed) {}

  double Number() {
    static const double kHostile[] = {std::numeric_limits<double>::quiet_NaN(),
                                      std::numeric_limits<double>::infinity(),
                                      -std::numeric_limits<double>::infinity(),
                                      1e300, -1e300, 4.9e-324, 0.0, -0.0, 1e-7, 2.0, 1e4};
    switch (Pick(4)) {
      case 0: return kHostile[Pick(sizeof kHostile / sizeof kHostile[0])];
      case 1: return std::uniform_real_distribution<double>(-10.0, 10.0)(rng_);
      default: return std::uniform_real_distribution<double>(-1.0, 1.0)(rng_);
    }
  }
  std::vector<double> Numbers(std::size_t usual) {
    std::vector<double> v(Pick(5) == 0 ? Pick(6) : (Pick(3) == 0 ? 0 : usual));
    for (double& x : v) x = Number();
    return v;
  }
  std::string Name(const std::vector<std::string>& good) {
    static const std::vector<std::string> kBad = {"", "nope", "big_sphere/nope", "/", "::",
                                                  std::string(300, 'x'), "tippe_top::nope"};
    return Pick(2) == 0 ? good[Pick(good.size())] : kBad[Pick(kBad.size())];
  }
  std::size_t Pick(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); }

 private:
  std::mt19937 rng_;
};

// Calls whose TCP exchange failed (roscpp's call() false without an exception in the node: it
// would log it) and that were answered when tried again. One such failure was seen in a fresh-clone
// CI run on a loaded machine, not reproduced in 10 runs since; a node that died fails the retry.
int g_retried_calls = 0;
constexpr int kMaxRetriedCalls = 3;

template <typename S>
void CallTimed(ros::NodeHandle& nh, const std::string& name, S srv) {
  ros::ServiceClient client = nh.serviceClient<S>(kNode + name);
  ASSERT_TRUE(client.waitForExistence(ros::Duration(20.0))) << name;
  const auto start = std::chrono::steady_clock::now();
  bool answered = client.call(srv);
  if (!answered) {
    ++g_retried_calls;
    std::cerr << "node_fuzz_test: " << name << ": no answer, retried (" << g_retried_calls
              << ")" << std::endl;
    ASSERT_TRUE(client.waitForExistence(ros::Duration(20.0))) << name << ": the node is gone";
    answered = client.call(srv);
  }
  ASSERT_TRUE(answered) << name << ": no answer twice (the node died?)";
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(wall, kMaxAnswerWall) << name;
}

TEST(NodeFuzz, EveryRequestIsAnsweredAndTheNodeStaysSound) {
  ros::NodeHandle nh;
  Recorder<rosgraph_msgs::Clock> clock(nh, "/clock");
  Fuzzer f(20261202);
  const std::vector<std::string> bodies = {"tippe_top"};
  const std::vector<std::string> contacts = {"big_sphere", "peg_sphere", "big_sphere/ground",
                                             "peg_sphere/ground"};
  const std::vector<std::string> sets = {"coulomb", "cylinder", "ellipsoid", "sphere", "exact"};
  const std::vector<std::string> solvers = {"jacobi", "modified_jacobi", "gauss_seidel"};
  for (int i = 0; i < kRequests && !HasFatalFailure(); ++i) {
    switch (f.Pick(10)) {
      case 0: CallTimed(nh, f.Pick(2) ? "pause_physics" : "unpause_physics", std_srvs::Empty()); break;
      case 1: {
        StepSimulation s;
        static const std::uint32_t kSteps[] = {0, 1, 7, 100, 1000, 100001, 4294967295u};
        s.request.steps = kSteps[f.Pick(7)];
        CallTimed(nh, "step", s);
        break;
      }
      case 2: {
        ResetState s;
        s.request.body = f.Name(bodies);
        s.request.inclination = f.Numbers(1);
        s.request.spin = f.Numbers(1);
        s.request.position = f.Numbers(3);
        s.request.orientation = f.Numbers(4);
        s.request.linear_velocity = f.Numbers(3);
        s.request.angular_velocity = f.Numbers(3);
        CallTimed(nh, "reset", s);
        break;
      }
      case 3: CallTimed(nh, f.Pick(2) ? "reset_world" : "reset_simulation", std_srvs::Empty()); break;
      case 4: {
        SetFrictionSet s;
        s.request.friction_set = f.Name(sets);
        s.request.contact = f.Pick(3) == 0 ? "" : f.Name(contacts);
        CallTimed(nh, "set_friction_set", s);
        break;
      }
      case 5: {
        SetSolverProperties s;
        s.request.time_step = f.Numbers(1);
        if (!s.request.time_step.empty() && f.Pick(2)) s.request.time_step[0] = 1e-4;
        s.request.solver = f.Pick(3) == 0 ? "" : f.Name(solvers);
        s.request.tolerance = f.Numbers(1);
        s.request.tolerance_abs = f.Numbers(1);
        if (f.Pick(2)) {
          static const int kIterations[] = {0, 1, 100, 100000, 100001, 2147483647, -5};
          s.request.max_iterations = {kIterations[f.Pick(7)]};
        }
        s.request.relaxation = f.Numbers(1);
        s.request.gyroscopic = f.Pick(2) ? "" : (f.Pick(2) ? "implicit_midpoint" : "nope");
        CallTimed(nh, "set_solver_properties", s);
        break;
      }
      case 6: {
        SetModelState s;
        s.request.model_state.model_name = f.Pick(4) ? "tippe_top" : "nope";
        const auto p = f.Numbers(3), q = f.Numbers(4), v = f.Numbers(3), w = f.Numbers(3);
        if (p.size() == 3) s.request.model_state.pose.position.x = p[0], s.request.model_state.pose.position.z = std::abs(p[2]);
        if (q.size() == 4) {
          s.request.model_state.pose.orientation.x = q[0];
          s.request.model_state.pose.orientation.w = q[3];
        }
        if (v.size() == 3) s.request.model_state.twist.linear.y = v[1];
        if (w.size() == 3) s.request.model_state.twist.angular.z = 100.0 * w[2];
        s.request.model_state.reference_frame = f.Pick(4) ? "" : f.Name(bodies);
        CallTimed(nh, "set_model_state", s);
        break;
      }
      case 7: {
        ApplyBodyWrench s;
        s.request.body_name = f.Name(bodies);
        s.request.wrench.force.x = 1e-3 * f.Number();
        s.request.wrench.torque.z = 1e-6 * f.Number();
        s.request.reference_point.z = 0.01 * f.Number();
        s.request.duration = ros::Duration(f.Pick(3) == 0 ? -1.0 : 0.01 * f.Pick(10));
        CallTimed(nh, "apply_body_wrench", s);
        break;
      }
      case 8: {
        GetModelState s;
        s.request.model_name = f.Pick(3) ? "tippe_top" : "nope";
        s.request.relative_entity_name = f.Pick(2) ? "" : f.Name(bodies);
        CallTimed(nh, "get_model_state", s);
        GetFrictionSet g;
        g.request.contact = f.Name(contacts);
        CallTimed(nh, "get_friction_set", g);
        break;
      }
      default: CallTimed(nh, "get_solver_properties", GetSolverProperties()); break;
    }
  }
  // alive, running, finite; the clock only advanced
  CallTimed(nh, "reset_world", std_srvs::Empty());
  CallTimed(nh, "unpause_physics", std_srvs::Empty());
  const auto state = Call<GetSimulationState>(nh, kNode + "get_state").response.state;
  EXPECT_TRUE(std::isfinite(state.sim_time));
  EXPECT_TRUE(std::isfinite(state.energy));
  for (const auto& b : state.bodies) {
    EXPECT_TRUE(std::isfinite(b.pose.position.x) && std::isfinite(b.pose.position.z) &&
                std::isfinite(b.twist.angular.z))
        << b.name;
  }
  // a dropped exchange now and then is the machine's; more is the node's
  EXPECT_LE(g_retried_calls, kMaxRetriedCalls);
  RecordProperty("retried_calls", g_retried_calls);
  const auto messages = clock.Messages();
  EXPECT_GT(messages.size(), 10u);
  for (std::size_t k = 1; k < messages.size(); ++k) {
    EXPECT_GE(messages[k].clock, messages[k - 1].clock) << k;
  }
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_fuzz_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
