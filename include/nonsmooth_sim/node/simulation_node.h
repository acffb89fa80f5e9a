// The ROS node: serves a world::World to ROS (docs/ros.md). Its handlers convert a request into a
// World call and the result into a response; it holds no physics and no world rules.
//
// Threads: the integrator runs on its own thread, paced by the wall clock (sim time = wall time ×
// ~real_time_factor, or as fast as possible for 0); services and the diagnostics wall timer run
// in the ROS spinner. One mutex guards the Simulator: the integrator holds it for a bounded chunk
// of steps, so every service applies its change between two steps. A service that waits for the
// mutex is served before the next chunk (LockForService). ~step has a callback queue and thread
// of its own, so that long step calls never take the spinner's threads from the other services;
// spawn and delete call the master without the mutex (model_services.cpp).
#ifndef NONSMOOTH_SIM_NODE_SIMULATION_NODE_H_
#define NONSMOOTH_SIM_NODE_SIMULATION_NODE_H_

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "nonsmooth_sim/ApplyBodyWrench.h"
#include "nonsmooth_sim/BodyRequest.h"
#include "nonsmooth_sim/ContactSteps.h"
#include "nonsmooth_sim/DeleteModel.h"
#include "nonsmooth_sim/GetFrictionSet.h"
#include "nonsmooth_sim/GetModelProperties.h"
#include "nonsmooth_sim/GetModelState.h"
#include "nonsmooth_sim/GetWorldProperties.h"
#include "nonsmooth_sim/SetModelState.h"
#include "nonsmooth_sim/GetSimulationState.h"
#include "nonsmooth_sim/GetSolverProperties.h"
#include "nonsmooth_sim/ResetState.h"
#include "nonsmooth_sim/SetFrictionSet.h"
#include "nonsmooth_sim/SetSolverProperties.h"
#include "nonsmooth_sim/SpawnModel.h"
#include "nonsmooth_sim/StepSimulation.h"
#include "nonsmooth_sim/core/adaptive_stepper.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/node/conversions.h"
#include "nonsmooth_sim/node/master_calls.h"
#include "nonsmooth_sim/node/node_parameters.h"
#include "nonsmooth_sim/world/world.h"

namespace nonsmooth_sim::node {

class SimulationNode {
 public:
  /// Builds the scene's start from the parameters, advertises topics and services and starts the
  /// integrator thread. Throws std::invalid_argument on bad initial conditions.
  SimulationNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh,
                 NodeParameters parameters, UrdfScene urdf);
  ~SimulationNode();
  SimulationNode(const SimulationNode&) = delete;
  SimulationNode& operator=(const SimulationNode&) = delete;

 private:
  using Clock = std::chrono::steady_clock;

  /// A message stream published every `period` steps (0 = never).
  struct Channel {
    double rate = 0.0;  ///< [Hz of sim time]
    std::int64_t period = 0;
    std::int64_t countdown = 0;
  };

  /// Accumulated over a diagnostics period (and over the whole run).
  struct RunStatistics {
    std::int64_t steps = 0;
    double busy_wall = 0.0;     ///< [s] in the integrator: stepping and publishing
    double publish_wall = 0.0;  ///< [s] of it publishing
    std::int64_t iterations_sum = 0;
    int iterations_max = 0;
    double residual_max = 0.0;
    std::int64_t unconverged = 0;
    double max_dt_omega = 0.0;
    void Add(const StepStatistics& step);
  };

  // --- integrator (mutex held)
  void Run();
  /// Steps until `budget` ticks are done, the deadline passes or the run pauses; returns the ticks.
  std::int64_t RunChunk(std::int64_t budget, Clock::time_point deadline);
  /// Advances the simulation by at least one and at most `max_ticks` ticks (tick_): one step of
  /// tick_ with fixed steps; with ~accuracy, up to the next sample a topic is due at, in steps the
  /// error estimate chooses. Returns the ticks advanced (those that a fault cut short count).
  std::int64_t StepOnce(std::int64_t max_ticks);
  /// ~accuracy: (re)creates stepper_ over sim_ with accuracy_ (TOL > 0), or removes it and
  /// gives sim_ back the fixed step tick_.
  void ResetStepper();
  /// After a chunk of steps that began at `start`: the pending samples sent, the chunk's wall
  /// time counted, and the end-of-run log line if ~duration was reached in it.
  void FinishChunk(Clock::time_point start);
  /// The end-of-run log line (~duration reached), once the chunk's wall time is counted.
  void LogSummaryIfDue();
  /// [s] of wall time spent unpaused up to `now`.
  double RunningWall(Clock::time_point now) const;
  /// A step threw or left a non-finite state: pause, log once, report in /diagnostics (ERROR).
  void Fault(const std::string& what);
  void Pause(const char* reason);
  void Unpause();
  std::unique_lock<std::mutex> LockForService();

  // --- publishing (mutex held)
  void UpdatePeriods();
  void RestartChannels();
  /// After `ticks` ticks: publishes what is due (a channel is due at most once per call).
  void PublishDue(std::int64_t ticks);
  void PublishTransforms();
  void PublishContacts();
  /// Sends the pending /tf and ~contacts samples, each topic as one message.
  void FlushSamples();
  void PublishState();
  void PublishMarkers();
  void PublishClock(bool flush);
  void AfterReset();

