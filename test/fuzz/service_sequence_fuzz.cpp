// libFuzzer target: the input bytes, decoded by FuzzedDataProvider, are a sequence of the node's
// service requests against the real world::World the node serves (include/nonsmooth_sim/world):
//
//   ~step (the scheduled wrenches applied before each step, as the node does), ~reset,
//   ~reset_world, ~reset_simulation, ~set_solver_properties, ~set_friction_set,
//   ~get_friction_set, ~apply_body_wrench, ~clear_body_wrenches, ~spawn_urdf_model,
//   ~delete_model; and of the core alone: SetState, SetTime, SetExternalWrench with any value.
//
// The rules, names and bounds are the World's own (no copy here): a request goes to the World
// call the node's handler makes, which validates it and hands it to the core's setter, which
// validates again. Checked:
//  - a rejected request leaves the world bit for bit as it was: state, time, diverged(), options,
//    scene sizes and names, every collider's and pair's friction set, the external wrenches, the
//    models, the scheduled wrenches and the configured start;
//  - only the documented exception types come out (std::invalid_argument, and
//    std::out_of_range for indices of the core's setters);
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
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fuzz_support.h"
#include "nonsmooth_sim/collision_fcl/fcl_pairs.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "nonsmooth_sim/world/world.h"

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
  std::vector<std::string> models;      // names and parts of the registry
  std::vector<double> scheduled;        // body, start, end of each scheduled wrench
  std::vector<std::string> configured;  // the configured start's bodies
  std::vector<BodyState> configured_state;

  explicit Snapshot(const world::World& world) : Snapshot(world.sim()) {
    for (const world::Model& m : world.models().models()) {
      models.push_back(m.name + "|" + m.prefix + "|" + std::to_string(m.bodies.size()) + "|" +
                       std::to_string(m.colliders.size()));
      for (int b : m.bodies) models.push_back(std::to_string(b));
    }
    for (const world::ExternalWrench& x : world.wrenches().wrenches()) {
      scheduled.insert(scheduled.end(), {static_cast<double>(x.body), x.start, x.end});
    }
    for (const RigidBody& b : world.configured_scene().bodies) configured.push_back(b.name);
    configured_state = world.configured_scene().initial_state;
  }

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

  void RequireUnchanged(const world::World& world, const std::string& request) const {
    const Snapshot now(world);
    Require(now.models == models, request + ": rejected, but the models changed");
    Require(now.scheduled.size() == scheduled.size(),
            request + ": rejected, but the wrench schedule changed");
    for (std::size_t i = 0; i < scheduled.size(); ++i) {
      Require(fuzz::SameBits(now.scheduled[i], scheduled[i]),
              request + ": rejected, but a scheduled wrench changed");
    }
    Require(now.configured == configured && fuzz::SameBits(now.configured_state, configured_state),
            request + ": rejected, but the configured start changed");
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

// A shipped scene: the URDF the node starts with, and as a model to spawn (no ground).
struct ShippedScene {
  scene_io::UrdfScene urdf;
  Scene model;
};

std::vector<ShippedScene>& Scenes() {
  static std::vector<ShippedScene> scenes;
  return scenes;
}

// The node's world for one input, with the fuzzer's bookkeeping.
struct Session {
  std::unique_ptr<world::World> world;
  int steps = 0;
  int spawned = 0;  // models spawned (a fresh name gets this as suffix)
  // a core-only request put a value beyond the node's bounds into the simulator (RawSetState,
  // RawWrench): the schedule's sums of wrenches may overflow then; the steps are held to the
  // whole contract all the same
  bool beyond_node_bounds = false;
  Simulator& sim() { return world->sim(); }
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

void Step(Session& w, FuzzedDataProvider& in) {
  const int n = in.ConsumeIntegralInRange<int>(1, 8);
  for (int k = 0; k < n && w.steps < kMaxSteps; ++k, ++w.steps) {
    // as the node's StepOnce: the scheduled wrenches of the step, then the step
    try {
      w.world->ApplyScheduledWrenches(w.sim().options().time_step);
    } catch (const std::exception& e) {
      // a raw wrench or state beyond the node's bounds can make the sums overflow: the core
      // refuses the non-finite wrench, as it refuses any
      Require(w.beyond_node_bounds,
              std::string("~step: the scheduled wrenches were refused: ") + e.what());
    }
    fuzz::StepUnderContract(w.sim(), "~step");
  }
}

// OnResetState: World::Reset (a body of the start-up model, its initial conditions).
void Reset(Session& w, FuzzedDataProvider& in) {
  const Scene& urdf_scene = w.world->urdf().scene;
  std::string body;
  if (in.ConsumeBool()) {  // a body name: one of the URDF's or anything
    std::vector<std::string> names;
    for (const RigidBody& b : urdf_scene.bodies) names.push_back(b.name);
    body = PickName(in, names);
  }
  world::InitialConditions request;
  if (in.ConsumeBool()) request.inclination = HostileDouble(in);
  if (in.ConsumeBool()) request.spin = HostileDouble(in);
  if (in.ConsumeBool()) request.position = HostileVector(in);
  if (in.ConsumeBool()) {
    const double x = HostileDouble(in), y = HostileDouble(in), z = HostileDouble(in);
    request.orientation = Eigen::Quaterniond(HostileDouble(in), x, y, z);
  }
  if (in.ConsumeBool()) request.linear_velocity = HostileVector(in);
  if (in.ConsumeBool()) request.angular_velocity = HostileVector(in);

  const Snapshot before(*w.world);
  try {
    w.world->Reset(body, request);
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "~reset");
    before.RequireUnchanged(*w.world, "~reset");
    return;
  } catch (const std::exception& e) {
    Finding(std::string("~reset threw an undocumented type: ") + e.what());
  }
  Require(fuzz::Finite(w.sim().state()), "~reset: an accepted start is not finite");
  Require(!w.sim().diverged(), "~reset: diverged() survives the reset");
}

// OnResetWorld: the configured start (the node calls it without a try: it must not throw).
void ResetWorld(Session& w) {
  try {
    w.world->ResetWorld();
  } catch (const std::exception& e) {
    Finding(std::string("~reset_world threw: ") + e.what());
  }
  // the configured start (SetState normalises the quaternions: those may differ in the last bit)
  const std::vector<BodyState>& start = w.world->configured_scene().initial_state;
  Require(w.sim().state().size() == start.size(), "~reset_world: the bodies changed");
  for (std::size_t i = 0; i < start.size(); ++i) {
    const BodyState& s = w.sim().state()[i];
    Require(s.position == start[i].position && s.linear_velocity == start[i].linear_velocity &&
                s.angular_velocity == start[i].angular_velocity,
            "~reset_world: the state is not the configured start");
  }
}

// OnResetSimulation: a fresh simulator with the configured scene and solver, the time kept.
void ResetSimulation(Session& w) {
  const double time = w.sim().time();
  try {
    w.world->ResetSimulation();
  } catch (const std::exception& e) {
    Finding(std::string("~reset_simulation threw: ") + e.what());
  }
  Require(fuzz::SameBits(w.sim().time(), time), "~reset_simulation: the time was not kept");
  // a fresh simulator has no raw wrench; one whose every model was deleted keeps its simulator
  w.beyond_node_bounds = false;
  for (std::size_t b = 0; b < w.sim().scene().bodies.size(); ++b) {
    const auto [f, t] = w.sim().ExternalWrench(static_cast<int>(b));
    w.beyond_node_bounds = w.beyond_node_bounds || !f.isZero(0.0) || !t.isZero(0.0);
  }
}

// OnSetSolverProperties: each field optional, names looked up, ValidateSimulatorOptions, SetOptions.
void SetSolverProperties(Session& w, FuzzedDataProvider& in) {
  static const char* kSolvers[] = {"jacobi", "modified_jacobi", "gauss_seidel", "gauss-seidel",
                                   "GAUSS_SEIDEL"};
  static const char* kSchemes[] = {"explicit", "implicit_midpoint", "implicit"};
  SimulatorOptions o = w.sim().options();
  const Snapshot before(*w.world);
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
    w.sim().SetOptions(o);
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "~set_solver_properties");
    before.RequireUnchanged(*w.world, "~set_solver_properties");
    return;
  } catch (const std::exception& e) {
    Finding(std::string("~set_solver_properties threw an undocumented type: ") + e.what());
  }
  Require(Snapshot::SameOptions(w.sim().options(), o),
          "~set_solver_properties: accepted, but the options are not the requested ones");
  Require(fuzz::SameBits(w.sim().state(), before.state),
          "~set_solver_properties changed the state");
}

