// Sphere–capsule: the closest point of the capsule's core segment.
#include "nonsmooth_sim/core/collision/sphere_capsule.h"

#include "nonsmooth_sim/core/collision/closest_points.h"

namespace nonsmooth_sim {

int CollideSphereCapsule(const Shape& sphere, const Eigen::Isometry3d& pose_sphere,
                         const Shape& capsule, const Eigen::Isometry3d& pose_capsule, double margin,
                         ContactGeometry* out) {
  const Eigen::Vector3d& c_a = pose_sphere.translation();
  const Eigen::Vector3d& c_b = pose_capsule.translation();
  const Eigen::Vector3d u = pose_capsule.linear().col(2);
  // q = c_b + s u, s = clamp(u·(c_a − c_b), −l, l)
  const double s = ClosestParameterOnSegment(c_b, u, capsule.half_length, c_a);
  const ContactGeometry contact =
      BallContact(c_a, sphere.radius, c_b + s * u, capsule.radius, /*feature=*/0);
  if (!(contact.gap <= margin)) return 0;
  out[0] = contact;
  return 1;
}

}  // namespace nonsmooth_sim
