// The links of a URDF grouped by what they become. See link_groups.h.
#include "link_groups.h"

#include <optional>

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
// by q about the axis (revolute, rad) or the shift by q along it (prismatic, m). The axis is
// normalised, as KDL (robot_state_publisher) does.
Eigen::Isometry3d HeldJointPose(const urdf::Joint& joint, double q) {
  Eigen::Isometry3d pose = ToEigen(joint.parent_to_joint_origin_transform);
  if (q == 0.0) return pose;
  const Eigen::Vector3d axis = ToEigen(joint.axis);
  if (!(axis.norm() > 0.0)) {
    throw UrdfError("urdf: " + JointLabel(joint) + " > axis: xyz=\"0 0 0\" gives no direction "
                    "to hold the joint at " + Format(q) + "; give a nonzero axis");
  }
  if (joint.type == urdf::Joint::REVOLUTE) {
    pose.rotate(Eigen::AngleAxisd(q, axis.normalized()));
  } else {
    pose.translate(q * axis.normalized());
  }
  return pose;
}

// "0.1 kg and 2 collisions": the mass and the collisions of a group's links; "" for none.
std::string Cargo(const LinkGroup& group) {
  double mass = 0.0;
  std::size_t collisions = 0;
  for (const LinkGroup::Member& member : group.members) {
    if (member.link->inertial) mass += member.link->inertial->mass;
    collisions += member.link->collision_array.size();
  }
  std::string cargo = mass > 0.0 ? Format(mass) + " kg" : "";
  if (collisions > 0) {
    cargo += (cargo.empty() ? "" : " and ") + std::to_string(collisions) +
             (collisions == 1 ? " collision" : " collisions");
  }
  return cargo;
}

class Grouper {
 public:
  Grouper(const urdf::ModelInterface& model, std::vector<std::string>* warnings)
      : model_(model), warnings_(warnings) {}

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
        if (j->type == urdf::Joint::FIXED) {
          self(self, *child, origin);
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
        (limited ? " (a joint with lower = upper cannot move and is merged as fixed)" : ""));
  }

  const urdf::ModelInterface& model_;
  std::vector<std::string>* warnings_;
  std::vector<LinkGroup> groups_;
};

}  // namespace

std::vector<LinkGroup> GroupLinks(const urdf::ModelInterface& model,
                                  std::vector<std::string>* warnings) {
  Grouper grouper(model, warnings);
  grouper.Collect(*model.getRoot(), nullptr, Eigen::Isometry3d::Identity());
  return std::move(grouper).Groups();
}

}  // namespace nonsmooth_sim::scene_io
