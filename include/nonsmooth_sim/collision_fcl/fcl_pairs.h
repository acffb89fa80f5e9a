// Narrow phase by FCL (the Flexible Collision Library 0.7, as MoveIt uses it) for the pairs of
// non-plane shapes that have no closed form in the core: sphere–ellipsoid, sphere–cylinder,
// capsule–ellipsoid, capsule–cylinder, capsule–box, ellipsoid–ellipsoid, ellipsoid–cylinder,
// ellipsoid–box, cylinder–cylinder, cylinder–box, box–box, and a convex hull (a mesh's, shape.h)
// against every shape but the plane (fcl::Convex over the hull's vertices and faces; the
// refinement below also starts from the hull's face normals), and a body of revolution against
// the same (fcl::Convex over the hull of its tessellation for GJK; its supports, below, from its
// smooth profile). A separate library: the core stays
// Eigen-only.
//
// CollideFcl() maps FCL's answers onto ContactGeometry (collision.h). FCL's contact normal points
// from o1 to o2, as ours; its nearest points are in the world frame (both checked in
// test/collision_fcl). PG(n) = min_B n·x − max_A n·y is the gap of the shapes' projections on a
// unit n (from their support functions): PG(n) ≤ the signed distance, with equality for the
// optimal normal.
//  - Penetrating box–box and sphere–cylinder: FCL's own formulas (box–box: its port of ODE's
//    clipping, up to kMaxPairContacts points, feature = FCL's index), each contact at FCL's
//    position p, between the surfaces:
//      gap = −depth,  point_a = p + (depth/2) n,  point_b = p − (depth/2) n.
//  - Penetrating, every other pair: FCL (libccd) answers with MPR, whose normal follows the line
//    of centres rather than the least penetration (measured on shallow contacts: normals off by
//    up to 1 rad, depths wrong by as much as the depth). Its normal only starts a fixed point:
//    B is moved along n_k until PG(n_k) = ε, GJK gives the nearest points p_a, p_b of the
//    separated shapes, n_{k+1} = (p_b − p_a)/|p_b − p_a|. At a fixed point n* B was moved along
//    the normal of the deepest points, which stay the nearest ones. It is started again from the
//    best face normal (a box's axes, a cylinder's axis, a cylinder's barrel normal) when that
//    separates better than the first fixed point; the larger PG wins. One contact, feature 0:
//      gap = PG(n*),  point_b = p_b − (the move),  point_a = point_b − gap n*.
//  - Separated by more than ε: GJK's nearest points (FCL's own GJK, GST_INDEP, tolerance 1e-13:
//    gaps to ~1e-12 m, normals to ~1e-5), returned when the distance ≤ margin:
//      point_a, point_b = the nearest points,  gap = |point_b − point_a|,
//      n = (point_b − point_a)/gap.
//  - Separated by less than ε, or exactly touching (FCL reports no contact, or a zero normal: a
//    cylinder placed exactly on a box): the fixed point above, from the nearest points' direction
//    or the line of centres.
//  - Box–box separated within the margin or touching: FCL's clipping with B moved into A by ε
//    along n, moved back, so that a box resting on a box has its four corners as contacts before
//    it touches as after (BoxBoxManifold in fcl_pairs.cpp).
//  - A hull against a hull or a box, separated within the margin or penetrating, with a face of
//    each along the contact's normal n (within 1e-3 rad): face to face, one point would let a
//    body resting on the other rock about it. B's face is clipped against A's (Sutherland–
//    Hodgman in A's face plane) and each corner of the overlap is a contact, its gap its height
//    above A's face along n, at most kMaxPairContacts (HullManifold in fcl_pairs.cpp).
// ε = kFclRefinementSeparation × the smaller bounding radius. Accuracy, measured in
// test/collision_fcl against the closed forms and the support functions: gaps and consistency
// (|PG(n) − gap|) to ~1e-11 m; where both shapes have edges or rims (cylinder–box, cylinder–
// cylinder, a corner in a barrel) the fixed point can stop at another local optimum, a separating
// direction whose depth is overstated (measured up to 31 % of a 2 mm depth for cylinder–box,
// 4.5 % for cylinder–cylinder); box–box by FCL's clipping overstates by up to 4 % (ODE prefers
// face axes to edge axes).
//
// Unlike the closed forms, CollideFcl allocates (FCL's result vectors, GJK's and MPR's work
// space) and costs 0.4–80 µs a call against 5–45 ns for the closed forms
// (bench/collision_bench.cpp: FCL's GJK takes ~10 µs a call on curved shapes near contact, and a
// refinement makes 2–6). It does not throw and reads no global state but FCL's dispatch tables
// and, for a hull, a per-thread cache of its fcl::Convex (built once per hull: its vertex
// adjacency).
#ifndef NONSMOOTH_SIM_COLLISION_FCL_FCL_PAIRS_H_
#define NONSMOOTH_SIM_COLLISION_FCL_FCL_PAIRS_H_

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/collision/collision_table.h"

namespace nonsmooth_sim {

/// ε of the refinement relative to the smaller bounding radius (see the top): large against
/// GJK's error in the nearest points (~1e-9 m), small against the shapes.
inline constexpr double kFclRefinementSeparation = 1e-2;

/// A CollideFunction for any two non-plane shapes in either order (returns 0 for a plane).
int CollideFcl(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
               const Eigen::Isometry3d& pose_b, double margin, ContactGeometry* out);

/// Registers CollideFcl in `table` for every pair listed at the top (CollisionTable::Register).
/// Pairs with a closed form keep it.
void RegisterFclPairs(CollisionTable* table);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_COLLISION_FCL_FCL_PAIRS_H_
