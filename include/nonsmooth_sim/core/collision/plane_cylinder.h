// Plane–cylinder, closed form. The cylinder has axis u = R_B ẑ, radius r, half-length l, and two
// faces k = 0, 1 with centres f_k = c + s_k l u, s_0 = −1, s_1 = +1 (outward normals s_k u).
// Its lowest point lies on a rim; per face, with n_⊥ = n − (u·n) u the part of the plane's normal
// in the face plane (|n_⊥| = sin of the tilt between face and plane):
//
//   rim point   point_b = f_k − r n_⊥/|n_⊥|    (the face's lowest point),     feature k;
//
// unless the face lies flat: its height varies by 2r|n_⊥| across it, and when
// 2r|n_⊥| ≤ kFlatFaceTolerance the face facing the plane (s_k u·n < 0) gives instead four face
// points (ContactGeometry::face_point)
//
//   point_b = f_k ± ρ e_x, f_k ± ρ e_y,  ρ = 2r/3,                    features 2 + 4k + j,
//
// on the face at the radius 2r/3, the mean distance from the centre of a disc of radius r, i.e.
// the drilling radius R̄ of a uniform pressure over it: spinning, their friction torque is μNρ =
// (2/3)μNr, the uniform pressure's (a coin spinning flat decays at (4/3)μg/r); sliding, μN; and
// they carry a tipping moment up to N·ρ, so a disc lying flat rests without rocking. The four
// share the face's lowest height as their gap (ShareFaceGap: a flat face touches as one, so that
// round-off cannot leave some of them open while the face rests on the others). (One patch
// contact at the face centre with R̄ = 2r/3 gives the same torque but no tipping resistance: a
// disc released 1e-4 rad off flat rocked on it for ever, switching between patch and rim.) A
// flat face facing away from the plane gives nothing (it lies 2l above the opposite face). For every point
// gap = n·(point_b − o_P), point_a = point_b − gap n (plane_contact.h); only points with
// gap ≤ margin are returned, so a cylinder lying on its side (u ⊥ n) gives two rim contacts (the
// ends of its line of contact), a tilted one its lowest rim point, a standing one four face
// points.
// The rim point is smooth in the pose while the face is not flat: a cylinder rolling on its rim
// keeps its feature and a continuous contact point.
#ifndef NONSMOOTH_SIM_CORE_COLLISION_PLANE_CYLINDER_H_
#define NONSMOOTH_SIM_CORE_COLLISION_PLANE_CYLINDER_H_

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/collision/collision.h"

namespace nonsmooth_sim {

/// Drilling radius of a uniform pressure over a disc of radius r: its mean distance from the
/// centre, (1/πr²)∫₀^r ρ 2πρ dρ = 2r/3 [m].
constexpr double DiscPatchRadius(double radius) { return 2.0 * radius / 3.0; }

/// CollideFunction of (plane, cylinder).
int CollidePlaneCylinder(const Shape& plane, const Eigen::Isometry3d& pose_plane,
                         const Shape& cylinder, const Eigen::Isometry3d& pose_cylinder,
                         double margin, ContactGeometry* out);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_PLANE_CYLINDER_H_
