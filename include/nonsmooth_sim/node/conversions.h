// Core state -> ROS messages: the one place where messages meet the core. The Fill* functions
// overwrite a message in place, so that publishing at kHz rates reuses its storage.
#ifndef NONSMOOTH_SIM_NODE_CONVERSIONS_H_
#define NONSMOOTH_SIM_NODE_CONVERSIONS_H_

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Twist.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/time.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <vector>

#include "nonsmooth_sim/ContactInfoArray.h"
#include "nonsmooth_sim/SimulationState.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "nonsmooth_sim/world/names.h"
#include "nonsmooth_sim/world/placement.h"

namespace nonsmooth_sim::node {

/// ROS stamp of simulated time t ≥ 0: t itself, except ros::TIME_MIN (1 ns) for t = 0, because
/// ros::Time(0) means "no time yet" to nodes on /use_sim_time (and rosbag refuses it).
ros::Time StampOf(double sim_time);

// the world's names (world/names.h): frames, topics, and the one-owner rule
using world::FrameName;
using world::FrameNameClash;
using world::FrameNames;
using world::GraphName;
using world::MakeFrameNames;

/// The first closed contact of slot `slot`, or nullptr (a scan of the contacts: O(contacts)).
const ContactState* SlotContact(const Simulator& sim, const FrameNames& frames, std::size_t slot);

/// Per collider the index in sim.contacts() of its first contact, -1 without one: one pass over
/// the contacts, so that a message over every slot costs O(contacts + colliders).
void FirstContacts(const Simulator& sim, std::vector<int>* first);

/// A pose and a twist of the world as messages (~get_model_state).
geometry_msgs::Pose ToMsg(const world::Pose& pose);
geometry_msgs::Twist ToMsg(const world::Twist& twist);

/// Pose of the link frame: the body pose composed with the translation -com_in_link.
geometry_msgs::Pose LinkPose(const RigidBody& body, const BodyState& state);

/// ~state / ~get_state: pose, twist, inclination, energy, Jellett's integral, vertical spin.
void FillState(const Simulator& sim, bool paused, const std::string& world_frame,
               SimulationState* msg);

/// ~contacts: every closed contact of the last step (body–ground, body–static, body–body), named
/// "<first collision>/<second collision>"; forces = percussions / Δt.
void FillContacts(const Simulator& sim, const StepStatistics& last_step, const FrameNames& frames,
                  ContactInfoArray* msg);

/// /tf: appends world → each body's link, and world → each slot's frame (see FrameNames), all
/// stamped `stamp`, after the transforms msg already holds (a message may carry several stamps).
void AppendTransforms(const Simulator& sim, const FrameNames& frames, const ros::Time& stamp,
                      tf2_msgs::TFMessage* msg);

/// /tf_static for one model: each link without a body of its own (scene_io::FixedLink) in the
/// frame of its body's link, or in `world_frame` for a link fixed to the world (only with
/// `world_links`); names prefixed with `prefix` ("" for the start-up model, "<model>/" for a
/// spawned one); a link that is `world_frame` itself is left out. Stamped `stamp`.
std::vector<geometry_msgs::TransformStamped> FixedLinkTransforms(
    const scene_io::UrdfScene& urdf, const std::string& prefix, const std::string& world_frame,
    bool world_links, const ros::Time& stamp);

/// The contact wrench λ = Λ/Δt on slot `slot`'s collider, summed over its closed contacts, about
/// and in the axes of its slot frame (one contact: the force and the drilling torque at it). Zero
/// and false without a closed contact.
bool FillWrench(const Simulator& sim, std::size_t slot, const FrameNames& frames,
                const ros::Time& stamp, geometry_msgs::WrenchStamped* msg);

/// Markers per contact in FillMarkers' message: force, drilling torque, rolling torque.
inline constexpr std::size_t kMarkersPerContact = 3;

/// Arrows in the world frame, kMarkersPerContact per closed contact i, tails at the contact
/// point: the force (namespace "contact_force", id i), the drilling torque (namespace
/// "drilling_torque", along the normal) and the rolling torque (namespace "rolling_torque", in the
/// tangent plane; DELETE for a contact without rolling components); DELETE for the ids up to
/// previous_count that have no contact now. Lengths: force_scale [m/N], torque_scale [m/(N m)].
void FillMarkers(const Simulator& sim, const FrameNames& frames, const ros::Time& stamp,
                 double force_scale, double torque_scale, std::size_t previous_count,
                 visualization_msgs::MarkerArray* msg);

/// One DELETEALL marker (sent after a reset).
visualization_msgs::MarkerArray DeleteAllMarkers(const std::string& world_frame);

}  // namespace nonsmooth_sim::node

#endif  // NONSMOOTH_SIM_NODE_CONVERSIONS_H_
