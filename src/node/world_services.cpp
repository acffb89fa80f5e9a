// The node's Gazebo-style world services (docs/ros.md, "World services"): the models in the world,
// their state, and external wrenches. Request and response fields are those of gazebo_msgs
// (ROS 1); every request is validated first and changes nothing on bad input.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "nonsmooth_sim/node/simulation_node.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "world_frames.h"

namespace nonsmooth_sim::node {

// ---------------------------------------------------------------------------------------------
// names

int SimulationNode::ModelIndex(const std::string& name) const {
  for (int m = 0; m < static_cast<int>(models_.size()); ++m) {
    if (models_[m].name == name) return m;
  }
  return -1;
}

std::string SimulationNode::UnknownModel(const std::string& name) const {
  std::string names;
  for (const Model& m : models_) names += (names.empty() ? "" : ", ") + m.name;
  return "no model \"" + name + "\"; the models are: " + names;
}

int SimulationNode::ScopedBodyIndex(const std::string& name) const {
  // "<model>::<link>", or the body's own name ("<link>" of the start-up model, "<model>/<link>" of
  // a spawned one)
  const std::size_t scope = name.find("::");
  if (scope == std::string::npos) return BodyIndex(name);
  const int m = ModelIndex(name.substr(0, scope));
  if (m < 0) return -1;
  const Model& model = models_[static_cast<std::size_t>(m)];
  const std::string body_name = model.prefix + name.substr(scope + 2);
  for (int body : model.bodies) {
    if (sim_->scene().bodies[static_cast<std::size_t>(body)].name == body_name) return body;
  }
  return -1;
}

std::string SimulationNode::ScopedBodyName(int body) const {
  const std::string& name = sim_->scene().bodies[static_cast<std::size_t>(body)].name;
  for (const Model& m : models_) {
    for (int b : m.bodies) {
      if (b == body) return m.name + "::" + name.substr(m.prefix.size());
    }
  }
  return name;
}

int SimulationNode::ReferenceBody(const std::string& name, const char* field) const {
  if (name.empty() || name == "world") return -1;
  const int body = ScopedBodyIndex(name);
  if (body < 0) {
    throw std::invalid_argument(std::string(field) + " \"" + name +
                                "\" is neither \"world\" nor a body (\"<model>::<link>\" or "
                                "\"<link>\")");
  }
  return body;
}

void SimulationNode::BuildModels() {
  // the URDF of robot_description (or ~urdf_file) is one model, named by ~model_name, else by its
  // <robot name>; its links that are free bodies are its bodies, all its collisions its geoms
  Model model;
  model.name = !parameters_.model_name.empty() ? parameters_.model_name : urdf_.robot_name;
  if (model.name.empty()) model.name = "model";
  const Scene& scene = sim_->scene();
  for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) model.bodies.push_back(b);
  for (int c = 0; c < static_cast<int>(scene.colliders.size()); ++c) {
    if (scene.colliders[static_cast<std::size_t>(c)].name != "ground" ||
        scene.colliders[static_cast<std::size_t>(c)].body != kWorld) {
      model.colliders.push_back(c);
    }
  }
  models_ = {model};
}

// ---------------------------------------------------------------------------------------------
// services

bool SimulationNode::OnGetWorldProperties(GetWorldProperties::Request&,
                                          GetWorldProperties::Response& res) {
  const auto lock = LockForService();
  res.sim_time = sim_->time();
  for (const Model& m : models_) res.model_names.push_back(m.name);
  res.rendering_enabled = false;
  res.success = true;
  res.status_message = paused_ ? "paused" : "running";
  return true;
}

