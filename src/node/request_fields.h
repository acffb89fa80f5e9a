// Request fields → the world's types (world/placement.h): the node's side of the world services
// (world_services.cpp, model_services.cpp). The checks and bounds are the world's. Internal to
// the node.
#ifndef NONSMOOTH_SIM_NODE_REQUEST_FIELDS_H_
#define NONSMOOTH_SIM_NODE_REQUEST_FIELDS_H_

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/Twist.h>
#include <geometry_msgs/Vector3.h>

#include <Eigen/Geometry>

#include "nonsmooth_sim/world/checks.h"
#include "nonsmooth_sim/world/placement.h"

namespace nonsmooth_sim::node {

using world::Check;

inline Eigen::Vector3d ToEigen(const geometry_msgs::Point& p) { return {p.x, p.y, p.z}; }
inline Eigen::Vector3d ToEigen(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }
/// As given (not normalised: the world checks and normalises it).
inline Eigen::Quaterniond ToEigen(const geometry_msgs::Quaternion& q) {
  return Eigen::Quaterniond(q.w, q.x, q.y, q.z);
}
inline world::Pose ToWorld(const geometry_msgs::Pose& pose) {
  return world::Pose{ToEigen(pose.position), ToEigen(pose.orientation)};
}
inline world::Twist ToWorld(const geometry_msgs::Twist& twist) {
  return world::Twist{ToEigen(twist.linear), ToEigen(twist.angular)};
}

}  // namespace nonsmooth_sim::node

#endif  // NONSMOOTH_SIM_NODE_REQUEST_FIELDS_H_
