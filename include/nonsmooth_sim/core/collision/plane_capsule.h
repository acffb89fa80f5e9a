// Plane–capsule, closed form: the plane against each of the capsule's two end spheres, centres
// e_k = c ∓ l u (u = R_B ẑ the capsule's axis; k = 0 at −l, k = 1 at +l):
//
//   point_b = e_k − r n,  gap = n·(e_k − o_P) − r,  point_a = point_b − gap n  (plane_contact.h).
//
// Every end whose gap ≤ margin is returned, feature k: a capsule lying flat (u ⊥ n) gives two
// contacts, the ends of its line of contact; a tilted one gives its lower end. The lower end's
// point is the capsule's lowest point (the height along the core is linear in s), on its surface;
// the upper end's lies on its end sphere, inside the capsule by r(1 − cos β) for an axis tilted by
// β from the plane (negligible where it is returned: near flat, where its gap is within margin).
// A capsule of half_length 0 is a sphere and gives one contact, feature 0.
#ifndef NONSMOOTH_SIM_CORE_COLLISION_PLANE_CAPSULE_H_
#define NONSMOOTH_SIM_CORE_COLLISION_PLANE_CAPSULE_H_

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/collision/collision.h"

namespace nonsmooth_sim {

/// CollideFunction of (plane, capsule).
int CollidePlaneCapsule(const Shape& plane, const Eigen::Isometry3d& pose_plane,
                        const Shape& capsule, const Eigen::Isometry3d& pose_capsule, double margin,
                        ContactGeometry* out);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_PLANE_CAPSULE_H_