bool SimulationNode::OnGetModelProperties(GetModelProperties::Request& req,
                                          GetModelProperties::Response& res) {
  const auto lock = LockForService();
  const int m = ModelIndex(req.model_name);
  if (m < 0) {
    res.success = false;
    res.status_message = UnknownModel(req.model_name);
    return true;
  }
  const Model& model = models_[static_cast<std::size_t>(m)];
  const Scene& scene = sim_->scene();
  for (int b : model.bodies) res.body_names.push_back(ScopedBodyName(b));
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
  res.header.stamp = StampOf(sim_->time());
  res.header.frame_id = req.relative_entity_name.empty() ? frames_.world : req.relative_entity_name;
  const int m = ModelIndex(req.model_name);
  if (m < 0) {
    res.success = false;
    res.status_message = UnknownModel(req.model_name);
    return true;
  }
  const Model& model = models_[static_cast<std::size_t>(m)];
  if (model.bodies.empty()) {
    res.success = false;
    res.status_message = "model \"" + model.name + "\" has no free body";
    return true;
  }
  Frame reference;  // the world
  try {
    reference = BodyFrame(*sim_, ReferenceBody(req.relative_entity_name, "relative_entity_name"));
  } catch (const std::invalid_argument& e) {
    res.success = false;
    res.status_message = e.what();
    return true;
  }
  const int b = model.bodies.front();
  const Frame f = LinkFrame(sim_->scene().bodies[static_cast<std::size_t>(b)],
                            sim_->state()[static_cast<std::size_t>(b)]);
  // in the reference frame: its pose; velocities as differences, in its axes (as Gazebo)
  const Eigen::Quaterniond inverse = reference.rotation.conjugate();
  const Eigen::Vector3d position = inverse * (f.origin - reference.origin);
  const Eigen::Quaterniond orientation = inverse * f.rotation;
  const Eigen::Vector3d linear = inverse * (f.linear_velocity - reference.linear_velocity);
  const Eigen::Vector3d angular = inverse * (f.angular_velocity - reference.angular_velocity);
  res.pose.position.x = position.x();
  res.pose.position.y = position.y();
  res.pose.position.z = position.z();
  res.pose.orientation.x = orientation.x();
  res.pose.orientation.y = orientation.y();
  res.pose.orientation.z = orientation.z();
  res.pose.orientation.w = orientation.w();
  res.twist.linear.x = linear.x();
  res.twist.linear.y = linear.y();
  res.twist.linear.z = linear.z();
  res.twist.angular.x = angular.x();
  res.twist.angular.y = angular.y();
  res.twist.angular.z = angular.z();
  res.success = true;
  res.status_message = "pose and twist of " + ScopedBodyName(b);
  return true;
}

bool SimulationNode::OnSetModelState(SetModelState::Request& req, SetModelState::Response& res) {
  const auto lock = LockForService();
  const ModelState& request = req.model_state;
  try {
    const int m = ModelIndex(request.model_name);
    Check(m >= 0, UnknownModel(request.model_name));
    const Model& model = models_[static_cast<std::size_t>(m)];
    Check(!model.bodies.empty(), "model \"" + model.name + "\" has no free body");
    const Frame reference =
        BodyFrame(*sim_, ReferenceBody(request.reference_frame, "reference_frame"));
    // the requested link frame of the canonical body, in the world
    const Eigen::Vector3d position = FiniteVector(
        "pose.position", ToEigen(request.pose.position), scene_io::kMaxInitialCoordinate);
    const Eigen::Quaterniond orientation = Orientation("pose.orientation", request.pose.orientation);
    const Eigen::Vector3d linear = FiniteVector("twist.linear", ToEigen(request.twist.linear),
                                                scene_io::kMaxInitialSpeed);
    const Eigen::Vector3d angular = FiniteVector("twist.angular", ToEigen(request.twist.angular),
                                                 scene_io::kMaxInitialAngularSpeed);
    Frame target;
    target.rotation = (reference.rotation * orientation).normalized();
    target.origin = reference.origin + reference.rotation * position;
    target.linear_velocity = reference.linear_velocity + reference.rotation * linear;
    target.angular_velocity = reference.angular_velocity + reference.rotation * angular;

    // every body of the model moves rigidly with the canonical body's link frame
    const int canonical = model.bodies.front();
    const Frame now = LinkFrame(sim_->scene().bodies[static_cast<std::size_t>(canonical)],
                                sim_->state()[static_cast<std::size_t>(canonical)]);
    const Eigen::Quaterniond turn = target.rotation * now.rotation.conjugate();
    std::vector<BodyState> states;
    for (int b : model.bodies) {
      BodyState s = sim_->state()[static_cast<std::size_t>(b)];
      s.position = target.origin + turn * (s.position - now.origin);
      s.orientation = (turn * s.orientation).normalized();
      s.linear_velocity =
          target.linear_velocity + target.angular_velocity.cross(s.position - target.origin);
      s.angular_velocity = s.orientation.conjugate() * target.angular_velocity;
      Check(s.position.lpNorm<Eigen::Infinity>() <= scene_io::kMaxInitialCoordinate &&
                s.linear_velocity.norm() <= scene_io::kMaxInitialSpeed,
            "body " + ScopedBodyName(b) + " would leave the allowed range (|x| <= " +
                std::to_string(scene_io::kMaxInitialCoordinate) + " m, |v| <= " +
                std::to_string(scene_io::kMaxInitialSpeed) + " m/s)");
      states.push_back(s);
    }
    // validates, throws and changes nothing on bad input; the other models keep their contacts
    sim_->SetBodyStates(model.bodies, states);
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string(e.what()) + "; nothing changed";
    return true;
  }
  AfterReset();
  res.success = true;
  res.status_message = "set " + request.model_name + " at t = " + std::to_string(sim_->time()) +
                       " s (warm starts of its contacts dropped)";
  return true;
}

