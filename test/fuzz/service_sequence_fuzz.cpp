// libFuzzer target: the input bytes, decoded by FuzzedDataProvider, are a sequence of requests
// against an in-process core Simulator that mirror the node's services (src/node/node_services.cpp,
// src/node/world_services.cpp) and the core's setters behind them:
//
//   ~step, ~reset, ~reset_world, ~reset_simulation, ~set_solver_properties, ~set_friction_set,
//   ~get_friction_set, ~apply_body_wrench, ~clear_body_wrenches; and of the core alone:
//   AddBodies, RemoveBodies, SetState, SetTime, SetExternalWrench with any value.
//
// Each request is validated the node's way (node::ValidateInitialConditions and
// node::InitialState are the node's own code, compiled in; ValidateSimulatorOptions, the name
// lookups and the bounds of world_services.cpp) and then handed to the core's setter, which
// validates again. Checked:
//  - a rejected request (the node's validation or the core's throws) leaves the simulator bit for
//    bit as it was: state, time, diverged(), options, scene sizes and names, every collider's and
//    pair's friction set, the external wrenches;
//  - only the documented exception types come out of a setter (std::invalid_argument, and
//    std::out_of_range for indices);
//  - an accepted request has the documented effect;
//  - the state is finite or a fault is reported (diverged()), after every request and every step,
//    and a simulator that is not diverged has a finite Energy() (SetState refuses a state whose
//    energy overflows);
//  - every step is held to the whole stepping contract of fuzz_support.h (a step reported finite
//    leaves a finite state, energy, contact report and statistics), also after a core-only request
//    put values far beyond the node's bounds into the simulator: the core checks the state and the
//    energies after the gap correction (the findings finding_levelling_nan.bin,
//    finding_energy_overflow.bin and finding_deep_lift_energy.bin, tolerated until 2026-12-02).
// Work per input is bounded (kMaxRequests requests, kMaxSteps steps, at most kMaxBodies bodies and
// kFuzzMaxIterations solver iterations per island and step), so an input runs in milliseconds.
#include <fuzzer/FuzzedDataProvider.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fuzz_support.h"
#include "nonsmooth_sim/collision_fcl/fcl_pairs.h"
#include "nonsmooth_sim/node/initial_conditions.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace {

using namespace nonsmooth_sim;
using fuzz::Finding;
using fuzz::Require;

constexpr int kMaxRequests = 48;
constexpr int kMaxSteps = 120;
constexpr std::size_t kMaxBodies = 6;
// The node accepts up to kMaxSimulatorIterations (1e5); here an accepted larger cap is applied as
// this one, so that an input stays in milliseconds (bounded_work_test covers the node's cap).
constexpr int kFuzzMaxIterations = 2000;
// world_services.cpp / simulation_node.h: |force|, |torque| <= kMaxExternalForce per request, at
// most kMaxWrenches at once
constexpr double kMaxExternalForce = 1e6;
constexpr int kMaxWrenches = 1000;

const double kInf = std::numeric_limits<double>::infinity();

// Values at and around every bound the validation has, and the hostile ones.
double HostileDouble(FuzzedDataProvider& in) {
  static const double kTable[] = {
      0.0, -0.0, 1.0, -1.0, 0.5, 0.1, 1e-3, 3.141592653589793, 3.1415926535897936, 2.0,
      std::nextafter(2.0, 0.0), 1e-7, std::nextafter(1e-7, 0.0), 1e-2, std::nextafter(1e-2, 1.0),
      1e3, std::nextafter(1e3, kInf), -1e3, 1e4, std::nextafter(1e4, kInf), 1e6,
      std::nextafter(1e6, kInf), 1e300, -1e300, std::numeric_limits<double>::max(),
      std::numeric_limits<double>::denorm_min(), 1e-300, kInf, -kInf,
      std::numeric_limits<double>::quiet_NaN()};
  switch (in.ConsumeIntegralInRange<int>(0, 3)) {
    case 0:
      return kTable[in.ConsumeIntegralInRange<std::size_t>(0, std::size(kTable) - 1)];
    case 1:
      return in.ConsumeFloatingPointInRange<double>(-10.0, 10.0);
    case 2:
      return in.ConsumeFloatingPointInRange<double>(-2e4, 2e4);
    default:
      return in.ConsumeFloatingPoint<double>();
  }
}

