// Plane–convex hull, closed form. The hull (shape.h, ConvexHull) has vertices v_i and faces f in
// its frame H (pose R_H, o_H); m = R_Hᵀ n is the plane's normal in H and a vertex's height above
// the plane is n·(o_H + R_H v_i − o_P).
//
// The face facing the plane is the one whose outward normal is most opposite to n,
// f* = argmin_f ν_f·m (the first on ties). Its height varies by max − min of m·v over its
// vertices; when that is ≤ kFlatFaceTolerance it lies flat and, as a box's face (plane_box.h),
// gives face points (ContactGeometry::face_point) instead of its vertices: one towards each of its
// vertices p_k (up to kMaxHullFacePoints of them, evenly spaced around the face), at the face's
// uniform-pressure drilling radius R̄_f (ConvexHull::face_patch_radius) from its centroid c_f,
//
//   face point  point_b = o_H + R_H (c_f + min(R̄_f, |p_k − c_f|) (p_k − c_f)/|p_k − c_f|),
//               feature = V + kMaxHullFacePoints f* + j   (V = the number of vertices),
//
// so that spinning their friction torque is μNR̄ (the uniform pressure's), sliding μN, and they
// resist tipping inside the face; they share the face's lowest height as their gap
// (ShareFaceGap). For a rectangle they are the box's face points.
//
// Otherwise (and for the vertices off a flat face) the support vertices: every vertex with
// gap ≤ margin, the lowest first, at most kMaxPairContacts in all:
//
//   vertex      point_b = o_H + R_H v_i,   feature i.
//
// For every point gap = n·(point_b − o_P), point_a = point_b − gap n (plane_contact.h).
//
// The search walks the hull's edges (ConvexHull::neighbours): steepest descent from vertex 0 to
// the lowest vertex (a linear function on a convex polyhedron has no other local minimum), then
// the vertices within the margin by their neighbours (its sublevel set is connected along the
// edges), and f* among their faces (a face with no vertex within the margin cannot touch). The
// contacts are those of scanning every vertex and face, bit for bit (plane_hull_walk_test), at
// a cost that grows with what is near the plane: the Tippe-Top as a 256-vertex hull, 88 814 →
// 12 599 instructions per step (docs/urdf.md). A hull whose edges do not reach every vertex is
// scanned.
#ifndef NONSMOOTH_SIM_CORE_COLLISION_PLANE_HULL_H_
#define NONSMOOTH_SIM_CORE_COLLISION_PLANE_HULL_H_

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/collision/collision.h"

namespace nonsmooth_sim {

/// Face points of a flat face of a hull, at most (a box's face has 4; a hexagon 6; the other
/// kMaxPairContacts − 6 slots stay for the lowest vertices off the face).
inline constexpr int kMaxHullFacePoints = 6;

/// CollideFunction of (plane, convex_hull).
int CollidePlaneHull(const Shape& plane, const Eigen::Isometry3d& pose_plane, const Shape& hull,
                     const Eigen::Isometry3d& pose_hull, double margin, ContactGeometry* out);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_PLANE_HULL_H_
