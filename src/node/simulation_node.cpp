// The node: set-up, the integrator thread, publishing, diagnostics. Services: node_services.cpp.
#include "nonsmooth_sim/node/simulation_node.h"

#include <rosgraph_msgs/Clock.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "nonsmooth_sim/core/overlaps.h"
#include "nonsmooth_sim/world/lost_bodies.h"

namespace nonsmooth_sim::node {
namespace {

// The integrator holds the mutex for at most this long before letting services in [s].
constexpr double kMaxChunkWall = 0.01;
// With a real-time factor > 0, a backlog longer than this (wall time the integrator could not
// keep up with) is dropped instead of being caught up in a burst [s].
constexpr double kMaxBacklogWall = 0.1;
// The smallest publisher queue of /tf and ~contacts [messages].
constexpr int kMinBatchedQueue = 100;
// How often (in steps) a long run checks the wall clock.
constexpr std::int64_t kWallCheckSteps = 16;
// A step with more solver iterations than this checks the wall clock at once.
constexpr int kLongStepIterations = 100;
// /diagnostics lists at most this many lost bodies by name (their count always).
constexpr std::size_t kMaxLostListed = 10;

double Seconds(std::chrono::steady_clock::duration d) {
  return std::chrono::duration<double>(d).count();
}

}  // namespace

void SimulationNode::RunStatistics::Add(const StepStatistics& step) {
  ++steps;
  iterations_sum += step.solver.iterations;
  iterations_max = std::max(iterations_max, step.solver.iterations);
  if (step.closed_contacts > 0) {
    residual_max = std::max(residual_max, step.solver.residual);
    if (!step.solver.converged) ++unconverged;
  }
  max_dt_omega = std::max(max_dt_omega, step.max_dt_omega);
}

SimulationNode::SimulationNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh,
                               NodeParameters parameters, UrdfScene urdf)
    : parameters_(std::move(parameters)),
      nh_(nh),
      private_nh_(private_nh),
      updater_(nh, private_nh) {
  world::WorldConfig config;
  config.model_name = parameters_.model_name;
  config.initial_body = parameters_.initial_body;
  config.initial = parameters_.initial;
  config.initial_state = parameters_.initial_state;
  config.simulator = parameters_.simulator;
  config.world_frame = parameters_.world_frame;
  // the start-up model at its configured start; throws std::invalid_argument with one line
  world_ = std::make_unique<world::World>(std::move(urdf), std::move(config));
  frames_ = MakeFrameNames(world_->sim().scene(), parameters_.world_frame);
  tick_ = parameters_.simulator.time_step;
  solver_tolerance_ = parameters_.simulator.solver.tolerance_rel;
  accuracy_ = parameters_.accuracy;
  ResetStepper();
  paused_ = parameters_.paused;
  for (const std::string& warning : world_->urdf().warnings) ROS_WARN_STREAM(warning);
  // overlaps at the start: resolved by the first steps, but a deep one is usually a scene error
  for (const Overlap& o : FindOverlaps(world_->sim().scene(), world_->sim().state(), kOverlapWarningDepth)) {
    ROS_WARN("nonsmooth_sim: collisions \"%s\" and \"%s\" overlap by %.3g m at the start "
             "(resolved by the first steps)",
             world_->sim().scene().colliders[static_cast<std::size_t>(o.collider_a)].name.c_str(),
             world_->sim().scene().colliders[static_cast<std::size_t>(o.collider_b)].name.c_str(),
             o.depth);
  }

  const int queue = parameters_.queue_size;
  // latched: a node joining while paused learns the time at once (and never sees 0); the same
  // queue as the other topics (a queue of 10 overflowed under load when recorded)
  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", queue, /*latch=*/true);
  // /tf and ~contacts carry up to ~max_samples_per_message samples per message: their queues hold
  // about ~queue_size samples, not ~queue_size of their larger messages (a slow subscriber kept
  // 300 MB queued), but at least kMinBatchedQueue messages (10 dropped samples under load)
  const int batched_queue =
      std::max(kMinBatchedQueue, (queue + parameters_.max_samples_per_message - 1) /
                                     parameters_.max_samples_per_message);
  tf_pub_ = nh_.advertise<tf2_msgs::TFMessage>("/tf", batched_queue);
  contacts_pub_ = private_nh_.advertise<ContactSteps>("contacts", batched_queue);
  state_pub_ = private_nh_.advertise<SimulationState>("state", queue);
  markers_pub_ = private_nh_.advertise<visualization_msgs::MarkerArray>("contact_markers", queue);
  // the links merged into bodies or fixed to the world, as robot_state_publisher sends fixed
  // joints: rviz's RobotModel shows every link with nothing else running
  tf_static_pub_ = nh_.advertise<tf2_msgs::TFMessage>("/tf_static", 1, /*latch=*/true);
  fixed_links_[world_->models().models().front().name] =
      FixedLinkTransforms(world_->urdf(), "", parameters_.world_frame, /*world_links=*/true,
                          StampOf(world_->sim().time()));
  PublishFixedLinks();
  for (const std::string& topic : frames_.topics) {
    wrench_pubs_.push_back(
        private_nh_.advertise<geometry_msgs::WrenchStamped>("wrench/" + topic, queue));
  }
  wrench_closed_.assign(frames_.slots.size(), false);

  auto& p = private_nh_;
  services_ = {
      p.advertiseService("pause_physics", &SimulationNode::OnPause, this),
      p.advertiseService("unpause_physics", &SimulationNode::OnUnpause, this),
      p.advertiseService("reset", &SimulationNode::OnResetState, this),
      p.advertiseService("reset_world", &SimulationNode::OnResetWorld, this),
      p.advertiseService("reset_simulation", &SimulationNode::OnResetSimulation, this),
      p.advertiseService("set_friction_set", &SimulationNode::OnSetFrictionSet, this),
      p.advertiseService("get_friction_set", &SimulationNode::OnGetFrictionSet, this),
      p.advertiseService("get_solver_properties", &SimulationNode::OnGetSolverProperties, this),
      p.advertiseService("set_solver_properties", &SimulationNode::OnSetSolverProperties, this),
      p.advertiseService("get_state", &SimulationNode::OnGetState, this),
      p.advertiseService("get_world_properties", &SimulationNode::OnGetWorldProperties, this),
      p.advertiseService("get_model_properties", &SimulationNode::OnGetModelProperties, this),
      p.advertiseService("get_model_state", &SimulationNode::OnGetModelState, this),
      p.advertiseService("set_model_state", &SimulationNode::OnSetModelState, this),
      p.advertiseService("apply_body_wrench", &SimulationNode::OnApplyBodyWrench, this),
      p.advertiseService("clear_body_wrenches", &SimulationNode::OnClearBodyWrenches, this),
  };

  {
    // spawns and deletes on a queue and thread of their own: one runs at a time anyway
    // (world_mutex_), and one that waits for the master (up to kMasterTimeout) never holds a
    // thread of the spinner that serves the other services
    ros::AdvertiseServiceOptions spawn;
    spawn.init<SpawnModel::Request, SpawnModel::Response>(
        "spawn_urdf_model", [this](SpawnModel::Request& req, SpawnModel::Response& res) {
          return OnSpawnUrdfModel(req, res);
        });
    spawn.callback_queue = &world_queue_;
    services_.push_back(p.advertiseService(spawn));
    ros::AdvertiseServiceOptions remove;
    remove.init<DeleteModel::Request, DeleteModel::Response>(
        "delete_model", [this](DeleteModel::Request& req, DeleteModel::Response& res) {
          return OnDeleteModel(req, res);
        });
    remove.callback_queue = &world_queue_;
    services_.push_back(p.advertiseService(remove));
    world_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &world_queue_);
    world_spinner_->start();
  }

  {
    ros::AdvertiseServiceOptions step;
    step.init<StepSimulation::Request, StepSimulation::Response>(
        "step", [this](StepSimulation::Request& req, StepSimulation::Response& res) {
          return OnStep(req, res);
        });
    step.callback_queue = &step_queue_;
    services_.push_back(p.advertiseService(step));
    step_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &step_queue_);
    step_spinner_->start();
  }

  updater_.setHardwareID("nonsmooth_sim");
  updater_.add("simulation", this, &SimulationNode::Diagnose);
  diagnostics_timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / parameters_.diagnostics_rate),
                                           &SimulationNode::OnDiagnosticsTimer, this);

  UpdatePeriods();
  RestartChannels();
  PublishClock(/*flush=*/true);
  anchor_wall_ = unpaused_at_ = Clock::now();

  ROS_INFO(
      "nonsmooth_sim: %zu bodies, %zu collisions, friction set %s, time step %g s, "
      "real-time factor %g%s, %s",
      world_->urdf().scene.bodies.size(), world_->urdf().scene.colliders.size(),
      FrictionSetSummary().c_str(),
      parameters_.simulator.time_step, parameters_.real_time_factor,
      parameters_.real_time_factor == 0.0 ? " (as fast as possible)" : "",
      paused_ ? "paused" : "running");
  if (pace_ != parameters_.real_time_factor) {
    ROS_INFO("nonsmooth_sim: real-time factor limited to %g by ~max_wall_publish_rate %g Hz", pace_,
             parameters_.max_wall_publish_rate);
  }
  bool use_sim_time = false;
  if (!nh_.getParam("/use_sim_time", use_sim_time) || !use_sim_time) {
    ROS_WARN(
        "nonsmooth_sim: /use_sim_time is not true: every stamp this node publishes (TF, contacts, "
        "markers) is simulated time from /clock, while the other nodes run on wall time, so tf "
        "lookups and rviz will not match them; set /use_sim_time true before they start (the "
        "launch files' default, use_sim_time:=true)");
  }
  integrator_ = std::thread(&SimulationNode::Run, this);
}

