// The node's Gazebo-style world services (docs/ros.md, "World services"): the models in the world,
// their state, and external wrenches. Request and response fields are those of gazebo_msgs
// (ROS 1); each handler converts the request into a world::World call (which validates it and
// changes nothing on bad input) and its result or its one-line refusal into the response.
#include <ros/console.h>

#include <stdexcept>
#include <string>

#include "nonsmooth_sim/node/simulation_node.h"
#include "request_fields.h"

namespace nonsmooth_sim::node {

bool SimulationNode::OnGetWorldProperties(GetWorldProperties::Request&,
                                          GetWorldProperties::Response& res) {
  const auto lock = LockForService();
  res.sim_time = world_->sim().time();
  for (const world::Model& m : world_->models().models()) res.model_names.push_back(m.name);
  res.rendering_enabled = false;
  res.success = true;
  res.status_message = paused_ ? "paused" : "running";
  return true;
}

bool SimulationNode::OnGetModelProperties(GetModelProperties::Request& req,
                                          GetModelProperties::Response& res) {
  const auto lock = LockForService();
  const world::ModelRegistry& models = world_->models();
  const int m = models.Find(req.model_name);
  if (m < 0) {
    res.success = false;
    res.status_message = models.Unknown(req.model_name);
    return true;
  }
  const world::Model& model = models.at(m);
  const Scene& scene = world_->sim().scene();
  for (int b : model.bodies) res.body_names.push_back(world_->BodyName(b));
  if (!res.body_names.empty()) res.canonical_body_name = res.body_names.front();
  std::string sets;
  for (int c : model.colliders) {
    const Collider& collider = scene.colliders[static_cast<std::size_t>(c)];
    const std::string name = collider.name.substr(model.prefix.size());
    res.geom_names.push_back(name);
    sets += (sets.empty() ? "" : ", ") + name + ": " +
            std::string(FrictionSetName(collider.law.friction_set));
  }
  res.is_static = model.bodies.empty();
  res.success = true;
  res.status_message = sets;
  return true;
}

bool SimulationNode::OnGetModelState(GetModelState::Request& req, GetModelState::Response& res) {
  const auto lock = LockForService();
  res.header.stamp = StampOf(world_->sim().time());
  res.header.frame_id = req.relative_entity_name.empty() ? frames_.world : req.relative_entity_name;
  world::World::ModelFrame f;
  try {
    f = world_->GetModelState(req.model_name, req.relative_entity_name);
  } catch (const std::invalid_argument& e) {
    res.success = false;
    res.status_message = e.what();
    return true;
  }
  res.pose = ToMsg(f.pose);
  res.twist = ToMsg(f.twist);
  res.success = true;
  res.status_message = "pose and twist of " + world_->BodyName(f.body);
  return true;
}

bool SimulationNode::OnSetModelState(SetModelState::Request& req, SetModelState::Response& res) {
  const auto lock = LockForService();
  const ModelState& request = req.model_state;
  try {
    world_->SetModelState(request.model_name, request.reference_frame, ToWorld(request.pose),
                          ToWorld(request.twist));
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string(e.what()) + "; nothing changed";
    return true;
  }
  AfterReset();
  res.success = true;
  res.status_message = "set " + request.model_name + " at t = " +
                       std::to_string(world_->sim().time()) +
                       " s (warm starts of its contacts dropped)";
  return true;
}

bool SimulationNode::OnApplyBodyWrench(ApplyBodyWrench::Request& req,
                                       ApplyBodyWrench::Response& res) {
  const auto lock = LockForService();
  world::WrenchRequest request;
  request.body = req.body_name;
  request.reference_frame = req.reference_frame;
  request.force = ToEigen(req.wrench.force);
  request.torque = ToEigen(req.wrench.torque);
  request.point = ToEigen(req.reference_point);
  request.start = req.start_time.toSec();
  request.duration = req.duration.toSec();
  std::optional<world::ExternalWrench> applied;
  try {
    applied = world_->ApplyWrench(request);
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string(e.what()) + "; nothing changed";
    return true;
  }
  res.success = true;
  res.status_message = applied ? "applied to " + world_->BodyName(applied->body) +
                                     " from t = " + std::to_string(applied->start) + " s"
                               : std::string("duration 0: nothing to apply");
  return true;
}

bool SimulationNode::OnClearBodyWrenches(BodyRequest::Request& req, BodyRequest::Response&) {
  const auto lock = LockForService();
  if (!world_->ClearWrenches(req.body_name)) {
    ROS_WARN_STREAM("nonsmooth_sim: ~clear_body_wrenches: \"" << req.body_name
                    << "\" is not a body; nothing cleared");
  }
  return true;  // BodyRequest has no response fields: the warning is the answer
}

}  // namespace nonsmooth_sim::node
