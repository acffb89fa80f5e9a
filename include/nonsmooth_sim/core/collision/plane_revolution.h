// Plane–body of revolution, closed form. The body (shape.h, revolution_profile.h) has its axis
// along z of its frame B (pose R_B, o_B); d = −R_Bᵀ n is the direction of the plane's normal into
// the body, split into u(θ) = (sin θ, cos θ), θ its angle from the axis, and its azimuth ê
// (SplitDirection; no trigonometry: u is d's horizontal length and height, normalised).
//
//   support     point_b = o_B + R_B (ρ(θ) ê + z(θ) ẑ),  (ρ, z)(θ) = c_k + r_k u(θ) on the arc k
//               whose normals hold θ,                                      feature 0;
//
// smooth in the pose across the arcs (the profile is G1). Where the arc k meets a straight
// stretch of the profile (a cone's or a cylinder's side, or a flat disc at a pole), the stretch's
// far end touches too when it comes within the margin (a cone lying on its side rests on both
// ends of its line of contact, as a cylinder's two rim points, plane_cylinder.h):
//
//   far end     point_b = o_B + R_B (its (ρ, z) at ê; a disc's: at −ê),
//               feature 1 + 2k (the stretch before arc k), 2 + 2k (after).
//
// A flat disc at a pole facing the plane and lying flat (2 ρ_d sin θ ≤ kFlatFaceTolerance) gives
// four face points at the disc's uniform-pressure radius 2ρ_d/3 instead (as a cylinder's face,
// plane_cylinder.h), features 2K + 3 + j (K arcs), sharing the lowest gap. For every point
// gap = n·(point_b − o_P), point_a = point_b − gap n (plane_contact.h); points with gap > margin
// are not returned.
#ifndef NONSMOOTH_SIM_CORE_COLLISION_PLANE_REVOLUTION_H_
#define NONSMOOTH_SIM_CORE_COLLISION_PLANE_REVOLUTION_H_

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/collision/collision.h"

namespace nonsmooth_sim {

/// CollideFunction of (plane, revolution).
int CollidePlaneRevolution(const Shape& plane, const Eigen::Isometry3d& pose_plane,
                           const Shape& body, const Eigen::Isometry3d& pose_body, double margin,
                           ContactGeometry* out);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_PLANE_REVOLUTION_H_
