// The node's private parameters: read once, with defaults, validated (docs/ros.md, "Parameters").
#ifndef NONSMOOTH_SIM_NODE_NODE_PARAMETERS_H_
#define NONSMOOTH_SIM_NODE_NODE_PARAMETERS_H_

#include <ros/node_handle.h>

#include <cstddef>
#include <string>

#include "nonsmooth_sim/core/adaptive_stepper.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "nonsmooth_sim/world/initial_conditions.h"

namespace nonsmooth_sim::node {

using scene_io::SceneFromUrdf;
using scene_io::UrdfError;
using scene_io::UrdfScene;
using scene_io::UrdfSceneOptions;
using scene_io::ValidateUrdfSceneOptions;
using world::InitialConditions;
using world::Merge;
using world::ValidateInitialConditions;

/// The largest ~max_samples_per_message.
constexpr int kMaxSamplesPerMessage = 10000;
/// A /tf or ~contacts message is also sent once it holds this many transforms or contacts: a large
/// world (1024 tops: 3072 transforms per sample) gets one sample per message, not megabytes.
constexpr std::size_t kMaxItemsPerMessage = 4096;

/// Publish rates are in Hz of simulated time (a message every round(1/(rate·Δt)) steps, at most
/// one per step; 0 = never) unless marked wall.
struct NodeParameters {
  std::string urdf_file;          ///< ~urdf_file: read the URDF from this file instead of
                                  ///< the robot_description parameter
  std::string urdf_xml;           ///< the URDF text (filled from either source)
  std::string world_frame = "world";  ///< ~world_frame: fixed frame of TF, markers, contacts
  std::string model_name;         ///< ~model_name: the URDF's model in the world services
                                  ///< (default: its <robot name>)
  UrdfSceneOptions scene;         ///< ~gravity, ~friction_set, ~mu, ~contact_radius,
                                  ///< ~rolling_resistance, ~hold_joints (the start-up URDF's),
                                  ///< ~max_urdf_bytes (max_bytes: of ~urdf_file,
                                  ///< robot_description and ~spawn_urdf_model's model_xml);
                                  ///< collision_table: the defaults (main adds FCL's pairs)
  SimulatorOptions simulator;     ///< ~time_step, ~solver, ~tolerance, ~tolerance_abs,
                                  ///< ~max_iterations, ~relaxation, ~gyroscopic, ~integrator,
                                  ///< ~gap_correction (bool, default true)
  /// ~accuracy (TOL; 0 = fixed steps of ~time_step), ~min_dt, ~max_dt: with TOL > 0 each step is
  /// chosen from an error estimate (AdaptiveStepper) and ~time_step is the node's tick only: the
  /// sample times it publishes at and the unit of ~step
  AccuracyOptions accuracy;
  std::string initial_body;       ///< ~initial/body: the body the initial conditions move
  InitialConditions initial;      ///< ~initial/{inclination,spin,position,orientation,
                                  ///< linear_velocity,angular_velocity}
  /// ~initial_state: config/<scene>.yaml loaded as parameters (bodies/<link>/{position,
  /// orientation, linear_velocity, angular_velocity}, each optional); applied after ~initial/...
  scene_io::InitialStateSpec initial_state;
  double real_time_factor = 1.0;  ///< ~real_time_factor: sim time / wall time, ≥ 0; 0 = as fast
                                  ///< as possible
  bool paused = false;            ///< ~paused: start paused
  double duration = 0.0;          ///< ~duration [s]: pause when the sim time reaches it; 0 = never
  double tf_rate = 1000.0;        ///< ~tf_rate: world → link and contact frames
  double contacts_rate = 1000.0;  ///< ~contacts_rate: ~contacts and the contact wrenches
  double state_rate = 100.0;      ///< ~state_rate: ~state
  double markers_rate = 30.0;     ///< ~markers_rate: ~contact_markers
  double clock_rate = 100.0;      ///< ~clock_rate [wall Hz]: /clock throttle, > 0
  double diagnostics_rate = 1.0;  ///< ~diagnostics_rate [wall Hz]: /diagnostics, > 0
  double wall_update_rate = 200.0;  ///< ~wall_update_rate [wall Hz]: how often the integrator
                                    ///< catches up with wall time when real_time_factor > 0
  int queue_size = 1000;          ///< ~queue_size: publisher queues, ≥ 1 (/tf and ~contacts:
                                  ///< ⌈queue_size / max_samples_per_message⌉ messages, ≥ 100)
  /// ~max_wall_publish_rate [wall Hz]: no topic is published more often than this in wall
  /// time; the simulation slows down instead of skipping messages (a cap on the real-time
  /// factor). 0 = no limit. For subscribers with small queues, e.g. rosbag record (100).
  double max_wall_publish_rate = 0.0;
  /// ~max_samples_per_message: /tf and ~contacts carry every sample due in one chunk of stepping
  /// (TF: several stamps in one TFMessage; ~contacts: several steps in one ContactSteps), sent at
  /// the chunk's end, before /clock passes them, or when this many are pending (or
  /// kMaxItemsPerMessage transforms or contacts); 1 ≤ n ≤ 10 000. 1 = one message per sample. Each message costs roscpp a send and a wake-up per subscriber.
  int max_samples_per_message = 100;
  double marker_force_scale = 0.5;     ///< ~marker_force_scale [m/N]: arrow length per force
  double marker_torque_scale = 5000.0; ///< ~marker_torque_scale [m/(N m)]: per drilling torque
};

/// Reads the private parameters of `private_nh` (and robot_description from `nh` unless
/// ~urdf_file is set). Throws std::invalid_argument with one line naming the parameter.
NodeParameters ReadNodeParameters(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh);

/// The checks ReadNodeParameters applies (ranges, names), for parameters built in code.
void ValidateNodeParameters(const NodeParameters& parameters);

}  // namespace nonsmooth_sim::node

#endif  // NONSMOOTH_SIM_NODE_NODE_PARAMETERS_H_
