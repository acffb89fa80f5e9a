// Plane–ellipsoid, closed form. The ellipsoid is x = c + R_B S y, |y| ≤ 1, S = diag(a, b, c);
// its support point in a direction d (ellipsoid frame) maximises d·(S y) over |y| = 1:
//
//   y* = S d/|S d|,  x* = S y* = S² d/|S d|                                      (support)
//
// The lowest point against the plane is the support point along d = −R_Bᵀ n:
//
//   point_b = c + R_B S² d/|S d|,  gap = n·(point_b − o_P),  point_a = point_b − gap n.
//
// |S d| ≥ min(a, b, c) > 0, so the point is smooth in the pose: an ellipsoid rolls with a
// continuous contact point (as a sphere does). One contact, feature 0, when gap ≤ margin.
#ifndef NONSMOOTH_SIM_CORE_COLLISION_PLANE_ELLIPSOID_H_
#define NONSMOOTH_SIM_CORE_COLLISION_PLANE_ELLIPSOID_H_

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/collision/collision.h"

namespace nonsmooth_sim {

/// CollideFunction of (plane, ellipsoid).
int CollidePlaneEllipsoid(const Shape& plane, const Eigen::Isometry3d& pose_plane,
                          const Shape& ellipsoid, const Eigen::Isometry3d& pose_ellipsoid,
                          double margin, ContactGeometry* out);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_PLANE_ELLIPSOID_H_
