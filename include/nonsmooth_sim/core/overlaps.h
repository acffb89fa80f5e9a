// Colliders that overlap in a given state: the check a scene gets before it runs (an overlap at
// the start is resolved by the first steps, as a penetration, but a deep one is usually a scene
// error the user wants to hear about).
#ifndef NONSMOOTH_SIM_CORE_OVERLAPS_H_
#define NONSMOOTH_SIM_CORE_OVERLAPS_H_

#include <vector>

#include "nonsmooth_sim/core/scene.h"

namespace nonsmooth_sim {

/// Penetration below which an overlap at the start is not worth a warning [m]: the gap
/// correction's slop (simulator.h) and the round-off of a pose written in a file.
inline constexpr double kOverlapWarningDepth = 1e-6;

struct Overlap {
  int collider_a = 0;  ///< index into Scene::colliders, a < b
  int collider_b = 0;
  double depth = 0.0;  ///< deepest penetration of the pair [m], > 0
};

/// Every pair of colliders (on different bodies, or a body and a static collider) that
/// penetrates deeper than `min_depth` in `state`. O(colliders²): for a check before a run, not
/// for stepping. Pairs without a function in the scene's collision table are skipped.
std::vector<Overlap> FindOverlaps(const Scene& scene, const std::vector<BodyState>& state,
                                  double min_depth);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_OVERLAPS_H_
