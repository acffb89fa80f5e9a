// Shapes: names, factories, validation, bounding radius, volume and unit-density inertia.
//
// Inertia about the shape frame's origin (the centroid: every solid shape is symmetric about it),
// per unit density, m = V:
//   sphere     I = (2/5) m r² · 1
//   ellipsoid  I_xx = m (b² + c²)/5, cyclically
//   box        I_xx = m (b² + c²)/3, cyclically (half-extents)
//   cylinder   I_zz = m r²/2,  I_xx = I_yy = m (r²/4 + l²/3)
//   capsule    the cylinder (m_c = 2πr²l) plus two hemispheres (together m_s = 4πr³/3):
//              I_zz = m_c r²/2 + (2/5) m_s r²,
//              I_xx = m_c (r²/4 + l²/3) + m_s (2r²/5 + l² + 3lr/4)
// The hemisphere term: a hemisphere of mass m_h has I = (2/5) m_h r² about a diameter of its flat
// face and its centroid 3r/8 from that face; moved by the parallel-axis theorem to the capsule's
// centre, l from the face: (2/5) m_h r² − m_h (3r/8)² + m_h (l + 3r/8)² = m_h (2r²/5 + l² + 3lr/4).
#include "nonsmooth_sim/core/shape.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "nonsmooth_sim/core/constants.h"

