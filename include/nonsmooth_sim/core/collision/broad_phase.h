// Broad phase: the pairs of colliders whose bounding spheres overlap, so that N bodies do not
// cost N² narrow-phase tests. Sweep and prune (as MuJoCo and Bullet do over boxes): project the
// spheres onto one direction, sort their intervals [a·c - r, a·c + r] and test only pairs whose
// intervals overlap. Static half-spaces (planes) have no bounding sphere: each body collider is
// tested against each plane directly (its centre's height above the plane against its radius),
// O(colliders × planes).
//
// The direction a is skew to the coordinate axes (kSweepDirection): along x, a scene laid out on
// a grid (N tops 5 m apart, a rack, a stack) puts every collider of a column into one interval,
// and the sweep tests each against all of its column, O(N^1.5) pairs for N on a square grid.
// The caller keeps the spheres in the order of its last call: the intervals then need an
// insertion sort of the few that moved past each other (O(N)), not a sort from scratch.
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
  /// a·center - radius along kSweepDirection [m]: written by SweepAndPrune
  double interval_start = 0.0;
};

/// The unit sweep direction a = (1, φ⁻¹, φ⁻²)/|·|, φ the golden ratio (irrational: no two points
/// of a grid in x and y, x and z or y and z share a projection). The points of an n × n grid of
/// spacing s in x and y (or x and z) project at least 0.073 s apart for n = 8, 0.017 s for
/// n = 32, 0.004 s for n = 100; in y and z 0.045 s, 0.011 s, 0.0025 s.
Eigen::Vector3d SweepDirection();

/// Appends to `pairs` every (i, j) of colliders, i < j, whose spheres overlap and that do not
/// belong to the same body nor are both static, in the order of the sweep. Reorders `spheres`
/// (sorted by interval start, stably: SortNearlySorted); `pairs` is neither cleared nor sorted.
/// Allocates only when `pairs` grows past its capacity.
void SweepAndPrune(std::vector<BoundingSphere>* spheres, std::vector<std::pair<int, int>>* pairs);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_BROAD_PHASE_H_
