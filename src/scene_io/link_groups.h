// The links of a URDF grouped by what they become in the scene (urdf_scene.h, "Bodies and the
// static world"; docs/urdf.md, "Bodies, the world, and joints"): a group is one link and the links
// held rigidly to it, by `fixed` joints, by joints that cannot move (a `revolute` or
// `prismatic` joint with lower = upper) and by moving joints the user holds rigid (<nonsmooth_sim
// joint="j"><hold/>, UrdfSceneOptions::hold_joints), recursively. The loader's private part (urdf_scene.cpp
// turns the groups into bodies and world colliders); no physics here beyond the joint poses.
#ifndef NONSMOOTH_SIM_SCENE_IO_LINK_GROUPS_H_
#define NONSMOOTH_SIM_SCENE_IO_LINK_GROUPS_H_

#include <urdf_parser/urdf_parser.h>

#include <Eigen/Geometry>
#include <map>
#include <string>
#include <vector>

#include "nonsmooth_sim/scene_io/urdf_xml.h"

namespace nonsmooth_sim::scene_io {

Eigen::Vector3d ToEigen(const urdf::Vector3& v);
Eigen::Quaterniond ToEigen(const urdf::Rotation& r);
/// child frame → parent frame
Eigen::Isometry3d ToEigen(const urdf::Pose& pose);

struct LinkGroup {
  enum class Kind {
    kWorld,  ///< the root's group when it is the static world: world colliders
    kFree,   ///< the root's group when it carries mass, or a link on a floating joint: a body
    /// a link on a joint the simulator does not model (revolute, continuous, prismatic, planar)
    /// whose group carries no mass and no collision: left out, with a warning
    kLeftOut,
  };
  /// One link of a group and its pose in the frame of the group's first link.
  struct Member {
    const urdf::Link* link = nullptr;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< member frame → group link frame
  };

  Kind kind = Kind::kFree;
  Eigen::Isometry3d world_pose = Eigen::Isometry3d::Identity();  ///< group link frame → world
  std::vector<Member> members;  ///< the group's own link first, then those held to it
};

/// A moving joint the user holds rigid, as Drake's Joint::Lock: merged at `position` exactly as a
/// joint with lower = upper is (HeldJointPose: turned by it about the axis, or shifted along it).
struct HeldJoint {
  double position = 0.0;  ///< rad (revolute, continuous), m (prismatic), 0 (planar)
  /// what holds it, for the warning: "<nonsmooth_sim joint="j"> (line 7)", "the option
  /// hold_joints", or both
  std::string source;
};
using HeldJoints = std::map<std::string, HeldJoint>;  ///< by joint name

/// The joints held by the URDF's <nonsmooth_sim joint> blocks (`blocks`, at their position) and
/// by the loader option `option` (UrdfSceneOptions::hold_joints: at 0, or at the block's position
/// when a block names the joint too). Throws UrdfError with one line naming the joint (and the
/// joints that move, or what is allowed) when a name is not a joint of `model`, the joint is
/// `fixed` or `floating`, a `planar` joint is given a position other than 0, or the position lies
/// outside [lower, upper] of a `revolute` or `prismatic` joint.
HeldJoints ResolveHeldJoints(const urdf::ModelInterface& model,
                             const std::vector<JointHold>& blocks,
                             const std::vector<std::string>& option);

/// The groups of `model`, depth first from the root (the root's group first; a group's members
/// in the order the joints are met). The root's group is a free body when the root or a link held
/// to it has an <inertial>, unless the root is named "world" (Gazebo's and Drake's name of the
/// world frame); otherwise it is the static world. Below any group, a link on a `floating` joint
/// starts a free body at the joint's pose (joints that do not move taken at 0); a link on another
/// moving joint starts a kLeftOut group if nothing in its group has mass or collisions.
/// A joint in `held` is merged at its position like a fixed joint, also when it could move.
/// Appends to `warnings` one line per joint held rigid (lower = upper, or in `held`) and per
/// left-out group. Throws UrdfError when a link on a moving joint, or a link held to it, has an
/// <inertial> or a <collision>: the simulator has no joints, and dropping it would lose its mass
/// silently (the message names the ways out: fixed, floating, or a hold).
std::vector<LinkGroup> GroupLinks(const urdf::ModelInterface& model, const HeldJoints& held,
                                  std::vector<std::string>* warnings);

}  // namespace nonsmooth_sim::scene_io

#endif  // NONSMOOTH_SIM_SCENE_IO_LINK_GROUPS_H_
