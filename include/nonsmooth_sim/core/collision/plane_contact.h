// The contact of a plane (shape frame P: the half-space z ≤ 0, see shape.h) with a point of the
// other shape's surface, shared by the plane pair functions.
//
//   n = R_P ẑ (world),  gap = n·(point_b − o_P) (the signed height of point_b above the plane),
//   point_a = point_b − gap n (its foot on the plane),  normal = n.
#ifndef NONSMOOTH_SIM_CORE_COLLISION_PLANE_CONTACT_H_
#define NONSMOOTH_SIM_CORE_COLLISION_PLANE_CONTACT_H_

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "nonsmooth_sim/core/collision/collision.h"

namespace nonsmooth_sim {

/// The plane's unit normal in the world, n = R_P ẑ.
inline Eigen::Vector3d PlaneNormal(const Eigen::Isometry3d& pose_plane) {
  return pose_plane.linear().col(2);
}

/// Signed height of a world point above the plane, n·(x − o_P) [m].
inline double PlaneHeight(const Eigen::Isometry3d& pose_plane, const Eigen::Vector3d& x) {
  return PlaneNormal(pose_plane).dot(x - pose_plane.translation());
}

/// The contact at point_b (a point of B's surface, world) with the plane, see the top.
inline ContactGeometry PlaneContact(const Eigen::Isometry3d& pose_plane,
                                    const Eigen::Vector3d& point_b, int feature,
                                    double patch_radius = 0.0) {
  ContactGeometry contact;
  contact.normal = PlaneNormal(pose_plane);
  contact.gap = PlaneHeight(pose_plane, point_b);
  contact.point_b = point_b;
  contact.point_a = point_b - contact.gap * contact.normal;
  contact.feature = feature;
  contact.patch_radius = patch_radius;
  return contact;
}

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_PLANE_CONTACT_H_