// OnSetFrictionSet: the set by name (unknown: rejected before the core), then SetFrictionSet
// (the node catches std::invalid_argument only).
void SetFrictionSet(Session& w, FuzzedDataProvider& in) {
  std::vector<std::string> set_names{"sphere_", "Exact", ""};
  for (FrictionSet s : kAllFrictionSets) set_names.emplace_back(FrictionSetName(s));
  const std::string set_name = PickName(in, set_names);
  const std::string contact = PickName(in, ContactNames(w.sim(), in));
  const auto set = FrictionSetFromName(set_name);
  if (!set) return;  // the node answers "unknown friction set" without touching the simulator
  const Snapshot before(*w.world);
  try {
    w.sim().SetFrictionSet(*set, contact);
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "~set_friction_set");
    before.RequireUnchanged(*w.world, "~set_friction_set");
    return;
  } catch (const std::exception& e) {
    Finding(std::string("~set_friction_set: SetFrictionSet threw what the node does not catch: ") +
            e.what());
  }
  Require(fuzz::SameBits(w.sim().state(), before.state), "~set_friction_set changed the state");
  const Scene& scene = w.sim().scene();
  if (contact.empty()) {
    for (const Collider& c : scene.colliders) {
      Require(c.law.friction_set == *set, "~set_friction_set \"\": a collider kept its set");
    }
  }
  if (!contact.empty()) {
    Require(w.sim().FrictionSetOf(contact) == *set,
            "~set_friction_set: accepted, but the contact does not have the set");
  }
}

