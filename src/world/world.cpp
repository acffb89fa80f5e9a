// The world. See world.h.
#include "nonsmooth_sim/world/world.h"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/world/checks.h"

namespace nonsmooth_sim::world {
namespace {

int ResolveBody(const scene_io::UrdfScene& urdf, const std::string& name) {
  if (name.empty()) return 0;
  for (int b = 0; b < static_cast<int>(urdf.scene.bodies.size()); ++b) {
    if (urdf.scene.bodies[static_cast<std::size_t>(b)].name == name) return b;
  }
  throw std::invalid_argument("parameter ~initial/body: \"" + name + "\" is not a free body");
}

Scene ConfiguredScene(const scene_io::UrdfScene& urdf, int body, const WorldConfig& config) {
  Scene scene = urdf.scene;
  scene.initial_state = StartState(urdf, StartSpec{body, config.initial, config.initial_state});
  return scene;
}

scene_io::UrdfScene AsUrdf(Scene scene, const std::string& name) {
  scene_io::UrdfScene urdf;
  urdf.robot_name = name;
  urdf.tippe_top.assign(scene.bodies.size(), std::nullopt);  // every body a general one
  urdf.scene = std::move(scene);
  return urdf;
}

WorldConfig ConfigOf(const std::string& name, const SimulatorOptions& options) {
  WorldConfig config;
  config.model_name = name;
  config.simulator = options;
  return config;
}

}  // namespace

World::World(Scene scene, const std::string& model_name, const SimulatorOptions& options)
    : urdf_(AsUrdf(scene, model_name)),
      config_(ConfigOf(model_name, options)),
      initial_body_(0),
      configured_(std::move(scene)) {
  sim_ = std::make_unique<Simulator>(configured_, config_.simulator);
  models_.Reset(model_name, sim_->scene());
}

World::World(scene_io::UrdfScene urdf, WorldConfig config)
    : urdf_(std::move(urdf)),
      config_(std::move(config)),
      initial_body_(ResolveBody(urdf_, config_.initial_body)),
      configured_(ConfiguredScene(urdf_, initial_body_, config_)) {
  // names map one-to-one to frames and topics (two transforms per frame otherwise)
  if (const std::string clash = FrameNameClash(urdf_.scene, config_.world_frame); !clash.empty()) {
    throw std::invalid_argument("urdf: " + clash);
  }
  sim_ = std::make_unique<Simulator>(configured_, config_.simulator);
  models_.Reset(!config_.model_name.empty() ? config_.model_name : urdf_.robot_name,
                sim_->scene());
}

const Model& World::Spawn(const std::string& name, const Scene& model_scene,
                          const std::string& reference_frame, const Pose& pose,
                          const std::string& description) {
  CheckModelName("model_name", name);
  Check(!model_scene.bodies.empty() || !model_scene.colliders.empty(),
        "model_xml has neither a free body nor a collision: nothing to spawn");
  Check(models_.Find(name) < 0,
        "model_name \"" + name + "\" exists already (~delete_model it first)");
  const Scene& scene = sim_->scene();
  const Frame reference =
      BodyFrame(*sim_, models_.ReferenceBody(scene, reference_frame, "reference_frame"));
  const Eigen::Isometry3d placement = PlaceInWorld(reference, pose, "initial_pose");
  Check(scene.bodies.size() + model_scene.bodies.size() <= ModelRegistry::kMaxWorldBodies,
        "the world would have " + std::to_string(scene.bodies.size() + model_scene.bodies.size()) +
            " bodies, more than " + std::to_string(ModelRegistry::kMaxWorldBodies) +
            " (the most it holds)");
  Check(scene.colliders.size() + model_scene.colliders.size() <=
            ModelRegistry::kMaxWorldCollisions,
        "the world would have " +
            std::to_string(scene.colliders.size() + model_scene.colliders.size()) +
            " collisions, more than " + std::to_string(ModelRegistry::kMaxWorldCollisions) +
            " (the bound on collisions per world)");
  const Scene model = PlacedModel(model_scene, name + "/", placement);
  {
    // frames and topics one-to-one over the whole world (two transforms per frame otherwise)
    Scene world = scene;
    AppendScene(model, &world);
    const std::string clash = FrameNameClash(world, config_.world_frame);
    Check(clash.empty(), "model " + name + ": " + clash);
  }
  const int first_collider = static_cast<int>(scene.colliders.size());
  const int first = sim_->AddBodies(model, model.initial_state);  // validates; or no change
  // committed: nothing below throws on input
  AppendScene(model, &configured_);
  Model added;
  added.name = name;
  added.prefix = name + "/";
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    added.bodies.push_back(first + static_cast<int>(b));
  }
  for (int c = first_collider; c < static_cast<int>(sim_->scene().colliders.size()); ++c) {
    added.colliders.push_back(c);
  }
  added.description = description;
  models_.Add(added);
  return models_.models().back();
}

