// The contact of a plane (shape frame P: the half-space z ≤ 0, see shape.h) with a point of the
// other shape's surface, shared by the plane pair functions.
//
//   n = R_P ẑ (world),  gap = n·(point_b − o_P) (the signed height of point_b above the plane),
//   point_a = point_b − gap n (its foot on the plane),  normal = n.
#ifndef NONSMOOTH_SIM_CORE_COLLISION_PLANE_CONTACT_H_
#define NONSMOOTH_SIM_CORE_COLLISION_PLANE_CONTACT_H_

#include <Eigen/Core>
#include <algorithm>
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
                                    bool face_point = false) {
  ContactGeometry contact;
  contact.normal = PlaneNormal(pose_plane);
  contact.gap = PlaneHeight(pose_plane, point_b);
  contact.point_b = point_b;
  contact.point_a = point_b - contact.gap * contact.normal;
  contact.feature = feature;
  contact.face_point = face_point;
  return contact;
}

/// The four points of a face lying flat touch as one: each gets the face's lowest height as its
/// gap (they differ by at most kFlatFaceTolerance), so that round-off cannot leave some of them
/// open while the face rests on the others; point_a follows (point_b − gap n).
inline void ShareFaceGap(ContactGeometry* points, int count) {
  double gap = points[0].gap;
  for (int j = 1; j < count; ++j) gap = std::min(gap, points[j].gap);
  for (int j = 0; j < count; ++j) {
    points[j].gap = gap;
    points[j].point_a = points[j].point_b - gap * points[j].normal;
  }
}

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_PLANE_CONTACT_H_