// OnGetFrictionSet: FrictionSetOf (std::invalid_argument caught).
void GetFrictionSet(Session& w, FuzzedDataProvider& in) {
  const std::string contact = PickName(in, ContactNames(w.sim(), in));
  if (contact.empty()) return;
  try {
    (void)w.sim().FrictionSetOf(contact);
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "~get_friction_set");
  } catch (const std::exception& e) {
    Finding(std::string("~get_friction_set threw what the node does not catch: ") + e.what());
  }
}

// OnApplyBodyWrench: World::ApplyWrench with hostile values; accepted with a non-zero duration, it
// is scheduled.
void ApplyBodyWrench(Session& w, FuzzedDataProvider& in) {
  std::vector<std::string> names = BodyNames(w.sim());
  for (std::size_t b = 0; b < w.sim().scene().bodies.size(); ++b) {
    names.push_back(w.world->BodyName(static_cast<int>(b)));
  }
  world::WrenchRequest request;
  request.body = PickName(in, names);
  if (in.ConsumeBool()) request.reference_frame = PickName(in, names);
  request.force = HostileVector(in);
  request.torque = HostileVector(in);
  request.point = HostileVector(in);
  if (in.ConsumeBool()) request.start = HostileDouble(in);
  request.duration = in.ConsumeBool() ? HostileDouble(in) : 0.05;
  const Snapshot before(*w.world);
  std::optional<world::ExternalWrench> applied;
  try {
    applied = w.world->ApplyWrench(request);
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "~apply_body_wrench");
    before.RequireUnchanged(*w.world, "~apply_body_wrench");
    return;
  } catch (const std::exception& e) {
    Finding(std::string("~apply_body_wrench threw an undocumented type: ") + e.what());
  }
  Require(applied.has_value() == (request.duration != 0.0),
          "~apply_body_wrench: accepted, but not scheduled iff its duration is not 0");
  Require(w.world->wrenches().wrenches().size() ==
              before.scheduled.size() / 3 + (applied ? 1 : 0),
          "~apply_body_wrench: accepted, but the schedule did not grow by it");
  Require(fuzz::SameBits(w.sim().state(), before.state), "~apply_body_wrench changed the state");
}

// OnClearBodyWrenches: World::ClearWrenches; a known body's wrenches gone, in the core too.
void ClearBodyWrenches(Session& w, FuzzedDataProvider& in) {
  const std::string name = PickName(in, BodyNames(w.sim()));
  const Snapshot before(*w.world);
  if (!w.world->ClearWrenches(name)) {
    before.RequireUnchanged(*w.world, "~clear_body_wrenches of no body");
    return;
  }
  const int b = w.world->BodyIndex(name);
  const auto [f, t] = w.sim().ExternalWrench(b);
  Require(f.isZero(0.0) && t.isZero(0.0), "~clear_body_wrenches: a wrench is left");
  for (const world::ExternalWrench& x : w.world->wrenches().wrenches()) {
    Require(x.body != b, "~clear_body_wrenches: a scheduled wrench on the body is left");
  }
}

