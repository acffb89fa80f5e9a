// Checks and frames shared by the world services (world_services.cpp, model_services.cpp):
// request fields to Eigen with their bounds, and link frames with their velocities. Internal to
// the node.
#ifndef NONSMOOTH_SIM_NODE_WORLD_FRAMES_H_
#define NONSMOOTH_SIM_NODE_WORLD_FRAMES_H_

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/Vector3.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim::node {

inline Eigen::Vector3d ToEigen(const geometry_msgs::Point& p) { return {p.x, p.y, p.z}; }
inline Eigen::Vector3d ToEigen(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }

inline void Check(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

inline Eigen::Vector3d FiniteVector(const char* field, const Eigen::Vector3d& v, double bound) {
  Check(v.allFinite(), std::string(field) + ": must be finite");
  Check(v.norm() <= bound, std::string(field) + ": |" + field + "| = " + std::to_string(v.norm()) +
                               " is above " + std::to_string(bound));
  return v;
}

// A pose's quaternion, normalised; a zero or non-finite one is an error.
inline Eigen::Quaterniond Orientation(const char* field, const geometry_msgs::Quaternion& q) {
  const Eigen::Quaterniond p(q.w, q.x, q.y, q.z);
  Check(p.coeffs().allFinite(), std::string(field) + ": must be finite");
  const double norm = p.norm();
  Check(norm > 1e-6 && std::isfinite(norm),
        std::string(field) + ": |q| = " + std::to_string(norm) +
            " cannot be normalised (x y z w all about 0, or too large)");
  return p.normalized();
}

// A rigid transform (rotation, translation).
struct Frame {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   // of the origin, world
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // world
};

// The link frame of a body in the world, with its velocity.
inline Frame LinkFrame(const RigidBody& body, const BodyState& s) {
  Frame f;
  f.rotation = s.orientation;
  f.origin = s.position - s.orientation * body.com_in_link;
  f.angular_velocity = s.orientation * s.angular_velocity;
  f.linear_velocity = s.linear_velocity + f.angular_velocity.cross(f.origin - s.position);
  return f;
}

// The link frame of body `body` of `sim`, or the world frame for -1.
inline Frame BodyFrame(const Simulator& sim, int body) {
  if (body < 0) return Frame();
  return LinkFrame(sim.scene().bodies[static_cast<std::size_t>(body)],
                   sim.state()[static_cast<std::size_t>(body)]);
}

}  // namespace nonsmooth_sim::node

#endif  // NONSMOOTH_SIM_NODE_WORLD_FRAMES_H_
