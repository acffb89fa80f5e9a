// Plane–ellipsoid: the exact support point along −n.
#include "nonsmooth_sim/core/collision/plane_ellipsoid.h"

#include "nonsmooth_sim/core/collision/plane_contact.h"

namespace nonsmooth_sim {

int CollidePlaneEllipsoid(const Shape& /*plane*/, const Eigen::Isometry3d& pose_plane,
                          const Shape& ellipsoid, const Eigen::Isometry3d& pose_ellipsoid,
                          double margin, ContactGeometry* out) {
  const Eigen::Matrix3d& rotation = pose_ellipsoid.linear();
  // d = −R_Bᵀ n in the ellipsoid frame
  const Eigen::Vector3d d = -(rotation.transpose() * PlaneNormal(pose_plane));
  // support point S² d/|S d|
  const Eigen::Vector3d s_d = ellipsoid.half_extents.cwiseProduct(d);
  const Eigen::Vector3d support = ellipsoid.half_extents.cwiseProduct(s_d) / s_d.norm();
  const Eigen::Vector3d point_b = pose_ellipsoid.translation() + rotation * support;
  const ContactGeometry contact = PlaneContact(pose_plane, point_b, /*feature=*/0);
  if (!(contact.gap <= margin)) return 0;
  out[0] = contact;
  return 1;
}

}  // namespace nonsmooth_sim