Eigen::Vector3d HostileVector(FuzzedDataProvider& in) {
  const double x = HostileDouble(in);
  const double y = HostileDouble(in);
  const double z = HostileDouble(in);
  return {x, y, z};
}

int HostileInt(FuzzedDataProvider& in) {
  static const int kTable[] = {0, 1, -1, 2, 10, 1000, 2000, 100000, 100001, 1000000, INT_MAX,
                               INT_MIN};
  if (in.ConsumeBool()) {
    return kTable[in.ConsumeIntegralInRange<std::size_t>(0, std::size(kTable) - 1)];
  }
  return in.ConsumeIntegral<int>();
}

// One of `names`, or a string of the input (a typo, an empty one, anything).
std::string PickName(FuzzedDataProvider& in, const std::vector<std::string>& names) {
  if (!names.empty() && in.ConsumeIntegralInRange<int>(0, 3) != 0) {
    return names[in.ConsumeIntegralInRange<std::size_t>(0, names.size() - 1)];
  }
  return in.ConsumeRandomLengthString(24);
}

// What a rejected request must leave unchanged, taken before it.
struct Snapshot {
  std::vector<BodyState> state;
  double time = 0.0;
  bool diverged = false;
  SimulatorOptions options;
  std::vector<std::string> bodies;
  std::vector<std::string> colliders;
  std::vector<FrictionSet> sets;  // per collider, then per pair (FrictionSetOf)
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> wrenches;

  explicit Snapshot(const Simulator& sim)
      : state(sim.state()), time(sim.time()), diverged(sim.diverged()), options(sim.options()) {
    const Scene& scene = sim.scene();
    for (const RigidBody& b : scene.bodies) bodies.push_back(b.name);
    for (const Collider& c : scene.colliders) {
      colliders.push_back(c.name);
      sets.push_back(c.law.friction_set);
    }
    for (std::size_t a = 0; a < scene.colliders.size(); ++a) {
      for (std::size_t b = a + 1; b < scene.colliders.size(); ++b) {
        sets.push_back(sim.FrictionSetOf(scene.colliders[a].name + "/" + scene.colliders[b].name));
      }
    }
    for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
      wrenches.push_back(sim.ExternalWrench(static_cast<int>(b)));
    }
  }

  static bool SameOptions(const SimulatorOptions& a, const SimulatorOptions& b) {
    return fuzz::SameBits(a.time_step, b.time_step) && a.solver.type == b.solver.type &&
           fuzz::SameBits(a.solver.tolerance_rel, b.solver.tolerance_rel) &&
           fuzz::SameBits(a.solver.tolerance_abs, b.solver.tolerance_abs) &&
           a.solver.max_iterations == b.solver.max_iterations &&
           fuzz::SameBits(a.solver.relaxation, b.solver.relaxation) &&
           a.solver.map_drilling_sets == b.solver.map_drilling_sets &&
           a.solver.direct_solve == b.solver.direct_solve &&
           a.gyroscopic == b.gyroscopic && a.gap_correction == b.gap_correction;
  }

  void RequireUnchanged(const Simulator& sim, const std::string& request) const {
    const Snapshot now(sim);
    Require(fuzz::SameBits(now.state, state), request + ": rejected, but the state changed");
    Require(fuzz::SameBits(now.time, time), request + ": rejected, but the time changed");
    Require(now.diverged == diverged, request + ": rejected, but diverged() changed");
    Require(SameOptions(now.options, options), request + ": rejected, but the options changed");
    Require(now.bodies == bodies && now.colliders == colliders,
            request + ": rejected, but the bodies or colliders changed");
    Require(now.sets == sets, request + ": rejected, but a friction set changed");
    Require(now.wrenches.size() == wrenches.size(), request + ": rejected, wrenches resized");
    for (std::size_t b = 0; b < wrenches.size(); ++b) {
      Require(now.wrenches[b].first == wrenches[b].first &&
                  now.wrenches[b].second == wrenches[b].second,
              request + ": rejected, but an external wrench changed");
    }
  }
};

