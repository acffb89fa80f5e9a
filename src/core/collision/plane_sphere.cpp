// Plane–sphere: the sphere's support point along −n.
#include "nonsmooth_sim/core/collision/plane_sphere.h"

#include "nonsmooth_sim/core/collision/plane_contact.h"

namespace nonsmooth_sim {

int CollidePlaneSphere(const Shape& /*plane*/, const Eigen::Isometry3d& pose_plane,
                       const Shape& sphere, const Eigen::Isometry3d& pose_sphere, double margin,
                       ContactGeometry* out) {
  // point_b = c − r n
  const Eigen::Vector3d point_b =
      pose_sphere.translation() - sphere.radius * PlaneNormal(pose_plane);
  const ContactGeometry contact = PlaneContact(pose_plane, point_b, /*feature=*/0);
  if (!(contact.gap <= margin)) return 0;
  out[0] = contact;
  return 1;
}

}  // namespace nonsmooth_sim
