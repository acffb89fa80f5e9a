// Sphere–box: the closest point of the box, or the nearest exit face when the centre is inside.
#include "nonsmooth_sim/core/collision/sphere_box.h"

#include <cmath>

namespace nonsmooth_sim {

int CollideSphereBox(const Shape& sphere, const Eigen::Isometry3d& pose_sphere, const Shape& box,
                     const Eigen::Isometry3d& pose_box, double margin, ContactGeometry* out) {
  const Eigen::Matrix3d& rotation = pose_box.linear();
  const Eigen::Vector3d& h = box.half_extents;
  const double r = sphere.radius;
  // p = R_Bᵀ(c_a − c_b): the sphere's centre in the box frame
  const Eigen::Vector3d p =
      rotation.transpose() * (pose_sphere.translation() - pose_box.translation());
  // q = clamp(p, −h, h)
  const Eigen::Vector3d q = p.cwiseMax(-h).cwiseMin(h);
  const double distance = (q - p).norm();

  ContactGeometry contact;
  if (distance > 0.0) {
    // outside: n = R_B (q − p)/|q − p|, gap = |q − p| − r
    contact.normal = rotation * ((q - p) / distance);
    contact.gap = distance - r;
    contact.point_b = pose_box * q;
  } else {
    // inside: the nearest exit face j, depth δ = h_j − |p_j|
    int j = 0;
    for (int k = 1; k < 3; ++k) {
      if (h[k] - std::abs(p[k]) < h[j] - std::abs(p[j])) j = k;
    }
    const double sigma = p[j] >= 0.0 ? 1.0 : -1.0;
    const double depth = h[j] - std::abs(p[j]);
    // n = −σ R_B e_j, gap = −(δ + r), q_j = σ h_j
    contact.normal = -sigma * rotation.col(j);
    contact.gap = -(depth + r);
    Eigen::Vector3d exit = p;
    exit[j] = sigma * h[j];
    contact.point_b = pose_box * exit;
  }
  contact.point_a = pose_sphere.translation() + r * contact.normal;
  contact.feature = 0;
  if (!(contact.gap <= margin)) return 0;
  out[0] = contact;
  return 1;
}

}  // namespace nonsmooth_sim
