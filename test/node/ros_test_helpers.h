// Helpers for the node rostests: waits with timeouts (never fixed sleeps), message recorders,
// service calls that fail the test when the service itself is unreachable.
#ifndef NONSMOOTH_SIM_TEST_NODE_ROS_TEST_HELPERS_H_
#define NONSMOOTH_SIM_TEST_NODE_ROS_TEST_HELPERS_H_

#include <diagnostic_msgs/DiagnosticStatus.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "nonsmooth_sim/ContactInfoArray.h"
#include "nonsmooth_sim/ContactSteps.h"
#include "nonsmooth_sim/GetFrictionSet.h"
#include "nonsmooth_sim/GetSolverProperties.h"
#include "nonsmooth_sim/SimulationState.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"

namespace nonsmooth_sim::node::test {

/// The node's private namespace in the launch file.
inline const std::string kNode = "/nonsmooth_sim/";

/// The contents of a text file ("" if it cannot be read: the callers assert on what they need).
inline std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// The number a /diagnostics status holds under `key`; false if it has none.
inline bool DiagnosticValue(const diagnostic_msgs::DiagnosticStatus& status,
                            const std::string& key, double* value) {
  for (const auto& kv : status.values) {
    if (kv.key == key) {
      *value = std::stod(kv.value);
      return true;
    }
  }
  return false;
}

/// Polls `condition` every millisecond until it holds or `timeout` wall seconds pass.
inline bool WaitFor(const std::function<bool()>& condition, double timeout) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  while (!condition()) {
    if (ros::WallTime::now() > end || !ros::ok()) return false;
    ros::WallDuration(0.001).sleep();
  }
  return true;
}

/// The samples a message of type M carries: the message itself, except for the topics the node
/// batches (~max_samples_per_message).
template <typename M>
struct SamplesOf {
  using Sample = M;
  static void Split(const M& m, std::vector<Sample>* out) { out->push_back(m); }
};

/// ~contacts: one ContactInfoArray per step.
template <>
struct SamplesOf<ContactSteps> {
  using Sample = ContactInfoArray;
  static void Split(const ContactSteps& m, std::vector<Sample>* out) {
    out->insert(out->end(), m.steps.begin(), m.steps.end());
  }
};

/// /tf: one TFMessage per run of equal stamps (a message may carry several stamps).
template <>
struct SamplesOf<tf2_msgs::TFMessage> {
  using Sample = tf2_msgs::TFMessage;
  static void Split(const tf2_msgs::TFMessage& m, std::vector<Sample>* out) {
    for (std::size_t i = 0; i < m.transforms.size(); ++i) {
      if (i == 0 || m.transforms[i].header.stamp != m.transforms[i - 1].header.stamp) {
        out->emplace_back();
      }
      out->back().transforms.push_back(m.transforms[i]);
    }
  }
};

/// Keeps every sample of one topic (see SamplesOf) and counts its messages (thread safe;
/// callbacks run in an AsyncSpinner).
template <typename M>
class Recorder {
 public:
  using Sample = typename SamplesOf<M>::Sample;
  Recorder(ros::NodeHandle& nh, const std::string& topic, int queue = 100000) {
    sub_ = nh.subscribe<M>(topic, queue, [this](const typename M::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex_);
      const std::size_t before = messages_.size();
      SamplesOf<M>::Split(*m, &messages_);
      ++message_count_;
      largest_message_ = std::max(largest_message_, messages_.size() - before);
    });
  }
  // Unsubscribes before the members go: a spinner thread may be inside the callback, and
  // shutdown() waits for it (the members would otherwise be destroyed under it).
  ~Recorder() { sub_.shutdown(); }
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;
  /// The samples so far, in arrival order.
  std::vector<Sample> Messages() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return messages_;
  }
  /// The messages (not samples) so far.
  std::size_t MessageCount() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return message_count_;
  }
  /// The most samples one message carried so far.
  std::size_t LargestMessage() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return largest_message_;
  }
  std::size_t Count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return messages_.size();
  }
  void Clear() {
    std::lock_guard<std::mutex> lock(mutex_);
    messages_.clear();
    message_count_ = 0;
    largest_message_ = 0;
  }
  bool WaitForCount(std::size_t n, double timeout) const {
    return WaitFor([&] { return Count() >= n; }, timeout);
  }
  /// Waits until a sample satisfies `predicate`.
  bool WaitForMessage(const std::function<bool(const Sample&)>& predicate, double timeout) const {
    return WaitFor(
        [&] {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const Sample& m : messages_) {
            if (predicate(m)) return true;
          }
          return false;
        },
        timeout);
  }
  bool Connected() const { return sub_.getNumPublishers() > 0; }

 private:
  ros::Subscriber sub_;
  mutable std::mutex mutex_;
  std::vector<Sample> messages_;
  std::size_t message_count_ = 0;
  std::size_t largest_message_ = 0;
};

