// Services: ~set_friction_set mid-run changes the law reported in ~contacts and the dynamics
// (exactly as the core does when switched at the same step); it selects all contacts (empty),
// those of one collision ("peg_sphere") or one contact ("big_sphere/ground"), and
// ~get_friction_set answers for each of these; unknown names, NaN/Inf and
// out-of-range values are rejected with a message and change nothing; ~reset twice with the same
// initial conditions gives bit-identical trajectories; reset_world / reset_simulation keep the
// time and restore what they promise; a reset clears the contact markers.
#include <gtest/gtest.h>
#include <std_srvs/Empty.h>
#include <visualization_msgs/MarkerArray.h>

#include <chrono>
#include <future>
#include <initializer_list>
#include <limits>
#include <memory>
#include <optional>
#include <thread>

#include "nonsmooth_sim/ContactInfoArray.h"
#include "nonsmooth_sim/GetFrictionSet.h"
#include "nonsmooth_sim/GetSimulationState.h"
#include "nonsmooth_sim/GetSolverProperties.h"
#include "nonsmooth_sim/ResetState.h"
#include "nonsmooth_sim/SetFrictionSet.h"
#include "nonsmooth_sim/SetSolverProperties.h"
#include "nonsmooth_sim/StepSimulation.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "nonsmooth_sim/node/conversions.h"
#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

class NodeServices : public testing::Test {
 protected:
  StepSimulation Step(std::uint32_t n) {
    StepSimulation srv;
    srv.request.steps = n;
    srv = Call(nh_, kNode + "step", srv);
    EXPECT_TRUE(srv.response.success) << srv.response.status_message;
    return srv;
  }
  SimulationState State() {
    return Call<GetSimulationState>(nh_, kNode + "get_state").response.state;
  }
  ResetState::Response Reset(ResetState srv = ResetState()) {
    return Call(nh_, kNode + "reset", srv).response;
  }
  SetFrictionSet::Response SetSet(const std::string& name, const std::string& contact = "") {
    SetFrictionSet srv;
    srv.request.friction_set = name;
    srv.request.contact = contact;
    return Call(nh_, kNode + "set_friction_set", srv).response;
  }
  GetFrictionSet::Response GetSets(const std::string& contact = "") {
    GetFrictionSet srv;
    srv.request.contact = contact;
    return Call(nh_, kNode + "get_friction_set", srv).response;
  }
  /// The set ~get_friction_set reports for one collision or contact ("" if it failed).
  std::string SetOf(const std::string& contact) {
    const GetFrictionSet::Response r = GetSets(contact);
    EXPECT_TRUE(r.success) << contact << ": " << r.status_message;
    EXPECT_EQ(r.contacts, std::vector<std::string>{contact});
    return r.success && r.friction_sets.size() == 1 ? r.friction_sets[0] : "";
  }
  GetSolverProperties::Response Solver() {
    return Call<GetSolverProperties>(nh_, kNode + "get_solver_properties").response;
  }
  SetSolverProperties::Response SetSolver(const SetSolverProperties& srv) {
    return Call(nh_, kNode + "set_solver_properties", SetSolverProperties(srv)).response;
  }
  /// The core simulator with the node's scene (urdf/tippe_top.urdf = MakeTippeTopScene()) and
  /// the node's current solver settings.
  Simulator Headless() { return Simulator(MakeTippeTopScene(), NodeSimulatorOptions(nh_)); }
  static SimulationState StateOf(const Simulator& sim) {
    SimulationState msg;
    FillState(sim, true, "world", &msg);
    return msg;
  }
  /// Steps until `recorder` has a message: a subscriber counts as connected before the node
  /// has its link.
  template <typename M>
  void WarmUp(const Recorder<M>& recorder, std::uint32_t steps_per_try) {
    ASSERT_TRUE(WaitFor(
        [&] {
          if (recorder.Count() > 0) return true;
          Step(steps_per_try);
          return WaitFor([&] { return recorder.Count() > 0; }, 0.2);
        },
        20.0));
  }

  ros::NodeHandle nh_;
};

