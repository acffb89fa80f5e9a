// Sphere–box, closed form. In the box frame (half-extents h), with p = R_Bᵀ(c_a − c_b) the sphere's
// centre:
//
//   outside (some |p_j| > h_j): q = clamp(p, −h, h) the closest point of the box,
//     n = R_B (q − p)/|q − p|,  gap = |q − p| − r,  point_b = c_b + R_B q;
//   inside (|p_j| ≤ h_j for all j): the exit face is the nearest one, j = argmin_j (h_j − |p_j|)
//     (first on ties), σ = sign(p_j) (+ at 0), depth δ = h_j − |p_j| ≥ 0:
//     n = −σ R_B e_j,  gap = −(δ + r),  point_b = c_b + R_B q, q = p with q_j = σ h_j;
//
// and point_a = c_a + r n (the sphere's point deepest in / closest to the box). Both branches
// give n = −σ R_B e_j and gap = −r on a face, so the result is continuous as the centre crosses
// the surface; inside, the exit face can switch (where two faces are equally near). One contact,
// feature 0, when gap ≤ margin.
#ifndef NONSMOOTH_SIM_CORE_COLLISION_SPHERE_BOX_H_
#define NONSMOOTH_SIM_CORE_COLLISION_SPHERE_BOX_H_

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/collision/collision.h"

namespace nonsmooth_sim {

/// CollideFunction of (sphere, box).
int CollideSphereBox(const Shape& sphere, const Eigen::Isometry3d& pose_sphere, const Shape& box,
                     const Eigen::Isometry3d& pose_box, double margin, ContactGeometry* out);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_SPHERE_BOX_H_