struct ShippedScene {
  scene_io::UrdfScene urdf;
  Scene configured;  // the node's configured scene (ConfiguredScene with no parameters)
};

std::vector<ShippedScene>& Scenes() {
  static std::vector<ShippedScene> scenes;
  return scenes;
}

// The node's world: its URDF and configured scene, and the simulator behind the services.
struct World {
  const ShippedScene* shipped = nullptr;
  SimulatorOptions configured_options;  // parameters_.simulator
  std::unique_ptr<Simulator> sim;
  int wrenches = 0;  // accepted ~apply_body_wrench requests since the last clear (node: at most 1000)
  int steps = 0;
  int added = 0;  // models spawned (their names get this as suffix)
  // a core-only request put a value beyond the node's bounds into the simulator (RawSetState,
  // RawWrench): the node's sums of wrenches may overflow then (ApplyBodyWrench); the steps are
  // held to the whole contract all the same
  bool beyond_node_bounds = false;
};

std::vector<std::string> BodyNames(const Simulator& sim) {
  std::vector<std::string> names;
  for (const RigidBody& b : sim.scene().bodies) names.push_back(b.name);
  return names;
}

std::vector<std::string> ContactNames(const Simulator& sim, FuzzedDataProvider& in) {
  std::vector<std::string> names{""};
  const auto& colliders = sim.scene().colliders;
  for (const Collider& c : colliders) names.push_back(c.name);
  if (!colliders.empty()) {
    const std::size_t a = in.ConsumeIntegralInRange<std::size_t>(0, colliders.size() - 1);
    const std::size_t b = in.ConsumeIntegralInRange<std::size_t>(0, colliders.size() - 1);
    names.push_back(colliders[a].name + "/" + colliders[b].name);  // a == b: not a contact
    names.push_back(colliders[a].name + "/");
  }
  return names;
}

// ---------------------------------------------------------------------------------------------
// the requests

void Step(World& w, FuzzedDataProvider& in) {
  const int n = in.ConsumeIntegralInRange<int>(1, 8);
  for (int k = 0; k < n && w.steps < kMaxSteps; ++k, ++w.steps) {
    fuzz::StepUnderContract(*w.sim, "~step");
  }
}

// OnResetState: body (empty = the initial body 0), then the node's ValidateInitialConditions and
// InitialState, then SetState.
void Reset(World& w, FuzzedDataProvider& in) {
  const Scene& urdf_scene = w.shipped->urdf.scene;
  int body = 0;
  if (in.ConsumeBool()) {  // a body name: one of the URDF's or anything
    std::vector<std::string> names;
    for (const RigidBody& b : urdf_scene.bodies) names.push_back(b.name);
    const std::string name = PickName(in, names);
    body = -1;
    for (std::size_t b = 0; b < urdf_scene.bodies.size(); ++b) {
      if (urdf_scene.bodies[b].name == name) body = static_cast<int>(b);
    }
  }
  node::InitialConditions request;
  if (in.ConsumeBool()) request.inclination = HostileDouble(in);
  if (in.ConsumeBool()) request.spin = HostileDouble(in);
  if (in.ConsumeBool()) request.position = HostileVector(in);
  if (in.ConsumeBool()) {
    const double x = HostileDouble(in), y = HostileDouble(in), z = HostileDouble(in);
    request.orientation = Eigen::Quaterniond(HostileDouble(in), x, y, z);
  }
  if (in.ConsumeBool()) request.linear_velocity = HostileVector(in);
  if (in.ConsumeBool()) request.angular_velocity = HostileVector(in);

  const Snapshot before(*w.sim);
  std::vector<BodyState> state;
  try {
    if (body < 0) throw std::invalid_argument("not a free body");
    node::ValidateInitialConditions(request);
    state = w.shipped->configured.initial_state;
    if (body == 0) {
      state = node::InitialState(w.shipped->urdf, body, request);
    } else {
      state[static_cast<std::size_t>(body)] =
          node::InitialState(w.shipped->urdf, body, request)[static_cast<std::size_t>(body)];
    }
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "~reset validation");
    before.RequireUnchanged(*w.sim, "~reset");
    return;
  } catch (const std::exception& e) {
    Finding(std::string("~reset: the node's validation threw an undocumented type: ") + e.what());
  }
  Require(fuzz::Finite(state), "~reset: a validated request gives a non-finite state");
  try {
    w.sim->SetState(state);
  } catch (const std::invalid_argument& e) {
    // Accepted rejections (the node's try block covers SetState, nothing changes): the world
    // changed (bodies added or removed), so the URDF's start does not fit any more; or an
    // orientation whose |q|² overflows (components ~1e300): ValidateInitialConditions lets it
    // through (finite, non-zero), normalized() makes it zero and SetState rejects that.
    const bool overflowing_orientation =
        request.orientation && !std::isfinite(request.orientation->squaredNorm());
    Require(state.size() != w.sim->scene().bodies.size() || overflowing_orientation,
            std::string("~reset: SetState rejected a validated start: ") + e.what());
    before.RequireUnchanged(*w.sim, "~reset");
    return;
  } catch (const std::exception& e) {
    Finding(std::string("~reset: SetState threw an undocumented type: ") + e.what());
  }
  Require(!w.sim->diverged(), "~reset: diverged() survives SetState");
}

