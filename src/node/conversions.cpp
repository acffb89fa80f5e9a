// Core state -> ROS messages. See conversions.h.
#include "nonsmooth_sim/node/conversions.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "nonsmooth_sim/core/tippe_top.h"

namespace nonsmooth_sim::node {
namespace {

void Set(const Eigen::Vector3d& v, geometry_msgs::Point* p) {
  p->x = v.x();
  p->y = v.y();
  p->z = v.z();
}
void Set(const Eigen::Vector3d& v, geometry_msgs::Vector3* p) {
  p->x = v.x();
  p->y = v.y();
  p->z = v.z();
}
void Set(const Eigen::Quaterniond& q, geometry_msgs::Quaternion* p) {
  p->x = q.x();
  p->y = q.y();
  p->z = q.z();
  p->w = q.w();
}

// The body's first sphere collider, for Jellett's integral; -1 without one.
int FirstSphere(const Scene& scene, int body) {
  for (int i = 0; i < static_cast<int>(scene.colliders.size()); ++i) {
    const Collider& c = scene.colliders[static_cast<std::size_t>(i)];
    if (c.body == body && c.shape.type == ShapeType::kSphere) return i;
  }
  return -1;
}

// The rotation whose columns are t1, t2, n: the contact frame's axes in the world.
Eigen::Quaterniond FrameRotation(const ContactFrame& frame) {
  Eigen::Matrix3d r;
  r.col(0) = frame.tangent1;
  r.col(1) = frame.tangent2;
  r.col(2) = frame.normal;
  return Eigen::Quaterniond(r);
}

constexpr double kMarkerShaft = 0.001;  // arrow shaft diameter [m]
constexpr double kMarkerHead = 0.002;   // arrow head diameter [m]

void Arrow(const std::string& frame, const ros::Time& stamp, const char* ns, int id,
           const Eigen::Vector3d& tail, const Eigen::Vector3d& head, float r, float g, float b,
           visualization_msgs::Marker* m) {
  m->header.frame_id = frame;
  m->header.stamp = stamp;
  m->ns = ns;
  m->id = id;
  m->type = visualization_msgs::Marker::ARROW;
  m->action = visualization_msgs::Marker::ADD;
  m->pose.orientation.w = 1.0;
  m->points.resize(2);
  Set(tail, &m->points[0]);
  Set(head, &m->points[1]);
  m->scale.x = kMarkerShaft;
  m->scale.y = kMarkerHead;
  m->scale.z = 0.0;
  m->color.r = r;
  m->color.g = g;
  m->color.b = b;
  m->color.a = 1.0f;
}

void Delete(const std::string& frame, const ros::Time& stamp, const char* ns, int id,
            visualization_msgs::Marker* m) {
  m->header.frame_id = frame;
  m->header.stamp = stamp;
  m->ns = ns;
  m->id = id;
  m->action = visualization_msgs::Marker::DELETE;
  m->points.clear();
}

}  // namespace

ros::Time StampOf(double sim_time) {
  const ros::Time t(sim_time);
  return t.isZero() ? ros::TIME_MIN : t;
}

const ContactState* SlotContact(const Simulator& sim, const FrameNames& frames, std::size_t slot) {
  return sim.FindContact(frames.slots[slot]);
}

void FirstContacts(const Simulator& sim, std::vector<int>* first) {
  first->assign(sim.scene().colliders.size(), -1);
  const std::vector<ContactState>& contacts = sim.contacts();
  for (int i = static_cast<int>(contacts.size()) - 1; i >= 0; --i) {
    const ContactState& c = contacts[static_cast<std::size_t>(i)];
    (*first)[static_cast<std::size_t>(c.collider_a)] = i;
    (*first)[static_cast<std::size_t>(c.collider_b)] = i;
  }
}

geometry_msgs::Pose ToMsg(const world::Pose& pose) {
  geometry_msgs::Pose msg;
  Set(pose.position, &msg.position);
  Set(pose.orientation, &msg.orientation);
  return msg;
}

geometry_msgs::Twist ToMsg(const world::Twist& twist) {
  geometry_msgs::Twist msg;
  Set(twist.linear, &msg.linear);
  Set(twist.angular, &msg.angular);
  return msg;
}

geometry_msgs::Pose LinkPose(const RigidBody& body, const BodyState& state) {
  geometry_msgs::Pose pose;
  Set(Eigen::Vector3d(state.position - state.orientation * body.com_in_link), &pose.position);
  Set(state.orientation, &pose.orientation);
  return pose;
}

void FillState(const Simulator& sim, bool paused, const std::string& world_frame,
               SimulationState* msg) {
  const Scene& scene = sim.scene();
  const std::vector<BodyState>& state = sim.state();
  msg->header.stamp = StampOf(sim.time());
  msg->header.frame_id = world_frame;
  msg->sim_time = sim.time();
  msg->paused = paused;
  msg->energy = sim.Energy();
  msg->bodies.resize(scene.bodies.size());
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const BodyState& s = state[b];
    BodyInfo& info = msg->bodies[b];
    const Eigen::Vector3d omega_world = s.orientation * s.angular_velocity;
    info.name = scene.bodies[b].name;
    info.pose = LinkPose(scene.bodies[b], s);
    Set(s.position, &info.center_of_mass);
    Set(s.linear_velocity, &info.twist.linear);
    Set(omega_world, &info.twist.angular);
    Set(s.angular_velocity, &info.angular_velocity_body);
    info.inclination = Inclination(s);
    info.vertical_spin = omega_world.z();
    const int sphere = FirstSphere(scene, static_cast<int>(b));
    info.jellett_integral = sphere >= 0 ? JellettIntegral(scene, state, sphere)
                                        : std::numeric_limits<double>::quiet_NaN();
  }
}

