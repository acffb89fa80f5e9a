// Overlapping colliders of a state, see overlaps.h.
#include "nonsmooth_sim/core/overlaps.h"

#include <algorithm>

#include "nonsmooth_sim/core/collision/collision_table.h"

namespace nonsmooth_sim {
namespace {

Eigen::Isometry3d WorldPose(const Collider& c, const std::vector<BodyState>& state) {
  if (c.body == kWorld) return c.pose;
  return BodyPose(state[static_cast<std::size_t>(c.body)]) * c.pose;
}

}  // namespace

std::vector<Overlap> FindOverlaps(const Scene& scene, const std::vector<BodyState>& state,
                                  double min_depth) {
  std::vector<Overlap> overlaps;
  const std::size_t n = scene.colliders.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Collider& a = scene.colliders[i];
    for (std::size_t j = i + 1; j < n; ++j) {
      const Collider& b = scene.colliders[j];
      if (a.body == b.body) continue;  // one body, or both static
      ContactGeometry points[kMaxPairContacts];
      const int count = scene.collision_table.Collide(a.shape, WorldPose(a, state), b.shape,
                                                      WorldPose(b, state), 0.0, points);
      double depth = 0.0;
      for (int k = 0; k < count; ++k) depth = std::max(depth, -points[k].gap);
      if (depth > min_depth) {
        overlaps.push_back(Overlap{static_cast<int>(i), static_cast<int>(j), depth});
      }
    }
  }
  return overlaps;
}

}  // namespace nonsmooth_sim