// OnResetWorld: the configured start (the node calls it without a try: it must not throw while
// the world is the configured one).
void ResetWorld(World& w) {
  if (w.sim->scene().bodies.size() != w.shipped->configured.bodies.size()) return;
  try {
    w.sim->SetState(w.shipped->configured.initial_state);
  } catch (const std::exception& e) {
    Finding(std::string("~reset_world threw: ") + e.what());
  }
}

// OnResetSimulation: a fresh simulator with the configured scene and solver, the time kept.
void ResetSimulation(World& w) {
  const double time = w.sim->time();
  try {
    w.sim = std::make_unique<Simulator>(w.shipped->configured, w.configured_options);
    w.sim->SetTime(time);
  } catch (const std::exception& e) {
    Finding(std::string("~reset_simulation threw: ") + e.what());
  }
  w.wrenches = 0;
  w.beyond_node_bounds = false;  // the configured scene, no wrench
}

// OnSetSolverProperties: each field optional, names looked up, ValidateSimulatorOptions, SetOptions.
void SetSolverProperties(World& w, FuzzedDataProvider& in) {
  static const char* kSolvers[] = {"jacobi", "modified_jacobi", "gauss_seidel", "gauss-seidel",
                                   "GAUSS_SEIDEL"};
  static const char* kSchemes[] = {"explicit", "implicit_midpoint", "implicit"};
  SimulatorOptions o = w.sim->options();
  const Snapshot before(*w.sim);
  try {
    if (in.ConsumeBool()) o.time_step = HostileDouble(in);
    if (in.ConsumeBool()) o.solver.tolerance_rel = HostileDouble(in);
    if (in.ConsumeBool()) o.solver.tolerance_abs = HostileDouble(in);
    if (in.ConsumeBool()) o.solver.relaxation = HostileDouble(in);
    if (in.ConsumeBool()) o.solver.max_iterations = HostileInt(in);
    if (in.ConsumeBool()) {
      const std::string name = kSolvers[in.ConsumeIntegralInRange<int>(0, 4)];
      const auto type = SolverTypeFromName(name);
      if (!type) throw std::invalid_argument("unknown solver \"" + name + "\"");
      o.solver.type = *type;
    }
    if (in.ConsumeBool()) {
      const std::string name = kSchemes[in.ConsumeIntegralInRange<int>(0, 2)];
      const auto scheme = GyroscopicSchemeFromName(name);
      if (!scheme) throw std::invalid_argument("unknown gyroscopic scheme \"" + name + "\"");
      o.gyroscopic = *scheme;
    }
    ValidateSimulatorOptions(o);
    o.solver.max_iterations = std::min(o.solver.max_iterations, kFuzzMaxIterations);
    w.sim->SetOptions(o);
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "~set_solver_properties");
    before.RequireUnchanged(*w.sim, "~set_solver_properties");
    return;
  } catch (const std::exception& e) {
    Finding(std::string("~set_solver_properties threw an undocumented type: ") + e.what());
  }
  Require(Snapshot::SameOptions(w.sim->options(), o),
          "~set_solver_properties: accepted, but the options are not the requested ones");
  Require(fuzz::SameBits(w.sim->state(), before.state),
          "~set_solver_properties changed the state");
}