namespace nonsmooth_sim {
namespace {

constexpr ShapeType kAllShapeTypes[kShapeTypeCount] = {ShapeType::kPlane,    ShapeType::kSphere,
                                                       ShapeType::kCapsule,  ShapeType::kEllipsoid,
                                                       ShapeType::kCylinder, ShapeType::kBox};

// "<where>: <what> = <value>: must be <allowed>"
[[noreturn]] void Reject(const std::string& where, const std::string& what, double value,
                         const std::string& allowed) {
  std::ostringstream s;
  s << where << ": " << what << " = " << value << ": must be " << allowed;
  throw std::invalid_argument(s.str());
}

void RequirePositive(const std::string& where, const std::string& what, double value) {
  if (!(std::isfinite(value) && value > 0.0)) Reject(where, what, value, "finite, > 0 [m]");
}

void RequireNonNegative(const std::string& where, const std::string& what, double value) {
  if (!(std::isfinite(value) && value >= 0.0)) Reject(where, what, value, "finite, >= 0 [m]");
}

void RequirePositiveAxes(const std::string& where, const std::string& what,
                         const Eigen::Vector3d& axes) {
  constexpr const char* kAxisNames[3] = {".x", ".y", ".z"};
  for (int i = 0; i < 3; ++i) RequirePositive(where, what + kAxisNames[i], axes[i]);
}

[[noreturn]] void RejectPlane(const char* what) {
  throw std::invalid_argument(std::string(what) + ": not defined for a plane (a half-space)");
}

Eigen::Matrix3d Diagonal(double xx, double yy, double zz) {
  return Eigen::Vector3d(xx, yy, zz).asDiagonal();
}

}  // namespace

std::string_view ShapeTypeName(ShapeType type) {
  switch (type) {
    case ShapeType::kPlane: return "plane";
    case ShapeType::kSphere: return "sphere";
    case ShapeType::kCapsule: return "capsule";
    case ShapeType::kEllipsoid: return "ellipsoid";
    case ShapeType::kCylinder: return "cylinder";
    case ShapeType::kBox: return "box";
  }
  return "unknown";
}

std::optional<ShapeType> ShapeTypeFromName(std::string_view name) {
  for (ShapeType type : kAllShapeTypes) {
    if (ShapeTypeName(type) == name) return type;
  }
  return std::nullopt;
}

Shape Shape::Plane() {
  Shape shape;
  shape.type = ShapeType::kPlane;
  return shape;
}

Shape Shape::Sphere(double radius) {
  Shape shape;
  shape.type = ShapeType::kSphere;
  shape.radius = radius;
  return shape;
}

Shape Shape::Capsule(double radius, double half_length) {
  Shape shape;
  shape.type = ShapeType::kCapsule;
  shape.radius = radius;
  shape.half_length = half_length;
  return shape;
}

Shape Shape::Ellipsoid(const Eigen::Vector3d& semi_axes) {
  Shape shape;
  shape.type = ShapeType::kEllipsoid;
  shape.half_extents = semi_axes;
  return shape;
}

Shape Shape::Cylinder(double radius, double half_length) {
  Shape shape;
  shape.type = ShapeType::kCylinder;
  shape.radius = radius;
  shape.half_length = half_length;
  return shape;
}

Shape Shape::Box(const Eigen::Vector3d& half_extents) {
  Shape shape;
  shape.type = ShapeType::kBox;
  shape.half_extents = half_extents;
  return shape;
}

double BoundingRadius(const Shape& shape) {
  switch (shape.type) {
    case ShapeType::kPlane: return std::numeric_limits<double>::infinity();
    case ShapeType::kSphere: return shape.radius;
    // the farthest points are the poles of the end spheres
    case ShapeType::kCapsule: return shape.radius + shape.half_length;
    case ShapeType::kEllipsoid: return shape.half_extents.maxCoeff();
    // the farthest points are on the rims
    case ShapeType::kCylinder: return std::hypot(shape.radius, shape.half_length);
    // the farthest points are the corners
    case ShapeType::kBox: return shape.half_extents.norm();
  }
  return std::numeric_limits<double>::infinity();
}

void ValidateShape(const Shape& shape, const std::string& where) {
  switch (shape.type) {
    case ShapeType::kPlane: return;
    case ShapeType::kSphere: RequirePositive(where, "radius", shape.radius); return;
    case ShapeType::kCapsule:
      RequirePositive(where, "radius", shape.radius);
      RequireNonNegative(where, "half_length", shape.half_length);
      return;
    case ShapeType::kEllipsoid: RequirePositiveAxes(where, "semi_axes", shape.half_extents); return;
    case ShapeType::kCylinder:
      RequirePositive(where, "radius", shape.radius);
      RequirePositive(where, "half_length", shape.half_length);
      return;
    case ShapeType::kBox: RequirePositiveAxes(where, "half_extents", shape.half_extents); return;
  }
  Reject(where, "type", static_cast<int>(shape.type), "a ShapeType (0 to 5)");
}

double ShapeVolume(const Shape& shape) {
  const double r = shape.radius;
  const double l = shape.half_length;
  const Eigen::Vector3d& h = shape.half_extents;
  switch (shape.type) {
    case ShapeType::kPlane: RejectPlane("ShapeVolume");
    case ShapeType::kSphere: return 4.0 / 3.0 * kPi * r * r * r;
    case ShapeType::kCapsule: return kPi * r * r * (2.0 * l + 4.0 / 3.0 * r);
    case ShapeType::kEllipsoid: return 4.0 / 3.0 * kPi * h.prod();
    case ShapeType::kCylinder: return 2.0 * kPi * r * r * l;
    case ShapeType::kBox: return 8.0 * h.prod();
  }
  throw std::invalid_argument("ShapeVolume: unknown shape type");
}

Eigen::Matrix3d ShapeUnitInertia(const Shape& shape) {
  const double r = shape.radius;
  const double l = shape.half_length;
  const Eigen::Vector3d h2 = shape.half_extents.cwiseAbs2();
  switch (shape.type) {
    case ShapeType::kPlane: RejectPlane("ShapeUnitInertia");
    case ShapeType::kSphere: {
      const double m = ShapeVolume(shape);
      return Diagonal(0.4 * m * r * r, 0.4 * m * r * r, 0.4 * m * r * r);
    }
    case ShapeType::kCapsule: {
      const double m_c = 2.0 * kPi * r * r * l;        // cylinder
      const double m_s = 4.0 / 3.0 * kPi * r * r * r;  // both hemispheres
      const double zz = 0.5 * m_c * r * r + 0.4 * m_s * r * r;
      const double xx =
          m_c * (0.25 * r * r + l * l / 3.0) + m_s * (0.4 * r * r + l * l + 0.75 * l * r);
      return Diagonal(xx, xx, zz);
    }
    case ShapeType::kEllipsoid: {
      const double m = ShapeVolume(shape);
      return Diagonal(m * (h2.y() + h2.z()) / 5.0, m * (h2.x() + h2.z()) / 5.0,
                      m * (h2.x() + h2.y()) / 5.0);
    }
    case ShapeType::kCylinder: {
      const double m = ShapeVolume(shape);
      const double xx = m * (0.25 * r * r + l * l / 3.0);
      return Diagonal(xx, xx, 0.5 * m * r * r);
    }
    case ShapeType::kBox: {
      const double m = ShapeVolume(shape);
      return Diagonal(m * (h2.y() + h2.z()) / 3.0, m * (h2.x() + h2.z()) / 3.0,
                      m * (h2.x() + h2.y()) / 3.0);
    }
  }
  throw std::invalid_argument("ShapeUnitInertia: unknown shape type");
}

}  // namespace nonsmooth_sim
