// The links of a URDF grouped by what they become. See link_groups.h.
#include "link_groups.h"

#include <optional>
#include <set>

#include "nonsmooth_sim/scene_io/format.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace nonsmooth_sim::scene_io {

Eigen::Vector3d ToEigen(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }
Eigen::Quaterniond ToEigen(const urdf::Rotation& r) { return {r.w, r.x, r.y, r.z}; }
Eigen::Isometry3d ToEigen(const urdf::Pose& pose) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = ToEigen(pose.rotation).toRotationMatrix();
  t.translation() = ToEigen(pose.position);
  return t;
}

namespace {

// Gazebo and Drake read a link of this name as the world frame itself, never as a body.
constexpr const char* kWorldLinkName = "world";

std::string LinkLabel(const std::string& name) { return "link " + Quoted(name); }

std::string JointTypeName(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE: return "revolute";
    case urdf::Joint::CONTINUOUS: return "continuous";
    case urdf::Joint::PRISMATIC: return "prismatic";
    case urdf::Joint::FLOATING: return "floating";
    case urdf::Joint::PLANAR: return "planar";
    case urdf::Joint::FIXED: return "fixed";
    default: return "unknown";
  }
}

// joint "j" (revolute)
std::string JointLabel(const urdf::Joint& joint) {
  return "joint " + Quoted(joint.name) + " (" + JointTypeName(joint.type) + ")";
}

// The position of a joint that cannot move: a revolute or prismatic joint whose limits are equal
// (URDF's lower and upper default to 0, so a <limit> with neither holds the joint at 0). Its
// link is where the URDF puts it at that position whatever the forces, exactly as if the joint
// were fixed there. nullopt: the joint moves (a continuous or planar one always can).
std::optional<double> HeldPosition(const urdf::Joint& joint) {
  if (joint.type != urdf::Joint::REVOLUTE && joint.type != urdf::Joint::PRISMATIC) {
    return std::nullopt;
  }
  if (!joint.limits || joint.limits->lower != joint.limits->upper) return std::nullopt;
  return joint.limits->lower;
}

// The child link's frame in the parent's for a joint held at `q`: the joint origin, then the turn
// by q about the axis (revolute, continuous: rad) or the shift by q along it (prismatic: m). The
// axis is normalised, as KDL (robot_state_publisher) does. A planar joint is held only at 0
// (ResolveHeldJoints).
Eigen::Isometry3d HeldJointPose(const urdf::Joint& joint, double q) {
  Eigen::Isometry3d pose = ToEigen(joint.parent_to_joint_origin_transform);
  if (q == 0.0) return pose;
  const Eigen::Vector3d axis = ToEigen(joint.axis);
  if (!(axis.norm() > 0.0)) {
    throw UrdfError("urdf: " + JointLabel(joint) + " > axis: xyz=\"0 0 0\" gives no direction "
                    "to hold the joint at " + Format(q) + "; give a nonzero axis");
  }
  if (joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS) {
    pose.rotate(Eigen::AngleAxisd(q, axis.normalized()));
  } else {
    pose.translate(q * axis.normalized());
  }
  return pose;
}

// "0.1 kg and 2 collisions"; "" for none.
std::string Cargo(double mass, std::size_t collisions) {
  std::string cargo = mass > 0.0 ? Format(mass) + " kg" : "";
  if (collisions > 0) {
    cargo += (cargo.empty() ? "" : " and ") + std::to_string(collisions) +
             (collisions == 1 ? " collision" : " collisions");
  }
  return cargo;
}

// The mass and the collisions of a group's links.
std::string Cargo(const LinkGroup& group) {
  double mass = 0.0;
  std::size_t collisions = 0;
  for (const LinkGroup::Member& member : group.members) {
    if (member.link->inertial) mass += member.link->inertial->mass;
    collisions += member.link->collision_array.size();
  }
  return Cargo(mass, collisions);
}

bool Moves(const urdf::Joint& joint) {
  return joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS ||
         joint.type == urdf::Joint::PRISMATIC || joint.type == urdf::Joint::PLANAR;
}

// " m" for a prismatic joint's position, " rad" for a revolute or continuous one's.
const char* Unit(const urdf::Joint& joint) {
  return joint.type == urdf::Joint::PRISMATIC ? " m" : " rad";
}

constexpr const char* kHoldOption = "the option hold_joints";

// What a hold may name: "allowed: ...; the joints that move here: "a" (continuous), ...".
std::string HoldAllowed(const urdf::ModelInterface& model) {
  std::string list;
  for (const auto& [name, joint] : model.joints_) {  // by name
    if (joint && Moves(*joint)) list += (list.empty() ? "" : ", ") + JointLabel(*joint);
  }
  return "allowed: a revolute, continuous, prismatic or planar joint; the joints that move "
         "here: " + (list.empty() ? std::string("none") : list);
}