// OnSetFrictionSet: the set by name (unknown: rejected before the core), then SetFrictionSet
// (the node catches std::invalid_argument only).
void SetFrictionSet(World& w, FuzzedDataProvider& in) {
  std::vector<std::string> set_names{"sphere_", "Exact", ""};
  for (FrictionSet s : kAllFrictionSets) set_names.emplace_back(FrictionSetName(s));
  const std::string set_name = PickName(in, set_names);
  const std::string contact = PickName(in, ContactNames(*w.sim, in));
  const auto set = FrictionSetFromName(set_name);
  if (!set) return;  // the node answers "unknown friction set" without touching the simulator
  const Snapshot before(*w.sim);
  try {
    w.sim->SetFrictionSet(*set, contact);
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "~set_friction_set");
    before.RequireUnchanged(*w.sim, "~set_friction_set");
    return;
  } catch (const std::exception& e) {
    Finding(std::string("~set_friction_set: SetFrictionSet threw what the node does not catch: ") +
            e.what());
  }
  Require(fuzz::SameBits(w.sim->state(), before.state), "~set_friction_set changed the state");
  const Scene& scene = w.sim->scene();
  if (contact.empty()) {
    for (const Collider& c : scene.colliders) {
      Require(c.law.friction_set == *set, "~set_friction_set \"\": a collider kept its set");
    }
  }
  if (!contact.empty()) {
    Require(w.sim->FrictionSetOf(contact) == *set,
            "~set_friction_set: accepted, but the contact does not have the set");
  }
}

// OnGetFrictionSet: FrictionSetOf (std::invalid_argument caught).
void GetFrictionSet(World& w, FuzzedDataProvider& in) {
  const std::string contact = PickName(in, ContactNames(*w.sim, in));
  if (contact.empty()) return;
  try {
    (void)w.sim->FrictionSetOf(contact);
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "~get_friction_set");
  } catch (const std::exception& e) {
    Finding(std::string("~get_friction_set threw what the node does not catch: ") + e.what());
  }
}

// OnApplyBodyWrench: body by name, force and torque finite and |.| <= kMaxExternalForce, the point
// of application within kMaxInitialCoordinate, at most kMaxWrenches; the wrenches of a body add
// up (ApplyWrenches) into one SetExternalWrench.
void ApplyBodyWrench(World& w, FuzzedDataProvider& in) {
  const std::string name = PickName(in, BodyNames(*w.sim));
  const Eigen::Vector3d force = HostileVector(in);
  const Eigen::Vector3d torque = HostileVector(in);
  const Eigen::Vector3d point = HostileVector(in);
  int body = -1;
  for (std::size_t b = 0; b < w.sim->scene().bodies.size(); ++b) {
    if (w.sim->scene().bodies[b].name == name) body = static_cast<int>(b);
  }
  const bool valid = body >= 0 && force.allFinite() && force.norm() <= kMaxExternalForce &&
                     torque.allFinite() && torque.norm() <= kMaxExternalForce &&
                     point.allFinite() &&
                     point.norm() <= scene_io::kMaxInitialCoordinate && w.wrenches < kMaxWrenches;
  if (!valid) return;  // the node answers without touching the simulator
  const BodyState& s = w.sim->state()[static_cast<std::size_t>(body)];
  const Eigen::Vector3d arm = point - s.position;
  const auto [f, t] = w.sim->ExternalWrench(body);
  const Eigen::Vector3d total_force = f + force;
  const Eigen::Vector3d total_torque = t + torque + arm.cross(force);
  // the node's sum stays below 1000 x (1e6 + 3.5e3 x 1e6); one of a raw wrench (1e308) overflows
  if (w.beyond_node_bounds && !(total_force.allFinite() && total_torque.allFinite())) return;
  try {
    w.sim->SetExternalWrench(body, total_force, total_torque);
  } catch (const std::exception& e) {
    Finding(std::string("~apply_body_wrench: SetExternalWrench rejected a validated wrench: ") +
            e.what());
  }
  ++w.wrenches;
}

