// Sphere–capsule, closed form: the sphere (centre c_a) against the ball of the capsule's radius
// centred at the point of its core segment closest to c_a (closest_points.h),
//
//   q = c_b + s u,  s = clamp(u·(c_a − c_b), −l, l),  u = R_B ẑ,
//   n = (q − c_a)/|q − c_a|,  gap = |q − c_a| − r_a − r_b,
//   point_a = c_a + r_a n,  point_b = q − r_b n.
//
// q is continuous in the poses, so one feature covers the side and both end caps: one contact,
// feature 0, when gap ≤ margin. A sphere centre on the core takes n = world +z.
#ifndef NONSMOOTH_SIM_CORE_COLLISION_SPHERE_CAPSULE_H_
#define NONSMOOTH_SIM_CORE_COLLISION_SPHERE_CAPSULE_H_

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/collision/collision.h"

namespace nonsmooth_sim {

/// CollideFunction of (sphere, capsule).
int CollideSphereCapsule(const Shape& sphere, const Eigen::Isometry3d& pose_sphere,
                         const Shape& capsule, const Eigen::Isometry3d& pose_capsule, double margin,
                         ContactGeometry* out);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_SPHERE_CAPSULE_H_
