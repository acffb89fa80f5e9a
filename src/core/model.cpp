// The model's derived arrays and pair laws, see model.h.
#include "nonsmooth_sim/core/model.h"

#include "nonsmooth_sim/core/step/contact_pipeline.h"

namespace nonsmooth_sim {

void Model::BuildCaches() {
  inertia.clear();
  for (const RigidBody& body : scene.bodies) {
    inertia.push_back(MakeBodyInertia(body.mass, body.inertia));
  }
  planes.clear();
  int first_body = kWorld;
  needs_sweep = false;
  for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
    const Collider& c = scene.colliders[i];
    if (c.shape.type == ShapeType::kPlane) {
      planes.push_back(static_cast<int>(i));
      continue;
    }
    if (c.body == kWorld || (first_body != kWorld && c.body != first_body)) needs_sweep = true;
    if (first_body == kWorld) first_body = c.body;
  }
  // static colliders have their pose once and for all
  static_pose.assign(scene.colliders.size(), Eigen::Isometry3d::Identity());
  collider_rotated.resize(scene.colliders.size());
  bounding_radius.resize(scene.colliders.size());
  for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
    collider_rotated[i] = !scene.colliders[i].pose.linear().isIdentity(0.0);
    // padded by the hysteresis of the index set (12): the broad phase must pass a pair whose
    // contact was closed and now has a round-off-level positive gap (a sphere's bounding sphere
    // is the sphere itself: unpadded, the pair was dropped before the narrow phase saw it)
    bounding_radius[i] = BoundingRadius(scene.colliders[i].shape) + kContactHysteresis;
  }
  for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
    if (scene.colliders[i].body == kWorld) static_pose[i] = scene.colliders[i].pose;
  }
}

}  // namespace nonsmooth_sim