void FillContacts(const Simulator& sim, const StepStatistics& last_step, const FrameNames& frames,
                  ContactInfoArray* msg) {
  const Scene& scene = sim.scene();
  const double dt = sim.options().time_step;
  msg->header.stamp = StampOf(sim.time());
  msg->header.frame_id = frames.world;
  msg->sim_time = sim.time();
  msg->time_step = dt;
  msg->solver_iterations = last_step.solver.iterations;
  msg->solver_residual = last_step.solver.residual;
  msg->solver_converged = last_step.solver.converged;
  const std::vector<ContactState>& contacts = sim.contacts();
  // per collider its first contact: the slot frame is named at that one (O(contacts + colliders))
  std::vector<int> first;
  FirstContacts(sim, &first);
  msg->contacts.resize(contacts.size());
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const ContactState& c = contacts[i];
    ContactInfo& info = msg->contacts[i];
    const Collider& b = scene.colliders[static_cast<std::size_t>(c.collider_b)];
    const Collider& a = scene.colliders[static_cast<std::size_t>(c.collider_a)];
    info.name = ContactName(scene, c);
    info.collision = b.name;
    info.body = scene.bodies[static_cast<std::size_t>(c.body_b)].name;
    info.other_collision = a.name;
    info.other_body =
        c.body_a == kWorld ? "" : scene.bodies[static_cast<std::size_t>(c.body_a)].name;
    info.feature = c.feature;
    // the slot frame of B's collider when this is its first contact
    info.frame.clear();
    const int slot = frames.slot_of_collider[static_cast<std::size_t>(c.collider_b)];
    if (slot >= 0 && first[static_cast<std::size_t>(c.collider_b)] == static_cast<int>(i)) {
      info.frame = frames.contacts[static_cast<std::size_t>(slot)];
    }
    info.friction_set = std::string(FrictionSetName(c.law.friction_set));
    info.mu = c.law.mu;
    info.average_friction_radius = c.dimension >= 4 ? c.law.rbar : 0.0;
    info.closed = true;
    info.gap = c.gap;
    Set(c.point, &info.position);
    Set(c.frame.normal, &info.normal);
    Set(c.frame.tangent1, &info.tangent1);
    Set(c.frame.tangent2, &info.tangent2);
    info.normal_percussion = c.percussion[0];
    info.tangential_percussion = {c.percussion[1], c.percussion[2]};
    info.drilling_percussion = c.percussion[3];
    info.normal_force = c.percussion[0] / dt;
    info.tangential_force = {c.percussion[1] / dt, c.percussion[2] / dt};
    info.drilling_torque = c.percussion[3] / dt;
    info.normal_velocity = c.relative_velocity[0];
    info.tangential_velocity = {c.relative_velocity[1], c.relative_velocity[2]};
    info.drilling_velocity = c.relative_velocity[3];
    const bool rolling = c.dimension == 6;
    info.rolling_resistance = rolling ? static_cast<double>(c.law.rolling_resistance) : 0.0;
    info.rolling_percussion = {c.rolling_percussion[0], c.rolling_percussion[1]};
    info.rolling_torque = {c.rolling_percussion[0] / dt, c.rolling_percussion[1] / dt};
  }
}

