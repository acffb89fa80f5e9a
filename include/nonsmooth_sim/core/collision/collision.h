// Narrow phase: one pure function per pair of shape types, chosen from a [type][type] table (as
// MuJoCo's mjCOLLISIONFUNC and Bullet's dispatcher; the table is collision_table.h). Each pair
// function lives in its own file pair under src/core/collision/ with its own test; a new pair is
// one function plus one line of registration (CollisionTable::Defaults, collision_table.cpp).
//
// A pair function receives the two shapes in ShapeType order (a.type ≤ b.type) with their world
// poses and returns up to kMaxPairContacts contact points. For each point:
//   gap      signed distance between the surfaces along the normal [m] (< 0: penetration);
//   point_a  the point of A's surface that is deepest in / closest to B (world) [m];
//   point_b  the point of B's surface that is deepest in / closest to A (world) [m];
//   normal   unit, world, from A towards B:  point_b - point_a = gap · normal;
//   feature  an id of the touching features, stable while the same features touch (a box corner,
//            a cylinder rim or face, a capsule end): contacts and their warm starts and tangent
//            frames are carried from step to step by (collider pair, feature);
//   face_point  true for one of the four points that stand for a face lying flat on a plane (a
//            surface contact, plane_cylinder.h, plane_box.h): they sit on the face at its
//            uniform-pressure drilling radius R̄ (a disc of radius r: 2r/3), so that together
//            they carry the friction torque of the face (μNR̄ spinning, μN sliding) and resist
//            tipping; such a point has no drilling component of its own. false: a point contact,
//            whose R̄ comes from its law.
// Points whose gap exceeds `margin` need not be returned (a pair function may return them).
// A pair function never allocates, never throws and never reads global state.
#ifndef NONSMOOTH_SIM_CORE_COLLISION_COLLISION_H_
#define NONSMOOTH_SIM_CORE_COLLISION_COLLISION_H_

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "nonsmooth_sim/core/shape.h"

namespace nonsmooth_sim {

inline constexpr int kMaxPairContacts = 8;

struct ContactGeometry {
  double gap = 0.0;
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d point_b = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  int feature = 0;
  bool face_point = false;
};

/// Shapes a, b in ShapeType order, poses shape frame → world; writes at most kMaxPairContacts
/// entries of `out` and returns how many.
using CollideFunction = int (*)(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                                const Eigen::Isometry3d& pose_b, double margin,
                                ContactGeometry* out);

/// Tolerance on the height difference across a face below which the face lies flat on a plane
/// and becomes a face contact (four face points) [m]: see collision/plane_cylinder.h and
/// plane_box.h.
inline constexpr double kFlatFaceTolerance = 1e-6;

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_COLLISION_H_
