// The node's services. Every setter validates first and changes nothing on bad input; changes
// happen with the simulator mutex held, i.e. between two steps.
#include <chrono>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "nonsmooth_sim/node/simulation_node.h"

namespace nonsmooth_sim::node {
namespace {

// ~step runs at most this many steps per call (10 s of simulated time at the default Δt; the
// shipped scenes take 0.02-0.1 s of wall time for it). A larger request is rejected: the service
// thread is busy for the whole call, so an unbounded count (uint32 allows 4.3e9) would freeze the
// node's services, diagnostics and shutdown.
constexpr std::uint32_t kMaxStepsPerCall = 100000;
// ~step releases the simulator mutex after at most this much wall time of stepping [s] (the
// integrator's chunk, simulation_node.cpp), so that no one waits for it longer than that.
constexpr double kStepChunkWall = 0.01;
// One ~step request stops after this much wall time [s] (success false, the steps done reported):
// 100 000 steps of 4 096 bodies take minutes. Requests queue on ~step's own thread.
constexpr double kMaxStepCallWall = 60.0;
// How often (in steps) ~step checks the wall clock.
constexpr std::uint32_t kStepWallCheck = 16;

// A field of a request given as an array: empty = not set, else exactly `count` values.
template <typename T>
std::optional<std::vector<T>> Optional(const char* field, const std::vector<T>& values,
                                       std::size_t count) {
  if (values.empty()) return std::nullopt;
  if (values.size() != count) {
    throw std::invalid_argument(std::string(field) + ": expected 0 (default) or " +
                                std::to_string(count) + " values, got " +
                                std::to_string(values.size()));
  }
  return values;
}

std::optional<Eigen::Vector3d> Vector3(const char* field, const std::vector<double>& values) {
  const auto v = Optional(field, values, 3);
  if (!v) return std::nullopt;
  return Eigen::Vector3d((*v)[0], (*v)[1], (*v)[2]);
}

std::optional<double> Scalar(const char* field, const std::vector<double>& values) {
  const auto v = Optional(field, values, 1);
  if (!v) return std::nullopt;
  return (*v)[0];
}

InitialConditions FromRequest(const ResetState::Request& req) {
  InitialConditions ic;
  ic.inclination = Scalar("inclination", req.inclination);
  ic.spin = Scalar("spin", req.spin);
  ic.position = Vector3("position", req.position);
  if (const auto q = Optional("orientation", req.orientation, 4)) {
    ic.orientation = Eigen::Quaterniond((*q)[3], (*q)[0], (*q)[1], (*q)[2]);
  }
  ic.linear_velocity = Vector3("linear_velocity", req.linear_velocity);
  ic.angular_velocity = Vector3("angular_velocity", req.angular_velocity);
  return ic;
}

}  // namespace

bool SimulationNode::OnPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  const auto lock = LockForService();
  Pause("~pause_physics");
  return true;
}

bool SimulationNode::OnUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  const auto lock = LockForService();
  Unpause();
  return true;
}

bool SimulationNode::OnStep(StepSimulation::Request& req, StepSimulation::Response& res) {
  auto lock = LockForService();
  res.sim_time = world_->sim().time();
  res.stamp = StampOf(world_->sim().time());
  if (!paused_) {
    res.success = false;
    res.status_message = "the simulation is running: call ~pause_physics first";
    return true;
  }
  if (req.steps < 1 || req.steps > kMaxStepsPerCall) {
    res.success = false;
    res.status_message = "steps must be >= 1 and <= " + std::to_string(kMaxStepsPerCall) +
                         " per call (got " + std::to_string(req.steps) +
                         "); nothing changed";
    return true;
  }
  // in chunks of at most kStepChunkWall, releasing the mutex in between (as the integrator does):
  // a service waiting for it is served between two steps
  std::uint32_t done = 0;
  bool failed = false;  // a step did not advance the time: it threw or diverged
  const char* interrupted = nullptr;
  const Clock::time_point call_deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(
                         std::chrono::duration<double>(kMaxStepCallWall));
  while (done < req.steps) {
    const Clock::time_point start = Clock::now();
    const Clock::time_point deadline =
        start + std::chrono::duration_cast<Clock::duration>(
                    std::chrono::duration<double>(kStepChunkWall));
    std::uint32_t calls = 0;
    while (done < req.steps) {
      const double before = world_->sim().time();
      const std::int64_t ticks = StepOnce(req.steps - done);
      if (world_->sim().time() == before || !fault_.empty()) {
        failed = true;
        break;
      }
      done += static_cast<std::uint32_t>(ticks);
      // ticks > 1: ~accuracy took several steps in this call
      if ((++calls % kStepWallCheck == 0 || ticks > 1) && Clock::now() > deadline) break;
    }
    FinishChunk(start);  // the chunk's samples sent, ~duration's log line if reached in it
    if (failed || done == req.steps) break;
    lock.unlock();
    while (waiting_services_.load() > 0) std::this_thread::yield();
    lock.lock();
    if (!ros::ok()) {
      interrupted = "the node is shutting down";
    } else if (Clock::now() > call_deadline) {
      interrupted = "the wall-time bound of one ~step request (60 s) was reached";
    } else if (!paused_) {
      interrupted = "~unpause_physics was called";
    }
    if (interrupted != nullptr) break;
  }
  PublishClock(/*flush=*/true);
  res.sim_time = world_->sim().time();
  res.stamp = StampOf(world_->sim().time());
  if (failed) {
    res.success = false;
    res.status_message =
        "stopped after " + std::to_string(done) + " of " + std::to_string(req.steps) +
        " steps: " +
        (fault_.empty() ? std::string("a step failed") : fault_);
    return true;
  }
  if (interrupted != nullptr) {
    res.success = false;
    res.status_message = "stopped after " + std::to_string(done) + " of " +
                         std::to_string(req.steps) + " steps: " + interrupted;
    return true;
  }
  res.success = true;
  res.status_message = "stepped " + std::to_string(req.steps) + " x " + std::to_string(tick_) +
                       " s";
  return true;
}

