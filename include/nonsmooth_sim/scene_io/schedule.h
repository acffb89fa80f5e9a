// A scripted schedule of world events (`simulate --schedule FILE.yaml`, docs/simulate.md): at
// given sim times, spawn a URDF model at a pose, apply a wrench to a body for a duration, set a
// model's state, delete a model. Parsed and bounded here (yaml-cpp, bounded_input.h); carried out
// by world::World, the same calls the node's services make.
//
//   events:
//     - at: 0.5                      # [s] of sim time, >= 0
//       spawn: {model: die2, urdf: die.urdf, position: [0.1, 0, 0.05], orientation: [0, 0, 0, 1]}
//     - at: 1.0
//       wrench: {body: die, force: [0.5, 0, 0], torque: [0, 0, 0], point: [0, 0, 0], duration: 0.01}
//     - at: 1.5
//       set_state: {model: die2, position: [0, 0.2, 0.05], linear_velocity: [0, 0, 0]}
//     - at: 1.8
//       delete: {model: die2}
//
// A relative urdf path is relative to the schedule file's folder. Every key but the event's name
// fields is optional (zero vectors, identity orientation; a wrench's duration < 0: to the end).
#ifndef NONSMOOTH_SIM_SCENE_IO_SCHEDULE_H_
#define NONSMOOTH_SIM_SCENE_IO_SCHEDULE_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <variant>
#include <vector>

namespace nonsmooth_sim::scene_io {

/// Events in one schedule at most (a bound on the work of a run).
inline constexpr std::size_t kMaxScheduleEvents = 10000;

struct SpawnEvent {
  std::string model;      ///< its name (letters, digits, _)
  std::string urdf_path;  ///< resolved against the schedule's folder
  Eigen::Vector3d position = Eigen::Vector3d::Zero();                ///< of its frame [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< as given (x y z w)
};
struct WrenchEvent {
  std::string body;  ///< its name ("<model>/<link>", or "<link>" of the start-up scene)
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< world axes [N]
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  ///< world axes [N m]
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< point of application, world [m]
  double duration = 0.0;                             ///< [s]; < 0: until the end
};
struct StateEvent {
  std::string model;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< canonical link frame, world [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   ///< of the link origin [m/s]
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  ///< world axes [rad/s]
};
struct DeleteEvent {
  std::string model;
};

struct ScheduledEvent {
  double time = 0.0;  ///< [s] of sim time
  int line = 0;       ///< of the event in the file, for error lines
  std::variant<SpawnEvent, WrenchEvent, StateEvent, DeleteEvent> what;
};

/// The events by time (equal times in file order). Throws std::invalid_argument with one line
/// ("line 7: wrench: unknown key \"forse\"; allowed: body, force, torque, point, duration").
std::vector<ScheduledEvent> ParseScheduleYaml(const std::string& text, const std::string& folder);

/// ParseScheduleYaml of the file at `path` (bounded: a regular file of at most 16 MiB), its
/// folder resolving relative URDF paths; errors start with the path.
std::vector<ScheduledEvent> LoadScheduleFile(const std::string& path);

}  // namespace nonsmooth_sim::scene_io

#endif  // NONSMOOTH_SIM_SCENE_IO_SCHEDULE_H_