TEST_F(NodeServices, FrictionSetSwitchedMidRunChangesTheLawAndTheDynamics) {
  Recorder<ContactSteps> contacts(nh_, kNode + "contacts");
  WarmUp(contacts, 10);
  ASSERT_TRUE(Reset().success);
  const StepSimulation before = Step(3000);
  ASSERT_TRUE(contacts.WaitForMessage(
      [&](const ContactInfoArray& m) { return m.sim_time == before.response.sim_time; }, 20.0));
  const ContactInfoArray last_before = contacts.Messages().back();
  ASSERT_EQ(last_before.sim_time, before.response.sim_time);
  // the spinning top on its big sphere; the peg is open, so not listed
  ASSERT_EQ(last_before.contacts.size(), 1u);
  EXPECT_TRUE(ContactsOf(last_before, "peg_sphere").empty());
  const ContactInfo& big_before = last_before.contacts[0];
  EXPECT_EQ(big_before.name, "big_sphere/ground");
  EXPECT_EQ(big_before.other_collision, "ground");
  EXPECT_EQ(big_before.friction_set, "sphere");
  EXPECT_TRUE(big_before.closed);
  EXPECT_NE(big_before.drilling_percussion, 0.0);  // the spinning top drills

  const SetFrictionSet::Response set = SetSet("coulomb");
  ASSERT_TRUE(set.success) << set.status_message;
  EXPECT_NE(set.status_message.find("coulomb"), std::string::npos) << set.status_message;
  const GetFrictionSet::Response sets = GetSets();
  EXPECT_TRUE(sets.success) << sets.status_message;
  EXPECT_EQ(sets.contacts, (std::vector<std::string>{"big_sphere", "peg_sphere"}));
  EXPECT_EQ(sets.friction_sets, (std::vector<std::string>{"coulomb", "coulomb"}));

  contacts.Clear();
  const StepSimulation after = Step(3000);
  const SimulationState switched = State();
  ASSERT_TRUE(contacts.WaitForMessage(
      [&](const ContactInfoArray& m) { return m.sim_time == after.response.sim_time; }, 20.0));
  std::size_t listed = 0;
  for (const ContactInfoArray& m : contacts.Messages()) {
    for (const ContactInfo& c : m.contacts) {
      EXPECT_TRUE(c.closed) << c.name << " at t = " << m.sim_time;
      EXPECT_EQ(c.friction_set, "coulomb") << c.name << " at t = " << m.sim_time;
      EXPECT_EQ(c.drilling_percussion, 0.0);  // coulomb has no drilling component
      ++listed;
    }
  }
  EXPECT_GT(listed, 0u) << "no contact in 3000 steps";

  // the same run without the switch
  ASSERT_TRUE(SetSet("sphere").success);
  ASSERT_TRUE(Reset().success);
  Step(6000);
  const SimulationState unswitched = State();
  EXPECT_NE(switched.bodies[0].inclination, unswitched.bodies[0].inclination);

  // both runs are the core's, switched at the same step or not at all
  Simulator reference = Headless();
  for (int k = 0; k < 3000; ++k) reference.Step();
  reference.SetFrictionSet(FrictionSet::kCoulomb);
  for (int k = 0; k < 3000; ++k) reference.Step();
  ExpectSameBodies(switched, StateOf(reference));
  Simulator unswitched_reference = Headless();
  for (int k = 0; k < 6000; ++k) unswitched_reference.Step();
  ExpectSameBodies(unswitched, StateOf(unswitched_reference));
}