bool SimulationNode::OnResetState(ResetState::Request& req, ResetState::Response& res) {
  const auto lock = LockForService();
  res.sim_time = world_->sim().time();
  try {
    // a body of the start-up model; spawned models: ~set_model_state
    world_->Reset(req.body, FromRequest(req));  // validates; clears the warm start
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string("rejected, state unchanged: ") + e.what();
    return true;
  }
  AfterReset();
  res.success = true;
  res.status_message = "reset at t = " + std::to_string(world_->sim().time()) + " s";
  return true;
}

bool SimulationNode::OnResetWorld(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  const auto lock = LockForService();
  world_->ResetWorld();
  AfterReset();
  return true;
}

bool SimulationNode::OnResetSimulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  const auto lock = LockForService();
  // a fresh simulator with the configured laws and solver; the time goes on (/clock monotone)
  world_->ResetSimulation();
  // the configured solver and accuracy, as the fresh simulator's
  tick_ = parameters_.simulator.time_step;
  solver_tolerance_ = parameters_.simulator.solver.tolerance_rel;
  accuracy_ = parameters_.accuracy;
  ResetStepper();
  last_step_ = StepStatistics();
  total_ = RunStatistics();
  UpdatePeriods();
  AfterReset();
  return true;
}

bool SimulationNode::OnSetFrictionSet(SetFrictionSet::Request& req,
                                      SetFrictionSet::Response& res) {
  const auto lock = LockForService();
  const auto set = FrictionSetFromName(req.friction_set);
  if (!set) {
    res.success = false;
    res.status_message = "unknown friction set \"" + req.friction_set + "\", expected one of " +
                         FrictionSetNameList() + "; nothing changed";
    return true;
  }
  try {
    world_->sim().SetFrictionSet(*set, req.contact);
  } catch (const std::invalid_argument& e) {
    res.success = false;
    res.status_message = std::string(e.what()) + "; nothing changed";
    return true;
  }
  res.success = true;
  res.status_message = "friction set at t = " + std::to_string(world_->sim().time()) +
                       " s: " + FrictionSetSummary();
  return true;
}

bool SimulationNode::OnGetFrictionSet(GetFrictionSet::Request& req,
                                      GetFrictionSet::Response& res) {
  const auto lock = LockForService();
  if (!req.contact.empty()) {
    // one collision or one contact "<a>/<b>"
    try {
      const FrictionSet set = world_->sim().FrictionSetOf(req.contact);
      res.contacts.push_back(req.contact);
      res.friction_sets.emplace_back(FrictionSetName(set));
      res.success = true;
      res.status_message = FrictionSetSummary();
    } catch (const std::invalid_argument& e) {
      res.success = false;
      res.status_message = e.what();
    }
    return true;
  }
  for (const Collider& c : world_->sim().scene().colliders) {
    if (c.body == kWorld) continue;
    res.contacts.push_back(c.name);
    res.friction_sets.emplace_back(FrictionSetName(c.law.friction_set));
  }
  res.success = true;
  res.status_message = FrictionSetSummary();
  return true;
}

