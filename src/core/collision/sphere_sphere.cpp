// Sphere–sphere: the line of centres.
#include "nonsmooth_sim/core/collision/sphere_sphere.h"

#include "nonsmooth_sim/core/collision/closest_points.h"

namespace nonsmooth_sim {

int CollideSphereSphere(const Shape& sphere_a, const Eigen::Isometry3d& pose_a,
                        const Shape& sphere_b, const Eigen::Isometry3d& pose_b, double margin,
                        ContactGeometry* out) {
  const ContactGeometry contact =
      BallContact(pose_a.translation(), sphere_a.radius, pose_b.translation(), sphere_b.radius,
                  /*feature=*/0);
  if (!(contact.gap <= margin)) return 0;
  out[0] = contact;
  return 1;
}

}  // namespace nonsmooth_sim