SimulationNode::~SimulationNode() {
  if (step_spinner_) step_spinner_->stop();  // a running ~step ends at its next chunk (ros::ok)
  if (world_spinner_) world_spinner_->stop();  // a running spawn or delete ends first
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (integrator_.joinable()) integrator_.join();
}

std::unique_lock<std::mutex> SimulationNode::LockForService() {
  ++waiting_services_;
  std::unique_lock<std::mutex> lock(mutex_);
  --waiting_services_;
  return lock;
}

// ---------------------------------------------------------------------------------------------
// integrator

void SimulationNode::Run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    if (paused_) {
      wake_.wait(lock);
      continue;
    }
    const Clock::time_point start = Clock::now();
    const double dt = tick_;
    const double factor = pace_;
    std::int64_t budget = std::numeric_limits<std::int64_t>::max();
    if (factor > 0.0) {
      // sim time follows wall time × factor since the anchor
      const auto due =
          static_cast<std::int64_t>(std::floor(factor * Seconds(start - anchor_wall_) / dt));
      budget = due - steps_since_anchor_;
      if (static_cast<double>(budget) * dt / factor > kMaxBacklogWall) {
        anchor_wall_ = start;
        steps_since_anchor_ = 0;
        budget = static_cast<std::int64_t>(std::floor(factor * kMaxBacklogWall / dt));
      }
    }
    std::int64_t done = 0;
    if (budget > 0) {
      done = RunChunk(budget, start + std::chrono::duration_cast<Clock::duration>(
                                          std::chrono::duration<double>(kMaxChunkWall)));
      PublishClock(/*flush=*/paused_);
    }
    if (factor > 0.0 && done >= budget) {
      const auto period = std::chrono::duration<double>(1.0 / parameters_.wall_update_rate);
      wake_.wait_until(lock, start + std::chrono::duration_cast<Clock::duration>(period));
    } else {
      // as fast as possible (or behind wall time): hand the mutex to waiting services first
      lock.unlock();
      while (waiting_services_.load() > 0) std::this_thread::yield();
      lock.lock();
    }
  }
}