// OnClearBodyWrenches: a known body's wrench zeroed.
void ClearBodyWrenches(World& w, FuzzedDataProvider& in) {
  const std::string name = PickName(in, BodyNames(*w.sim));
  for (std::size_t b = 0; b < w.sim->scene().bodies.size(); ++b) {
    if (w.sim->scene().bodies[b].name != name) continue;
    w.sim->SetExternalWrench(static_cast<int>(b), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    const auto [f, t] = w.sim->ExternalWrench(static_cast<int>(b));
    Require(f.isZero(0.0) && t.isZero(0.0), "~clear_body_wrenches: a wrench is left");
  }
  w.wrenches = 0;
}

// The core alone: SetExternalWrench with any index and value (std::out_of_range,
// std::invalid_argument for non-finite; a finite one is accepted, whatever its size).
void RawWrench(World& w, FuzzedDataProvider& in) {
  const int body = in.ConsumeIntegralInRange<int>(-2, static_cast<int>(kMaxBodies) + 1);
  const Eigen::Vector3d force = HostileVector(in);
  const Eigen::Vector3d torque = HostileVector(in);
  const Snapshot before(*w.sim);
  try {
    w.sim->SetExternalWrench(body, force, torque);
  } catch (const std::out_of_range& e) {
    Require(body < 0 || static_cast<std::size_t>(body) >= w.sim->scene().bodies.size(),
            "SetExternalWrench: out_of_range for a valid body");
    before.RequireUnchanged(*w.sim, "SetExternalWrench");
    return;
  } catch (const std::invalid_argument& e) {
    Require(!force.allFinite() || !torque.allFinite(),
            std::string("SetExternalWrench rejected a finite wrench: ") + e.what());
    before.RequireUnchanged(*w.sim, "SetExternalWrench");
    return;
  } catch (const std::exception& e) {
    Finding(std::string("SetExternalWrench threw an undocumented type: ") + e.what());
  }
  Require(force.allFinite() && torque.allFinite(), "SetExternalWrench accepted a non-finite value");
  w.beyond_node_bounds = true;
}

// The core alone: SetState with one entry of one body replaced by any value (std::invalid_argument
// for a non-finite value, a zero quaternion, a wrong size, or a state whose energy overflows: a
// term of MechanicalEnergy, their sum, |v|² or |ω|²; any other is accepted).
void RawSetState(World& w, FuzzedDataProvider& in) {
  std::vector<BodyState> state = w.sim->state();
  if (!state.empty()) {
    BodyState& s = state[in.ConsumeIntegralInRange<std::size_t>(0, state.size() - 1)];
    switch (in.ConsumeIntegralInRange<int>(0, 3)) {
      case 0: s.position = HostileVector(in); break;
      case 1: s.linear_velocity = HostileVector(in); break;
      case 2: s.angular_velocity = HostileVector(in); break;
      default: {
        const double x = HostileDouble(in), y = HostileDouble(in), z = HostileDouble(in);
        s.orientation = Eigen::Quaterniond(HostileDouble(in), x, y, z);
      }
    }
  }
  if (in.ConsumeIntegralInRange<int>(0, 15) == 0) state.emplace_back();  // a wrong size
  if (std::getenv("FUZZ_TRACE") != nullptr && !state.empty()) {
    const BodyState& s = state.front();
    std::fprintf(stderr, "  SetState body 0: r %.17g %.17g %.17g q %.17g %.17g %.17g %.17g "
                 "v %.17g %.17g %.17g w %.17g %.17g %.17g\n", s.position.x(), s.position.y(),
                 s.position.z(), s.orientation.x(), s.orientation.y(), s.orientation.z(),
                 s.orientation.w(), s.linear_velocity.x(), s.linear_velocity.y(),
                 s.linear_velocity.z(), s.angular_velocity.x(), s.angular_velocity.y(),
                 s.angular_velocity.z());
  }
  const Snapshot before(*w.sim);
  try {
    w.sim->SetState(state);
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "SetState");
    before.RequireUnchanged(*w.sim, "SetState");
    bool refusable = state.size() != w.sim->scene().bodies.size() || !fuzz::Finite(state);
    if (!refusable) {
      refusable = !std::isfinite(MechanicalEnergy(w.sim->scene(), state));
      for (const BodyState& s : state) {
        refusable = refusable || !(s.orientation.coeffs().squaredNorm() > 0.0) ||
                    !std::isfinite(s.linear_velocity.squaredNorm()) ||
                    !std::isfinite(s.angular_velocity.squaredNorm());
      }
    }
    Require(refusable, std::string("SetState refused a finite state of finite energy: ") +
                           e.what());
    return;
  } catch (const std::exception& e) {
    Finding(std::string("SetState threw an undocumented type: ") + e.what());
  }
  Require(fuzz::Finite(w.sim->state()) && !w.sim->diverged(),
          "SetState accepted a non-finite state");
  Require(std::isfinite(w.sim->Energy()), "SetState accepted a state whose energy overflows");
  w.beyond_node_bounds = true;
}

