// ~spawn_urdf_model and ~delete_model (docs/ros.md, "World services"): models added to and removed
// from the running world between two steps. The core does the work (Simulator::AddBodies,
// RemoveBodies: the rest of the world keeps its state and contact memory); the node keeps its
// views of the world in step: the configured start (reset_simulation), the models, the wrenches,
// the contact frames and wrench topics, the markers.
//
// Names: a spawned model's bodies and collisions are "<model>/<link>" and "<model>/<collision>"
// in the core scene, so its TF frames are "<model>/<link>" (rviz's RobotModel with TF prefix
// <model> on the robot_description set under its namespace); services address its bodies as
// "<model>::<link>" (as Gazebo) or by that full name.
//
// Locks: the world changes under the simulator mutex; the master calls (the namespace checks,
// setting or deleting the robot_description, advertising and unadvertising ~wrench/ topics) are
// made without it, under world_mutex_, which serialises spawns and deletes. A slot of a spawned
// collision publishes from when its topic is advertised.
#include <ros/names.h>

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "nonsmooth_sim/node/simulation_node.h"
#include "nonsmooth_sim/scene_io/bounded_input.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "world_frames.h"

namespace nonsmooth_sim::node {
namespace {

// The model frame in the world from a request's initial_pose relative to `reference`.
Eigen::Isometry3d Placement(const Frame& reference, const geometry_msgs::Pose& pose) {
  const Eigen::Vector3d position = FiniteVector("initial_pose.position", ToEigen(pose.position),
                                                scene_io::kMaxInitialCoordinate);
  const Eigen::Quaterniond orientation = Orientation("initial_pose.orientation", pose.orientation);
  Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();
  placement.linear() = (reference.rotation * orientation).normalized().toRotationMatrix();
  placement.translation() = reference.origin + reference.rotation * position;
  return placement;
}

// The URDF's scene placed at `placement`, its names prefixed with "<model>/".
Scene PlacedModel(Scene scene, const std::string& prefix, const Eigen::Isometry3d& placement) {
  const Eigen::Quaterniond turn(placement.linear());
  for (RigidBody& body : scene.bodies) body.name = prefix + body.name;
  for (Collider& collider : scene.colliders) {
    collider.name = prefix + collider.name;
    if (collider.body == kWorld) collider.pose = placement * collider.pose;
  }
  for (std::size_t b = 0; b < scene.initial_state.size(); ++b) {
    BodyState& s = scene.initial_state[b];
    s.position = placement * s.position;
    s.orientation = (turn * s.orientation).normalized();
    s.linear_velocity = turn * s.linear_velocity;  // body axes: angular_velocity stays
    Check(s.position.lpNorm<Eigen::Infinity>() <= scene_io::kMaxInitialCoordinate,
          "body " + scene.bodies[b].name + " would start outside |x|, |y|, |z| <= " +
              std::to_string(scene_io::kMaxInitialCoordinate) + " m");
  }
  return scene;
}

}  // namespace

// The parameter namespace of a spawned model's URDF (robot_namespace, empty: the model's name): it
// must resolve to the model's own namespace or one under it, so that no model reaches "/", a
// global parameter (/rosdistro, /use_sim_time, the start-up robot_description) or another model's
// namespace; and the master must not hold a value there that setting the URDF would replace.
// Talks to the master: call it without the simulator mutex.
std::string SimulationNode::ModelNamespace(const std::string& model_name,
                                           const std::string& robot_namespace) const {
  const std::string own = nh_.resolveName(model_name);
  std::string ns = own;
  if (!robot_namespace.empty()) {
    std::string why;
    Check(ros::names::validate(robot_namespace, why),
          "robot_namespace \"" + robot_namespace + "\": " + why);
    Check(robot_namespace.front() != '~',
          "robot_namespace \"" + robot_namespace + "\": a private name is not allowed");
    ns = nh_.resolveName(robot_namespace);
  }
  Check(ns == own || ns.rfind(own + "/", 0) == 0,
        "robot_namespace \"" + robot_namespace + "\" resolves to " + (ns.empty() ? "/" : ns) +
            ": must be the model's own namespace " + own + " or one under it (never /, a global "
            "parameter or another model's namespace)");
  const std::string description = ros::names::append(ns, "robot_description");
  Check(!nh_.hasParam(description),
        "the parameter " + description + " exists already (set by someone else: deleting the "
        "model would remove it); choose another robot_namespace");
  XmlRpc::XmlRpcValue value;
  for (std::string part = ns; part.size() > 1; part = part.substr(0, part.rfind('/'))) {
    if (!nh_.getParam(part, value)) continue;
    Check(value.getType() == XmlRpc::XmlRpcValue::TypeStruct,
          "the parameter " + part + " holds a value, not a namespace: setting " + description +
              " would replace it; choose another model_name or robot_namespace");
    break;  // a namespace: the ones above it are namespaces too
  }
  return description;
}

bool SimulationNode::OnSpawnUrdfModel(SpawnModel::Request& req, SpawnModel::Response& res) {
  // one spawn or delete at a time, held across its master calls; the simulator mutex only while
  // the world changes, so that the simulation steps and the other services answer meanwhile
  const std::lock_guard<std::mutex> world_lock(world_mutex_);
  std::vector<std::string> warnings;
  std::string description;
  UrdfScene urdf;
  // the checks that need neither the simulator nor its mutex: names, the size of the URDF, the
  // namespace (the master), the URDF parsed
  try {
    scene_io::CheckNameLength("model_name", req.model_name);
    Check(!req.model_name.empty() && GraphName(req.model_name) == req.model_name,
          "model_name \"" + req.model_name +
              "\": must be letters, digits and '_', not starting with a digit (it prefixes the "
              "model's TF frames and collision names)");
    Check(req.model_xml.size() <= parameters_.scene.max_bytes,
          "model_xml has " + std::to_string(req.model_xml.size()) +
              " bytes, more than the bound ~max_urdf_bytes = " +
              scene_io::DescribeBytes(parameters_.scene.max_bytes) + " (refused before parsing)");
    scene_io::CheckNameLength("robot_namespace", req.robot_namespace);
    description = ModelNamespace(req.model_name, req.robot_namespace);
    UrdfSceneOptions options = parameters_.scene;  // the node's ~gravity, ~mu, ~friction_set, ...
    options.ground = false;                        // the world has its ground already
    urdf = SceneFromUrdf(req.model_xml, options);  // one-line reasons, as at start-up
    Check(!urdf.scene.bodies.empty() || !urdf.scene.colliders.empty(),
          "model_xml has neither a free body nor a collision: nothing to spawn");
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string(e.what()) + "; nothing changed";
    return true;
  }
  WrenchTopics topics;
  std::string name;
  auto lock = LockForService();
  try {
    Check(ModelIndex(req.model_name) < 0,
          "model_name \"" + req.model_name + "\" exists already (~delete_model it first)");
    const Frame reference =
        BodyFrame(*sim_, ReferenceBody(req.reference_frame, "reference_frame"));
    const Eigen::Isometry3d placement = Placement(reference, req.initial_pose);
    Check(sim_->scene().bodies.size() + urdf.scene.bodies.size() <= kMaxWorldBodies,
          "the world would have " +
              std::to_string(sim_->scene().bodies.size() + urdf.scene.bodies.size()) +
              " bodies, more than " + std::to_string(kMaxWorldBodies) + " (the most it holds)");
    Check(sim_->scene().colliders.size() + urdf.scene.colliders.size() <= kMaxWorldCollisions,
          "the world would have " +
              std::to_string(sim_->scene().colliders.size() + urdf.scene.colliders.size()) +
              " collisions, more than " + std::to_string(kMaxWorldCollisions) +
              " (the bound on collisions per world)");
    const Scene model = PlacedModel(urdf.scene, req.model_name + "/", placement);
    {
      // frames and topics one-to-one over the whole world (two transforms per frame otherwise)
      Scene world = sim_->scene();
      AppendScene(model, &world);
      const std::string clash = FrameNameClash(world, parameters_.world_frame);
      Check(clash.empty(), "model " + req.model_name + ": " + clash);
    }

    const int first_collider = static_cast<int>(sim_->scene().colliders.size());
    const int first = sim_->AddBodies(model, model.initial_state);  // validates; or no change
    // committed: nothing below throws on input
    AppendScene(model, &configured_scene_);
    Model added;
    added.name = req.model_name;
    added.prefix = req.model_name + "/";
    for (std::size_t b = 0; b < model.bodies.size(); ++b) {
      added.bodies.push_back(first + static_cast<int>(b));
    }
    for (int c = first_collider; c < static_cast<int>(sim_->scene().colliders.size()); ++c) {
      added.colliders.push_back(c);
    }
    added.description = description;
    models_.push_back(added);
    warnings = urdf.warnings;
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string(e.what()) + "; nothing changed";
    return true;
  }
  const Model& added = models_.back();
  name = added.name;
  topics = WorldChanged();
  res.success = true;
  res.status_message = "spawned " + added.name + " (" + std::to_string(added.bodies.size()) +
                       " bodies, " + std::to_string(added.colliders.size()) +
                       " collisions) at t = " + std::to_string(sim_->time()) +
                       " s; its URDF is " + added.description;
  lock.unlock();
  // the master, without the simulator mutex: the simulation steps on and the other services
  // answer while it is slow or stopped
  nh_.setParam(description, req.model_xml);
  AdvertiseWrenches(&topics);
  for (const std::string& warning : warnings) {
    ROS_WARN_STREAM("nonsmooth_sim: spawn " << name << ": " << warning);
  }
  return true;
}

bool SimulationNode::OnDeleteModel(DeleteModel::Request& req, DeleteModel::Response& res) {
  const std::lock_guard<std::mutex> world_lock(world_mutex_);  // as in OnSpawnUrdfModel
  WrenchTopics topics;
  std::string description;
  auto lock = LockForService();
  const int m = ModelIndex(req.model_name);
  if (m < 0) {
    res.success = false;
    res.status_message = UnknownModel(req.model_name) + "; nothing changed";
    return true;
  }
  const Model removed = models_[static_cast<std::size_t>(m)];
  const Scene& scene = sim_->scene();
  std::vector<char> remove_body(scene.bodies.size(), 0);
  std::vector<char> remove_collider(scene.colliders.size(), 0);
  std::vector<int> statics;
  for (int b : removed.bodies) remove_body[static_cast<std::size_t>(b)] = 1;
  for (int c : removed.colliders) {
    remove_collider[static_cast<std::size_t>(c)] = 1;
    if (scene.colliders[static_cast<std::size_t>(c)].body == kWorld) statics.push_back(c);
  }
  try {
    sim_->RemoveBodies(removed.bodies, statics);
  } catch (const std::exception& e) {  // the models hold valid indices: not expected
    res.success = false;
    res.status_message = std::string(e.what()) + "; nothing changed";
    return true;
  }
  // the same removal on the configured start: the same old → new maps
  std::vector<int> body_map;
  std::vector<int> collider_map;
  RemoveFromScene(remove_body, remove_collider, &configured_scene_, &body_map, &collider_map);
  models_.erase(models_.begin() + m);
  for (Model& model : models_) {
    for (int& b : model.bodies) b = body_map[static_cast<std::size_t>(b)];
    for (int& c : model.colliders) c = collider_map[static_cast<std::size_t>(c)];
  }
  std::vector<ExternalWrench> kept;
  for (ExternalWrench w : wrenches_) {
    w.body = body_map[static_cast<std::size_t>(w.body)];
    if (w.body >= 0) kept.push_back(w);
  }
  wrenches_.swap(kept);
  description = removed.description;
  topics = WorldChanged();
  res.success = true;
  res.status_message = "deleted " + removed.name + " (" + std::to_string(removed.bodies.size()) +
                       " bodies, " + std::to_string(removed.colliders.size()) +
                       " collisions) at t = " + std::to_string(sim_->time()) + " s";
  lock.unlock();
  // the master, without the simulator mutex (as in OnSpawnUrdfModel)
  if (!description.empty()) nh_.deleteParam(description);
  AdvertiseWrenches(&topics);  // the removed topics unadvertised
  return true;
}

SimulationNode::WrenchTopics SimulationNode::WorldChanged() {
  // wrench topics: kept for the collisions that stay; a new one gets no publisher until
  // AdvertiseWrenches (outside the mutex) installs it; a removed one gets a zero wrench (rviz
  // clears its arrow) and is unadvertised when AdvertiseWrenches drops the last copy
  std::map<std::string, ros::Publisher> previous;
  for (std::size_t i = 0; i < wrench_pubs_.size(); ++i) {
    if (wrench_pubs_[i]) previous[wrench_pubs_[i].getTopic()] = wrench_pubs_[i];
  }
  const FrameNames old_frames = frames_;
  frames_ = MakeFrameNames(sim_->scene(), parameters_.world_frame);
  WrenchTopics topics;
  std::vector<ros::Publisher> publishers;
  for (std::size_t slot = 0; slot < frames_.slots.size(); ++slot) {
    const std::string topic = WrenchTopic(slot);
    const auto found = previous.find(private_nh_.resolveName(topic));
    if (found != previous.end()) {
      publishers.push_back(found->second);
      previous.erase(found);
    } else {
      publishers.emplace_back();
      topics.to_advertise.push_back(topic);
    }
  }
  for (std::size_t i = 0; i < wrench_pubs_.size(); ++i) {
    if (!wrench_pubs_[i] || previous.count(wrench_pubs_[i].getTopic()) == 0) continue;  // kept
    geometry_msgs::WrenchStamped zero;
    zero.header.stamp = StampOf(sim_->time());
    zero.header.frame_id = old_frames.contacts[i];
    wrench_pubs_[i].publish(zero);
    topics.retired.push_back(wrench_pubs_[i]);
  }
  wrench_pubs_.swap(publishers);
  wrench_closed_.assign(frames_.slots.size(), false);
  first_contact_.clear();
  // the contact arrows are numbered by contact: redrawn from the next message on
  markers_pub_.publish(DeleteAllMarkers(frames_.world));
  markers_count_ = 0;
  return topics;
}

std::string SimulationNode::WrenchTopic(std::size_t slot) const {
  return "wrench/" +
         GraphName(sim_->scene().colliders[static_cast<std::size_t>(frames_.slots[slot])].name);
}

void SimulationNode::AdvertiseWrenches(WrenchTopics* topics) {
  std::map<std::string, ros::Publisher> advertised;  // resolved topic → publisher
  for (const std::string& topic : topics->to_advertise) {
    advertised[private_nh_.resolveName(topic)] =
        private_nh_.advertise<geometry_msgs::WrenchStamped>(topic, parameters_.queue_size);
  }
  if (!advertised.empty()) {
    const auto lock = LockForService();
    for (std::size_t slot = 0; slot < wrench_pubs_.size(); ++slot) {
      if (wrench_pubs_[slot]) continue;
      const auto found = advertised.find(private_nh_.resolveName(WrenchTopic(slot)));
      if (found != advertised.end()) wrench_pubs_[slot] = found->second;
    }
  }
  topics->retired.clear();  // the last copies of the removed topics: unadvertised here
}

}  // namespace nonsmooth_sim::node