std::int64_t SimulationNode::RunChunk(std::int64_t budget, Clock::time_point deadline) {
  const Clock::time_point start = Clock::now();
  std::int64_t done = 0;
  std::int64_t calls = 0;
  while (done < budget && !paused_) {
    const std::int64_t ticks = StepOnce(budget - done);
    running_sim_time_ += static_cast<double>(ticks) * tick_;
    steps_since_anchor_ += ticks;
    done += ticks;
    // the clock every kWallCheckSteps steps, or after every step that iterated long (up to
    // SimulatorOptions' cap of iterations, a step can take milliseconds) or advanced several
    // ticks (~accuracy: many steps)
    if ((++calls % kWallCheckSteps == 0 || ticks > 1 ||
         last_step_.solver.iterations > kLongStepIterations) &&
        Clock::now() > deadline) {
      break;
    }
  }
  FinishChunk(start);
  return done;
}

void SimulationNode::FinishChunk(Clock::time_point start) {
  const Clock::time_point flush = Clock::now();
  FlushSamples();
  const Clock::time_point end = Clock::now();
  period_.publish_wall += Seconds(end - flush);
  total_.publish_wall += Seconds(end - flush);
  const double busy = Seconds(end - start);
  period_.busy_wall += busy;
  total_.busy_wall += busy;
  LogSummaryIfDue();
}

