// The world changed between two steps, see simulator.h: bodies added and removed, external
// wrenches.
//
// Everything that holds a body or collider index is carried over:
//  - AddBodies appends bodies and colliders, so every index already held (the warm-start and
//    tangent-frame memory keyed by (collider pair, feature), the friction sets set per contact, the
//    contact report, the wrenches) stays valid as it is.
//  - RemoveBodies keeps the order of what remains: old → new index maps that are increasing, under
//    which every (first < second) collider pair stays ordered, and the contacts of the remaining
//    pairs keep their relative order (the Gauss-Seidel order of an island). The memory is re-keyed
//    through the collider map (entries of removed colliders dropped), and so are the friction sets
//    per pair and the contact report; the wrenches are filtered by the body map.
// Both build the new scene, state and indexed data in locals, validate, and only then swap them
// in; the arrays derived from the scene are rebuilt by BuildCaches (as in the constructor).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include "nonsmooth_sim/core/contact/contact_key.h"
#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim {
namespace {

// The key with both colliders mapped by `map` (old → new index, -1: removed); false if one of
// them was removed.
bool RekeyContact(std::uint64_t key, const std::vector<int>& map, std::uint64_t* out) {
  const std::size_t first = static_cast<std::size_t>(ContactKeyFirst(key));
  const std::size_t second = static_cast<std::size_t>(ContactKeySecond(key));
  if (first >= map.size() || second >= map.size()) return false;  // not a key of this scene
  const int new_first = map[first];
  const int new_second = map[second];
  if (new_first < 0 || new_second < 0) return false;
  *out = ContactKey(new_first, new_second, ContactKeyFeature(key));
  return true;
}

int MapBody(int body, const std::vector<int>& map) {
  return body == kWorld ? kWorld : map[static_cast<std::size_t>(body)];
}

// ValidateScene, also for a scene of static colliders only (ValidateScene asks for a body: the
// constructor's scene needs one, a world between two steps may have none).
void ValidateWorld(const Scene& scene) {
  if (!scene.bodies.empty()) {
    ValidateScene(scene);
    return;
  }
  Scene probe = scene;  // its colliders are all static: a body appended is referenced by none
  probe.bodies.emplace_back();
  probe.initial_state.emplace_back();
  ValidateScene(probe);
}

std::string IndexRange(int index, std::size_t count) {
  return std::to_string(index) + " not in [0, " + std::to_string(count) + ")";
}

}  // namespace

int Simulator::AddBodies(const Scene& model, const std::vector<BodyState>& state) {
  const int first = static_cast<int>(model_.scene.bodies.size());
  if (state.size() != model.bodies.size()) {
    throw std::invalid_argument("AddBodies: " + std::to_string(state.size()) +
                                " start states for " + std::to_string(model.bodies.size()) +
                                " bodies (one per model body)");
  }
  // the model's collider → body indices before they are shifted (a shifted -2 would name a body
  // already there)
  for (std::size_t i = 0; i < model.colliders.size(); ++i) {
    const int body = model.colliders[i].body;
    if (body != kWorld && (body < 0 || static_cast<std::size_t>(body) >= model.bodies.size())) {
      throw std::invalid_argument("AddBodies: model.colliders[" + std::to_string(i) + "] (" +
                                  model.colliders[i].name + ").body = " + std::to_string(body) +
                                  ": must index model.bodies (in [0, " +
                                  std::to_string(model.bodies.size()) + ")) or be kWorld (-1)");
    }
  }
  // body names (where given) address the models: unique across the world
  {
    std::unordered_set<std::string> names;
    for (const RigidBody& body : model_.scene.bodies) {
      if (!body.name.empty()) names.insert(body.name);
    }
    for (std::size_t b = 0; b < model.bodies.size(); ++b) {
      const std::string& name = model.bodies[b].name;
      if (!name.empty() && !names.insert(name).second) {
        throw std::invalid_argument("AddBodies: model.bodies[" + std::to_string(b) + "] (" + name +
                                    ").name is already used by a body");
      }
    }
  }
  // the merged scene: appended, validated like the constructor's before anything changes
  Scene merged = model_.scene;
  Scene appended = model;
  appended.initial_state = state;
  AppendScene(appended, &merged);
  ValidateWorld(merged);
  std::vector<BodyState> merged_state = state_;
  for (const BodyState& s : state) {
    merged_state.push_back(s);
    merged_state.back().orientation.normalize();
  }
  RequireFiniteEnergy(merged, merged_state);
  std::vector<BodyWrench> merged_wrench = model_.wrench;
  merged_wrench.resize(merged.bodies.size());

  // commit: the memory, friction sets per pair, contact report and wrenches keep their indices
  model_.scene = std::move(merged);
  state_ = std::move(merged_state);
  model_.wrench = std::move(merged_wrench);
  BuildCaches();
  data_.closed_count = 0;
  return first;
}

