// Test-side geometry of the shapes, written from their definitions in shape.h and independent of
// the pair functions: random poses and shapes, exact support functions, a residual that is zero on
// a shape's surface, brute-force minimisation over a parametrisation, and the properties every
// ContactGeometry must have (collision.h).
#ifndef NONSMOOTH_SIM_TEST_CORE_COLLISION_TEST_UTIL_H_
#define NONSMOOTH_SIM_TEST_CORE_COLLISION_TEST_UTIL_H_

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <memory>
#include <utility>
#include <vector>

#include "nonsmooth_sim/core/collision/collision.h"
#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/core/shape.h"

namespace nonsmooth_sim::collision_test {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr unsigned kSeed = 12345;
constexpr int kPoses = 1000;

inline double Uniform(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

/// Uniformly distributed rotation (normalised Gaussian quaternion).
inline Eigen::Matrix3d RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
  return q.normalized().toRotationMatrix();
}

/// Random rotation, translation uniform in [−extent, extent]³.
inline Eigen::Isometry3d RandomPose(std::mt19937& rng, double extent) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = RandomRotation(rng);
  pose.translation() = Eigen::Vector3d(Uniform(rng, -extent, extent), Uniform(rng, -extent, extent),
                                       Uniform(rng, -extent, extent));
  return pose;
}

inline Eigen::Isometry3d Pose(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  pose.translation() = translation;
  return pose;
}

