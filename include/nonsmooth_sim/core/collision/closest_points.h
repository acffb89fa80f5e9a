// Closest points shared by the pair functions of round shapes (sphere, capsule): on a segment,
// between two segments, and the contact of two balls.
//
// A segment is written as centre c, unit direction u and half-length l ≥ 0: x(s) = c + s u,
// s ∈ [−l, l] (a capsule's core, see shape.h).
#ifndef NONSMOOTH_SIM_CORE_COLLISION_CLOSEST_POINTS_H_
#define NONSMOOTH_SIM_CORE_COLLISION_CLOSEST_POINTS_H_

#include <Eigen/Core>

#include "nonsmooth_sim/core/collision/collision.h"

namespace nonsmooth_sim {

/// v/|v|, or `fallback` when |v| is zero or underflows (coincident centres: the direction is
/// undefined and any unit vector is as good as another).
Eigen::Vector3d NormalizedOr(const Eigen::Vector3d& v, const Eigen::Vector3d& fallback);

/// The normal chosen when two centres coincide: world +z.
inline Eigen::Vector3d DegenerateNormal() { return Eigen::Vector3d::UnitZ(); }

/// Parameter s ∈ [−l, l] of the point of the segment (c, u, l) closest to p: clamp(u·(p − c)).
double ClosestParameterOnSegment(const Eigen::Vector3d& c, const Eigen::Vector3d& u, double l,
                                 const Eigen::Vector3d& p);

/// Parameters (s, t) of a pair of closest points of the segments (c_a, u_a, l_a) and
/// (c_b, u_b, l_b). With r = c_a − c_b, β = u_a·u_b, the lines' closest points solve
///   s − β t = −u_a·r,   β s − t = −u_b·r   ⇒   s = (β u_b·r − u_a·r) / (1 − β²),  t = u_b·r + β s;
/// s is clamped to [−l_a, l_a], then t to [−l_b, l_b] and s recomputed from the clamped t
/// (Ericson, Real-Time Collision Detection, 5.1.9). For (near-)parallel segments, 1 − β² below
/// kParallelDenominator, s starts from 0: every s of the overlap is then a closest point.
Eigen::Vector2d ClosestParametersBetweenSegments(const Eigen::Vector3d& c_a,
                                                 const Eigen::Vector3d& u_a, double l_a,
                                                 const Eigen::Vector3d& c_b,
                                                 const Eigen::Vector3d& u_b, double l_b);
/// 1 − (u_a·u_b)² = sin²θ below which the formula above starts from s = 0 (θ < 1e-6 rad: the
/// division would only amplify round-off, and the clamping steps find the closest pair).
inline constexpr double kParallelDenominator = 1e-12;

/// The contact of the ball (centre c_a, radius r_a) with the ball (c_b, r_b):
///   n = (c_b − c_a)/|c_b − c_a| (DegenerateNormal() if the centres coincide),
///   gap = |c_b − c_a| − r_a − r_b,  point_a = c_a + r_a n,  point_b = c_b − r_b n.
ContactGeometry BallContact(const Eigen::Vector3d& c_a, double r_a, const Eigen::Vector3d& c_b,
                            double r_b, int feature);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_CLOSEST_POINTS_H_