TEST_F(NodeServices, FrictionSetOfOneCollisionOrOneContact) {
  // a collision name selects all contacts of that collision
  const SetFrictionSet::Response set = SetSet("exact", "peg_sphere");
  ASSERT_TRUE(set.success) << set.status_message;
  const GetFrictionSet::Response sets = GetSets();
  EXPECT_EQ(sets.contacts, (std::vector<std::string>{"big_sphere", "peg_sphere"}));
  EXPECT_EQ(sets.friction_sets, (std::vector<std::string>{"sphere", "exact"}));
  EXPECT_EQ(SetOf("peg_sphere"), "exact");
  EXPECT_EQ(SetOf("peg_sphere/ground"), "exact");
  EXPECT_EQ(SetOf("big_sphere/ground"), "sphere");
  ASSERT_TRUE(SetSet("sphere", "peg_sphere").success);
  EXPECT_EQ(SetOf("peg_sphere/ground"), "sphere");

  // a contact name selects that contact only: the collision's own set stays
  Recorder<ContactSteps> contacts(nh_, kNode + "contacts");
  WarmUp(contacts, 10);
  ResetState upright;  // at rest on the big sphere
  upright.request.inclination = {0.0};
  upright.request.spin = {0.0};
  ASSERT_TRUE(Reset(upright).success);
  const SetFrictionSet::Response one = SetSet("ellipsoid", "big_sphere/ground");
  ASSERT_TRUE(one.success) << one.status_message;
  EXPECT_EQ(SetOf("big_sphere/ground"), "ellipsoid");
  EXPECT_EQ(SetOf("big_sphere"), "sphere");
  EXPECT_EQ(SetOf("peg_sphere/ground"), "sphere");
  EXPECT_EQ(GetSets().friction_sets, (std::vector<std::string>{"sphere", "sphere"}));
  contacts.Clear();
  const StepSimulation stepped = Step(20);
  ASSERT_TRUE(contacts.WaitForMessage(
      [&](const ContactInfoArray& m) { return m.sim_time == stepped.response.sim_time; }, 20.0));
  const ContactInfoArray last = contacts.Messages().back();
  ASSERT_EQ(last.contacts.size(), 1u);
  EXPECT_EQ(last.contacts[0].name, "big_sphere/ground");
  EXPECT_EQ(last.contacts[0].friction_set, "ellipsoid");

  // the collision's name again: all its contacts, the one set above included
  ASSERT_TRUE(SetSet("sphere", "big_sphere").success);
  EXPECT_EQ(SetOf("big_sphere/ground"), "sphere");
}

TEST_F(NodeServices, RejectedRequestsChangeNothing) {
  Step(500);
  const SimulationState state = State();
  const GetFrictionSet::Response sets = GetSets();
  const GetSolverProperties::Response solver = Solver();

  auto rejected = [](bool success, const std::string& message, const std::string& expected) {
    EXPECT_FALSE(success) << message;
    EXPECT_NE(message.find(expected), std::string::npos)
        << "\"" << expected << "\" not in: " << message;
  };
  SetFrictionSet::Response set = SetSet("sticky");
  rejected(set.success, set.status_message, "unknown friction set \"sticky\"");
  rejected(set.success, set.status_message, "coulomb, cylinder, ellipsoid, sphere, exact");
  set = SetSet("exact", "handle");
  rejected(set.success, set.status_message, "unknown contact \"handle\"");
  rejected(set.success, set.status_message, "nothing changed");
  set = SetSet("exact", "big_sphere/handle");
  rejected(set.success, set.status_message, "unknown contact \"big_sphere/handle\"");
  set = SetSet("exact", "big_sphere/big_sphere");
  rejected(set.success, set.status_message, "unknown contact \"big_sphere/big_sphere\"");
  const GetFrictionSet::Response unknown = GetSets("handle");
  rejected(unknown.success, unknown.status_message, "unknown contact \"handle\"");

  ResetState reset;
  reset.request.inclination = {kNaN};
  ResetState::Response r = Reset(reset);
  rejected(r.success, r.status_message, "inclination");
  reset.request.inclination = {4.0};
  r = Reset(reset);
  rejected(r.success, r.status_message, "[0, pi]");
  reset = ResetState();
  reset.request.spin = {kInf};
  r = Reset(reset);
  rejected(r.success, r.status_message, "spin");
  reset = ResetState();
  reset.request.position = {1.0, 2.0};
  r = Reset(reset);
  rejected(r.success, r.status_message, "position: expected 0 (default) or 3 values");
  reset = ResetState();
  reset.request.orientation = {0.0, 0.0, 0.0, 0.0};
  r = Reset(reset);
  rejected(r.success, r.status_message, "orientation");
  reset = ResetState();
  reset.request.body = "handle";
  r = Reset(reset);
  rejected(r.success, r.status_message, "\"handle\" is not a free body");

  SetSolverProperties solver_request;
  solver_request.request.time_step = {1.0};
  SetSolverProperties::Response s = SetSolver(solver_request);
  rejected(s.success, s.status_message, "time_step");
  solver_request.request.time_step = {-1e-4};
  s = SetSolver(solver_request);
  rejected(s.success, s.status_message, "time_step");
  solver_request.request.time_step = {kNaN};
  s = SetSolver(solver_request);
  rejected(s.success, s.status_message, "time_step");
  solver_request = SetSolverProperties();
  solver_request.request.relaxation = {2.5};
  s = SetSolver(solver_request);
  rejected(s.success, s.status_message, "relaxation");
  solver_request = SetSolverProperties();
  solver_request.request.solver = "newton";
  s = SetSolver(solver_request);
  rejected(s.success, s.status_message, "unknown solver \"newton\"");
  // a valid field next to an invalid one: the whole request is rejected
  solver_request = SetSolverProperties();
  solver_request.request.tolerance = {1e-4};
  solver_request.request.max_iterations = {0};
  s = SetSolver(solver_request);
  rejected(s.success, s.status_message, "max_iterations");

  const SimulationState after = State();
  EXPECT_EQ(after.sim_time, state.sim_time);
  ExpectSameBodies(after, state);
  const GetFrictionSet::Response sets_after = GetSets();
  EXPECT_EQ(sets_after.friction_sets, sets.friction_sets);
  EXPECT_EQ(SetOf("big_sphere/ground"), "sphere");
  EXPECT_EQ(SetOf("peg_sphere/ground"), "sphere");
  EXPECT_EQ(Solver(), solver);
}

