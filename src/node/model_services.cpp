// ~spawn_urdf_model and ~delete_model (docs/ros.md, "World services"): models added to and removed
// from the running world between two steps. The world does the work and keeps the rules
// (world::World::Spawn, Delete: the names, the bounds, the placement, the configured start, the
// wrenches; the rest of the world keeps its state and contact memory); the node keeps the master
// (the URDF's parameter), the contact frames and wrench topics and the markers in step.
//
// Names: world/model_registry.h (rviz's RobotModel with TF prefix <model> on the
// robot_description set under the model's namespace shows a spawned model).
//
// Locks: the world changes under the simulator mutex; the master calls (the namespace checks,
// setting or deleting the robot_description, advertising ~wrench/ topics) are made without it, on
// master_calls_ (in order, on their own thread), waited for at most kMasterTimeout under
// world_mutex_, which serialises spawns and deletes. A master that does not answer in time: the
// namespace check refuses the spawn (nothing changed); after the world changed, the reply says
// that the parameter and topics follow when the master answers. A slot of a spawned collision
// publishes from when its topic is advertised. A deleted collision's topic is not unadvertised
// but kept for the next collision of that name (simulation_node.h, kept_wrench_pubs_): roscpp
// unregisters a topic with the master while holding the lock every publish takes.
#include <ros/master.h>
#include <ros/names.h>
#include <ros/this_node.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "nonsmooth_sim/node/simulation_node.h"
#include "nonsmooth_sim/scene_io/bounded_input.h"
#include "request_fields.h"

