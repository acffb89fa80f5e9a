// A mesh as a smooth body of revolution: the axis through its hull's centroid, the profile of its
// vertices, the check both ways. See mesh_revolution.h.
#include "nonsmooth_sim/mesh/mesh_revolution.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/mesh/mesh_hull.h"

namespace nonsmooth_sim::mesh {
namespace {

constexpr int kCheckAngles = 512;      // normal angles of the vertices' check
constexpr int kSupportAngles = 32;     // the support functions' check: normal angles
constexpr int kSupportAzimuths = 37;   // and azimuths (prime: off any mesh's sectors)
constexpr int kTessellationAngles = 64;

std::string Vector(const Eigen::Vector3d& v) {
  std::ostringstream s;
  s.precision(6);
  s << v.x() << " " << v.y() << " " << v.z();
  return s.str();
}

// The profile's (ρ, z) along its length for the tessellation: 64 normal angles, both ends of
// every straight stretch longer than 1/64 of the profile, and the polar discs' rims.
std::vector<Eigen::Vector2d> TessellationProfile(const RevolutionProfile& profile) {
  std::vector<Eigen::Vector2d> points;
  double length = 0.0, begin = 0.0;
  for (const RevolutionArc& arc : profile.arcs) {
    length += arc.radius * (arc.theta_end - begin) + arc.stretch;
    begin = arc.theta_end;
  }
  for (int j = 0; j <= kTessellationAngles; ++j) {
    points.push_back(ProfilePoint(profile, kPi * j / kTessellationAngles));
  }
  const int arcs = static_cast<int>(profile.arcs.size());
  for (int k = 0; k + 1 < arcs; ++k) {
    if (!(profile.arcs[k].stretch > length / kTessellationAngles)) continue;
    points.push_back(ArcEnd(profile, k));
    points.push_back(ArcStart(profile, k + 1));
  }
  points.push_back(ArcStart(profile, 0));
  points.push_back(ArcEnd(profile, arcs - 1));
  points.emplace_back(0.0, profile.top_z);
  points.emplace_back(0.0, profile.bottom_z);
  return points;
}

}  // namespace

Eigen::Vector3d HullCentroid(const ConvexHull& hull) {
  const Eigen::Vector3d& o = hull.vertices[0];
  double six_volume = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  for (int f = 0; f < hull.face_count; ++f) {
    const int start = hull.face_start[f];
    const int count = hull.faces[start];
    const Eigen::Vector3d& a = hull.vertices[hull.faces[start + 1]];
    for (int k = 1; k + 1 < count; ++k) {
      const Eigen::Vector3d& b = hull.vertices[hull.faces[start + 1 + k]];
      const Eigen::Vector3d& c = hull.vertices[hull.faces[start + 2 + k]];
      const double v = (a - o).dot((b - o).cross(c - o));
      six_volume += v;
      moment += v * (o + a + b + c) / 4.0;
    }
  }
  return moment / six_volume;
}

BodyOfRevolution FitBodyOfRevolution(const std::vector<Eigen::Vector3d>& points,
                                     const Eigen::Vector3d& axis,
                                     std::optional<double> tolerance) {
  if (!axis.allFinite() || !(axis.norm() > 0.0)) {
    throw std::invalid_argument("axis (" + Vector(axis) + ") is not a direction; allowed: three "
                                "finite numbers, not all 0");
  }
  // every vertex counts (no cap): a fine mesh's capped hull would be a subset's
  const std::shared_ptr<const ConvexHull> hull = FullHullOfPoints(points);
  BodyOfRevolution result;
  // the frame: z along the axis, origin at the hull's centroid
  const Eigen::Vector3d z = axis.normalized();
  const Eigen::Vector3d x = z.unitOrthogonal();
  result.frame.linear() << x, z.cross(x), z;
  result.frame.translation() = HullCentroid(*hull);
  const Eigen::Isometry3d to_shape = result.frame.inverse();
  std::vector<Eigen::Vector3d> vertices;  // the hull's, in the shape frame
  double size = 0.0;
  for (const Eigen::Vector3d& v : hull->vertices) {
    vertices.push_back(to_shape * v);
    size = std::max(size, vertices.back().norm());
  }
  result.tolerance = tolerance.value_or(kDefaultRevolutionTolerance * size);
  if (!(std::isfinite(result.tolerance) && result.tolerance > 0.0)) {
    throw std::invalid_argument("tolerance " + std::to_string(result.tolerance) +
                                " m: allowed: finite, > 0");
  }
  // (every point inside the hull lies inside the body its vertices' profile describes)
  std::vector<Eigen::Vector2d> meridian;
  for (const Eigen::Vector3d& q : vertices) meridian.emplace_back(q.head<2>().norm(), q.z());
  const std::shared_ptr<const RevolutionProfile> profile =
      MakeRevolutionProfile(meridian, 0.5 * result.tolerance);

  Eigen::Vector3d worst = Eigen::Vector3d::Zero();
  const auto consider = [&](double distance, const Eigen::Vector3d& where) {
    if (distance > result.deviation) result.deviation = distance, worst = result.frame * where;
  };
  // the hull's vertices against the fitted surface, in their meridian planes
  std::vector<Eigen::Vector2d> u(kCheckAngles + 1);
  std::vector<double> h(kCheckAngles + 1);
  for (int j = 0; j <= kCheckAngles; ++j) {
    const double theta = kPi * j / kCheckAngles;
    u[j] = Eigen::Vector2d(std::sin(theta), std::cos(theta));
    h[j] = u[j].dot(ProfilePoint(*profile, theta));
  }
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    double outside = -INFINITY, inside = INFINITY;
    for (int j = 0; j <= kCheckAngles; ++j) {
      const double s = meridian[i].dot(u[j]) - h[j];
      outside = std::max(outside, s);
      inside = std::min(inside, -s);
    }
    consider(outside > 0.0 ? outside : inside, vertices[i]);
  }
  // the fitted surface against the hull: their support functions on a grid of directions
  for (int j = 0; j <= kSupportAngles; ++j) {
    const double theta = kPi * j / kSupportAngles;
    const Eigen::Vector2d rho_z = ProfilePoint(*profile, theta);
    for (int k = 0; k < kSupportAzimuths; ++k) {
      const double phi = 2.0 * kPi * k / kSupportAzimuths;
      const Eigen::Vector3d radial(std::cos(phi), std::sin(phi), 0.0);
      const Eigen::Vector3d normal = std::sin(theta) * radial + std::cos(theta) * Eigen::Vector3d::UnitZ();
      const Eigen::Vector3d on_surface = AtAzimuth(rho_z, radial);
      double mesh = -INFINITY;
      for (const Eigen::Vector3d& q : vertices) mesh = std::max(mesh, normal.dot(q));
      consider(std::abs(normal.dot(on_surface) - mesh), on_surface);
    }
  }
  if (!(result.deviation <= result.tolerance)) {
    std::ostringstream s;
    s.precision(3);
    s << "is not a body of revolution about the axis (" << Vector(z)
      << ") through its centroid (" << Vector(result.frame.translation())
      << ") within the tolerance " << result.tolerance << " m: the fitted surface and the mesh's "
      << "hull lie " << result.deviation << " m apart at (" << Vector(worst)
      << "); allowed: a mesh of revolution about that axis, or a larger tolerance";
    throw std::invalid_argument(s.str());
  }
  // the tessellation for FCL (at most kMaxHullVerticesBound points: qhull's cap would hull a
  // subset)
  std::vector<Eigen::Vector3d> tessellation;
  const std::vector<Eigen::Vector2d> rings = TessellationProfile(*profile);
  const int ring_sectors = std::min(
      kRevolutionSectors, kMaxHullVerticesBound / static_cast<int>(rings.size()));
  for (const Eigen::Vector2d& rho_z : rings) {
    const int sectors = rho_z.x() > 0.0 ? ring_sectors : 1;
    for (int s = 0; s < sectors; ++s) {
      const double phi = 2.0 * kPi * s / sectors;
      tessellation.push_back(
          AtAzimuth(rho_z, Eigen::Vector3d(std::cos(phi), std::sin(phi), 0.0)));
    }
  }
  result.shape = Shape::Revolution(profile, HullOfPoints(tessellation, kMaxHullVerticesBound));
  return result;
}

}  // namespace nonsmooth_sim::mesh
