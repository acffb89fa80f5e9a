// The prox of the rolling-resistance sets in the mapped coordinates (prox_rolling.h).
#include "nonsmooth_sim/core/prox_rolling.h"

#include <cmath>

namespace nonsmooth_sim {

Prox5 ProxRollingBall(const Vector5d& x, double radius) {
  // apex: the ball has shrunk to the point 0
  if (!(radius > 0.0)) return {Vector5d::Zero(), ProxRegion::kApex};
  const double norm_sq = x.squaredNorm();
  // interior, first case of (59)
  if (norm_sq <= radius * radius) return {x, ProxRegion::kInterior};
  // boundary, second case of (59): μΛ_N x / ||x||
  return {x * (radius / std::sqrt(norm_sq)), ProxRegion::kBoundary};
}

Prox5 ProxRollingDecoupled(const Vector5d& x, double radius) {
  // apex: both factors have shrunk to the point 0
  if (!(radius > 0.0)) return {Vector5d::Zero(), ProxRegion::kApex};
  // a product set: each factor projected on its own, S_F by (59) and the rolling disk
  const Prox3 friction = ProxBall(x.head<3>(), radius);
  const Prox2 rolling = ProxDisk(x.tail<2>(), radius);
  Prox5 result;
  result.point << friction.point, rolling.point;
  const bool inside =
      friction.region == ProxRegion::kInterior && rolling.region == ProxRegion::kInterior;
  result.region = inside ? ProxRegion::kInterior : ProxRegion::kBoundary;
  return result;
}

}  // namespace nonsmooth_sim