std::int64_t SimulationNode::StepOnce(std::int64_t max_ticks) {
  std::int64_t ticks = 1;
  if (stepper_) {
    // up to the next tick a topic is due at (or ~duration)
    for (const Channel* c : {&tf_, &contacts_, &state_, &markers_}) {
      if (c->period > 0) max_ticks = std::min(max_ticks, std::max<std::int64_t>(1, c->countdown));
    }
    if (parameters_.duration > 0.0 && !duration_reached_) {
      const auto left = std::llround((parameters_.duration - world_->sim().time()) / tick_);
      max_ticks = std::min(max_ticks, std::max<std::int64_t>(1, left));
    }
    ticks = std::max<std::int64_t>(1, max_ticks);
  }
  const double interval = static_cast<double>(ticks) * tick_;
  try {
    world_->ApplyScheduledWrenches(interval);
    if (stepper_) {
      // each accepted step counted in the statistics; last_step_ is the last one's
      last_step_ = stepper_->AdvanceTo(world_->sim().time() + interval,
                                       [this](const StepStatistics& s, double) {
                                         period_.Add(s);
                                         total_.Add(s);
                                       });
    } else {
      // in place: the statistics' per-contact flags keep their storage (no allocation per step)
      world_->sim().Step(&last_step_);
    }
  } catch (const std::exception& e) {
    // the core validates its inputs and throws on what it cannot step; never abort the node
    Fault(std::string("a step failed: ") + e.what());
    return ticks;
  }
  if (!last_step_.state_finite) {
    char reason[256];
    std::snprintf(reason, sizeof reason,
                  "the state became non-finite (dt*|omega| = %.3g, ~gyroscopic %s)",
                  last_step_.max_dt_omega,
                  std::string(GyroscopicSchemeName(world_->sim().options().gyroscopic)).c_str());
    Fault(reason);
    return ticks;
  }
  if (last_step_.explicit_gyroscopic_unsafe) {
    const double dt = world_->sim().options().time_step;
    ROS_WARN_ONCE(
        "nonsmooth_sim: warning: explicit gyroscopic term outside its safe range "
        "dt*|omega| <= %g (reached %.2g at t = %.4g s): energy can grow by "
        "O((dt*|omega|)^2) per step and diverge; use ~gyroscopic implicit_midpoint or "
        "~time_step <= %.1e",
        kExplicitGyroscopicMaxDtOmega, last_step_.max_dt_omega, world_->sim().time(),
        kExplicitGyroscopicMaxDtOmega * dt / last_step_.max_dt_omega);
  }
  if (!stepper_) {
    period_.Add(last_step_);
    total_.Add(last_step_);
  }
  PublishDue(ticks);
  if (parameters_.duration > 0.0 && !duration_reached_ &&
      world_->sim().time() >= parameters_.duration - 0.5 * tick_) {
    duration_reached_ = true;
    summary_due_ = true;  // logged by the caller once this chunk's wall time is counted
    Pause("duration reached");
  }
  return ticks;
}

