// Where bodies go. See placement.h.
#include "nonsmooth_sim/world/placement.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "nonsmooth_sim/core/collision/collision_table.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/world/checks.h"

namespace nonsmooth_sim::world {

Frame LinkFrame(const RigidBody& body, const BodyState& s) {
  Frame f;
  f.rotation = s.orientation;
  f.origin = s.position - s.orientation * body.com_in_link;
  f.angular_velocity = s.orientation * s.angular_velocity;
  f.linear_velocity = s.linear_velocity + f.angular_velocity.cross(f.origin - s.position);
  return f;
}

Frame BodyFrame(const Simulator& sim, int body) {
  if (body < 0) return Frame();
  return LinkFrame(sim.scene().bodies[static_cast<std::size_t>(body)],
                   sim.state()[static_cast<std::size_t>(body)]);
}

Eigen::Isometry3d PlaceInWorld(const Frame& reference, const Pose& pose, const std::string& field) {
  const Eigen::Vector3d position = FiniteVector((field + ".position").c_str(), pose.position,
                                                scene_io::kMaxInitialCoordinate);
  const Eigen::Quaterniond orientation = Orientation((field + ".orientation").c_str(),
                                                     pose.orientation);
  Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();
  placement.linear() = (reference.rotation * orientation).normalized().toRotationMatrix();
  placement.translation() = reference.origin + reference.rotation * position;
  return placement;
}

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

std::vector<BodyState> RigidlyMoved(const Simulator& sim, const std::vector<int>& bodies,
                                    const std::vector<std::string>& names, const Frame& reference,
                                    const Pose& pose, const Twist& twist) {
  // the requested link frame of the canonical body, in the world
  const Eigen::Vector3d position =
      FiniteVector("pose.position", pose.position, scene_io::kMaxInitialCoordinate);
  const Eigen::Quaterniond orientation = Orientation("pose.orientation", pose.orientation);
  const Eigen::Vector3d linear =
      FiniteVector("twist.linear", twist.linear, scene_io::kMaxInitialSpeed);
  const Eigen::Vector3d angular =
      FiniteVector("twist.angular", twist.angular, scene_io::kMaxInitialAngularSpeed);
  Frame target;
  target.rotation = (reference.rotation * orientation).normalized();
  target.origin = reference.origin + reference.rotation * position;
  target.linear_velocity = reference.linear_velocity + reference.rotation * linear;
  target.angular_velocity = reference.angular_velocity + reference.rotation * angular;

  // every body moves rigidly with the canonical body's link frame
  const int canonical = bodies.front();
  const Frame now = LinkFrame(sim.scene().bodies[static_cast<std::size_t>(canonical)],
                              sim.state()[static_cast<std::size_t>(canonical)]);
  const Eigen::Quaterniond turn = target.rotation * now.rotation.conjugate();
  std::vector<BodyState> states;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    BodyState s = sim.state()[static_cast<std::size_t>(bodies[i])];
    s.position = target.origin + turn * (s.position - now.origin);
    s.orientation = (turn * s.orientation).normalized();
    s.linear_velocity =
        target.linear_velocity + target.angular_velocity.cross(s.position - target.origin);
    s.angular_velocity = s.orientation.conjugate() * target.angular_velocity;
    Check(s.position.lpNorm<Eigen::Infinity>() <= scene_io::kMaxInitialCoordinate &&
              s.linear_velocity.norm() <= scene_io::kMaxInitialSpeed,
          "body " + names[i] + " would leave the allowed range (|x| <= " +
              std::to_string(scene_io::kMaxInitialCoordinate) + " m, |v| <= " +
              std::to_string(scene_io::kMaxInitialSpeed) + " m/s)");
    states.push_back(s);
  }
  return states;
}

double TouchingHeight(const Scene& scene, int body, const Eigen::Quaterniond& q, double fallback) {
  const Shape ground = Shape::Plane();
  Eigen::Isometry3d body_pose = Eigen::Isometry3d::Identity();
  body_pose.linear() = q.normalized().toRotationMatrix();  // r_S at the origin
  double height = -std::numeric_limits<double>::infinity();
  for (const Collider& c : scene.colliders) {
    if (c.body != body) continue;
    ContactGeometry points[kMaxPairContacts];
    const int count = scene.collision_table.Collide(
        ground, Eigen::Isometry3d::Identity(), c.shape, body_pose * c.pose,
        std::numeric_limits<double>::infinity(), points);
    // gap = height of the lowest point with r_S at z = 0: r_S must be raised by -gap
    for (int k = 0; k < count; ++k) height = std::max(height, -points[k].gap);
  }
  return std::isfinite(height) ? height : fallback;
}

}  // namespace nonsmooth_sim::world
