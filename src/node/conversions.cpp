// Core state -> ROS messages. See conversions.h.
#include "nonsmooth_sim/node/conversions.h"

#include <cctype>
#include <cmath>
#include <limits>

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

// The contact report of sphere i; an open contact before the first step (the core reports
// contacts "from the last step", none after a SetState).
const ContactState& ContactOf(const Simulator& sim, std::size_t i) {
  static const ContactState kOpen;
  return i < sim.contacts().size() ? sim.contacts()[i] : kOpen;
}

// the body's first sphere, for Jellett's integral; -1 without spheres
int FirstSphere(const Scene& scene, int body) {
  for (int i = 0; i < static_cast<int>(scene.spheres.size()); ++i) {
    if (scene.spheres[i].body == body) return i;
  }
  return -1;
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

std::string GraphName(const std::string& name) {
  std::string out = name;
  for (char& c : out) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  }
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out.front()))) out = "_" + out;
  return out;
}

FrameNames MakeFrameNames(const Scene& scene, const std::string& world_frame) {
  FrameNames names;
  names.world = world_frame;
  for (const Sphere& s : scene.spheres) names.contacts.push_back(GraphName(s.name) + "_contact");
  return names;
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
  msg->contacts.resize(scene.spheres.size());
  for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& sphere = scene.spheres[i];
    const ContactState& c = ContactOf(sim, i);
    ContactInfo& info = msg->contacts[i];
    info.name = sphere.name;
    info.body = scene.bodies[sphere.body].name;
    info.frame = frames.contacts[i];
    info.friction_set = std::string(FrictionSetName(sphere.law.friction_set));
    info.mu = sphere.law.mu;
    info.average_friction_radius = sphere.law.rbar;
    info.closed = c.closed;
    info.gap = c.gap;
    Set(c.point, &info.position);
    Set(c.normal, &info.normal);
    Set(Eigen::Vector3d::UnitX(), &info.tangent1);
    Set(Eigen::Vector3d::UnitY(), &info.tangent2);
    info.normal_percussion = c.percussion[0];
    info.tangential_percussion = {c.percussion[1], c.percussion[2]};
    info.drilling_percussion = c.percussion[3];
    info.normal_force = c.percussion[0] / dt;
    info.tangential_force = {c.percussion[1] / dt, c.percussion[2] / dt};
    info.drilling_torque = c.percussion[3] / dt;
    info.normal_velocity = c.relative_velocity[0];
    info.tangential_velocity = {c.relative_velocity[1], c.relative_velocity[2]};
    info.drilling_velocity = c.relative_velocity[3];
  }
}

void FillTransforms(const Simulator& sim, const FrameNames& frames, const ros::Time& stamp,
                    tf2_msgs::TFMessage* msg) {
  const Scene& scene = sim.scene();
  msg->transforms.resize(scene.bodies.size() + scene.spheres.size());
  std::size_t k = 0;
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
  for (std::size_t i = 0; i < scene.spheres.size(); ++i, ++k) {
    geometry_msgs::TransformStamped& t = msg->transforms[k];
    t.header.stamp = stamp;
    t.header.frame_id = frames.world;
    t.child_frame_id = frames.contacts[i];
    Set(ContactOf(sim, i).point, &t.transform.translation);
    t.transform.rotation = geometry_msgs::Quaternion();
    t.transform.rotation.w = 1.0;
  }
}

void FillWrench(const Simulator& sim, int sphere, const FrameNames& frames, const ros::Time& stamp,
                geometry_msgs::WrenchStamped* msg) {
  const ContactState& c = ContactOf(sim, static_cast<std::size_t>(sphere));
  const Eigen::Vector4d lambda =
      c.closed ? Eigen::Vector4d(c.percussion / sim.options().time_step) : Eigen::Vector4d::Zero();
  msg->header.stamp = stamp;
  msg->header.frame_id = frames.contacts[sphere];
  // contact frame axes: tangent1 = x, tangent2 = y, normal = z
  msg->wrench.force.x = lambda[1];
  msg->wrench.force.y = lambda[2];
  msg->wrench.force.z = lambda[0];
  msg->wrench.torque.x = 0.0;
  msg->wrench.torque.y = 0.0;
  msg->wrench.torque.z = lambda[3];
}

void FillMarkers(const Simulator& sim, const FrameNames& frames, const ros::Time& stamp,
                 double force_scale, double torque_scale, visualization_msgs::MarkerArray* msg) {
  const std::size_t n = sim.scene().spheres.size();
  msg->markers.resize(2 * n);
  const double dt = sim.options().time_step;
  for (std::size_t i = 0; i < n; ++i) {
    const ContactState& c = ContactOf(sim, i);
    visualization_msgs::Marker* force = &msg->markers[2 * i];
    visualization_msgs::Marker* torque = &msg->markers[2 * i + 1];
    if (!c.closed) {
      Delete(frames.world, stamp, "contact_force", static_cast<int>(i), force);
      Delete(frames.world, stamp, "drilling_torque", static_cast<int>(i), torque);
      continue;
    }
    const Eigen::Vector3d f(c.percussion[1] / dt, c.percussion[2] / dt, c.percussion[0] / dt);
    Arrow(frames.world, stamp, "contact_force", static_cast<int>(i), c.point,
          c.point + force_scale * f, 1.0f, 0.55f, 0.0f, force);
    Arrow(frames.world, stamp, "drilling_torque", static_cast<int>(i), c.point,
          c.point + torque_scale * (c.percussion[3] / dt) * c.normal, 0.1f, 0.4f, 1.0f, torque);
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