bool SimulationNode::OnGetSolverProperties(GetSolverProperties::Request&,
                                           GetSolverProperties::Response& res) {
  const auto lock = LockForService();
  const SimulatorOptions& o = world_->sim().options();
  res.time_step = tick_;  // the simulator's changes at every step with ~accuracy
  res.solver = std::string(SolverTypeName(o.solver.type));
  res.tolerance = solver_tolerance_;  // as asked (~accuracy lowers the solver's to TOL/100)
  res.tolerance_abs = o.solver.tolerance_abs;
  res.max_iterations = o.solver.max_iterations;
  res.relaxation = o.solver.relaxation;
  res.gyroscopic = std::string(GyroscopicSchemeName(o.gyroscopic));
  res.integrator = std::string(IntegratorName(o.integrator));
  res.accuracy = accuracy_.tolerance;
  res.min_dt = accuracy_.min_time_step;
  res.max_dt = accuracy_.max_time_step;
  return true;
}

bool SimulationNode::OnSetSolverProperties(SetSolverProperties::Request& req,
                                           SetSolverProperties::Response& res) {
  const auto lock = LockForService();
  SimulatorOptions o = world_->sim().options();
  o.time_step = tick_;
  o.solver.tolerance_rel = solver_tolerance_;
  AccuracyOptions accuracy = accuracy_;
  try {
    if (auto v = Scalar("accuracy", req.accuracy)) accuracy.tolerance = *v;
    if (auto v = Scalar("min_dt", req.min_dt)) accuracy.min_time_step = *v;
    if (auto v = Scalar("max_dt", req.max_dt)) accuracy.max_time_step = *v;
    if (auto v = Scalar("time_step", req.time_step)) o.time_step = *v;
    if (auto v = Scalar("tolerance", req.tolerance)) o.solver.tolerance_rel = *v;
    if (auto v = Scalar("tolerance_abs", req.tolerance_abs)) o.solver.tolerance_abs = *v;
    if (auto v = Scalar("relaxation", req.relaxation)) o.solver.relaxation = *v;
    if (auto v = Optional("max_iterations", req.max_iterations, 1)) {
      o.solver.max_iterations = (*v)[0];
    }
    if (!req.solver.empty()) {
      const auto type = SolverTypeFromName(req.solver);
      if (!type) {
        throw std::invalid_argument("unknown solver \"" + req.solver + "\", expected one of " +
                                    SolverTypeNameList());
      }
      o.solver.type = *type;
    }
    if (!req.gyroscopic.empty()) {
      const auto scheme = GyroscopicSchemeFromName(req.gyroscopic);
      if (!scheme) {
        throw std::invalid_argument("unknown gyroscopic scheme \"" + req.gyroscopic +
                                    "\", expected auto, explicit or implicit_midpoint");
      }
      o.gyroscopic = *scheme;
    }
    if (!req.integrator.empty()) {
      const auto integrator = IntegratorFromName(req.integrator);
      if (!integrator) {
        throw std::invalid_argument("unknown integrator \"" + req.integrator +
                                    "\", expected moreau2 or moreau");
      }
      o.integrator = *integrator;
    }
    ValidateSimulatorOptions(o);
    ValidateAccuracyOptions(accuracy);
    world_->sim().SetOptions(o);
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string("rejected, nothing changed: ") + e.what();
    return true;
  }
  tick_ = o.time_step;
  solver_tolerance_ = o.solver.tolerance_rel;
  accuracy_ = accuracy;
  ResetStepper();
  UpdatePeriods();
  RestartChannels();
  anchor_wall_ = Clock::now();
  steps_since_anchor_ = 0;
  res.success = true;
  std::ostringstream message;
  message << "time step " << o.time_step << " s, solver " << SolverTypeName(o.solver.type)
          << ", tolerance " << o.solver.tolerance_rel << " (abs " << o.solver.tolerance_abs
          << "), max iterations " << o.solver.max_iterations << ", relaxation "
          << o.solver.relaxation << ", gyroscopic " << GyroscopicSchemeName(o.gyroscopic)
          << ", integrator " << IntegratorName(o.integrator) << ", accuracy "
          << accuracy.tolerance;
  if (accuracy.tolerance > 0.0) {
    message << " (steps in [" << accuracy.min_time_step << ", " << accuracy.max_time_step
            << "] s)";
  }
  res.status_message = message.str();
  return true;
}

bool SimulationNode::OnGetState(GetSimulationState::Request&, GetSimulationState::Response& res) {
  const auto lock = LockForService();
  FillState(world_->sim(), paused_, frames_.world, &res.state);
  return true;
}

}  // namespace nonsmooth_sim::node
