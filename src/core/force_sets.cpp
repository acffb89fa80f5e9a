// Closed-form projections: unilateral set, Coulomb disk, ball S_F (59), cylinder C_F (54).
// The ellipsoid E_F and the exact set B_F live in prox_ellipsoid.cpp and
// prox_coulomb_contensou.cpp.
#include "nonsmooth_sim/core/force_sets.h"

#include <algorithm>
#include <cmath>

namespace nonsmooth_sim {

Prox1 ProxNonNegative(double x) {
  // interior: x ≥ 0 is kept
  if (x >= 0.0) return {x, ProxRegion::kInterior};
  // apex: the set's only boundary point 0
  return {0.0, ProxRegion::kApex};
}

Prox2 ProxDisk(const Eigen::Vector2d& x, double radius) {
  // apex: the disk has shrunk to the point 0
  if (!(radius > 0.0)) return {Eigen::Vector2d::Zero(), ProxRegion::kApex};
  const double norm_sq = x.squaredNorm();
  // interior: ||x|| ≤ radius
  if (norm_sq <= radius * radius) return {x, ProxRegion::kInterior};
  // boundary: radial projection (exact for a disk)
  return {x * (radius / std::sqrt(norm_sq)), ProxRegion::kBoundary};
}

Prox3 ProxFlatDisk(const Eigen::Vector3d& x, double radius) {
  const Prox2 disk = ProxDisk(x.head<2>(), radius);
  // interior only if x already lies in the plane Λ_τ = 0
  const bool inside = disk.region == ProxRegion::kInterior && x.z() == 0.0;
  return {Eigen::Vector3d(disk.point.x(), disk.point.y(), 0.0),
          inside ? ProxRegion::kInterior : disk.region == ProxRegion::kApex ? ProxRegion::kApex
                                                                             : ProxRegion::kBoundary};
}

Prox3 ProxBall(const Eigen::Vector3d& x, double radius) {
  // apex: the ball has shrunk to the point 0
  if (!(radius > 0.0)) return {Eigen::Vector3d::Zero(), ProxRegion::kApex};
  const double norm_sq = x.squaredNorm();
  // interior, first case of (59)
  if (norm_sq <= radius * radius) return {x, ProxRegion::kInterior};
  // boundary, second case of (59): μΛ_N x / ||x||
  return {x * (radius / std::sqrt(norm_sq)), ProxRegion::kBoundary};
}

Prox3 ProxCylinder(const Eigen::Vector3d& x, double radius, double rbar) {
  // apex: the cylinder has shrunk to the point 0
  if (!(radius > 0.0)) return {Eigen::Vector3d::Zero(), ProxRegion::kApex};
  // C_F (54) is the product {||Λ_T|| ≤ μΛ_N} × {|Λ_τ| ≤ R̄μΛ_N}: project each factor
  const Prox2 tangential = ProxDisk(x.head<2>(), radius);
  const double half_height = rbar * radius;
  const double tau = std::clamp(x.z(), -half_height, half_height);
  const bool inside = tangential.region == ProxRegion::kInterior && tau == x.z();
  return {Eigen::Vector3d(tangential.point.x(), tangential.point.y(), tau),
          inside ? ProxRegion::kInterior : ProxRegion::kBoundary};
}

}  // namespace nonsmooth_sim
