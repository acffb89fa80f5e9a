// Closed-form projections: the flat disk and the cylinder C_F (54); the unilateral set, the
// Coulomb disk and the ball S_F (59) are inline in force_sets.h.
// The ellipsoid E_F and the exact set B_F live in prox_ellipsoid.cpp and
// prox_coulomb_contensou.cpp.
#include "nonsmooth_sim/core/force_sets.h"

#include <algorithm>
#include <cmath>

namespace nonsmooth_sim {

Prox3 ProxFlatDisk(const Eigen::Vector3d& x, double radius) {
  const Prox2 disk = ProxDisk(x.head<2>(), radius);
  // interior only if x already lies in the plane Λ_τ = 0
  const bool inside = disk.region == ProxRegion::kInterior && x.z() == 0.0;
  return {Eigen::Vector3d(disk.point.x(), disk.point.y(), 0.0),
          inside ? ProxRegion::kInterior : disk.region == ProxRegion::kApex ? ProxRegion::kApex
                                                                             : ProxRegion::kBoundary};
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
