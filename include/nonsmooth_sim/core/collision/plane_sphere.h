// Plane–sphere, closed form. With n the plane's normal and c the sphere's centre:
//
//   point_b = c − r n  (the sphere's support point along −n),
//   gap = n·(c − o_P) − r,  point_a = point_b − gap n  (plane_contact.h).
//
// One contact, feature 0, returned when gap ≤ margin. The point is smooth in the pose.
#ifndef NONSMOOTH_SIM_CORE_COLLISION_PLANE_SPHERE_H_
#define NONSMOOTH_SIM_CORE_COLLISION_PLANE_SPHERE_H_

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/collision/collision.h"

namespace nonsmooth_sim {

/// CollideFunction of (plane, sphere).
int CollidePlaneSphere(const Shape& plane, const Eigen::Isometry3d& pose_plane, const Shape& sphere,
                       const Eigen::Isometry3d& pose_sphere, double margin, ContactGeometry* out);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_PLANE_SPHERE_H_