inline Eigen::Matrix3d Rotation(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

/// A shape of the type with lengths drawn from [lo, hi] [m] (half_length of a capsule from
/// [0, hi]).
inline Shape RandomShape(ShapeType type, std::mt19937& rng, double lo = 0.05, double hi = 0.5) {
  const auto length = [&] { return Uniform(rng, lo, hi); };
  switch (type) {
    case ShapeType::kPlane: return Shape::Plane();
    case ShapeType::kSphere: return Shape::Sphere(length());
    case ShapeType::kCapsule: return Shape::Capsule(length(), Uniform(rng, 0.0, hi));
    case ShapeType::kEllipsoid: return Shape::Ellipsoid({length(), length(), length()});
    case ShapeType::kCylinder: return Shape::Cylinder(length(), length());
    case ShapeType::kBox: return Shape::Box({length(), length(), length()});
    case ShapeType::kConvexHull:  // hulls are written by their tests (plane_hull)
    case ShapeType::kRevolution: break;  // profiles too (revolution_profile_test)
  }
  return Shape::Sphere(lo);
}

/// The box |x − c| ≤ h as a convex hull: corners i (bit j of i: +h_j), faces counter-clockwise
/// from outside.
inline std::shared_ptr<const ConvexHull> BoxHull(
    const Eigen::Vector3d& h, const Eigen::Vector3d& c = Eigen::Vector3d::Zero()) {
  std::vector<Eigen::Vector3d> v;
  for (int i = 0; i < 8; ++i) {
    v.push_back(c + Eigen::Vector3d((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                                    (i & 4) ? h.z() : -h.z()));
  }
  const std::vector<int> faces = {4, 0, 2, 3, 1,   // −z
                                  4, 4, 5, 7, 6,   // +z
                                  4, 0, 4, 6, 2,   // −x
                                  4, 1, 3, 7, 5,   // +x
                                  4, 0, 1, 5, 4,   // −y
                                  4, 2, 6, 7, 3};  // +y
  return MakeConvexHull(v, faces);
}

/// The point of the (solid, bounded) shape maximising d·x, world (d ≠ 0, world). Textbook support
/// functions of the solids of shape.h; ties (a flat face or edge along d) resolved arbitrarily.
inline Eigen::Vector3d Support(const Shape& shape, const Eigen::Isometry3d& pose,
                               const Eigen::Vector3d& d_world) {
  const Eigen::Vector3d d = pose.linear().transpose() * d_world.normalized();
  const auto sign = [](double x) { return x >= 0.0 ? 1.0 : -1.0; };
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  switch (shape.type) {
    case ShapeType::kPlane: break;
    case ShapeType::kSphere: x = shape.radius * d; break;
    case ShapeType::kCapsule:
      x = shape.radius * d + Eigen::Vector3d(0, 0, sign(d.z()) * shape.half_length);
      break;
    case ShapeType::kEllipsoid: {
      // maximise d·x over (x/a)² + ... = 1: Lagrange, x = S² d/|S d|
      const Eigen::Vector3d& s = shape.half_extents;
      x = s.cwiseProduct(s).cwiseProduct(d) / s.cwiseProduct(d).norm();
      break;
    }
    case ShapeType::kCylinder: {
      const double rho = std::hypot(d.x(), d.y());
      if (rho > 0.0) x.head<2>() = shape.radius * d.head<2>() / rho;
      x.z() = sign(d.z()) * shape.half_length;
      break;
    }
    case ShapeType::kBox:
      for (int j = 0; j < 3; ++j) x[j] = sign(d[j]) * shape.half_extents[j];
      break;
    case ShapeType::kConvexHull: {
      // the vertex maximising d·v, by enumeration
      double best = -kInf;
      for (const Eigen::Vector3d& v : shape.hull->vertices) {
        if (d.dot(v) > best) best = d.dot(v), x = v;
      }
      break;
    }
    case ShapeType::kRevolution: {
      // the best over every arc of its point whose normal is nearest the direction's
      const double rho = std::hypot(d.x(), d.y());
      const double theta = std::atan2(rho, d.z());
      const Eigen::Vector3d radial = rho > 0.0 ? Eigen::Vector3d(d.x() / rho, d.y() / rho, 0.0)
                                               : Eigen::Vector3d::UnitX();
      double best = -kInf, begin = 0.0;
      for (const RevolutionArc& arc : shape.revolution->arcs) {
        const double t = std::clamp(theta, begin, arc.theta_end);
        const Eigen::Vector2d p = arc.centre + arc.radius * Eigen::Vector2d(std::sin(t), std::cos(t));
        const Eigen::Vector3d candidate = p.x() * radial + p.y() * Eigen::Vector3d::UnitZ();
        if (d.dot(candidate) > best) best = d.dot(candidate), x = candidate;
        begin = arc.theta_end;
      }
      break;
    }
  }
  return pose * x;
}

/// min over B of n·x − max over A of n·y: the gap of A and B along the direction n (from A to B).
/// It equals the signed distance (gap) for the optimal normal and is smaller for any other n.
inline double ProjectionGap(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                            const Eigen::Isometry3d& pose_b, const Eigen::Vector3d& n) {
  return n.dot(Support(b, pose_b, -n)) - n.dot(Support(a, pose_a, n));
}

/// A residual that is 0 exactly on the shape's surface, < 0 inside, > 0 outside (not a distance
/// for the ellipsoid, whose residual is |S⁻¹y| − 1 scaled by its smallest semi-axis) [m].
inline double SurfaceResidual(const Shape& shape, const Eigen::Isometry3d& pose,
                              const Eigen::Vector3d& x_world) {
  const Eigen::Vector3d y = pose.inverse() * x_world;
  switch (shape.type) {
    case ShapeType::kPlane: return y.z();
    case ShapeType::kSphere: return y.norm() - shape.radius;
    case ShapeType::kCapsule: {
      const double z = std::clamp(y.z(), -shape.half_length, shape.half_length);
      return (y - Eigen::Vector3d(0, 0, z)).norm() - shape.radius;
    }
    case ShapeType::kEllipsoid:
      return (y.cwiseQuotient(shape.half_extents).norm() - 1.0) * shape.half_extents.minCoeff();
    case ShapeType::kCylinder:
      return std::max(std::hypot(y.x(), y.y()) - shape.radius, std::abs(y.z()) - shape.half_length);
    case ShapeType::kBox: return (y.cwiseAbs() - shape.half_extents).maxCoeff();
    case ShapeType::kConvexHull: {
      // the largest height above a face's plane
      double residual = -kInf;
      for (int f = 0; f < shape.hull->face_count; ++f) {
        const ConvexHull& hull = *shape.hull;
        residual = std::max(residual, hull.face_normal[f].dot(y - hull.face_centroid[f]));
      }
      return residual;
    }
    case ShapeType::kRevolution: break;  // not used: its tests check supports
  }
  return kInf;
}

/// Minimum of f over [lo, hi] by brute force: a grid of `grid` cells, then repeatedly a finer grid
/// over the two cells on either side of the best point. A periodic variable (an angle over one
/// period) is not clamped to [lo, hi], so that a minimum near lo is found on its side of lo.
/// Returns (min, argmin).
template <typename F>
std::pair<double, double> BruteMinimize1(F f, double lo, double hi, bool periodic = false,
                                         int grid = 200, int levels = 12) {
  double best_x = lo;
  double best = kInf;
  for (int level = 0; level < levels; ++level) {
    const double step = (hi - lo) / grid;
    for (int i = 0; i <= grid; ++i) {
      const double x = lo + i * step;
      const double v = f(x);
      if (v < best) best = v, best_x = x;
    }
    lo = periodic ? best_x - 2 * step : std::max(lo, best_x - 2 * step);
    hi = periodic ? best_x + 2 * step : std::min(hi, best_x + 2 * step);
  }
  return {best, best_x};
}

/// Minimum of f(u, v) over [lo, hi] (2-D) by the same zooming grid; `periodic` per coordinate.
/// Returns (min, argmin).
template <typename F>
std::pair<double, Eigen::Vector2d> BruteMinimize2(F f, Eigen::Vector2d lo, Eigen::Vector2d hi,
                                                  Eigen::Array2i periodic = {0, 0}, int grid = 20,
                                                  int levels = 12) {
  Eigen::Vector2d best_x = lo;
  double best = kInf;
  for (int level = 0; level < levels; ++level) {
    const Eigen::Vector2d step = (hi - lo) / grid;
    for (int i = 0; i <= grid; ++i) {
      for (int j = 0; j <= grid; ++j) {
        const Eigen::Vector2d x = lo + Eigen::Vector2d(i * step.x(), j * step.y());
        const double v = f(x);
        if (v < best) best = v, best_x = x;
      }
    }
    for (int k = 0; k < 2; ++k) {
      const double new_lo = best_x[k] - 2 * step[k];
      const double new_hi = best_x[k] + 2 * step[k];
      lo[k] = periodic[k] ? new_lo : std::max(lo[k], new_lo);
      hi[k] = periodic[k] ? new_hi : std::min(hi[k], new_hi);
    }
  }
  return {best, best_x};
}

/// Minimum of f(ω) over the unit sphere |ω| = 1 by brute force, free of the poles of spherical
/// angles: over each face of the cube [−1, 1]³, ω = x/|x| with x on the face, by BruteMinimize2.
/// Returns (min, argmin ω).
template <typename F>
std::pair<double, Eigen::Vector3d> BruteMinimizeOverSphere(F f) {
  double best = kInf;
  Eigen::Vector3d best_omega = Eigen::Vector3d::UnitZ();
  for (int axis = 0; axis < 3; ++axis) {
    for (double side : {-1.0, 1.0}) {
      const auto omega = [&](const Eigen::Vector2d& uv) {
        Eigen::Vector3d x;
        x[axis] = side;
        x[(axis + 1) % 3] = uv[0];
        x[(axis + 2) % 3] = uv[1];
        return Eigen::Vector3d(x.normalized());
      };
      const auto [value, uv] = BruteMinimize2([&](const Eigen::Vector2d& p) { return f(omega(p)); },
                                              Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
      if (value < best) best = value, best_omega = omega(uv);
    }
  }
  return {best, best_omega};
}

/// The properties every contact has (collision.h): finite, unit normal, point_b − point_a =
/// gap·normal and a feature ≥ 0.
inline ::testing::AssertionResult WellFormed(const ContactGeometry& c, double tolerance = 1e-12) {
  const bool finite = std::isfinite(c.gap) && c.point_a.allFinite() && c.point_b.allFinite() &&
                      c.normal.allFinite();
  if (!finite) return ::testing::AssertionFailure() << "not finite";
  if (std::abs(c.normal.norm() - 1.0) > tolerance) {
    return ::testing::AssertionFailure() << "|normal| = " << c.normal.norm();
  }
  const double residual = (c.point_b - c.point_a - c.gap * c.normal).norm();
  if (residual > tolerance * std::max(1.0, std::abs(c.gap))) {
    return ::testing::AssertionFailure() << "|point_b - point_a - gap n| = " << residual;
  }
  if (c.feature < 0) {
    return ::testing::AssertionFailure() << "feature " << c.feature;
  }
  return ::testing::AssertionSuccess();
}

/// Rotation angle of R_b R_aᵀ [rad].
inline double AngleBetween(const Eigen::Matrix3d& r_a, const Eigen::Matrix3d& r_b) {
  return Eigen::AngleAxisd(r_b * r_a.transpose()).angle();
}

}  // namespace nonsmooth_sim::collision_test

#endif  // NONSMOOTH_SIM_TEST_CORE_COLLISION_TEST_UTIL_H_
