// The models of the world. See model_registry.h.
#include "nonsmooth_sim/world/model_registry.h"

#include <stdexcept>

namespace nonsmooth_sim::world {

void ModelRegistry::Reset(const std::string& name, const Scene& scene) {
  // the start-up URDF is one model; its links that are free bodies are its bodies, all its
  // collisions its geoms
  Model model;
  model.name = name.empty() ? "model" : name;
  for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) model.bodies.push_back(b);
  for (int c = 0; c < static_cast<int>(scene.colliders.size()); ++c) {
    if (scene.colliders[static_cast<std::size_t>(c)].name != "ground" ||
        scene.colliders[static_cast<std::size_t>(c)].body != kWorld) {
      model.colliders.push_back(c);
    }
  }
  models_ = {model};
}

int ModelRegistry::Find(const std::string& name) const {
  for (int m = 0; m < static_cast<int>(models_.size()); ++m) {
    if (models_[static_cast<std::size_t>(m)].name == name) return m;
  }
  return -1;
}

std::string ModelRegistry::Unknown(const std::string& name) const {
  std::string names;
  for (const Model& m : models_) names += (names.empty() ? "" : ", ") + m.name;
  return "no model \"" + name + "\"; the models are: " + names;
}

const Model* ModelRegistry::StartUp() const {
  for (const Model& model : models_) {
    if (model.prefix.empty()) return &model;
  }
  return nullptr;
}

int ModelRegistry::BodyIndex(const Scene& scene, const std::string& name) const {
  // the body's name ("<link>" of the start-up model, "<model>/<link>" of a spawned one), or
  // "<model>::<link>"
  const std::size_t scope = name.find("::");
  if (scope == std::string::npos) {
    for (int b = 0; b < static_cast<int>(scene.bodies.size()); ++b) {
      if (scene.bodies[static_cast<std::size_t>(b)].name == name) return b;
    }
    return -1;
  }
  const int m = Find(name.substr(0, scope));
  if (m < 0) return -1;
  const Model& model = models_[static_cast<std::size_t>(m)];
  const std::string body_name = model.prefix + name.substr(scope + 2);
  for (int body : model.bodies) {
    if (scene.bodies[static_cast<std::size_t>(body)].name == body_name) return body;
  }
  return -1;
}

int ModelRegistry::ReferenceBody(const Scene& scene, const std::string& name,
                                 const char* field) const {
  if (name.empty() || name == "world") return -1;
  const int body = BodyIndex(scene, name);
  if (body < 0) {
    throw std::invalid_argument(std::string(field) + " \"" + name +
                                "\" is neither \"world\" nor a body (\"<model>/<link>\" or "
                                "\"<link>\")");
  }
  return body;
}

void ModelRegistry::Remove(int index, const std::vector<int>& body_map,
                           const std::vector<int>& collider_map) {
  models_.erase(models_.begin() + index);
  for (Model& model : models_) {
    for (int& b : model.bodies) b = body_map[static_cast<std::size_t>(b)];
    for (int& c : model.colliders) c = collider_map[static_cast<std::size_t>(c)];
  }
}

}  // namespace nonsmooth_sim::world
