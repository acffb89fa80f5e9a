// Bodies that can no longer touch anything: lost_bodies.h.
#include "nonsmooth_sim/world/lost_bodies.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>

#include "nonsmooth_sim/core/shape.h"

namespace nonsmooth_sim::world {
namespace {

// Per body, the radius about its centre of mass that holds all its colliders (-1: none), in one
// pass over the colliders.
std::vector<double> BodySizes(const Scene& scene) {
  std::vector<double> size(scene.bodies.size(), -1.0);
  for (const Collider& c : scene.colliders) {
    if (c.body < 0 || static_cast<std::size_t>(c.body) >= size.size()) continue;
    double& s = size[static_cast<std::size_t>(c.body)];
    s = std::max(s, c.pose.translation().norm() + BoundingRadius(c.shape));
  }
  return size;
}

// Whether a body at r with size `size` is below the finite static collider `c` by more than
// its size (`up`: against gravity, a unit vector).
bool Below(const Collider& c, const Eigen::Vector3d& r, double size, const Eigen::Vector3d& up) {
  const double lowest = up.dot(c.pose.translation()) - BoundingRadius(c.shape);
  return up.dot(r) < lowest - size;
}

}  // namespace

std::vector<LostBody> FindLostBodies(const Scene& scene, const std::vector<BodyState>& state) {
  // bodies can fall past the finite static colliders only: none if a plane holds them (or
  // nothing pulls them down)
  std::vector<const Collider*> statics;
  bool plane = false;
  for (const Collider& c : scene.colliders) {
    if (c.body != kWorld) continue;
    statics.push_back(&c);
    plane = plane || c.shape.type == ShapeType::kPlane;
  }
  const double g = scene.gravity.norm();
  const bool can_fall = !statics.empty() && !plane && g > 0.0;
  const Eigen::Vector3d up = g > 0.0 ? Eigen::Vector3d(-scene.gravity / g)
                                     : Eigen::Vector3d(Eigen::Vector3d::Zero());
  const std::vector<double> sizes = BodySizes(scene);
  std::vector<LostBody> lost;
  for (std::size_t b = 0; b < scene.bodies.size() && b < state.size(); ++b) {
    const int body = static_cast<int>(b);
    const double size = sizes[b];
    if (size < 0.0) {
      lost.push_back({body, LostBody::Why::kNoCollider, 0.0});
      continue;
    }
    const Eigen::Vector3d& r = state[b].position;
    if (can_fall && std::all_of(statics.begin(), statics.end(), [&](const Collider* c) {
          return Below(*c, r, size, up);
        })) {
      lost.push_back({body, LostBody::Why::kBelowEveryStaticCollider, size});
    }
  }
  return lost;
}

std::string DescribeLostBody(const LostBody& lost) {
  if (lost.why == LostBody::Why::kNoCollider) {
    return "has no collision: it never touches anything";
  }
  char size[32];
  std::snprintf(size, sizeof size, "%.3g", lost.size);
  return std::string("is more than its size (") + size +
         " m) below every static collider: fallen off the world, it touches nothing again";
}

}  // namespace nonsmooth_sim::world