void RawSetTime(World& w, FuzzedDataProvider& in) {
  const double time = HostileDouble(in);
  const Snapshot before(*w.sim);
  try {
    w.sim->SetTime(time);
  } catch (const std::invalid_argument&) {
    Require(!std::isfinite(time), "SetTime rejected a finite time");
    before.RequireUnchanged(*w.sim, "SetTime");
    return;
  }
  Require(fuzz::SameBits(w.sim->time(), time), "SetTime: the time is not the one set");
}

// AddBodies: one shipped scene's bodies and their colliders as a model (names suffixed, or not:
// then they clash), moved by an offset within the start bounds (the node's bound for every pose).
void AddBodies(World& w, FuzzedDataProvider& in) {
  const ShippedScene& source = Scenes()[in.ConsumeIntegralInRange<std::size_t>(0, Scenes().size() - 1)];
  if (w.sim->scene().bodies.size() + source.configured.bodies.size() > kMaxBodies) return;
  Scene model;
  const bool rename = in.ConsumeIntegralInRange<int>(0, 3) != 0;
  const std::string suffix = "_" + std::to_string(++w.added);
  model.bodies = source.configured.bodies;
  for (RigidBody& b : model.bodies) {
    if (rename) b.name += suffix;
  }
  for (const Collider& c : source.configured.colliders) {
    if (c.body == kWorld) continue;  // the model's ground is the world's
    model.colliders.push_back(c);
    if (rename) model.colliders.back().name += suffix;
  }
  Eigen::Vector3d offset = HostileVector(in);
  std::vector<BodyState> state = source.configured.initial_state;
  const Snapshot before(*w.sim);
  try {
    scene_io::CheckInitialPosition("offset", offset);
    for (BodyState& s : state) {
      s.position += offset;
      scene_io::CheckInitialPosition("position", s.position);
    }
  } catch (const std::invalid_argument&) {
    return;  // rejected before the core
  }
  int first = -1;
  try {
    first = w.sim->AddBodies(model, state);
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "AddBodies");
    Require(!rename, std::string("AddBodies rejected a model with fresh names: ") + e.what());
    before.RequireUnchanged(*w.sim, "AddBodies");
    return;
  } catch (const std::exception& e) {
    Finding(std::string("AddBodies threw an undocumented type: ") + e.what());
  }
  Require(first == static_cast<int>(before.state.size()) &&
              w.sim->scene().bodies.size() == before.state.size() + model.bodies.size(),
          "AddBodies: the bodies are not appended");
  for (std::size_t b = 0; b < before.state.size(); ++b) {
    Require(fuzz::SameBits(w.sim->state()[b], before.state[b]),
            "AddBodies changed the state of a body already there");
  }
}

