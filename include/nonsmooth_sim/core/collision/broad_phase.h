// Broad phase: the pairs of colliders whose bounding spheres overlap, so that N bodies do not
// cost N² narrow-phase tests. Sweep and prune along world x (as MuJoCo and Bullet do over boxes):
// sort the spheres' intervals [x - r, x + r] and test only pairs whose intervals overlap. Static
// half-spaces (planes) have no bounding sphere: each body collider is tested against each plane
// directly (its centre's height above the plane against its radius), O(colliders × planes).
#ifndef NONSMOOTH_SIM_CORE_COLLISION_BROAD_PHASE_H_
#define NONSMOOTH_SIM_CORE_COLLISION_BROAD_PHASE_H_

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace nonsmooth_sim {

/// One collider's bounding sphere in the world (not a plane).
struct BoundingSphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< [m]
  double radius = 0.0;                               ///< [m], includes any margin
  int collider = 0;
  int body = -1;  ///< -1 for a static collider
};

/// Appends to `pairs` every (i, j) of colliders, i < j, whose spheres overlap and that do not
/// belong to the same body nor are both static. Reorders `spheres` (sorted by interval start);
/// `pairs` is neither cleared nor sorted. Allocates only when `pairs` grows past its capacity.
void SweepAndPrune(std::vector<BoundingSphere>* spheres, std::vector<std::pair<int, int>>* pairs);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_BROAD_PHASE_H_