bool SimulationNode::OnApplyBodyWrench(ApplyBodyWrench::Request& req,
                                       ApplyBodyWrench::Response& res) {
  const auto lock = LockForService();
  try {
    const int b = ScopedBodyIndex(req.body_name);
    Check(b >= 0, "body_name \"" + req.body_name +
                      "\" is not a body (\"<model>::<link>\" or \"<link>\" of a free link)");
    const Frame reference =
        BodyFrame(*sim_, ReferenceBody(req.reference_frame, "reference_frame"));
    const Eigen::Vector3d force = FiniteVector("wrench.force", ToEigen(req.wrench.force),
                                               kMaxExternalForce);
    const Eigen::Vector3d torque = FiniteVector("wrench.torque", ToEigen(req.wrench.torque),
                                                kMaxExternalForce);
    const Eigen::Vector3d point = FiniteVector("reference_point", ToEigen(req.reference_point),
                                               scene_io::kMaxInitialCoordinate);
    Check(std::isfinite(req.start_time.toSec()) && std::isfinite(req.duration.toSec()),
          "start_time, duration: must be finite");
    ExternalWrench w;
    w.body = b;
    w.force = reference.rotation * force;
    w.torque = reference.rotation * torque;
    // the point of application is fixed in the body (it turns with it)
    const BodyState& s = sim_->state()[static_cast<std::size_t>(b)];
    w.point_in_body =
        s.orientation.conjugate() * (reference.origin + reference.rotation * point - s.position);
    w.start = std::max(req.start_time.toSec(), sim_->time());
    w.end = req.duration.toSec() < 0.0 ? std::numeric_limits<double>::infinity()
                                       : w.start + req.duration.toSec();
    Check(wrenches_.size() < kMaxWrenches,
          "already " + std::to_string(kMaxWrenches) +
              " wrenches active (the most at once): clear some with ~clear_body_wrenches");
    if (req.duration.toSec() == 0.0) {
      res.success = true;
      res.status_message = "duration 0: nothing to apply";
      return true;
    }
    wrenches_.push_back(w);
    wrenches_active_ = true;
  } catch (const std::exception& e) {
    res.success = false;
    res.status_message = std::string(e.what()) + "; nothing changed";
    return true;
  }
  res.success = true;
  res.status_message = "applied to " + ScopedBodyName(wrenches_.back().body) + " from t = " +
                       std::to_string(wrenches_.back().start) + " s";
  return true;
}

bool SimulationNode::OnClearBodyWrenches(BodyRequest::Request& req, BodyRequest::Response&) {
  const auto lock = LockForService();
  const int b = ScopedBodyIndex(req.body_name);
  if (b < 0) {
    ROS_WARN_STREAM("nonsmooth_sim: ~clear_body_wrenches: \"" << req.body_name
                    << "\" is not a body; nothing cleared");
    return true;  // BodyRequest has no response fields: the warning is the answer
  }
  std::vector<ExternalWrench> kept;
  for (const ExternalWrench& w : wrenches_) {
    if (w.body != b) kept.push_back(w);
  }
  wrenches_.swap(kept);
  sim_->SetExternalWrench(b, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  return true;
}

// ---------------------------------------------------------------------------------------------
// the wrenches of the next step (integrator, mutex held)

void SimulationNode::ApplyWrenches(double interval) {
  // each wrench weighted by the part of [t, t + Δt] it covers (Δt: the step, or with ~accuracy the
  // ticks StepOnce advances): the impulse over it is exactly the wrench integrated over the
  // requested interval
  const double t = sim_->time();
  const double dt = interval;
  const std::size_t bodies = sim_->scene().bodies.size();
  wrench_force_.assign(bodies, Eigen::Vector3d::Zero());
  wrench_torque_.assign(bodies, Eigen::Vector3d::Zero());
  std::size_t kept = 0;
  for (const ExternalWrench& w : wrenches_) {
    const double overlap = std::min(t + dt, w.end) - std::max(t, w.start);
    if (overlap > 0.0) {
      const double fraction = std::min(1.0, overlap / dt);
      const BodyState& s = sim_->state()[static_cast<std::size_t>(w.body)];
      const Eigen::Vector3d arm = s.orientation * w.point_in_body;
      wrench_force_[static_cast<std::size_t>(w.body)] += fraction * w.force;
      wrench_torque_[static_cast<std::size_t>(w.body)] +=
          fraction * (w.torque + arm.cross(w.force));
    }
    if (w.end > t + dt) wrenches_[kept++] = w;  // still to come
  }
  wrenches_.resize(kept);
  bool any = false;  // a non-zero wrench in this step: the next one must look again (to clear it)
  for (std::size_t b = 0; b < bodies; ++b) {
    const auto current = sim_->ExternalWrench(static_cast<int>(b));
    if (current.first != wrench_force_[b] || current.second != wrench_torque_[b]) {
      sim_->SetExternalWrench(static_cast<int>(b), wrench_force_[b], wrench_torque_[b]);
    }
    any = any || !wrench_force_[b].isZero(0.0) || !wrench_torque_[b].isZero(0.0);
  }
  wrenches_active_ = any || !wrenches_.empty();
}

}  // namespace nonsmooth_sim::node
