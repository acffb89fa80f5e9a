// The hammer: several clients at once (threads of this test, each with its own connections and
// fixed seed) send random requests to every service of the node, a mix of valid values and hostile
// ones (NaN, ±Inf, 1e300, denormals, huge counts, unknown names, wrong array lengths, malformed
// URDFs), spawning and deleting models under each other's feet, while the node runs as fast as
// possible: every call is answered (a failed exchange is tried once more, at most 3 times in the
// run), each within a bounded wall time; afterwards the node is alive, its state finite and /clock
// never went backwards: no input or interleaving crashes, freezes or corrupts the node.
//
// Bounded in count and time: NONSMOOTH_SIM_HAMMER_REQUESTS (default 2 000, over all clients) and
// NONSMOOTH_SIM_HAMMER_SECONDS (default 60 s of wall time, then the clients stop where they are;
// ctest and rostest allow the test 1 500 s).
// A long run, by option: NONSMOOTH_SIM_HAMMER_REQUESTS=30000 NONSMOOTH_SIM_HAMMER_SECONDS=600
// ctest --test-dir build-release -R node_fuzz (docs/testing.md).
#include <gtest/gtest.h>
#include <rosgraph_msgs/Clock.h>
#include <std_srvs/Empty.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "nonsmooth_sim/ApplyBodyWrench.h"
#include "nonsmooth_sim/DeleteModel.h"
#include "nonsmooth_sim/GetFrictionSet.h"
#include "nonsmooth_sim/GetModelState.h"
#include "nonsmooth_sim/GetSimulationState.h"
#include "nonsmooth_sim/GetSolverProperties.h"
#include "nonsmooth_sim/ResetState.h"
#include "nonsmooth_sim/SetFrictionSet.h"
#include "nonsmooth_sim/SetModelState.h"
#include "nonsmooth_sim/SetSolverProperties.h"
#include "nonsmooth_sim/SpawnModel.h"
#include "nonsmooth_sim/StepSimulation.h"
#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

constexpr int kClients = 4;
constexpr std::size_t kModelNames = 3;  // spawned as h0, h1, h2: the clients race for them
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
// would log it) and that were answered when tried again; a node that died fails the retry. Every
// call opens a connection of its own: 0-1 such failures in 2 000 requests, 16 in 30 000 sent in
// 75 s, spread over 8 services (likely the client's ports, not measured: 30 000 connections in
// 75 s against a range of 28 000 ports, each held 60 s in TIME_WAIT).
// Allowed: 3, or one per 1 000 requests.
std::atomic<int> g_retried_calls{0};
int MaxRetriedCalls(std::size_t requests) {
  return std::max(3, static_cast<int>(requests / 1000));
}

// Spawns and deletes the node accepted: the hammer must reach them, not only their refusals.
std::atomic<int> g_spawned{0};
std::atomic<int> g_deleted{0};

template <typename S>
void CallTimed(ros::NodeHandle& nh, const std::string& name, S&& srv) {
  ros::ServiceClient client = nh.serviceClient<std::decay_t<S>>(kNode + name);
  ASSERT_TRUE(client.waitForExistence(ros::Duration(20.0))) << name;
  const auto start = std::chrono::steady_clock::now();
  bool answered = client.call(srv);
  if (!answered) {
    const int retried = ++g_retried_calls;
    std::cerr << "node_fuzz_test: " << name << ": no answer, retried (" << retried << ")"
              << std::endl;
    ASSERT_TRUE(client.waitForExistence(ros::Duration(20.0))) << name << ": the node is gone";
    answered = client.call(srv);
  }
  ASSERT_TRUE(answered) << name << ": no answer twice (the node died?)";
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(wall, kMaxAnswerWall) << name;
}

// One random request (fixed by the state of `f`) to one of the node's services.
void RandomRequest(Fuzzer& f, ros::NodeHandle& nh, const std::string& urdf) {
  const std::vector<std::string> bodies = {"tippe_top"};
  const std::vector<std::string> contacts = {"big_sphere", "peg_sphere", "big_sphere/ground",
                                             "peg_sphere/ground"};
  const std::vector<std::string> sets = {"coulomb", "cylinder", "ellipsoid", "sphere", "exact"};
  const std::vector<std::string> solvers = {"jacobi", "modified_jacobi", "gauss_seidel"};
switch (f.Pick(12)) {
    case 0:
      CallTimed(nh, f.Pick(2) ? "pause_physics" : "unpause_physics", std_srvs::Empty());
      break;
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
      if (p.size() == 3) {
        s.request.model_state.pose.position.x = p[0];
        s.request.model_state.pose.position.z = std::abs(p[2]);
      }
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
    case 9: {
      SpawnModel s;
      s.request.model_name = f.Pick(5) ? "h" + std::to_string(f.Pick(kModelNames)) : f.Name(bodies);
      s.request.model_xml = f.Pick(5) ? urdf : urdf.substr(0, f.Pick(urdf.size()));
      s.request.initial_pose.position.x = 0.3 * (1.0 + f.Pick(kModelNames)) + 1e-3 * f.Number();
      s.request.initial_pose.position.z = std::abs(f.Number());
      s.request.initial_pose.orientation.w = f.Pick(4) ? 1.0 : f.Number();
      s.request.robot_namespace = f.Pick(4) ? "" : (f.Pick(2) ? "/" : "/tippe_top");
      CallTimed(nh, "spawn_urdf_model", s);
      if (s.response.success) ++g_spawned;
      break;
    }
    case 10: {
      DeleteModel s;
      s.request.model_name = f.Pick(5) ? "h" + std::to_string(f.Pick(kModelNames)) : f.Name(bodies);
      CallTimed(nh, "delete_model", s);
      if (s.response.success) ++g_deleted;
      break;
    }
    default: CallTimed(nh, "get_solver_properties", GetSolverProperties()); break;
  }
}

std::size_t FromEnvironment(const char* name, std::size_t fallback) {
  const char* value = std::getenv(name);
  return value == nullptr ? fallback : std::stoul(value);
}

TEST(NodeFuzz, EveryRequestIsAnsweredAndTheNodeStaysSound) {
  ros::NodeHandle nh;
  Recorder<rosgraph_msgs::Clock> clock(nh, "/clock");
  const std::size_t requests = FromEnvironment("NONSMOOTH_SIM_HAMMER_REQUESTS", 2000);
  const double seconds = FromEnvironment("NONSMOOTH_SIM_HAMMER_SECONDS", 60);
  const std::string urdf =
      ReadFile(std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/urdf/tippe_top.urdf");
  ASSERT_FALSE(urdf.empty());
  const auto start = std::chrono::steady_clock::now();
  std::atomic<std::size_t> sent{0};
  std::vector<std::thread> clients;
  for (int k = 0; k < kClients; ++k) {
    clients.emplace_back([&, k] {
      ros::NodeHandle own;
      Fuzzer f(20261202 + k);
      while (!HasFatalFailure() && sent++ < requests &&
             std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() <
                 seconds) {
        RandomRequest(f, own, urdf);
      }
    });
  }
  for (std::thread& client : clients) client.join();
  RecordProperty("requests", static_cast<int>(std::min<std::size_t>(sent, requests)));
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
  EXPECT_GT(g_spawned, 0);
  EXPECT_GT(g_deleted, 0);
  RecordProperty("spawned", g_spawned);
  RecordProperty("deleted", g_deleted);
  // a dropped exchange now and then is the machine's; more is the node's
  EXPECT_LE(g_retried_calls, MaxRetriedCalls(requests));
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
