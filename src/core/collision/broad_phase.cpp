// Sweep and prune over bounding spheres, see broad_phase.h.
#include "nonsmooth_sim/core/collision/broad_phase.h"

#include <algorithm>

namespace nonsmooth_sim {

void SweepAndPrune(std::vector<BoundingSphere>* spheres, std::vector<std::pair<int, int>>* pairs) {
  std::vector<BoundingSphere>& s = *spheres;
  // sort by interval start x - r (insertion sort: nearly sorted from one step to the next would
  // be the usual case if the caller kept the order; std::sort allocates nothing either)
  std::sort(s.begin(), s.end(), [](const BoundingSphere& a, const BoundingSphere& b) {
    return a.center.x() - a.radius < b.center.x() - b.radius;
  });
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double end = s[i].center.x() + s[i].radius;
    for (std::size_t j = i + 1; j < s.size() && s[j].center.x() - s[j].radius <= end; ++j) {
      if (s[i].body == s[j].body) continue;  // one body, or both static
      const double reach = s[i].radius + s[j].radius;
      if ((s[i].center - s[j].center).squaredNorm() > reach * reach) continue;
      pairs->emplace_back(std::min(s[i].collider, s[j].collider),
                          std::max(s[i].collider, s[j].collider));
    }
  }
}

}  // namespace nonsmooth_sim