// The core alone: SetExternalWrench with any index and value (std::out_of_range,
// std::invalid_argument for non-finite; a finite one is accepted, whatever its size).
void RawWrench(Session& w, FuzzedDataProvider& in) {
  const int body = in.ConsumeIntegralInRange<int>(-2, static_cast<int>(kMaxBodies) + 1);
  const Eigen::Vector3d force = HostileVector(in);
  const Eigen::Vector3d torque = HostileVector(in);
  const Snapshot before(*w.world);
  try {
    w.sim().SetExternalWrench(body, force, torque);
  } catch (const std::out_of_range& e) {
    Require(body < 0 || static_cast<std::size_t>(body) >= w.sim().scene().bodies.size(),
            "SetExternalWrench: out_of_range for a valid body");
    before.RequireUnchanged(*w.world, "SetExternalWrench");
    return;
  } catch (const std::invalid_argument& e) {
    Require(!force.allFinite() || !torque.allFinite(),
            std::string("SetExternalWrench rejected a finite wrench: ") + e.what());
    before.RequireUnchanged(*w.world, "SetExternalWrench");
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
void RawSetState(Session& w, FuzzedDataProvider& in) {
  std::vector<BodyState> state = w.sim().state();
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
  const Snapshot before(*w.world);
  try {
    w.sim().SetState(state);
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "SetState");
    before.RequireUnchanged(*w.world, "SetState");
    bool refusable = state.size() != w.sim().scene().bodies.size() || !fuzz::Finite(state);
    if (!refusable) {
      refusable = !std::isfinite(MechanicalEnergy(w.sim().scene(), state));
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
  Require(fuzz::Finite(w.sim().state()) && !w.sim().diverged(),
          "SetState accepted a non-finite state");
  Require(std::isfinite(w.sim().Energy()), "SetState accepted a state whose energy overflows");
  w.beyond_node_bounds = true;
}

void RawSetTime(Session& w, FuzzedDataProvider& in) {
  const double time = HostileDouble(in);
  const Snapshot before(*w.world);
  try {
    w.sim().SetTime(time);
  } catch (const std::invalid_argument&) {
    Require(!std::isfinite(time), "SetTime rejected a finite time");
    before.RequireUnchanged(*w.world, "SetTime");
    return;
  }
  Require(fuzz::SameBits(w.sim().time(), time), "SetTime: the time is not the one set");
}

// OnSpawnUrdfModel: World::Spawn of one shipped scene as a model, under a name of the input (fresh,
// taken, or anything), at a hostile pose relative to the world or a body.
void Spawn(Session& w, FuzzedDataProvider& in) {
  const ShippedScene& source =
      Scenes()[in.ConsumeIntegralInRange<std::size_t>(0, Scenes().size() - 1)];
  if (w.sim().scene().bodies.size() + source.model.bodies.size() > kMaxBodies) return;
  std::vector<std::string> names{"m" + std::to_string(++w.spawned), "1m", "a/b", ""};
  for (const world::Model& m : w.world->models().models()) names.push_back(m.name);
  const std::string name = PickName(in, names);
  std::vector<std::string> frames{"", "world"};
  for (const RigidBody& b : w.sim().scene().bodies) frames.push_back(b.name);
  const std::string reference = in.ConsumeBool() ? PickName(in, frames) : "";
  world::Pose pose;
  pose.position = in.ConsumeBool() ? HostileVector(in) : Eigen::Vector3d(0.5, 0.0, 0.1);
  if (in.ConsumeBool()) {
    const double x = HostileDouble(in), y = HostileDouble(in), z = HostileDouble(in);
    pose.orientation = Eigen::Quaterniond(HostileDouble(in), x, y, z);
  }
  const Snapshot before(*w.world);
  try {
    w.world->Spawn(name, source.model, reference, pose, "/" + name + "/robot_description");
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "~spawn_urdf_model");
    before.RequireUnchanged(*w.world, "~spawn_urdf_model");
    return;
  } catch (const std::exception& e) {
    Finding(std::string("~spawn_urdf_model threw an undocumented type: ") + e.what());
  }
  Require(w.world->models().Find(name) >= 0, "~spawn_urdf_model: accepted, but no such model");
  Require(w.sim().scene().bodies.size() == before.state.size() + source.model.bodies.size() &&
              w.world->configured_scene().bodies.size() ==
                  before.configured.size() + source.model.bodies.size(),
          "~spawn_urdf_model: the bodies are not appended to the world and its configured start");
  for (std::size_t b = 0; b < before.state.size(); ++b) {
    Require(fuzz::SameBits(w.sim().state()[b], before.state[b]),
            "~spawn_urdf_model changed the state of a body already there");
  }
}

// OnDeleteModel: World::Delete of a model of the world or any name.
void Delete(Session& w, FuzzedDataProvider& in) {
  std::vector<std::string> names;
  for (const world::Model& m : w.world->models().models()) names.push_back(m.name);
  const std::string name = PickName(in, names);
  const Snapshot before(*w.world);
  const int m = w.world->models().Find(name);
  std::vector<int> removed_bodies;
  if (m >= 0) removed_bodies = w.world->models().at(m).bodies;
  try {
    w.world->Delete(name);
  } catch (const std::invalid_argument& e) {
    fuzz::RequireMessage(e, "~delete_model");
    Require(m < 0, std::string("~delete_model refused a model of the world: ") + e.what());
    before.RequireUnchanged(*w.world, "~delete_model");
    return;
  } catch (const std::exception& e) {
    Finding(std::string("~delete_model threw an undocumented type: ") + e.what());
  }
  Require(w.world->models().Find(name) < 0, "~delete_model: accepted, but the model is there");
  // the rest keep their state bit for bit, in order
  std::vector<BodyState> kept;
  for (int b = 0; b < static_cast<int>(before.state.size()); ++b) {
    if (std::find(removed_bodies.begin(), removed_bodies.end(), b) == removed_bodies.end()) {
      kept.push_back(before.state[static_cast<std::size_t>(b)]);
    }
  }
  Require(fuzz::SameBits(w.sim().state(), kept), "~delete_model: the remaining bodies changed");
  Require(w.world->configured_scene().bodies.size() == kept.size(),
          "~delete_model: the configured start still holds the model");
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  scene_io::UrdfSceneOptions options;
  RegisterFclPairs(&options.collision_table);  // as the node and simulate load
  for (const char* name : {"tippe_top", "tippe_top_duel", "die", "coin"}) {
    const std::string path = std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/urdf/" + name + ".urdf";
    ShippedScene s;
    s.urdf = scene_io::LoadUrdfFile(path, options);
    scene_io::UrdfSceneOptions no_ground = options;
    no_ground.ground = false;  // as a spawned model: the world has its ground
    s.model = scene_io::LoadUrdfFile(path, no_ground).scene;
    Scenes().push_back(std::move(s));
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  Session w;
  const ShippedScene& start =
      Scenes()[in.ConsumeIntegralInRange<std::size_t>(0, Scenes().size() - 1)];
  w.world = std::make_unique<world::World>(start.urdf, world::WorldConfig{});
  // FUZZ_TRACE=1 in the environment: print the requests of an input (to read a finding)
  static const bool trace = std::getenv("FUZZ_TRACE") != nullptr;
  for (int request = 0; request < kMaxRequests && in.remaining_bytes() > 0; ++request) {
    const int kind = in.ConsumeIntegralInRange<int>(0, 15);
    if (trace) {
      std::fprintf(stderr, "request %d: kind %d, t = %.17g, options dt %.17g tol %.17g/%.17g "
                   "it %d alpha %.17g solver %d gyro %d\n", request, kind, w.sim().time(),
                   w.sim().options().time_step, w.sim().options().solver.tolerance_rel,
                   w.sim().options().solver.tolerance_abs, w.sim().options().solver.max_iterations,
                   w.sim().options().solver.relaxation,
                   static_cast<int>(w.sim().options().solver.type),
                   static_cast<int>(w.sim().options().gyroscopic));
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
      case 14: Spawn(w, in); break;
      default: Delete(w, in); break;
    }
    fuzz::RequireFiniteOrFault(w.sim(), "after a request", /*energy=*/true);
  }
  return 0;
}
