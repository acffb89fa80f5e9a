// Closest points on and between segments, and the contact of two balls.
#include "nonsmooth_sim/core/collision/closest_points.h"

#include <algorithm>
#include <cmath>

namespace nonsmooth_sim {

Eigen::Vector3d NormalizedOr(const Eigen::Vector3d& v, const Eigen::Vector3d& fallback) {
  const double norm = v.norm();
  // |v| = 0 also when |v|² underflows (|v| < 1e-154): then v/|v| would not be unit
  if (!(norm > 0.0)) return fallback;
  return v / norm;
}

double ClosestParameterOnSegment(const Eigen::Vector3d& c, const Eigen::Vector3d& u, double l,
                                 const Eigen::Vector3d& p) {
  return std::clamp(u.dot(p - c), -l, l);
}

Eigen::Vector2d ClosestParametersBetweenSegments(const Eigen::Vector3d& c_a,
                                                 const Eigen::Vector3d& u_a, double l_a,
                                                 const Eigen::Vector3d& c_b,
                                                 const Eigen::Vector3d& u_b, double l_b) {
  const Eigen::Vector3d r = c_a - c_b;
  const double beta = u_a.dot(u_b);
  const double ua_r = u_a.dot(r);
  const double ub_r = u_b.dot(r);
  const double denominator = 1.0 - beta * beta;
  // closest points of the lines, s clamped to segment a
  double s = 0.0;
  if (denominator > kParallelDenominator) {
    s = std::clamp((beta * ub_r - ua_r) / denominator, -l_a, l_a);
  }
  // t of the point of b closest to x_a(s): t = u_b·(x_a(s) − c_b)
  double t = ub_r + beta * s;
  if (t < -l_b || t > l_b) {
    // t clamped to segment b, s of the point of a closest to x_b(t)
    t = std::clamp(t, -l_b, l_b);
    s = std::clamp(beta * t - ua_r, -l_a, l_a);
  }
  return {s, t};
}

ContactGeometry BallContact(const Eigen::Vector3d& c_a, double r_a, const Eigen::Vector3d& c_b,
                            double r_b, int feature) {
  const Eigen::Vector3d d = c_b - c_a;
  ContactGeometry contact;
  contact.normal = NormalizedOr(d, DegenerateNormal());
  // gap = |c_b − c_a| − r_a − r_b, along n (also when the centres coincide: |d| = 0)
  contact.gap = contact.normal.dot(d) - r_a - r_b;
  contact.point_a = c_a + r_a * contact.normal;
  contact.point_b = c_b - r_b * contact.normal;
  contact.feature = feature;
  return contact;
}

}  // namespace nonsmooth_sim
