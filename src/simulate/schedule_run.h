// `simulate --schedule FILE.yaml`: the scripted events of scene_io/schedule.h carried out on a
// world::World between two steps, through the calls the node's services make (spawn, apply a
// wrench, set a model's state, delete), and the CSV columns of every body the run will hold.
#ifndef NONSMOOTH_SIM_SIMULATE_SCHEDULE_RUN_H_
#define NONSMOOTH_SIM_SIMULATE_SCHEDULE_RUN_H_

#include <cstddef>
#include <string>
#include <vector>

#include "nonsmooth_sim/scene_io/schedule.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "nonsmooth_sim/world/world.h"

namespace nonsmooth_sim::simulate {

class ScheduleRunner {
 public:
  /// Loads every URDF the schedule spawns (with `options`, no second ground), so that a bad
  /// file stops the run before its first step. Throws std::invalid_argument with one line.
  ScheduleRunner(std::vector<scene_io::ScheduledEvent> events, scene_io::UrdfSceneOptions options);

  /// Before the step [t, t + dt): the events whose time is before t + dt, in order (a wrench
  /// from exactly its time, the others at t), then the scheduled wrenches of the step. A refused
  /// event throws std::invalid_argument "schedule line N (at T s): <reason>".
  void Before(world::World* world, double t, double dt);

  /// The bodies of `start` and of every spawned model, in that order ("<model>/<link>"): the
  /// CSV's columns (a body absent at a row writes nan).
  std::vector<std::string> BodyColumns(const Scene& start) const;

 private:
  std::vector<scene_io::ScheduledEvent> events_;
  std::vector<Scene> models_;  ///< per event: the spawned URDF's scene (empty for the others)
  std::size_t next_ = 0;
};

}  // namespace nonsmooth_sim::simulate

#endif  // NONSMOOTH_SIM_SIMULATE_SCHEDULE_RUN_H_