TEST_F(NodeServices, ResetTwiceWithTheSameInitialConditionsGivesIdenticalStates) {
  ResetState reset;
  reset.request.inclination = {0.2};
  reset.request.spin = {150.0};
  ASSERT_TRUE(Reset(reset).success);
  Step(1500);
  const SimulationState first = State();
  Step(700);  // leaves warm starts and contact history behind
  ASSERT_TRUE(Reset(reset).success);
  Step(1500);
  const SimulationState second = State();
  EXPECT_GT(second.sim_time, first.sim_time);
  ExpectSameBodies(first, second);

  // and other initial conditions give another state
  reset.request.spin = {149.0};
  ASSERT_TRUE(Reset(reset).success);
  Step(1500);
  EXPECT_NE(State().bodies[0].pose.orientation, first.bodies[0].pose.orientation);
}

TEST_F(NodeServices, ResetWorldAndResetSimulationKeepTheTime) {
  const GetSolverProperties::Response configured = Solver();
  ASSERT_TRUE(SetSet("coulomb").success);
  SetSolverProperties tolerance;
  tolerance.request.tolerance = {1e-6};
  ASSERT_TRUE(SetSolver(tolerance).success);
  Step(100);
  const double time = State().sim_time;

  Call<std_srvs::Empty>(nh_, kNode + "reset_world");
  const SimulationState world = State();
  EXPECT_EQ(world.sim_time, time);                        // time kept
  ExpectSameBodies(world, StateOf(Simulator(MakeTippeTopScene(), SimulatorOptions{})));
  EXPECT_EQ(GetSets().friction_sets[0], "coulomb");       // settings kept
  EXPECT_EQ(Solver().tolerance, 1e-6);

  Recorder<visualization_msgs::MarkerArray> markers(nh_, kNode + "contact_markers");
  ASSERT_TRUE(WaitFor([&] { return markers.Connected(); }, 20.0));
  WarmUp(markers, 400);  // ~markers_rate 30 Hz: a message every 333 steps
  Call<std_srvs::Empty>(nh_, kNode + "reset_simulation");
  const SimulationState simulation = State();
  EXPECT_EQ(simulation.sim_time, State().sim_time);
  EXPECT_GE(simulation.sim_time, time);                   // never back
  ExpectSameBodies(simulation, StateOf(Simulator(MakeTippeTopScene(), SimulatorOptions{})));
  EXPECT_EQ(GetSets().friction_sets[0], "sphere");        // the configured law again
  EXPECT_EQ(Solver(), configured);                        // the configured solver again
  // rviz is told to forget the old arrows
  EXPECT_TRUE(markers.WaitForMessage(
      [](const visualization_msgs::MarkerArray& m) {
        return !m.markers.empty() &&
               m.markers[0].action == visualization_msgs::Marker::DELETEALL;
      },
      20.0));
  EXPECT_GT(Step(10).response.sim_time, simulation.sim_time);
}