void Simulator::RemoveBodies(const std::vector<int>& bodies, const std::vector<int>& colliders) {
  const std::size_t body_count = model_.scene.bodies.size();
  const std::size_t collider_count = model_.scene.colliders.size();
  std::vector<char> remove_body(body_count, 0);
  for (int b : bodies) {
    if (b < 0 || static_cast<std::size_t>(b) >= body_count) {
      throw std::out_of_range("RemoveBodies: body index " + IndexRange(b, body_count));
    }
    if (remove_body[static_cast<std::size_t>(b)]) {
      throw std::invalid_argument("RemoveBodies: body index " + std::to_string(b) + " given twice");
    }
    remove_body[static_cast<std::size_t>(b)] = 1;
  }
  std::vector<char> remove_collider(collider_count, 0);
  for (int i : colliders) {
    if (i < 0 || static_cast<std::size_t>(i) >= collider_count) {
      throw std::out_of_range("RemoveBodies: collider index " + IndexRange(i, collider_count));
    }
    const Collider& c = model_.scene.colliders[static_cast<std::size_t>(i)];
    if (c.body != kWorld) {
      throw std::invalid_argument("RemoveBodies: collider " + std::to_string(i) + " (" + c.name +
                                  ") is on a body, not static: remove its body");
    }
    if (remove_collider[static_cast<std::size_t>(i)]) {
      throw std::invalid_argument("RemoveBodies: collider index " + std::to_string(i) +
                                  " given twice");
    }
    remove_collider[static_cast<std::size_t>(i)] = 1;
  }

  // old → new indices, increasing (-1: removed)
  std::vector<int> body_map;
  std::vector<int> collider_map;
  Scene rest = model_.scene;
  RemoveFromScene(remove_body, remove_collider, &rest, &body_map, &collider_map);
  std::vector<BodyState> rest_state;
  std::vector<BodyWrench> rest_wrench;
  for (std::size_t b = 0; b < body_count; ++b) {
    if (remove_body[b]) continue;
    rest_state.push_back(state_[b]);
    rest_wrench.push_back(model_.wrench[b]);
  }
  // warm starts and tangent frames by (pair, feature), re-keyed
  ContactMemoryMap rest_memory;
  rest_memory.reserve(data_.memory.size());
  for (const auto& [key, memory] : data_.memory) {
    std::uint64_t new_key = 0;
    if (RekeyContact(key, collider_map, &new_key)) rest_memory.emplace(new_key, memory);
  }
  // friction sets per pair (first < second stays ordered: the map is increasing)
  std::vector<std::pair<std::pair<int, int>, FrictionSet>> rest_sets;
  for (const auto& [pair, set] : model_.pair_sets) {
    const int a = collider_map[static_cast<std::size_t>(pair.first)];
    const int b = collider_map[static_cast<std::size_t>(pair.second)];
    if (a >= 0 && b >= 0) rest_sets.emplace_back(std::make_pair(a, b), set);
  }
  // the last step's contact report, of what remains
  std::vector<ContactState> rest_contacts;
  rest_contacts.reserve(contacts_.capacity());
  for (const ContactState& contact : contacts_) {
    const int a = collider_map[static_cast<std::size_t>(contact.collider_a)];
    const int b = collider_map[static_cast<std::size_t>(contact.collider_b)];
    if (a < 0 || b < 0) continue;
    ContactState& kept = rest_contacts.emplace_back(contact);
    kept.collider_a = a;
    kept.collider_b = b;
    kept.body_a = MapBody(contact.body_a, body_map);
    kept.body_b = MapBody(contact.body_b, body_map);
  }
  bool any_wrench = false;
  for (const BodyWrench& w : rest_wrench) any_wrench = any_wrench || w.set;

  // commit
  model_.scene = std::move(rest);
  state_ = std::move(rest_state);
  model_.wrench = std::move(rest_wrench);
  model_.any_wrench = any_wrench;
  data_.memory = std::move(rest_memory);
  model_.pair_sets = std::move(rest_sets);
  contacts_ = std::move(rest_contacts);
  BuildCaches();
  data_.closed_count = 0;  // closed_ pointed into the old memory; rewritten by the next step
}