  // --- services (service thread)
  bool OnPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool OnUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool OnStep(StepSimulation::Request& req, StepSimulation::Response& res);
  bool OnResetState(ResetState::Request& req, ResetState::Response& res);
  bool OnResetWorld(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool OnResetSimulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool OnSetFrictionSet(SetFrictionSet::Request& req, SetFrictionSet::Response& res);
  bool OnGetFrictionSet(GetFrictionSet::Request& req, GetFrictionSet::Response& res);
  bool OnGetSolverProperties(GetSolverProperties::Request&, GetSolverProperties::Response& res);
  bool OnSetSolverProperties(SetSolverProperties::Request& req,
                             SetSolverProperties::Response& res);
  bool OnGetState(GetSimulationState::Request&, GetSimulationState::Response& res);
  // --- world services (world_services.cpp)
  bool OnGetWorldProperties(GetWorldProperties::Request&, GetWorldProperties::Response& res);
  bool OnGetModelProperties(GetModelProperties::Request& req, GetModelProperties::Response& res);
  bool OnGetModelState(GetModelState::Request& req, GetModelState::Response& res);
  bool OnSetModelState(SetModelState::Request& req, SetModelState::Response& res);
  bool OnApplyBodyWrench(ApplyBodyWrench::Request& req, ApplyBodyWrench::Response& res);
  bool OnClearBodyWrenches(BodyRequest::Request& req, BodyRequest::Response& res);
  // --- spawn and delete (model_services.cpp)
  bool OnSpawnUrdfModel(SpawnModel::Request& req, SpawnModel::Response& res);
  bool OnDeleteModel(DeleteModel::Request& req, DeleteModel::Response& res);
  /// The parameter for a spawned model's URDF: <robot_namespace>/robot_description, confined to
  /// the model's own namespace and checked against the master (model_services.cpp). Throws
  /// std::invalid_argument with the reason. Talks to the master: call without the mutex.
  std::string ModelNamespace(const std::string& model_name,
                             const std::string& robot_namespace) const;
  /// What a change of the world leaves for the master (AdvertiseWrenches, without the mutex).
  struct WrenchTopics {
    std::vector<std::string> to_advertise;  ///< ~wrench/ topics of new slots (relative names)
    std::vector<ros::Publisher> dropped;    ///< kept ones beyond the bound: their last copies
  };
  /// After bodies or colliders were added or removed: the contact frames and wrench topics of the
  /// world, the markers cleared (simulator mutex and world_mutex_ held). A new slot takes a kept
  /// publisher of its topic if there is one, else it has none until AdvertiseWrenches; a removed
  /// slot's publisher sends a zero wrench and is kept (kept_wrench_pubs_).
  WrenchTopics WorldChanged();
  /// Advertises the new topics and installs them in their slots (takes the mutex for that only;
  /// a topic whose slot is gone meanwhile is kept), then drops the publishers kept beyond the
  /// bound (unadvertised): the master calls of a spawn or delete, made on master_calls_.
  void AdvertiseWrenches(WrenchTopics* topics);
  /// Keeps the publisher of a removed slot (mutex held); the oldest beyond the bound go to
  /// `dropped`.
  void KeepWrenchPublisher(const ros::Publisher& publisher, std::vector<ros::Publisher>* dropped);
  std::string WrenchTopic(std::size_t slot) const;  ///< "wrench/<collision>" (mutex held)
  /// Sends every model's fixed links on /tf_static as one latched message.
  void PublishFixedLinks();
  // --- diagnostics (spinner thread)
  void OnDiagnosticsTimer(const ros::WallTimerEvent&);
  void Diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  std::string FrictionSetSummary() const;

  const NodeParameters parameters_;
  FrameNames frames_;  ///< of the current world (WorldChanged)

  ros::NodeHandle nh_, private_nh_;
  ros::Publisher clock_pub_, tf_pub_, contacts_pub_, state_pub_, markers_pub_;
  /// /tf_static (latched): the links without a body of their own, per model (the start-up one
  /// at construction, spawned ones under world_mutex_); PublishFixedLinks sends them all
  ros::Publisher tf_static_pub_;
  std::map<std::string, std::vector<geometry_msgs::TransformStamped>> fixed_links_;
  std::vector<ros::Publisher> wrench_pubs_;  ///< per slot; empty until advertised
  std::vector<ros::ServiceServer> services_;
  ros::WallTimer diagnostics_timer_;
  diagnostic_updater::Updater updater_;

  std::mutex mutex_;
  /// Serialises ~spawn_urdf_model and ~delete_model, held while they wait for their master calls
  /// (taken before mutex_, never while holding it).
  std::mutex world_mutex_;
  /// ~wrench/ publishers of removed collisions (resolved topic → publisher, and the topics oldest
  /// first), under mutex_. They stay advertised, silent, and serve the next collision with
  /// that topic: unadvertising calls the master while roscpp holds the lock that every publish
  /// and getNumSubscribers of the integrator takes, so a slow or stopped master would stall the
  /// stepping (under the simulator mutex) and with it every service. Beyond
  /// kMaxKeptWrenchTopics the oldest is unadvertised (AdvertiseWrenches).
  std::map<std::string, ros::Publisher> kept_wrench_pubs_;
  std::deque<std::string> kept_wrench_order_;
  static constexpr std::size_t kMaxKeptWrenchTopics = 1024;
  std::condition_variable wake_;
  std::atomic<int> waiting_services_{0};
  bool stop_ = false;

  // --- guarded by mutex_
  /// the world: the simulator, its models, wrenches and the configured start (resets)
  std::unique_ptr<world::World> world_;
  /// [s] the node's tick, ~time_step: its step with fixed steps; with ~accuracy the unit of ~step
  /// and of the publish periods (the stepper changes sim_'s time step at every step)
  double tick_ = 0.0;
  double solver_tolerance_ = 0.0;   ///< ~tolerance as asked (the stepper lowers sim_'s)
  AccuracyOptions accuracy_;        ///< ~accuracy, ~min_dt, ~max_dt
  std::unique_ptr<AdaptiveStepper> stepper_;  ///< with ~accuracy > 0, over sim_
  StepStatistics last_step_;
  bool paused_ = false;
  bool duration_reached_ = false;
  Channel tf_, contacts_, state_, markers_;
  ros::Time last_tf_stamp_, last_clock_stamp_;
  Clock::time_point last_clock_wall_;
  std::vector<bool> wrench_closed_;  ///< per slot: had a contact at the last publish
  std::size_t markers_count_ = 0;     ///< contacts drawn by the last marker message
  std::vector<int> first_contact_;    ///< per collider its first contact (FirstContacts)
  double pace_ = 0.0;  ///< real-time factor the integrator keeps (0: as fast as possible)
  Clock::time_point anchor_wall_;
  std::int64_t steps_since_anchor_ = 0;
  RunStatistics period_, total_;
  double run_wall_ = 0.0;  ///< [s] of wall time spent unpaused, up to the last pause
  Clock::time_point unpaused_at_;
  double running_sim_time_ = 0.0;  ///< [s] of sim time the integrator advanced while unpaused
  std::string fault_;        ///< why the last step failed, until a reset ("" = none)
  std::int64_t faults_ = 0;  ///< failed steps since start
  bool summary_due_ = false;        ///< ~duration reached: LogSummaryIfDue logs the run
  // reused messages
  tf2_msgs::TFMessage tf_msg_;       ///< the pending TF samples (FlushSamples sends them)
  ContactSteps contacts_msg_;        ///< the pending ~contacts samples
  int tf_samples_ = 0, contacts_samples_ = 0;  ///< samples in them
  std::size_t pending_contact_count_ = 0;       ///< contacts in contacts_msg_
  SimulationState state_msg_;
  visualization_msgs::MarkerArray markers_msg_;
  geometry_msgs::WrenchStamped wrench_msg_;

  // --- diagnostics thread only
  struct DiagnosticsSnapshot {
    RunStatistics period;
    std::int64_t unconverged_total = 0;
    double sim_time = 0.0;
    double real_time_factor = 0.0;  ///< sim time / wall time while running, over the period
    double running_wall = 0.0;      ///< [s] the integrator ran (unpaused) in the period
    bool paused = false;
    int closed_contacts = 0;
    int islands = 0;  ///< contact problems of the last step
    std::size_t bodies = 0;
    std::size_t models = 0;
    std::string friction_sets;
    std::string solver;
    double time_step = 0.0;
    AccuracyOptions accuracy;
    AdaptiveStatistics adaptive;  ///< of the stepper since it was made (~accuracy > 0)
    double pace = 0.0;
    std::string fault;
    std::int64_t faults = 0;
    /// bodies that can no longer touch anything (world/lost_bodies.h): "<name> <why>"
    std::vector<std::string> lost;
  } snapshot_;
  /// the lost bodies already logged (a WARN once each; diagnostics thread)
  std::vector<std::string> logged_lost_;
  double previous_running_wall_ = 0.0;
  double previous_running_sim_time_ = 0.0;

  /// ~step's own callback queue and thread: a long step call (or several, served one after the
  /// other) never holds a thread of the node's spinner, so the other services keep answering
  ros::CallbackQueue step_queue_;
  std::unique_ptr<ros::AsyncSpinner> step_spinner_;
  /// ~spawn_urdf_model's and ~delete_model's queue and thread (one at a time, world_mutex_)
  ros::CallbackQueue world_queue_;
  std::unique_ptr<ros::AsyncSpinner> world_spinner_;

  /// the master calls of spawns and deletes (model_services.cpp): destroyed before the members
  /// above, which its queued calls use, after the integrator has stopped
  MasterCalls master_calls_;
  /// the longest a spawn or delete waits for its master calls (docs/ros.md, "Bounds")
  static constexpr std::chrono::milliseconds kMasterTimeout{5000};

  std::thread integrator_;  // last: started when everything above exists
};

}  // namespace nonsmooth_sim::node

#endif  // NONSMOOTH_SIM_NODE_SIMULATION_NODE_H_
