// The names of the world. See names.h.
#include "nonsmooth_sim/world/names.h"

#include <cctype>
#include <map>
#include <stdexcept>

#include "nonsmooth_sim/scene_io/bounded_input.h"

namespace nonsmooth_sim::world {

std::string GraphName(const std::string& name) {
  std::string out = name;
  for (char& c : out) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  }
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out.front()))) out = "_" + out;
  return out;
}

std::string FrameName(const std::string& name) {
  std::string out;
  std::size_t start = 0;
  while (true) {
    const std::size_t slash = name.find('/', start);
    out += GraphName(name.substr(start, slash == std::string::npos ? slash : slash - start));
    if (slash == std::string::npos) return out;
    out += '/';
    start = slash + 1;
  }
}

FrameNames MakeFrameNames(const Scene& scene, const std::string& world_frame) {
  FrameNames names;
  names.world = world_frame;
  for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
    if (scene.colliders[i].body == kWorld) continue;
    names.slots.push_back(static_cast<int>(i));
    names.contacts.push_back(FrameName(scene.colliders[i].name) + "_contact");
    names.topics.push_back(FrameName(scene.colliders[i].name));
  }
  names.slot_of_collider.assign(scene.colliders.size(), -1);
  for (std::size_t k = 0; k < names.slots.size(); ++k) {
    names.slot_of_collider[static_cast<std::size_t>(names.slots[k])] = static_cast<int>(k);
  }
  return names;
}

std::string FrameNameClash(const Scene& scene, const std::string& world_frame) {
  // every TF frame the node broadcasts → who owns it; a contact frame's topic ~wrench/<x> is
  // unique exactly when its frame <x>_contact is
  std::map<std::string, std::string> owners;
  owners.emplace(world_frame, "the fixed frame ~world_frame");
  const auto claim = [&owners](const std::string& frame, const std::string& owner,
                               const std::string& what) -> std::string {
    const auto [it, inserted] = owners.emplace(frame, owner);
    if (inserted) return "";
    return owner + " would have the " + what + " of " + it->second +
           " (frames and ~wrench/ topics replace every character other than A-Z a-z 0-9 _ / by _; "
           "rename one)";
  };
  for (const RigidBody& body : scene.bodies) {
    const std::string clash = claim(body.name, "body \"" + body.name + "\"",
                                    "TF frame \"" + body.name + "\"");
    if (!clash.empty()) return clash;
  }
  for (const Collider& collider : scene.colliders) {
    if (collider.body == kWorld) continue;
    const std::string base = FrameName(collider.name);
    const std::string clash =
        claim(base + "_contact", "collision \"" + collider.name + "\"",
              "contact frame \"" + base + "_contact\" and topic ~wrench/" + base);
    if (!clash.empty()) return clash;
  }
  return "";
}

void CheckModelName(const char* field, const std::string& name) {
  scene_io::CheckNameLength(field, name);
  if (name.empty() || GraphName(name) != name) {
    throw std::invalid_argument(std::string(field) + " \"" + name +
                                "\": must be letters, digits and '_', not starting with a digit "
                                "(it prefixes the model's TF frames and collision names)");
  }
}

}  // namespace nonsmooth_sim::world