// RemoveBodies: indices from the input (some out of range, repeated, or colliders on bodies).
void RemoveBodies(World& w, FuzzedDataProvider& in) {
  const int bodies = static_cast<int>(w.sim->scene().bodies.size());
  const int colliders = static_cast<int>(w.sim->scene().colliders.size());
  std::vector<int> remove_bodies;
  std::vector<int> remove_colliders;
  for (int k = in.ConsumeIntegralInRange<int>(0, 2); k > 0; --k) {
    remove_bodies.push_back(in.ConsumeIntegralInRange<int>(-1, bodies));
  }
  for (int k = in.ConsumeIntegralInRange<int>(0, 1); k > 0; --k) {
    remove_colliders.push_back(in.ConsumeIntegralInRange<int>(-1, colliders));
  }
  const Snapshot before(*w.sim);
  try {
    w.sim->RemoveBodies(remove_bodies, remove_colliders);
  } catch (const std::out_of_range& e) {
    fuzz::RequireMessage(e, "RemoveBodies");
    before.RequireUnchanged(*w.sim, "RemoveBodies");
    return;
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "RemoveBodies");
    before.RequireUnchanged(*w.sim, "RemoveBodies");
    return;
  } catch (const std::exception& e) {
    Finding(std::string("RemoveBodies threw an undocumented type: ") + e.what());
  }
  // the rest keep their state bit for bit, in order
  std::vector<BodyState> kept;
  for (int b = 0; b < bodies; ++b) {
    if (std::find(remove_bodies.begin(), remove_bodies.end(), b) == remove_bodies.end()) {
      kept.push_back(before.state[static_cast<std::size_t>(b)]);
    }
  }
  Require(fuzz::SameBits(w.sim->state(), kept), "RemoveBodies: the remaining bodies changed");
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  RegisterFclPairs();
  for (const char* name : {"tippe_top", "tippe_top_duel", "die", "coin"}) {
    ShippedScene s;
    s.urdf = scene_io::LoadUrdfFile(std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/urdf/" + name +
                                    ".urdf");
    s.configured = s.urdf.scene;
    s.configured.initial_state = node::InitialState(s.urdf, 0, node::InitialConditions{});
    Scenes().push_back(std::move(s));
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  World w;
  w.shipped = &Scenes()[in.ConsumeIntegralInRange<std::size_t>(0, Scenes().size() - 1)];
  w.sim = std::make_unique<Simulator>(w.shipped->configured, w.configured_options);
  // FUZZ_TRACE=1 in the environment: print the requests of an input (to read a finding)
  static const bool trace = std::getenv("FUZZ_TRACE") != nullptr;
  for (int request = 0; request < kMaxRequests && in.remaining_bytes() > 0; ++request) {
    const int kind = in.ConsumeIntegralInRange<int>(0, 15);
    if (trace) {
      std::fprintf(stderr, "request %d: kind %d, t = %.17g, options dt %.17g tol %.17g/%.17g "
                   "it %d alpha %.17g solver %d gyro %d\n", request, kind, w.sim->time(),
                   w.sim->options().time_step, w.sim->options().solver.tolerance_rel,
                   w.sim->options().solver.tolerance_abs, w.sim->options().solver.max_iterations,
                   w.sim->options().solver.relaxation,
                   static_cast<int>(w.sim->options().solver.type),
                   static_cast<int>(w.sim->options().gyroscopic));
    }
    switch (kind) {
      case 0: case 1: case 2: Step(w, in); break;
      case 3: Reset(w, in); break;
      case 4: ResetWorld(w); break;
      case 5: ResetSimulation(w); break;
      case 6: SetSolverProperties(w, in); break;
      case 7: SetFrictionSet(w, in); break;
      case 8: GetFrictionSet(w, in); break;
      case 9: ApplyBodyWrench(w, in); break;
      case 10: ClearBodyWrenches(w, in); break;
      case 11: RawWrench(w, in); break;
      case 12: RawSetState(w, in); break;
      case 13: RawSetTime(w, in); break;
      case 14: AddBodies(w, in); break;
      default: RemoveBodies(w, in); break;
    }
    fuzz::RequireFiniteOrFault(*w.sim, "after a request", /*energy=*/true);
  }
  return 0;
}