/// Calls service `name` (waiting up to 20 s for it); a transport failure fails the test. No handler
/// of the node returns false, so a false call is the transport's: on a loaded machine roscpp can see
/// a one-shot connection's hang-up before it reads the response (ros/ros_comm#1976; seen in ctest
/// -j2 runs, the node without any error). A query (a Get* service, which changes nothing) is
/// called again, up to twice; a call that changes the node is not, as the node may have carried it
/// out.
template <typename S>
S Call(ros::NodeHandle& nh, const std::string& name, S srv = S()) {
  ros::ServiceClient client = nh.serviceClient<S>(name);
  EXPECT_TRUE(client.waitForExistence(ros::Duration(20.0))) << name;
  const bool query =
      std::string(ros::service_traits::datatype<S>()).find("/Get") != std::string::npos;
  bool called = client.call(srv);
  for (int again = 0; !called && query && again < 2; ++again) {
    ros::Duration(0.1).sleep();
    called = client.call(srv);
  }
  EXPECT_TRUE(called) << name;
  return srv;
}

/// The running node's simulator settings (~get_solver_properties).
inline SimulatorOptions NodeSimulatorOptions(ros::NodeHandle& nh) {
  const GetSolverProperties::Response p =
      Call<GetSolverProperties>(nh, kNode + "get_solver_properties").response;
  SimulatorOptions options;
  options.time_step = p.time_step;
  options.solver.type = *SolverTypeFromName(p.solver);
  options.solver.tolerance_rel = p.tolerance;
  options.solver.tolerance_abs = p.tolerance_abs;
  options.solver.max_iterations = p.max_iterations;
  options.solver.relaxation = p.relaxation;
  options.gyroscopic = *GyroscopicSchemeFromName(p.gyroscopic);
  options.integrator = *IntegratorFromName(p.integrator);
  // a start-up parameter only (no service sets it)
  nh.param(kNode + "extrapolate_warm_start", options.extrapolate_warm_start,
           SimulatorOptions().extrapolate_warm_start);
  return options;
}

/// The headless core's Tippe-Top with the running node's settings and the first collision's
/// friction set: the reference a node run must equal.
inline Simulator HeadlessTippeTop(ros::NodeHandle& nh) {
  const GetFrictionSet::Response sets =
      Call<GetFrictionSet>(nh, kNode + "get_friction_set").response;
  TippeTopParameters parameters;
  parameters.friction_set = *FrictionSetFromName(sets.friction_sets.at(0));
  return Simulator(MakeTippeTopScene(parameters), NodeSimulatorOptions(nh));
}

/// The contacts of `msg` that involve collision `collision` (on either side), in message order.
/// ~contacts lists closed contacts only: an open contact is simply absent.
inline std::vector<const ContactInfo*> ContactsOf(const ContactInfoArray& msg,
                                                  const std::string& collision) {
  std::vector<const ContactInfo*> found;
  for (const ContactInfo& c : msg.contacts) {
    if (c.collision == collision || c.other_collision == collision) found.push_back(&c);
  }
  return found;
}

/// The bodies of two states are bit for bit equal (poses, twists and derived quantities).
inline void ExpectSameBodies(const SimulationState& a, const SimulationState& b) {
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_EQ(a.bodies[i], b.bodies[i]) << "body " << a.bodies[i].name;
  }
  EXPECT_EQ(a.energy, b.energy);
}

}  // namespace nonsmooth_sim::node::test

#endif  // NONSMOOTH_SIM_TEST_NODE_ROS_TEST_HELPERS_H_
