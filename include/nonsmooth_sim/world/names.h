// The names of the world: one scheme for every part of every model, used by the services, TF, the
// contacts and the wrench topics (docs/ros.md, "Names").
//
// A part (link, collision) of the start-up model is named by its URDF name; a part of a spawned
// model "<model>/<part>" (model_registry.h). That name is the body's TF frame and what the
// services take and reply (Gazebo's "<model>::<link>" is accepted as another spelling); a
// collision on a body has the contact frame "<name>_contact" and the topic ~wrench/<name>, with
// each '/'-separated segment of the name made a graph name (GraphName). Each frame and topic has
// one owner (FrameNameClash). ROS-free (the node turns them into frames and topics).
#ifndef NONSMOOTH_SIM_WORLD_NAMES_H_
#define NONSMOOTH_SIM_WORLD_NAMES_H_

#include <string>
#include <vector>

#include "nonsmooth_sim/core/scene.h"

namespace nonsmooth_sim::world {

/// A ROS graph name made of [A-Za-z0-9_] (other characters become '_').
std::string GraphName(const std::string& name);

/// A name as TF frames and topic names take it: each '/'-separated segment a GraphName
/// ("top2/big sphere" → "top2/big_sphere").
std::string FrameName(const std::string& name);

/// Names of the TF frames and topics of one scene. Every collider on a body is a contact "slot":
/// a TF frame "<collision>_contact" (at its first closed contact, axes t1, t2, n; without a
/// contact at the collider's origin with world axes) and a wrench topic ~wrench/<collision>, both
/// with the collision's name as FrameName.
struct FrameNames {
  std::string world;                  ///< fixed frame
  std::vector<int> slots;             ///< the colliders on bodies, in scene order
  std::vector<std::string> contacts;  ///< per slot: "<collision name>_contact"
  std::vector<std::string> topics;    ///< per slot: "<collision name>", of the topic ~wrench/<it>
  std::vector<int> slot_of_collider;  ///< per collider: its slot, -1 for a static one
};
FrameNames MakeFrameNames(const Scene& scene, const std::string& world_frame);

/// "" when every TF frame of `scene` (the fixed frame, each body's frame = its name, each contact
/// frame of MakeFrameNames) and every ~wrench/ topic belongs to one name only; else one line
/// naming both owners and the frame, e.g. 'collision "x-y" would have the contact frame
/// "x_y_contact" and topic ~wrench/x_y of collision "x_y" (...)'.
std::string FrameNameClash(const Scene& scene, const std::string& world_frame);

/// A model's name: at most scene_io::kMaxNameLength characters of [A-Za-z0-9_], not starting with
/// a digit (it prefixes the model's frames and collision names). Throws std::invalid_argument
/// naming `field`.
void CheckModelName(const char* field, const std::string& name);

}  // namespace nonsmooth_sim::world

#endif  // NONSMOOTH_SIM_WORLD_NAMES_H_