Model World::Delete(const std::string& name) {
  const int m = models_.Find(name);
  Check(m >= 0, models_.Unknown(name));
  const Model removed = models_.at(m);
  const Scene& scene = sim_->scene();
  std::vector<char> remove_body(scene.bodies.size(), 0);
  std::vector<char> remove_collider(scene.colliders.size(), 0);
  std::vector<int> statics;
  for (int b : removed.bodies) remove_body[static_cast<std::size_t>(b)] = 1;
  for (int c : removed.colliders) {
    remove_collider[static_cast<std::size_t>(c)] = 1;
    if (scene.colliders[static_cast<std::size_t>(c)].body == kWorld) statics.push_back(c);
  }
  sim_->RemoveBodies(removed.bodies, statics);  // throws and changes nothing, or removes
  // the same removal on the configured start: the same old → new maps
  std::vector<int> body_map;
  std::vector<int> collider_map;
  RemoveFromScene(remove_body, remove_collider, &configured_, &body_map, &collider_map);
  models_.Remove(m, body_map, collider_map);
  wrenches_.Remap(body_map);
  return removed;
}

World::ModelFrame World::GetModelState(const std::string& name,
                                       const std::string& reference_frame) const {
  const int m = models_.Find(name);
  Check(m >= 0, models_.Unknown(name));
  const Model& model = models_.at(m);
  Check(!model.bodies.empty(), "model \"" + model.name + "\" has no free body");
  const Frame reference = BodyFrame(
      *sim_, models_.ReferenceBody(sim_->scene(), reference_frame, "relative_entity_name"));
  ModelFrame out;
  out.body = model.bodies.front();
  const Frame f = BodyFrame(*sim_, out.body);
  // in the reference frame: its pose; velocities as differences, in its axes (as Gazebo)
  const Eigen::Quaterniond inverse = reference.rotation.conjugate();
  out.pose.position = inverse * (f.origin - reference.origin);
  out.pose.orientation = inverse * f.rotation;
  out.twist.linear = inverse * (f.linear_velocity - reference.linear_velocity);
  out.twist.angular = inverse * (f.angular_velocity - reference.angular_velocity);
  return out;
}

void World::SetModelState(const std::string& name, const std::string& reference_frame,
                          const Pose& pose, const Twist& twist) {
  const int m = models_.Find(name);
  Check(m >= 0, models_.Unknown(name));
  const Model& model = models_.at(m);
  Check(!model.bodies.empty(), "model \"" + model.name + "\" has no free body");
  const Frame reference =
      BodyFrame(*sim_, models_.ReferenceBody(sim_->scene(), reference_frame, "reference_frame"));
  std::vector<std::string> names;
  for (int b : model.bodies) names.push_back(BodyName(b));
  const std::vector<BodyState> states =
      RigidlyMoved(*sim_, model.bodies, names, reference, pose, twist);
  // validates, throws and changes nothing on bad input; the other models keep their contacts
  sim_->SetBodyStates(model.bodies, states);
}