void SimulationNode::ResetStepper() {
  stepper_.reset();
  SimulatorOptions options = world_->sim().options();
  options.time_step = tick_;
  options.solver.tolerance_rel = solver_tolerance_;
  world_->sim().SetOptions(options);
  // the stepper lowers the solver's tolerance to TOL/100 and changes the step at every step
  if (accuracy_.tolerance > 0.0) stepper_ = std::make_unique<AdaptiveStepper>(&world_->sim(), accuracy_);
}

void SimulationNode::LogSummaryIfDue() {
  if (!summary_due_) return;
  summary_due_ = false;
  const double steps = static_cast<double>(std::max<std::int64_t>(total_.steps, 1));
  const double stepping = std::max(0.0, total_.busy_wall - total_.publish_wall);
  ROS_INFO(
      "nonsmooth_sim: reached t = %.6f s after %lld steps: %.4g s wall running "
      "(real-time factor %.2f), %.3f us/step stepping + %.3f us/step publishing, "
      "%lld unconverged steps",
      world_->sim().time(), static_cast<long long>(total_.steps), run_wall_,
      run_wall_ > 0.0 ? running_sim_time_ / run_wall_ : 0.0, 1e6 * stepping / steps,
      1e6 * total_.publish_wall / steps, static_cast<long long>(total_.unconverged));
}

double SimulationNode::RunningWall(Clock::time_point now) const {
  return run_wall_ + (paused_ ? 0.0 : Seconds(now - unpaused_at_));
}

void SimulationNode::Fault(const std::string& what) {
  fault_ = what + " at t = " + std::to_string(world_->sim().time()) +
           " s: paused at the last finite state; call ~reset, ~reset_world or "
           "~reset_simulation to go on";
  ++faults_;
  ROS_ERROR_STREAM("nonsmooth_sim: " << fault_);  // once per occurrence: each one pauses
  Pause("fault");
}

void SimulationNode::Pause(const char* reason) {
  if (!paused_) run_wall_ += Seconds(Clock::now() - unpaused_at_);
  paused_ = true;
  PublishClock(/*flush=*/true);
  ROS_DEBUG("nonsmooth_sim: paused (%s) at t = %.6f s", reason, world_->sim().time());
  wake_.notify_all();
}

void SimulationNode::Unpause() {
  if (paused_) unpaused_at_ = Clock::now();
  paused_ = false;
  anchor_wall_ = Clock::now();
  steps_since_anchor_ = 0;
  wake_.notify_all();
}

// ---------------------------------------------------------------------------------------------
// publishing

void SimulationNode::UpdatePeriods() {
  const double dt = tick_;
  tf_.rate = parameters_.tf_rate;
  contacts_.rate = parameters_.contacts_rate;
  state_.rate = parameters_.state_rate;
  markers_.rate = parameters_.markers_rate;
  for (Channel* c : {&tf_, &contacts_, &state_, &markers_}) {
    // a message every round(1/(rate Δt)) steps, at most one per step
    c->period = c->rate > 0.0 ? std::max<std::int64_t>(1, std::llround(1.0 / (c->rate * dt))) : 0;
  }
  // the fastest topic [messages per sim second] must stay below ~max_wall_publish_rate in wall
  // time: cap the real-time factor
  pace_ = parameters_.real_time_factor;
  std::int64_t shortest = 0;
  for (const Channel* c : {&tf_, &contacts_, &state_, &markers_}) {
    if (c->period > 0 && (shortest == 0 || c->period < shortest)) shortest = c->period;
  }
  if (parameters_.max_wall_publish_rate > 0.0 && shortest > 0) {
    const double cap = parameters_.max_wall_publish_rate * static_cast<double>(shortest) * dt;
    pace_ = pace_ > 0.0 ? std::min(pace_, cap) : cap;
  }
}

void SimulationNode::RestartChannels() {
  for (Channel* c : {&tf_, &contacts_, &state_, &markers_}) c->countdown = c->period;
}

