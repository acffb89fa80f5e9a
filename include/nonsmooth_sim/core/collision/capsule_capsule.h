// Capsule–capsule, closed form: two balls of the capsules' radii centred at closest points of
// their core segments (c_a + s u_a, c_b + t u_b; closest_points.h):
//
//   general    (s, t) = ClosestParametersBetweenSegments(...),   one contact, feature 0;
//   parallel   the cores overlap over [s₀, s₁] (A's parameter) along L = s₁ − s₀ and
//              L·sin θ ≤ kFlatFaceTolerance (θ the angle between the axes: the distance between
//              the cores varies by less than the tolerance along the overlap): one contact at
//              each end of the overlap, s = s₀ (feature 1) and s = s₁ (feature 2), each with t
//              the closest point of B's core to c_a + s u_a.
//
// For each, with p and q the two core points: n = (q − p)/|q − p|, gap = |q − p| − r_a − r_b,
// point_a = p + r_a n, point_b = q − r_b n (BallContact; cores that cross take n = world +z).
// Two contacts keep a capsule lying along another from rocking on one point; an overlap shorter
// than kFlatFaceTolerance is one point. Contacts with gap ≤ margin are returned.
#ifndef NONSMOOTH_SIM_CORE_COLLISION_CAPSULE_CAPSULE_H_
#define NONSMOOTH_SIM_CORE_COLLISION_CAPSULE_CAPSULE_H_

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/collision/collision.h"

namespace nonsmooth_sim {

/// CollideFunction of (capsule, capsule).
int CollideCapsuleCapsule(const Shape& capsule_a, const Eigen::Isometry3d& pose_a,
                          const Shape& capsule_b, const Eigen::Isometry3d& pose_b, double margin,
                          ContactGeometry* out);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_CAPSULE_CAPSULE_H_