[[noreturn]] void FailHold(const std::string& where, const std::string& reason) {
  throw UrdfError("urdf: " + where + ": " + reason);
}

// Throws unless `name` is a joint of `model` that moves and `q` a position it can be held at.
// `where`: the block's <hold> element or the option (then q = 0, the option's position).
void CheckHold(const urdf::ModelInterface& model, const std::string& where,
               const std::string& name, double q) {
  const auto fail = [&where](const std::string& reason) { FailHold(where, reason); };
  const urdf::JointConstSharedPtr joint = model.getJoint(name);
  if (!joint) FailHold(where, "no joint named " + Quoted(name) + "; " + HoldAllowed(model));
  if (joint->type == urdf::Joint::FIXED) {
    fail(JointLabel(*joint) + " does not move, there is nothing to hold (its link is merged "
         "already); " + HoldAllowed(model));
  }
  if (!Moves(*joint)) {
    fail(JointLabel(*joint) + " makes its link a free body of its own, not a joint to hold "
         "(make it fixed to merge the link); " + HoldAllowed(model));
  }
  if (joint->type == urdf::Joint::PLANAR && q != 0.0) {
    fail(JointLabel(*joint) + " can be held only at its zero position, not at " + Format(q) +
         " (a planar joint has two shifts and a turn, one position cannot give them); allowed: "
         "no position, or position=\"0\"");
  }
  const bool limited =
      joint->type == urdf::Joint::REVOLUTE || joint->type == urdf::Joint::PRISMATIC;
  if (limited && joint->limits && !(q >= joint->limits->lower && q <= joint->limits->upper)) {
    const std::string range = "[" + Format(joint->limits->lower) + ", " +
                              Format(joint->limits->upper) + "]" + Unit(*joint);
    if (where == kHoldOption) {
      fail(JointLabel(*joint) + " would be held at 0" + Unit(*joint) + ", outside its limits " +
           range + "; give a position within them in <nonsmooth_sim joint=" + Quoted(name) +
           "><hold position=\"...\"/></nonsmooth_sim>");
    }
    fail(JointLabel(*joint) + ": position " + Format(q) + Unit(*joint) +
         " is outside its limits; allowed: " + range + " (its <limit> lower and upper)");
  }
}

// The warning of a joint held by the user's opt-in (one line).
std::string HoldWarning(const urdf::Joint& joint, const HeldJoint& held, const urdf::Link& child,
                        const std::string& parent) {
  const std::string at = joint.type == urdf::Joint::PLANAR
                             ? "at its zero position"
                             : "at " + Format(held.position) + Unit(joint);
  std::string cargo = Cargo(child.inertial ? child.inertial->mass : 0.0,
                            child.collision_array.size());
  if (cargo.empty()) cargo = "no mass, no collision";
  return "urdf: " + JointLabel(joint) + " is held rigid " + at + " by " + held.source + ": its " +
         LinkLabel(child.name) + " (" + cargo + ") is merged into its parent " +
         LinkLabel(parent) + "; the simulator has no joints";
}

class Grouper {
 public:
  Grouper(const urdf::ModelInterface& model, const HeldJoints& held,
          std::vector<std::string>* warnings)
      : model_(model), held_(held), warnings_(warnings) {}

  // The group of `link` (attached by `joint`, nullptr for the root), then the groups below it.
  void Collect(const urdf::Link& link, const urdf::Joint* joint,
               const Eigen::Isometry3d& world_pose) {
    struct Next {
      const urdf::Link* link;
      const urdf::Joint* joint;
      Eigen::Isometry3d world_pose;
    };
    std::vector<Next> below;
    LinkGroup group;
    group.world_pose = world_pose;
    const auto add = [&](const auto& self, const urdf::Link& member,
                         const Eigen::Isometry3d& pose) -> void {
      group.members.push_back({&member, pose});
      for (const urdf::JointSharedPtr& j : member.child_joints) {
        const urdf::LinkConstSharedPtr child = model_.getLink(j->child_link_name);
        if (!child) continue;
        const Eigen::Isometry3d origin = pose * ToEigen(j->parent_to_joint_origin_transform);
        const auto held = held_.find(j->name);
        if (j->type == urdf::Joint::FIXED) {
          self(self, *child, origin);
        } else if (held != held_.end()) {  // the user's opt-in, checked by ResolveHeldJoints
          warnings_->push_back(HoldWarning(*j, held->second, *child, member.name));
          self(self, *child, pose * HeldJointPose(*j, held->second.position));
        } else if (const std::optional<double> q = HeldPosition(*j)) {
          warnings_->push_back(
              "urdf: " + JointLabel(*j) + " has lower = upper = " + Format(*q) +
              (j->type == urdf::Joint::REVOLUTE ? " rad" : " m") + ", so it cannot move: " +
              LinkLabel(child->name) + " is merged into its parent " +
              LinkLabel(member.name) + " as if the joint were fixed there");
          self(self, *child, pose * HeldJointPose(*j, *q));
        } else {
          // a moving joint's child starts at the joint's zero position
          below.push_back({child.get(), j.get(), world_pose * origin});
        }
      }
    };
    add(add, link, Eigen::Isometry3d::Identity());
    if (joint == nullptr) {
      group.kind = RootKind(group);
    } else if (joint->type == urdf::Joint::FLOATING) {
      group.kind = LinkGroup::Kind::kFree;
    } else {
      group.kind = LinkGroup::Kind::kLeftOut;
      CheckNothingIsLost(group, *joint);
    }
    groups_.push_back(std::move(group));
    for (const Next& next : below) Collect(*next.link, next.joint, next.world_pose);
  }