void SimulationNode::PublishDue(std::int64_t ticks) {
  bool due[4];
  bool any = false;
  Channel* channels[4] = {&tf_, &contacts_, &state_, &markers_};
  for (int i = 0; i < 4; ++i) {
    Channel& c = *channels[i];
    c.countdown -= ticks;
    due[i] = c.period > 0 && c.countdown <= 0;
    if (due[i]) c.countdown = c.period + (c.countdown % c.period);
    any = any || due[i];
  }
  if (!any) return;
  const Clock::time_point start = Clock::now();
  if (due[0]) PublishTransforms();
  if (due[1]) PublishContacts();
  if (due[2]) PublishState();
  if (due[3]) PublishMarkers();
  PublishClock(/*flush=*/false);
  const double spent = Seconds(Clock::now() - start);
  period_.publish_wall += spent;
  total_.publish_wall += spent;
}

void SimulationNode::PublishTransforms() {
  const ros::Time stamp = StampOf(world_->sim().time());
  if (stamp <= last_tf_stamp_) return;  // tf2 warns about repeated stamps
  last_tf_stamp_ = stamp;
  if (tf_pub_.getNumSubscribers() == 0) return;
  AppendTransforms(world_->sim(), frames_, stamp, &tf_msg_);
  if (++tf_samples_ >= parameters_.max_samples_per_message ||
      tf_msg_.transforms.size() >= kMaxItemsPerMessage) {
    FlushSamples();
  }
}

void SimulationNode::PublishContacts() {
  const ros::Time stamp = StampOf(world_->sim().time());
  if (contacts_pub_.getNumSubscribers() > 0) {
    contacts_msg_.steps.emplace_back();
    FillContacts(world_->sim(), last_step_, frames_, &contacts_msg_.steps.back());
    pending_contact_count_ += contacts_msg_.steps.back().contacts.size();
    if (++contacts_samples_ >= parameters_.max_samples_per_message ||
        pending_contact_count_ >= kMaxItemsPerMessage) {
      FlushSamples();
    }
  }
  // a wrench per closed contact, and one zero wrench when a contact opens (clears rviz)
  FirstContacts(world_->sim(), &first_contact_);
  for (std::size_t i = 0; i < wrench_pubs_.size(); ++i) {
    const bool closed = first_contact_[static_cast<std::size_t>(frames_.slots[i])] >= 0;
    // (a slot of a spawned collision has no publisher until AdvertiseWrenches)
    if ((closed || wrench_closed_[i]) && wrench_pubs_[i] &&
        wrench_pubs_[i].getNumSubscribers() > 0) {
      FillWrench(world_->sim(), i, frames_, stamp, &wrench_msg_);
      wrench_pubs_[i].publish(wrench_msg_);
    }
    wrench_closed_[i] = closed;
  }
}

void SimulationNode::FlushSamples() {
  if (tf_samples_ > 0) {
    tf_pub_.publish(tf_msg_);
    tf_msg_.transforms.clear();
    tf_samples_ = 0;
  }
  if (contacts_samples_ > 0) {
    contacts_msg_.header = contacts_msg_.steps.back().header;
    contacts_pub_.publish(contacts_msg_);
    contacts_msg_.steps.clear();
    contacts_samples_ = 0;
    pending_contact_count_ = 0;
  }
}

void SimulationNode::PublishState() {
  if (state_pub_.getNumSubscribers() == 0) return;
  FillState(world_->sim(), paused_, frames_.world, &state_msg_);
  state_pub_.publish(state_msg_);
}

void SimulationNode::PublishMarkers() {
  if (markers_pub_.getNumSubscribers() == 0) return;
  FillMarkers(world_->sim(), frames_, StampOf(world_->sim().time()), parameters_.marker_force_scale,
              parameters_.marker_torque_scale, markers_count_, &markers_msg_);
  markers_count_ = world_->sim().contacts().size();
  markers_pub_.publish(markers_msg_);
}

