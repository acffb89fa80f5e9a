// The world: a Simulator with the rules around it that the node's services and `simulate
// --schedule` share. It owns the models and their names (model_registry.h), the wrench schedule
// (wrench_schedule.h), the rules that place bodies (placement.h), the one route to a start
// (initial_conditions.h) and the configured start that the resets go back to.
//
// Every call either does what it says or throws std::invalid_argument with one line (what was
// wrong, what is allowed) and leaves the world exactly as it was. ROS-free; never logs or prints;
// not thread-safe (the node calls it with its simulator mutex held).
#ifndef NONSMOOTH_SIM_WORLD_WORLD_H_
#define NONSMOOTH_SIM_WORLD_WORLD_H_

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "nonsmooth_sim/world/initial_conditions.h"
#include "nonsmooth_sim/world/model_registry.h"
#include "nonsmooth_sim/world/names.h"
#include "nonsmooth_sim/world/placement.h"
#include "nonsmooth_sim/world/wrench_schedule.h"

namespace nonsmooth_sim::world {

/// What the world is made from besides its URDF (the node's parameters).
struct WorldConfig {
  std::string model_name;      ///< the start-up model's name ("": the URDF's <robot name>)
  std::string initial_body;    ///< the body `initial` moves ("": the first free body)
  InitialConditions initial;   ///< ~initial/...
  scene_io::InitialStateSpec initial_state;  ///< ~initial_state/bodies/<link>/...
  SimulatorOptions simulator;
  std::string world_frame = "world";  ///< the fixed frame (a name no body or contact may take)
};

/// A wrench request: force and torque in the axes of `reference_frame`, applied at `point`
/// (in that frame) for `duration` [s] from `start` [s] of sim time (start before now: now;
/// duration < 0: until cleared; 0: nothing).
struct WrenchRequest {
  std::string body;             ///< the body's name ("<model>/<link>"; or "<model>::<link>")
  std::string reference_frame;  ///< "" or "world", or a body
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double start = 0.0;
  double duration = 0.0;
};

class World {
 public:
  /// The start-up model `urdf` at its configured start (StartState of config's ~initial/... and
  /// ~initial_state/...). Throws std::invalid_argument with one line.
  World(scene_io::UrdfScene urdf, WorldConfig config);
  /// A world over a scene built elsewhere (`simulate`: the built-in Tippe-Top or a URDF with its
  /// YAML start), its initial_state the configured start: one start-up model `model_name`, a
  /// Simulator(scene, options) exactly as without a world.
  World(Scene scene, const std::string& model_name, const SimulatorOptions& options);

  Simulator& sim() { return *sim_; }
  const Simulator& sim() const { return *sim_; }
  const ModelRegistry& models() const { return models_; }
  const WrenchSchedule& wrenches() const { return wrenches_; }
  const scene_io::UrdfScene& urdf() const { return urdf_; }
  const WorldConfig& config() const { return config_; }
  /// The configured start: the start-up URDF with its configured start, and each spawned model
  /// at its spawn pose (reset_world, reset_simulation).
  const Scene& configured_scene() const { return configured_; }

  /// Adds `model` (a URDF's scene without ground) as model `name` at `pose` relative to
  /// `reference_frame`, between two steps; the rest of the world keeps its state and contacts.
  /// `description` is kept with it (the node: the parameter holding its URDF). Refused: a name
  /// taken or not a graph name, an unknown reference, a pose out of bounds, a world beyond
  /// kMaxWorldBodies / kMaxWorldCollisions, a frame or topic name taken.
  const Model& Spawn(const std::string& name, const Scene& model, const std::string& reference_frame,
                     const Pose& pose, const std::string& description);
  /// Removes model `name` (its wrenches with it) and returns it as it was.
  Model Delete(const std::string& name);

  /// The canonical body's link frame of model `name` relative to `reference_frame`: its pose,
  /// and its velocities as differences in the reference axes (as Gazebo).
  struct ModelFrame {
    int body = -1;  ///< the canonical body
    Pose pose;
    Twist twist;
  };
  ModelFrame GetModelState(const std::string& name, const std::string& reference_frame) const;
  /// Moves model `name` rigidly so that its canonical body's link frame has `pose` and `twist`
  /// relative to `reference_frame`; the other models keep their contacts.
  void SetModelState(const std::string& name, const std::string& reference_frame,
                     const Pose& pose, const Twist& twist);

  /// Schedules a wrench; nullopt for duration 0 (nothing to apply), else the scheduled wrench.
  std::optional<ExternalWrench> ApplyWrench(const WrenchRequest& request);
  /// Clears the wrenches of `body`; false (nothing changed) if it is not a body.
  bool ClearWrenches(const std::string& body);
  /// Before the next step over `interval` [s]: the scheduled wrenches into the simulator.
  void ApplyScheduledWrenches(double interval) {
    if (wrenches_.active()) wrenches_.Apply(sim_.get(), interval);
  }

  /// ~reset: body `body` of the start-up model ("" = the configured initial body) to `request`
  /// (merged over the configured ~initial/... for the initial body); the other bodies to the
  /// configured start.
  void Reset(const std::string& body, const InitialConditions& request);
  /// Every body to the configured start (time kept).
  void ResetWorld();
  /// A fresh simulator over the configured start with the configured options; time kept.
  void ResetSimulation();

  /// The name of body `body` (names.h: "<model>/<link>", or "<link>" of the start-up model).
  const std::string& BodyName(int body) const {
    return sim_->scene().bodies[static_cast<std::size_t>(body)].name;
  }
  /// The body a name addresses (its name, or "<model>::<link>"), -1 if none.
  int BodyIndex(const std::string& name) const { return models_.BodyIndex(sim_->scene(), name); }

 private:
  const scene_io::UrdfScene urdf_;  ///< the start-up model
  const WorldConfig config_;
  const int initial_body_;  ///< of ~reset, an index into urdf_
  Scene configured_;
  std::unique_ptr<Simulator> sim_;
  ModelRegistry models_;
  WrenchSchedule wrenches_;
};

}  // namespace nonsmooth_sim::world

#endif  // NONSMOOTH_SIM_WORLD_WORLD_H_
