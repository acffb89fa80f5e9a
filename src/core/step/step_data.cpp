// The step's data sized for a model, and the contacts' names, see step_data.h and step_report.h.
#include "nonsmooth_sim/core/step/step_data.h"

#include <algorithm>

namespace nonsmooth_sim {

void StepData::Resize(const Model& model) {
  body.assign(model.scene.bodies.size(), BodyStep{});
  collider_pose = model.static_pose;  // the bodies' are written at q_M before they are read
  closed.reserve(2 * model.scene.colliders.size());
  closed_count = 0;
  memory.reserve(4 * model.scene.colliders.size());
}

std::string ContactName(const Scene& scene, const ContactState& contact) {
  const int first = std::min(contact.collider_a, contact.collider_b);
  const int second = std::max(contact.collider_a, contact.collider_b);
  return scene.colliders[static_cast<std::size_t>(first)].name + "/" +
         scene.colliders[static_cast<std::size_t>(second)].name;
}

}  // namespace nonsmooth_sim
