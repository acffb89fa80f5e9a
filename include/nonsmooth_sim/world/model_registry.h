// The models of the world (get_world_properties): which bodies and collisions of the simulator's
// scene belong to which model, and how a model's parts are named.
//
// Names (names.h): the start-up model's bodies and collisions keep their URDF names; a spawned
// model's are "<model>/<link>" and "<model>/<collision>". A body's name is its TF frame and what
// the services take and reply; "<model>::<link>" (Gazebo's spelling) is accepted too.
#ifndef NONSMOOTH_SIM_WORLD_MODEL_REGISTRY_H_
#define NONSMOOTH_SIM_WORLD_MODEL_REGISTRY_H_

#include <cstddef>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/scene.h"

namespace nonsmooth_sim::world {

/// A model of the world: the bodies and colliders of one URDF.
struct Model {
  std::string name;
  /// of its body and collider names in the scene: "" for the start-up model, "<name>/" for a
  /// spawned one
  std::string prefix;
  std::vector<int> bodies;     ///< free bodies; the first is the canonical one
  std::vector<int> colliders;  ///< its collisions (on its bodies and its static links)
  std::string description;     ///< where its URDF is kept ("" for the start-up model)
};

class ModelRegistry {
 public:
  /// A spawn is refused that would make the world larger than this many bodies (a bound on the
  /// work per step).
  static constexpr std::size_t kMaxWorldBodies = 4096;
  /// A spawn is refused that would make the world hold more collisions than this (a bound on the
  /// work per step and on the ~wrench/ topics).
  static constexpr std::size_t kMaxWorldCollisions = 16384;

  /// The start-up model `name` ("model" if empty): every body of `scene`, every collision but
  /// the world's ground.
  void Reset(const std::string& name, const Scene& scene);

  const std::vector<Model>& models() const { return models_; }
  int Find(const std::string& name) const;  ///< -1 if unknown
  const Model& at(int index) const { return models_[static_cast<std::size_t>(index)]; }
  /// 'no model "<name>"; the models are: a, b' (the reply to an unknown model name)
  std::string Unknown(const std::string& name) const;
  /// The start-up model (prefix ""), or nullptr once deleted.
  const Model* StartUp() const;

  /// The body named `name` (its name, or "<model>::<link>"); -1 if none.
  int BodyIndex(const Scene& scene, const std::string& name) const;
  /// The body a reference frame names: -1 for "" or "world"; throws std::invalid_argument naming
  /// `field` for anything else that is not a body.
  int ReferenceBody(const Scene& scene, const std::string& name, const char* field) const;

  /// Adds a model (its bodies and colliders already appended to the scene).
  void Add(Model model) { models_.push_back(std::move(model)); }
  /// Removes model `index` and renumbers the others by the old → new maps of RemoveFromScene.
  void Remove(int index, const std::vector<int>& body_map, const std::vector<int>& collider_map);

 private:
  std::vector<Model> models_;
};

}  // namespace nonsmooth_sim::world

#endif  // NONSMOOTH_SIM_WORLD_MODEL_REGISTRY_H_