void SimulationNode::PublishClock(bool flush) {
  const ros::Time stamp = StampOf(world_->sim().time());
  if (!last_clock_stamp_.isZero() && stamp <= last_clock_stamp_) return;  // monotone
  const Clock::time_point now = Clock::now();
  if (!flush && Seconds(now - last_clock_wall_) < 1.0 / parameters_.clock_rate) return;
  FlushSamples();  // every sample up to the new time before /clock passes it
  rosgraph_msgs::Clock clock;
  clock.clock = stamp;
  clock_pub_.publish(clock);
  last_clock_stamp_ = stamp;
  last_clock_wall_ = now;
}

void SimulationNode::AfterReset() {
  FlushSamples();  // what was sampled before the reset (nothing after a chunk)
  fault_.clear();
  RestartChannels();
  std::fill(wrench_closed_.begin(), wrench_closed_.end(), false);
  geometry_msgs::WrenchStamped zero;
  for (std::size_t i = 0; i < wrench_pubs_.size(); ++i) {
    if (!wrench_pubs_[i]) continue;  // advertised after a spawn (AdvertiseWrenches)
    zero.header.stamp = StampOf(world_->sim().time());
    zero.header.frame_id = frames_.contacts[i];
    wrench_pubs_[i].publish(zero);
  }
  markers_pub_.publish(DeleteAllMarkers(frames_.world));
  markers_count_ = 0;
  anchor_wall_ = Clock::now();
  steps_since_anchor_ = 0;
}

// ---------------------------------------------------------------------------------------------
// diagnostics

void SimulationNode::OnDiagnosticsTimer(const ros::WallTimerEvent&) {
  double running_wall = 0.0;
  double running_sim_time = 0.0;
  {
    std::unique_lock<std::mutex> lock = LockForService();
    running_wall = RunningWall(Clock::now());
    running_sim_time = running_sim_time_;
    snapshot_.period = period_;
    period_ = RunStatistics();
    snapshot_.unconverged_total = total_.unconverged;
    snapshot_.sim_time = world_->sim().time();
    snapshot_.paused = paused_;
    snapshot_.closed_contacts = last_step_.closed_contacts;
    snapshot_.islands = last_step_.islands;
    snapshot_.bodies = world_->sim().scene().bodies.size();
    snapshot_.models = world_->models().models().size();
    snapshot_.friction_sets = FrictionSetSummary();
    snapshot_.solver = std::string(SolverTypeName(world_->sim().options().solver.type));
    snapshot_.time_step = tick_;
    snapshot_.accuracy = accuracy_;
    snapshot_.adaptive = stepper_ ? stepper_->statistics() : AdaptiveStatistics();
    snapshot_.pace = pace_;
    snapshot_.fault = fault_;
    snapshot_.faults = faults_;
    snapshot_.lost.clear();
    const Scene& scene = world_->sim().scene();
    for (const world::LostBody& lost : world::FindLostBodies(scene, world_->sim().state())) {
      snapshot_.lost.push_back(scene.bodies[static_cast<std::size_t>(lost.body)].name + " " +
                               world::DescribeLostBody(lost));
    }
  }
  for (const std::string& lost : snapshot_.lost) {
    if (std::find(logged_lost_.begin(), logged_lost_.end(), lost) != logged_lost_.end()) continue;
    logged_lost_.push_back(lost);
    ROS_WARN_STREAM("nonsmooth_sim: body " << lost);
  }
  // over the wall time the integrator ran in this period (not the paused time), and the sim time
  // it advanced in it (not ~step calls)
  const double wall = running_wall - previous_running_wall_;
  snapshot_.running_wall = wall;
  snapshot_.real_time_factor = wall > 0.0 ? (running_sim_time - previous_running_sim_time_) / wall
                                          : 0.0;
  previous_running_wall_ = running_wall;
  previous_running_sim_time_ = running_sim_time;
  updater_.force_update();
}

