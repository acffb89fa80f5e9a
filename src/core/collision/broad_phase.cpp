// Sweep and prune over bounding spheres, see broad_phase.h.
#include "nonsmooth_sim/core/collision/broad_phase.h"

#include <algorithm>

#include "nonsmooth_sim/core/nearly_sorted.h"

namespace nonsmooth_sim {
namespace {

const Eigen::Vector3d kSweepDirection =
    Eigen::Vector3d(1.0, 0.6180339887498949, 0.3819660112501051).normalized();

}  // namespace

Eigen::Vector3d SweepDirection() { return kSweepDirection; }

void SweepAndPrune(std::vector<BoundingSphere>* spheres, std::vector<std::pair<int, int>>* pairs) {
  std::vector<BoundingSphere>& s = *spheres;
  for (BoundingSphere& sphere : s) {
    sphere.interval_start = kSweepDirection.dot(sphere.center) - sphere.radius;
  }
  // by interval start: nearly sorted when the caller kept the order of its last call
  SortNearlySorted(s.begin(), s.end(), [](const BoundingSphere& a, const BoundingSphere& b) {
    return a.interval_start < b.interval_start;
  });
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double end = s[i].interval_start + 2.0 * s[i].radius;
    for (std::size_t j = i + 1; j < s.size() && s[j].interval_start <= end; ++j) {
      if (s[i].body == s[j].body) continue;  // one body, or both static
      const double reach = s[i].radius + s[j].radius;
      if ((s[i].center - s[j].center).squaredNorm() > reach * reach) continue;
      pairs->emplace_back(std::min(s[i].collider, s[j].collider),
                          std::max(s[i].collider, s[j].collider));
    }
  }
}

}  // namespace nonsmooth_sim