std::optional<ExternalWrench> World::ApplyWrench(const WrenchRequest& request) {
  const int b = BodyIndex(request.body);
  Check(b >= 0, "body_name \"" + request.body +
                    "\" is not a body (\"<model>/<link>\" or \"<link>\" of a free link)");
  const Frame reference = BodyFrame(
      *sim_, models_.ReferenceBody(sim_->scene(), request.reference_frame, "reference_frame"));
  const Eigen::Vector3d force =
      FiniteVector("wrench.force", request.force, WrenchSchedule::kMaxForce);
  const Eigen::Vector3d torque =
      FiniteVector("wrench.torque", request.torque, WrenchSchedule::kMaxForce);
  const Eigen::Vector3d point =
      FiniteVector("reference_point", request.point, scene_io::kMaxInitialCoordinate);
  Check(std::isfinite(request.start) && std::isfinite(request.duration),
        "start_time, duration: must be finite");
  ExternalWrench w;
  w.body = b;
  w.force = reference.rotation * force;
  w.torque = reference.rotation * torque;
  // the point of application is fixed in the body (it turns with it)
  const BodyState& s = sim_->state()[static_cast<std::size_t>(b)];
  w.point_in_body =
      s.orientation.conjugate() * (reference.origin + reference.rotation * point - s.position);
  w.start = std::max(request.start, sim_->time());
  w.end = request.duration < 0.0 ? std::numeric_limits<double>::infinity()
                                 : w.start + request.duration;
  wrenches_.CheckRoom();
  if (request.duration == 0.0) return std::nullopt;
  wrenches_.Add(w);
  return w;
}

bool World::ClearWrenches(const std::string& body) {
  const int b = BodyIndex(body);
  if (b < 0) return false;
  wrenches_.Clear(b);
  sim_->SetExternalWrench(b, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  return true;
}

void World::Reset(const std::string& body_name, const InitialConditions& request) {
  // a body of the start-up model (urdf_); spawned models: SetModelState
  int body = body_name.empty() ? initial_body_ : -1;
  for (std::size_t b = 0; b < urdf_.scene.bodies.size() && body < 0; ++b) {
    if (urdf_.scene.bodies[b].name == body_name) body = static_cast<int>(b);
  }
  Check(body >= 0, "body \"" + body_name +
                       "\" is not a free body of the start-up model (a spawned model's: "
                       "~set_model_state)");
  const Model* start_up = models_.StartUp();
  Check(start_up != nullptr, "the start-up model was deleted (~delete_model)");
  const std::vector<int>& where = start_up->bodies;  // per urdf_ body its index in the world
  ValidateInitialConditions(request);
  std::vector<BodyState> state = configured_.initial_state;
  if (body == initial_body_) {
    const std::vector<BodyState> start =
        InitialState(urdf_, body, Merge(config_.initial, request));
    for (std::size_t b = 0; b < start.size(); ++b) state[static_cast<std::size_t>(where[b])] = start[b];
  } else {
    state[static_cast<std::size_t>(where[static_cast<std::size_t>(body)])] =
        InitialState(urdf_, body, request)[static_cast<std::size_t>(body)];
  }
  sim_->SetState(state);  // validates; clears the warm start
}

void World::ResetWorld() { sim_->SetState(configured_.initial_state); }

void World::ResetSimulation() {
  // a fresh simulator with the configured laws and solver; the time goes on
  const double time = sim_->time();
  if (configured_.bodies.empty()) {
    // every model deleted (a simulator needs a body): only the state of the static world is left
    sim_->SetState(configured_.initial_state);
  } else {
    sim_ = std::make_unique<Simulator>(configured_, config_.simulator);
    sim_->SetTime(time);
  }
}

}  // namespace nonsmooth_sim::world