// ~step with `steps` called from another thread; the answer if it comes within `timeout` wall
// seconds (a node busy for longer leaves the call running).
std::optional<StepSimulation::Response> StepWithin(std::uint32_t steps, double timeout) {
  const auto answer = std::make_shared<std::promise<StepSimulation::Response>>();
  std::future<StepSimulation::Response> future = answer->get_future();
  std::thread([answer, steps] {
    StepSimulation srv;
    srv.request.steps = steps;
    ros::service::call(kNode + "step", srv);
    answer->set_value(srv.response);
  }).detach();
  if (future.wait_for(std::chrono::duration<double>(timeout)) != std::future_status::ready) {
    return std::nullopt;
  }
  return future.get();
}

TEST_F(NodeServices, HostileRequestsAreRejectedAndChangeNothing) {
  // finite values that multiplied the work without bound or made the state
  // non-finite were accepted; one ~step then iterated 2^31 times holding the node's lock
  Step(200);
  const SimulationState state = State();
  const GetSolverProperties::Response solver = Solver();
  auto rejected = [](bool success, const std::string& message,
                     std::initializer_list<std::string> expected) {
    EXPECT_FALSE(success) << message;
    for (const std::string& part : expected) {
      EXPECT_NE(message.find(part), std::string::npos) << "\"" << part << "\" not in: " << message;
    }
  };

  SetSolverProperties solver_request;
  solver_request.request.max_iterations = {2147483647};
  SetSolverProperties::Response s = SetSolver(solver_request);
  rejected(s.success, s.status_message, {"max_iterations", "<= 100000 in a simulation"});
  solver_request = SetSolverProperties();
  solver_request.request.relaxation = {4.9e-324};
  s = SetSolver(solver_request);
  rejected(s.success, s.status_message, {"relaxation", "[0.001, 2)"});
  EXPECT_EQ(Solver(), solver);

  ResetState reset;
  reset.request.spin = {1e300};
  ResetState::Response r = Reset(reset);
  rejected(r.success, r.status_message, {"spin", "<= 10000 rad/s"});
  reset = ResetState();
  reset.request.angular_velocity = {0.0, 2e4, 0.0};
  r = Reset(reset);
  rejected(r.success, r.status_message, {"angular_velocity", "<= 10000 rad/s"});
  reset = ResetState();
  reset.request.linear_velocity = {1e300, 0.0, 0.0};
  r = Reset(reset);
  rejected(r.success, r.status_message, {"linear_velocity", "<= 1000 m/s"});
  reset = ResetState();
  reset.request.position = {0.0, 0.0, 1e300};
  r = Reset(reset);
  rejected(r.success, r.status_message, {"position", "[-1000, 1000] m"});

  // 4294967295 steps: rejected at once, not run for hours
  const std::optional<StepSimulation::Response> step = StepWithin(4294967295u, 10.0);
  ASSERT_TRUE(step.has_value()) << "~step 4294967295 did not answer within 10 s";
  rejected(step->success, step->status_message, {"steps", "<= 100000"});
  EXPECT_EQ(step->sim_time, state.sim_time);

  const SimulationState after = State();
  EXPECT_EQ(after.sim_time, state.sim_time);
  ExpectSameBodies(after, state);
  EXPECT_EQ(Solver(), solver);
  // and the largest accepted step count runs (10 s of simulated time)
  const StepSimulation largest = Step(100000);
  EXPECT_NEAR(largest.response.sim_time - state.sim_time, 100000 * solver.time_step, 1e-9);
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_services_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