std::vector<geometry_msgs::TransformStamped> FixedLinkTransforms(
    const scene_io::UrdfScene& urdf, const std::string& prefix, const std::string& world_frame,
    bool world_links, const ros::Time& stamp) {
  std::vector<geometry_msgs::TransformStamped> transforms;
  for (const scene_io::FixedLink& link : urdf.fixed_links) {
    if (link.body == kWorld && !world_links) continue;
    geometry_msgs::TransformStamped t;
    t.header.stamp = stamp;
    t.header.frame_id =
        link.body == kWorld ? world_frame
                            : prefix + urdf.scene.bodies[static_cast<std::size_t>(link.body)].name;
    t.child_frame_id = prefix + link.name;
    if (t.child_frame_id == t.header.frame_id || t.child_frame_id == world_frame) continue;
    Set(Eigen::Vector3d(link.pose.translation()), &t.transform.translation);
    Set(Eigen::Quaterniond(link.pose.linear()), &t.transform.rotation);
    transforms.push_back(std::move(t));
  }
  return transforms;
}

void AppendTransforms(const Simulator& sim, const FrameNames& frames, const ros::Time& stamp,
                      tf2_msgs::TFMessage* msg) {
  const Scene& scene = sim.scene();
  std::size_t k = msg->transforms.size();
  msg->transforms.resize(k + scene.bodies.size() + frames.slots.size());
  for (std::size_t b = 0; b < scene.bodies.size(); ++b, ++k) {
    geometry_msgs::TransformStamped& t = msg->transforms[k];
    t.header.stamp = stamp;
    t.header.frame_id = frames.world;
    t.child_frame_id = scene.bodies[b].name;
    const geometry_msgs::Pose pose = LinkPose(scene.bodies[b], sim.state()[b]);
    t.transform.translation.x = pose.position.x;
    t.transform.translation.y = pose.position.y;
    t.transform.translation.z = pose.position.z;
    t.transform.rotation = pose.orientation;
  }
  std::vector<int> first;
  FirstContacts(sim, &first);
  for (std::size_t i = 0; i < frames.slots.size(); ++i, ++k) {
    geometry_msgs::TransformStamped& t = msg->transforms[k];
    t.header.stamp = stamp;
    t.header.frame_id = frames.world;
    t.child_frame_id = frames.contacts[i];
    const int index = first[static_cast<std::size_t>(frames.slots[i])];
    if (index >= 0) {
      const ContactState* c = &sim.contacts()[static_cast<std::size_t>(index)];
      // at the contact point, axes (t1, t2, n)
      Set(c->point, &t.transform.translation);
      Set(FrameRotation(c->frame), &t.transform.rotation);
    } else {
      // no contact: at the collider's origin, world axes
      const Collider& collider = scene.colliders[static_cast<std::size_t>(frames.slots[i])];
      const Eigen::Vector3d origin =
          BodyPose(sim.state()[static_cast<std::size_t>(collider.body)]) *
          collider.pose.translation();
      Set(origin, &t.transform.translation);
      t.transform.rotation = geometry_msgs::Quaternion();
      t.transform.rotation.w = 1.0;
    }
  }
}