  std::vector<LinkGroup> Groups() && { return std::move(groups_); }

 private:
  // The root is a free body when it or a link held to it has mass (the root without <inertial>
  // that exporters write, `base_footprint` above `base_link`: Gazebo lumps it the same way), the
  // static world otherwise, and always when it is named "world".
  static LinkGroup::Kind RootKind(const LinkGroup& group) {
    const urdf::Link& root = *group.members.front().link;
    if (root.inertial) return LinkGroup::Kind::kFree;
    if (root.name == kWorldLinkName) return LinkGroup::Kind::kWorld;
    for (const LinkGroup::Member& member : group.members) {
      if (member.link->inertial) return LinkGroup::Kind::kFree;
    }
    return LinkGroup::Kind::kWorld;
  }

  // A link on a joint the simulator does not model can be left out only when it carries nothing
  // physical: its mass or its collisions dropped silently would change the scene the user wrote.
  void CheckNothingIsLost(const LinkGroup& group, const urdf::Joint& joint) {
    const std::string cargo = Cargo(group);
    const std::string& link = group.members.front().link->name;
    if (cargo.empty()) {
      warnings_->push_back("urdf: " + LinkLabel(link) + " hangs on " + JointLabel(joint) +
                           ", which the simulator does not model; it has no mass and no "
                           "collision, so it is left out (no TF frame)");
      return;
    }
    const bool limited =
        joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::PRISMATIC;
    throw UrdfError(
        "urdf: " + JointLabel(joint) + " moves " + LinkLabel(link) + ", which carries " + cargo +
        (group.members.size() > 1 ? " with the links fixed to it" : "") +
        ", but the simulator has no joints, only free bodies: make it fixed to merge the link "
        "into its parent, or floating to make it a body of its own" +
        (limited ? " (a joint with lower = upper cannot move and is merged as fixed)" : "") +
        "; or hold it rigid without editing it: <nonsmooth_sim joint=" + Quoted(joint.name) +
        "><hold/></nonsmooth_sim>, or the loader option hold_joints (simulate --hold-joint, the "
        "node's ~hold_joints)");
  }

  const urdf::ModelInterface& model_;
  const HeldJoints& held_;
  std::vector<std::string>* warnings_;
  std::vector<LinkGroup> groups_;
};

}  // namespace

HeldJoints ResolveHeldJoints(const urdf::ModelInterface& model,
                             const std::vector<JointHold>& blocks,
                             const std::vector<std::string>& option) {
  HeldJoints held;
  for (const JointHold& hold : blocks) {
    const double q = hold.position.value_or(0.0);
    CheckHold(model, hold.where, hold.joint, q);
    held[hold.joint] = {q, "<nonsmooth_sim joint=" + Quoted(hold.joint) + "> (line " +
                               std::to_string(hold.line) + ")"};
  }
  std::set<std::string> named;  // a name given twice holds once
  for (const std::string& name : option) {
    if (!named.insert(name).second) continue;
    if (const auto it = held.find(name); it != held.end()) {
      it->second.source += std::string(" and ") + kHoldOption;  // at the block's position
      continue;
    }
    CheckHold(model, kHoldOption, name, 0.0);
    held[name] = {0.0, kHoldOption};
  }
  return held;
}

std::vector<LinkGroup> GroupLinks(const urdf::ModelInterface& model, const HeldJoints& held,
                                  std::vector<std::string>* warnings) {
  Grouper grouper(model, held, warnings);
  grouper.Collect(*model.getRoot(), nullptr, Eigen::Isometry3d::Identity());
  return std::move(grouper).Groups();
}

}  // namespace nonsmooth_sim::scene_io
