// Where bodies go: link frames with their velocities, a pose relative to a reference frame, a
// model placed in the world, a model moved rigidly to a new pose and twist, and a body lowered
// (or raised) until it touches the ground z = 0.
#ifndef NONSMOOTH_SIM_WORLD_PLACEMENT_H_
#define NONSMOOTH_SIM_WORLD_PLACEMENT_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/scene.h"
#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim::world {

/// A rigid frame (rotation, origin) with the velocity of its origin.
struct Frame {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   ///< of the origin, world [m/s]
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  ///< world [rad/s]
};

/// A pose or twist given in a frame (position [m], orientation link axes → frame axes).
struct Pose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};
struct Twist {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   ///< [m/s]
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  ///< [rad/s]
};

/// The link frame of a body in the world, with its velocity.
Frame LinkFrame(const RigidBody& body, const BodyState& s);

/// The link frame of body `body` of `sim`, or the world frame for -1.
Frame BodyFrame(const Simulator& sim, int body);

/// The model frame in the world from `pose` relative to `reference` (checked: position within
/// kMaxInitialCoordinate, orientation normalisable; fields named "<field>.position", ...).
Eigen::Isometry3d PlaceInWorld(const Frame& reference, const Pose& pose, const std::string& field);

/// A URDF's scene placed at `placement`, its body and collision names prefixed with `prefix`.
/// Throws std::invalid_argument if a body would start outside |x|, |y|, |z| ≤ kMaxInitialCoordinate.
Scene PlacedModel(Scene scene, const std::string& prefix, const Eigen::Isometry3d& placement);

/// The states of `bodies` of `sim` moved rigidly so that the link frame of the first one has
/// `pose` and `twist` relative to `reference` (a rigid motion of all of them). Throws
/// std::invalid_argument for a value out of its bounds, naming `names[i]` for a body that would
/// leave the allowed range.
std::vector<BodyState> RigidlyMoved(const Simulator& sim, const std::vector<int>& bodies,
                                    const std::vector<std::string>& names, const Frame& reference,
                                    const Pose& pose, const Twist& twist);

/// Height of r_S at which the lowest collider of `body` just touches z = 0 in orientation `q`
/// (its gap against the ground plane by the scene's collision table); `fallback` for a body
/// without colliders the table can put on a plane.
double TouchingHeight(const Scene& scene, int body, const Eigen::Quaterniond& q, double fallback);

}  // namespace nonsmooth_sim::world

#endif  // NONSMOOTH_SIM_WORLD_PLACEMENT_H_