bool FillWrench(const Simulator& sim, std::size_t slot, const FrameNames& frames,
                const ros::Time& stamp, geometry_msgs::WrenchStamped* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = frames.contacts[slot];
  const ContactState* first = SlotContact(sim, frames, slot);
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // world
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // world, about the first contact point
  if (first != nullptr) {
    const double dt = sim.options().time_step;
    const int collider = frames.slots[slot];
    for (const ContactState& c : sim.contacts()) {
      if (c.collider_a != collider && c.collider_b != collider) continue;
      // the force on B; on A it is the opposite
      const double sign = c.collider_b == collider ? 1.0 : -1.0;
      const Eigen::Vector3d f =
          sign / dt *
          (c.percussion[0] * c.frame.normal + c.percussion[1] * c.frame.tangent1 +
           c.percussion[2] * c.frame.tangent2);
      force += f;
      // and its drilling and rolling torques (Λ_R about t1, t2; 0 without rolling)
      torque += (c.point - first->point).cross(f) +
                sign / dt *
                    (c.percussion[3] * c.frame.normal + c.rolling_percussion[0] * c.frame.tangent1 +
                     c.rolling_percussion[1] * c.frame.tangent2);
    }
    // in the slot frame's axes (t1, t2, n of the first contact)
    const Eigen::Matrix3d axes = FrameRotation(first->frame).toRotationMatrix();
    force = axes.transpose() * force;
    torque = axes.transpose() * torque;
  }
  Set(force, &msg->wrench.force);
  Set(torque, &msg->wrench.torque);
  return first != nullptr;
}

void FillMarkers(const Simulator& sim, const FrameNames& frames, const ros::Time& stamp,
                 double force_scale, double torque_scale, std::size_t previous_count,
                 visualization_msgs::MarkerArray* msg) {
  const std::vector<ContactState>& contacts = sim.contacts();
  const std::size_t n = std::max(contacts.size(), previous_count);
  msg->markers.resize(kMarkersPerContact * n);
  const double dt = sim.options().time_step;
  for (std::size_t i = 0; i < n; ++i) {
    visualization_msgs::Marker* force = &msg->markers[kMarkersPerContact * i];
    visualization_msgs::Marker* torque = force + 1;
    visualization_msgs::Marker* rolling = force + 2;
    const int id = static_cast<int>(i);
    if (i >= contacts.size()) {
      // a marker of the last message that has no contact now
      Delete(frames.world, stamp, "contact_force", id, force);
      Delete(frames.world, stamp, "drilling_torque", id, torque);
      Delete(frames.world, stamp, "rolling_torque", id, rolling);
      continue;
    }
    const ContactState& c = contacts[i];
    const Eigen::Vector3d f =
        (c.percussion[0] * c.frame.normal + c.percussion[1] * c.frame.tangent1 +
         c.percussion[2] * c.frame.tangent2) /
        dt;
    Arrow(frames.world, stamp, "contact_force", id, c.point, c.point + force_scale * f, 1.0f,
          0.55f, 0.0f, force);
    Arrow(frames.world, stamp, "drilling_torque", id, c.point,
          c.point + torque_scale * (c.percussion[3] / dt) * c.frame.normal, 0.1f, 0.4f, 1.0f,
          torque);
    if (c.dimension == 6) {
      // the rolling torque Λ_R/Δt about t1, t2: an arrow in the tangent plane
      const Eigen::Vector3d tau = (c.rolling_percussion[0] * c.frame.tangent1 +
                                   c.rolling_percussion[1] * c.frame.tangent2) /
                                  dt;
      Arrow(frames.world, stamp, "rolling_torque", id, c.point, c.point + torque_scale * tau,
            0.1f, 0.75f, 0.2f, rolling);
    } else {
      Delete(frames.world, stamp, "rolling_torque", id, rolling);
    }
  }
}

visualization_msgs::MarkerArray DeleteAllMarkers(const std::string& world_frame) {
  visualization_msgs::MarkerArray msg;
  msg.markers.resize(1);
  msg.markers[0].header.frame_id = world_frame;
  msg.markers[0].action = visualization_msgs::Marker::DELETEALL;
  return msg;
}

}  // namespace nonsmooth_sim::node
