// Capsule–capsule: closest points of the core segments; the ends of the overlap when parallel.
#include "nonsmooth_sim/core/collision/capsule_capsule.h"

#include <algorithm>

#include "nonsmooth_sim/core/collision/closest_points.h"

namespace nonsmooth_sim {

int CollideCapsuleCapsule(const Shape& capsule_a, const Eigen::Isometry3d& pose_a,
                          const Shape& capsule_b, const Eigen::Isometry3d& pose_b, double margin,
                          ContactGeometry* out) {
  const Eigen::Vector3d& c_a = pose_a.translation();
  const Eigen::Vector3d& c_b = pose_b.translation();
  const Eigen::Vector3d u_a = pose_a.linear().col(2);
  const Eigen::Vector3d u_b = pose_b.linear().col(2);
  const double l_a = capsule_a.half_length;
  const double l_b = capsule_b.half_length;

  // overlap [s₀, s₁] of the cores along A's axis: B's ends projected onto it, clamped to A
  const double t_minus = u_a.dot(c_b - l_b * u_b - c_a);
  const double t_plus = u_a.dot(c_b + l_b * u_b - c_a);
  const double s0 = std::max(-l_a, std::min(t_minus, t_plus));
  const double s1 = std::min(l_a, std::max(t_minus, t_plus));
  const double overlap = s1 - s0;
  const double sin_theta = u_a.cross(u_b).norm();

  int count = 0;
  if (overlap > kFlatFaceTolerance && overlap * sin_theta <= kFlatFaceTolerance) {
    // parallel: one contact at each end of the overlap, features 1 and 2
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector3d p = c_a + (k == 0 ? s0 : s1) * u_a;
      const double t = ClosestParameterOnSegment(c_b, u_b, l_b, p);
      const ContactGeometry contact =
          BallContact(p, capsule_a.radius, c_b + t * u_b, capsule_b.radius, /*feature=*/1 + k);
      if (contact.gap <= margin) out[count++] = contact;
    }
    return count;
  }
  // general: the closest points of the cores, feature 0
  const Eigen::Vector2d st = ClosestParametersBetweenSegments(c_a, u_a, l_a, c_b, u_b, l_b);
  const ContactGeometry contact = BallContact(c_a + st[0] * u_a, capsule_a.radius,
                                              c_b + st[1] * u_b, capsule_b.radius, /*feature=*/0);
  if (contact.gap <= margin) out[count++] = contact;
  return count;
}

}  // namespace nonsmooth_sim
