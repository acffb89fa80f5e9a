// Sphere–sphere, closed form (closest_points.h, BallContact):
//
//   n = (c_b − c_a)/|c_b − c_a|,  gap = |c_b − c_a| − r_a − r_b,
//   point_a = c_a + r_a n,  point_b = c_b − r_b n.
//
// Coincident centres take n = world +z. One contact, feature 0, when gap ≤ margin.
#ifndef NONSMOOTH_SIM_CORE_COLLISION_SPHERE_SPHERE_H_
#define NONSMOOTH_SIM_CORE_COLLISION_SPHERE_SPHERE_H_

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/collision/collision.h"

namespace nonsmooth_sim {

/// CollideFunction of (sphere, sphere).
int CollideSphereSphere(const Shape& sphere_a, const Eigen::Isometry3d& pose_a,
                        const Shape& sphere_b, const Eigen::Isometry3d& pose_b, double margin,
                        ContactGeometry* out);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_SPHERE_SPHERE_H_
