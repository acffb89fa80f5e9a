// Free bodies that can no longer touch anything, so that a run never loses one silently (a body
// whose collision was skipped falls for ever; one that tunnelled through the ground keeps
// falling): `simulate` warns once per body, the node reports them in /diagnostics (WARN).
//
// A body is lost when it has no collider at all, or when it has fallen more than its size below
// every static collider of the scene, "below" along gravity: past a finite collider's lowest
// point (a floor made of a box, a table, a ledge). A plane never lets a body pass: it is a
// half-space, and a body behind it is in (deep) contact with it, which the gap correction
// resolves; so a scene with a static plane loses only bodies without colliders, and with zero
// gravity only those. Its size is the radius about its centre of mass that holds all its
// colliders. The test is conservative: a body under a table but above the floor is not lost.
#ifndef NONSMOOTH_SIM_WORLD_LOST_BODIES_H_
#define NONSMOOTH_SIM_WORLD_LOST_BODIES_H_

#include <string>
#include <vector>

#include "nonsmooth_sim/core/scene.h"

namespace nonsmooth_sim::world {

struct LostBody {
  enum class Why { kNoCollider, kBelowEveryStaticCollider };
  int body = 0;
  Why why = Why::kNoCollider;
  double size = 0.0;  ///< [m] the radius about S that holds its colliders (below every collider)
};

/// The lost bodies of `scene` in `state` (one per body), in body order.
std::vector<LostBody> FindLostBodies(const Scene& scene, const std::vector<BodyState>& state);

/// "has no collision: it never touches anything" or "is more than its size (0.05 m) below every
/// static collider: fallen off the world, it touches nothing again".
std::string DescribeLostBody(const LostBody& lost);

}  // namespace nonsmooth_sim::world

#endif  // NONSMOOTH_SIM_WORLD_LOST_BODIES_H_