void Simulator::SetBodyStates(const std::vector<int>& bodies,
                              const std::vector<BodyState>& states) {
  if (bodies.size() != states.size()) {
    throw std::invalid_argument("SetBodyStates: " + std::to_string(states.size()) +
                                " states for " + std::to_string(bodies.size()) + " bodies");
  }
  std::vector<char> moved(model_.scene.bodies.size(), 0);
  std::vector<BodyState> next = state_;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const int b = bodies[i];
    if (b < 0 || static_cast<std::size_t>(b) >= model_.scene.bodies.size()) {
      throw std::out_of_range("SetBodyStates: body index " + IndexRange(b, model_.scene.bodies.size()));
    }
    if (moved[static_cast<std::size_t>(b)]) {
      throw std::invalid_argument("SetBodyStates: body index " + std::to_string(b) +
                                  " given twice");
    }
    moved[static_cast<std::size_t>(b)] = 1;
    next[static_cast<std::size_t>(b)] = states[i];
  }
  ValidateState(model_.scene, next);
  RequireFiniteEnergy(model_.scene, next);  // the bodies not set have a finite energy: they stepped to it
  for (int b : bodies) next[static_cast<std::size_t>(b)].orientation.normalize();
  // forget the contacts of the moved bodies only
  auto involved = [&](int collider) {
    const int body = model_.scene.colliders[static_cast<std::size_t>(collider)].body;
    return body != kWorld && moved[static_cast<std::size_t>(body)] != 0;
  };
  for (auto it = data_.memory.begin(); it != data_.memory.end();) {
    if (involved(ContactKeyFirst(it->first)) || involved(ContactKeySecond(it->first))) {
      it = data_.memory.erase(it);
    } else {
      ++it;
    }
  }
  contacts_.erase(std::remove_if(contacts_.begin(), contacts_.end(),
                                 [&](const ContactState& c) {
                                   return involved(c.collider_a) || involved(c.collider_b);
                                 }),
                  contacts_.end());
  state_ = std::move(next);
  diverged_ = false;
  data_.closed_count = 0;  // closed_ may point into the erased memory; rewritten by the next step
}

void Simulator::SetExternalWrench(int body, const Eigen::Vector3d& force,
                                  const Eigen::Vector3d& torque) {
  if (body < 0 || static_cast<std::size_t>(body) >= model_.wrench.size()) {
    throw std::out_of_range("SetExternalWrench: body index " +
                            IndexRange(body, model_.wrench.size()));
  }
  if (!force.allFinite() || !torque.allFinite()) {
    throw std::invalid_argument("SetExternalWrench: force and torque must be finite [N, N m]");
  }
  BodyWrench& w = model_.wrench[static_cast<std::size_t>(body)];
  w.force = force;
  w.torque = torque;
  // zero is "none": the body steps exactly as without a wrench
  w.set = !(force.isZero(0.0) && torque.isZero(0.0));
  model_.any_wrench = std::any_of(model_.wrench.begin(), model_.wrench.end(),
                                  [](const BodyWrench& x) { return x.set; });
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> Simulator::ExternalWrench(int body) const {
  if (body < 0 || static_cast<std::size_t>(body) >= model_.wrench.size()) {
    throw std::out_of_range("ExternalWrench: body index " +
                            IndexRange(body, model_.wrench.size()));
  }
  const BodyWrench& w = model_.wrench[static_cast<std::size_t>(body)];
  return {w.force, w.torque};
}

}  // namespace nonsmooth_sim