void SimulationNode::Diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  const DiagnosticsSnapshot& s = snapshot_;
  const RunStatistics& p = s.period;
  const double steps = static_cast<double>(std::max<std::int64_t>(p.steps, 1));
  if (!s.fault.empty()) {
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, s.fault);
  } else if (!s.lost.empty()) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                    "%zu bodies can no longer touch anything: body %s%s", s.lost.size(),
                    s.lost.front().c_str(), s.lost.size() > 1 ? "; ..." : "");
  } else if (p.unconverged > 0) {
    status.summaryf(diagnostic_msgs::DiagnosticStatus::WARN,
                    "%lld of %lld steps: contact solver not converged",
                    static_cast<long long>(p.unconverged), static_cast<long long>(p.steps));
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, s.paused ? "paused" : "running");
  }
  status.add("sim time [s]", s.sim_time);
  status.add("paused", s.paused);
  status.add("real-time factor", s.real_time_factor);  // over the running wall time
  status.add("running wall time in period [s]", s.running_wall);
  status.add("requested real-time factor (0: as fast as possible)", parameters_.real_time_factor);
  status.add("real-time factor kept (0: as fast as possible)", s.pace);
  status.add("steps in period", p.steps);
  status.add("step wall time [us]", 1e6 * (p.busy_wall - p.publish_wall) / steps);
  status.add("publish wall time per step [us]", 1e6 * p.publish_wall / steps);
  status.add("time step [s] (with accuracy > 0: the tick of ~step and the publish periods)",
             s.time_step);
  status.add("accuracy (0: fixed steps)", s.accuracy.tolerance);
  if (s.accuracy.tolerance > 0.0) {
    const AdaptiveStatistics& a = s.adaptive;
    status.add("accepted steps (accuracy, in total)", a.accepted_steps);
    status.add("rejected steps (accuracy, in total)", a.rejected_steps);
    status.add("forced steps at min_dt (accuracy, in total)", a.forced_steps);
    status.add("smallest step [s] (accuracy)", a.accepted_steps > 0 ? a.smallest_step : 0.0);
    status.add("largest step [s] (accuracy)", a.largest_step);
    status.add("max error estimate (accuracy: <= TOL * step, unless forced)", a.max_error);
  }
  status.add("solver", s.solver);
  status.add("solver iterations (mean)", static_cast<double>(p.iterations_sum) / steps);
  status.add("solver iterations (max)", p.iterations_max);
  status.add("solver residual (max, <= 1: converged)", p.residual_max);
  status.add("unconverged steps in period", p.unconverged);
  status.add("unconverged steps in total", s.unconverged_total);
  status.add("max dt*|omega| (explicit gyroscopic error ~ its square)", p.max_dt_omega);
  status.add("friction set", s.friction_sets);
  status.add("closed contacts", s.closed_contacts);
  status.add("contact islands (problems solved in the last step)", s.islands);
  status.add("models", s.models);
  status.add("bodies", s.bodies);
  status.add("faults (failed steps) in total", s.faults);
  status.add("bodies that can no longer touch anything", s.lost.size());
  for (std::size_t k = 0; k < s.lost.size() && k < kMaxLostListed; ++k) {
    status.add("lost body " + std::to_string(k + 1), s.lost[k]);
  }
}

// ---------------------------------------------------------------------------------------------
// lookups

std::string SimulationNode::FrictionSetSummary() const {
  // "sphere" when all collisions on bodies agree, else "big_sphere: exact, peg_sphere: coulomb"
  const Scene& scene = world_->sim().scene();
  std::vector<const Collider*> on_bodies;
  for (const Collider& c : scene.colliders) {
    if (c.body != kWorld) on_bodies.push_back(&c);
  }
  if (on_bodies.empty()) return "none";
  bool same = true;
  for (const Collider* c : on_bodies) {
    same = same && c->law.friction_set == on_bodies[0]->law.friction_set;
  }
  if (same) return std::string(FrictionSetName(on_bodies[0]->law.friction_set));
  std::string out;
  for (const Collider* c : on_bodies) {
    out += (out.empty() ? "" : ", ") + c->name + ": " +
           std::string(FrictionSetName(c->law.friction_set));
  }
  return out;
}

}  // namespace nonsmooth_sim::node
