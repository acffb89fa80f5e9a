// A mesh that is a body of revolution, as the smooth convex body its profile describes (shape.h,
// revolution_profile.h): a faceted hull rolls as a polygon, which a top must not (docs/urdf.md,
// "Bodies of revolution").
//
// The axis: the given direction through the centroid of the vertices' convex hull H (every
// vertex counted, no cap; a body of revolution's centroid lies on its axis). The profile: the
// (ρ, z) of H's vertices about that axis, rounded within τ/2 (MakeRevolutionProfile). The
// check, both ways:
//   - every vertex of H lies within τ of the fitted surface (in its meridian plane: the distance
//     to the profile's boundary, from its support function on 513 normal angles);
//   - the support functions of H and of the fitted body differ by at most τ on 33 × 37
//     directions (normal angle × azimuth; over all directions that difference is the Hausdorff
//     distance of two convex bodies).
// The largest of these distances is the fit's deviation; above τ the mesh is refused. A UV
// mesh of M sectors deviates by ρ(1 − cos(π/M)) between its vertices (M = 48: 0.2 % of ρ).
//
// The shape's tessellation (for the pairs FCL collides, fcl_pairs.h): the profile at 64 normal
// angles and at the ends of its straight stretches longer than 1/64 of it, each at
// kRevolutionSectors azimuths (fewer if that made more than 4096 points), hulled.
#ifndef NONSMOOTH_SIM_MESH_MESH_REVOLUTION_H_
#define NONSMOOTH_SIM_MESH_MESH_REVOLUTION_H_

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "nonsmooth_sim/core/shape.h"

namespace nonsmooth_sim::mesh {

inline constexpr int kRevolutionSectors = 48;
/// The default τ as a fraction of the hull's bounding radius about its centroid.
inline constexpr double kDefaultRevolutionTolerance = 0.01;

struct BodyOfRevolution {
  Shape shape;  ///< revolution: its profile and tessellation, in its frame
  /// its frame (origin at the centroid, z along the axis) in the points' frame
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  double deviation = 0.0;  ///< the largest distance between H and the fitted surface [m]
  double tolerance = 0.0;  ///< τ [m]
};

/// The body of revolution about `axis` (any length > 0) fitted to `points` within `tolerance`
/// (> 0 [m]; unset: kDefaultRevolutionTolerance of the hull's size). Throws std::invalid_argument
/// with one line: the hull's errors (HullOfPoints), a zero or non-finite axis, a non-positive
/// tolerance, or "is not a body of revolution about ... within ...: ..." with the deviation and
/// where it is largest.
BodyOfRevolution FitBodyOfRevolution(const std::vector<Eigen::Vector3d>& points,
                                     const Eigen::Vector3d& axis,
                                     std::optional<double> tolerance);

/// The centroid of the hull's volume [m].
Eigen::Vector3d HullCentroid(const ConvexHull& hull);

}  // namespace nonsmooth_sim::mesh

#endif  // NONSMOOTH_SIM_MESH_MESH_REVOLUTION_H_
