// Plane–capsule: the support points of the two end spheres.
#include "nonsmooth_sim/core/collision/plane_capsule.h"

#include "nonsmooth_sim/core/collision/plane_contact.h"

namespace nonsmooth_sim {

int CollidePlaneCapsule(const Shape& /*plane*/, const Eigen::Isometry3d& pose_plane,
                        const Shape& capsule, const Eigen::Isometry3d& pose_capsule, double margin,
                        ContactGeometry* out) {
  const Eigen::Vector3d n = PlaneNormal(pose_plane);
  const Eigen::Vector3d axis = pose_capsule.linear().col(2);
  // a capsule of half_length 0 has one end sphere
  const int ends = capsule.half_length > 0.0 ? 2 : 1;
  int count = 0;
  for (int k = 0; k < ends; ++k) {
    // end centre e_k = c ∓ l u, support point e_k − r n
    const double s = k == 0 ? -capsule.half_length : capsule.half_length;
    const Eigen::Vector3d point_b = pose_capsule.translation() + s * axis - capsule.radius * n;
    const ContactGeometry contact = PlaneContact(pose_plane, point_b, /*feature=*/k);
    if (contact.gap <= margin) out[count++] = contact;
  }
  return count;
}

}  // namespace nonsmooth_sim