namespace nonsmooth_sim::node {
namespace {

std::string InSeconds(std::chrono::milliseconds duration) {
  return std::to_string(duration.count() / 1000) + " s";
}

// A parameter call to the master, made until the master answers: roscpp's ros::param calls other
// than set give up at once on a failed connection (e.g. one the master dropped while stopped)
// and report it as a missing parameter. Called on master_calls_ only (it may wait for ever).
// Returns whether the master took the call (false: also "not set"); `value` its payload.
bool AskMaster(const char* method, const std::string& key, XmlRpc::XmlRpcValue* value) {
  XmlRpc::XmlRpcValue request, response;
  request[0] = ros::this_node::getName();
  request[1] = key;
  return ros::master::execute(method, request, response, *value, /*wait_for_master=*/true);
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
  XmlRpc::XmlRpcValue value;
  Check(AskMaster("hasParam", description, &value) && !static_cast<bool>(value),
        "the parameter " + description + " exists already (set by someone else: deleting the "
        "model would remove it); choose another robot_namespace");
  for (std::string part = ns; part.size() > 1; part = part.substr(0, part.rfind('/'))) {
    if (!AskMaster("getParam", part, &value)) continue;
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
    world::CheckModelName("model_name", req.model_name);
    Check(req.model_xml.size() <= parameters_.scene.max_bytes,
          "model_xml has " + std::to_string(req.model_xml.size()) +
              " bytes, more than the bound ~max_urdf_bytes = " +
              scene_io::DescribeBytes(parameters_.scene.max_bytes) + " (refused before parsing)");
    scene_io::CheckNameLength("robot_namespace", req.robot_namespace);
    auto checked = std::make_shared<std::string>();
    const bool answered = master_calls_.Run(
        [this, checked, model = req.model_name, ns = req.robot_namespace] {
          *checked = ModelNamespace(model, ns);
        },
        kMasterTimeout);
    Check(answered, "the master did not answer within " + InSeconds(kMasterTimeout) +
                        " (checking robot_namespace)");
    description = *checked;
    UrdfSceneOptions options = parameters_.scene;  // the node's ~gravity, ~mu, ~friction_set, ...
    options.ground = false;                        // the world has its ground already
    options.hold_joints.clear();                   // ~hold_joints names the start-up URDF's
    urdf = SceneFromUrdf(req.model_xml, options);  // one-line reasons, as at start-up
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string(e.what()) + "; nothing changed";
    return true;
  }
  WrenchTopics topics;
  std::string name;
  auto lock = LockForService();
  const world::Model* spawned = nullptr;
  try {
    spawned = &world_->Spawn(req.model_name, urdf.scene, req.reference_frame,
                             ToWorld(req.initial_pose), description);
    warnings = urdf.warnings;
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string(e.what()) + "; nothing changed";
    return true;
  }
  const world::Model& added = *spawned;
  name = added.name;
  topics = WorldChanged();
  // its links merged into its bodies (its static links are placed by the spawn: not in TF)
  fixed_links_[name] = FixedLinkTransforms(urdf, added.prefix, parameters_.world_frame,
                                           /*world_links=*/false, StampOf(world_->sim().time()));
  res.success = true;
  res.status_message = "spawned " + added.name + " (" + std::to_string(added.bodies.size()) +
                       " bodies, " + std::to_string(added.colliders.size()) +
                       " collisions) at t = " + std::to_string(world_->sim().time()) +
                       " s; its URDF is " + added.description;
  lock.unlock();
  PublishFixedLinks();
  // the master, without the simulator mutex: the simulation steps on and the other services
  // answer while it is slow or stopped
  const bool answered = master_calls_.Run(
      [this, description, xml = req.model_xml, topics = std::move(topics)]() mutable {
        nh_.setParam(description, xml);
        AdvertiseWrenches(&topics);
      },
      kMasterTimeout);
  if (!answered) {
    res.status_message += "; the master did not answer within " + InSeconds(kMasterTimeout) + ": " +
                          description + " and the ~wrench/ topics are set when it does";
  }
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
  world::Model removed;
  try {
    removed = world_->Delete(req.model_name);  // its wrenches with it
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string(e.what()) + "; nothing changed";
    return true;
  }
  description = removed.description;
  topics = WorldChanged();
  fixed_links_.erase(removed.name);
  res.success = true;
  res.status_message = "deleted " + removed.name + " (" + std::to_string(removed.bodies.size()) +
                       " bodies, " + std::to_string(removed.colliders.size()) +
                       " collisions) at t = " + std::to_string(world_->sim().time()) + " s";
  lock.unlock();
  PublishFixedLinks();
  // the master, without the simulator mutex (as in OnSpawnUrdfModel)
  const bool answered = master_calls_.Run(
      [this, description, topics = std::move(topics)]() mutable {
        XmlRpc::XmlRpcValue unused;
        if (!description.empty()) AskMaster("deleteParam", description, &unused);
        AdvertiseWrenches(&topics);  // the removed topics kept (beyond the bound: unadvertised)
      },
      kMasterTimeout);
  if (!answered) {
    res.status_message += "; the master did not answer within " + InSeconds(kMasterTimeout) +
                          (description.empty() ? std::string()
                                               : ": " + description + " is deleted when it does");
  }
  return true;
}

SimulationNode::WrenchTopics SimulationNode::WorldChanged() {
  // wrench topics: kept for the collisions that stay; a new one takes the kept publisher of its
  // topic or gets none until AdvertiseWrenches (outside the mutex) installs it; a removed one
  // gets a zero wrench (rviz clears its arrow) and is kept, beyond the bound the oldest dropped
  std::map<std::string, ros::Publisher> previous;
  for (std::size_t i = 0; i < wrench_pubs_.size(); ++i) {
    if (wrench_pubs_[i]) previous[wrench_pubs_[i].getTopic()] = wrench_pubs_[i];
  }
  const FrameNames old_frames = frames_;
  frames_ = MakeFrameNames(world_->sim().scene(), parameters_.world_frame);
  WrenchTopics topics;
  std::vector<ros::Publisher> publishers;
  for (std::size_t slot = 0; slot < frames_.slots.size(); ++slot) {
    const std::string topic = WrenchTopic(slot);
    const std::string resolved = private_nh_.resolveName(topic);
    const auto found = previous.find(resolved);
    const auto kept = kept_wrench_pubs_.find(resolved);
    if (found != previous.end()) {
      publishers.push_back(found->second);
      previous.erase(found);
    } else if (kept != kept_wrench_pubs_.end()) {
      publishers.push_back(kept->second);
      kept_wrench_pubs_.erase(kept);
      kept_wrench_order_.erase(
          std::find(kept_wrench_order_.begin(), kept_wrench_order_.end(), resolved));
    } else {
      publishers.emplace_back();
      topics.to_advertise.push_back(topic);
    }
  }
  for (std::size_t i = 0; i < wrench_pubs_.size(); ++i) {
    if (!wrench_pubs_[i] || previous.count(wrench_pubs_[i].getTopic()) == 0) continue;  // stays
    geometry_msgs::WrenchStamped zero;
    zero.header.stamp = StampOf(world_->sim().time());
    zero.header.frame_id = old_frames.contacts[i];
    wrench_pubs_[i].publish(zero);
    KeepWrenchPublisher(wrench_pubs_[i], &topics.dropped);
  }
  wrench_pubs_.swap(publishers);
  wrench_closed_.assign(frames_.slots.size(), false);
  first_contact_.clear();
  // the contact arrows are numbered by contact: redrawn from the next message on
  markers_pub_.publish(DeleteAllMarkers(frames_.world));
  markers_count_ = 0;
  return topics;
}

void SimulationNode::PublishFixedLinks() {
  tf2_msgs::TFMessage message;
  for (const auto& [model, transforms] : fixed_links_) {
    message.transforms.insert(message.transforms.end(), transforms.begin(), transforms.end());
  }
  tf_static_pub_.publish(message);
}

void SimulationNode::KeepWrenchPublisher(const ros::Publisher& publisher,
                                         std::vector<ros::Publisher>* dropped) {
  kept_wrench_pubs_[publisher.getTopic()] = publisher;
  kept_wrench_order_.push_back(publisher.getTopic());
  while (kept_wrench_order_.size() > kMaxKeptWrenchTopics) {
    const auto oldest = kept_wrench_pubs_.find(kept_wrench_order_.front());
    dropped->push_back(oldest->second);
    kept_wrench_pubs_.erase(oldest);
    kept_wrench_order_.pop_front();
  }
}

std::string SimulationNode::WrenchTopic(std::size_t slot) const {
  return "wrench/" + frames_.topics[slot];
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
      if (found == advertised.end()) continue;
      wrench_pubs_[slot] = found->second;
      advertised.erase(found);
    }
    // slots removed since (a delete after a spawn whose master calls were late): kept
    for (const auto& [topic, publisher] : advertised) {
      KeepWrenchPublisher(publisher, &topics->dropped);
    }
  }
  topics->dropped.clear();  // the last copies of the oldest kept topics: unadvertised here
}

}  // namespace nonsmooth_sim::node
