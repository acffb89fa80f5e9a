// Convex shapes of colliders, each in its own frame (the shape frame, placed on a body or in the
// world by Collider::pose). Every shape is symmetric about its frame's origin except the plane.
//
//   type        parameters                                       solid in the shape frame
//   plane       -                                                z ≤ 0 (a half-space, normal +z)
//   sphere      radius r                                         |x| ≤ r
//   capsule     radius r, half_length l (segment along z)        dist(x, [-l ẑ, l ẑ]) ≤ r
//   ellipsoid   semi_axes (a, b, c) along x, y, z                (x/a)² + (y/b)² + (z/c)² ≤ 1
//   cylinder    radius r, half_length l (axis along z)           x² + y² ≤ r², |z| ≤ l
//   box         half_extents (a, b, c)                           |x| ≤ a, |y| ≤ b, |z| ≤ c
//
// URDF conventions: <cylinder radius length> has its axis along z and length = 2l; <box size>
// is the full size (2a, 2b, 2c). The types are ordered: the collision table (collision_table.h)
// is indexed by them and a pair function takes its shapes in this order.
#ifndef NONSMOOTH_SIM_CORE_SHAPE_H_
#define NONSMOOTH_SIM_CORE_SHAPE_H_

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>

namespace nonsmooth_sim {

enum class ShapeType : int { kPlane = 0, kSphere, kCapsule, kEllipsoid, kCylinder, kBox };
inline constexpr int kShapeTypeCount = 6;

/// "plane", "sphere", "capsule", "ellipsoid", "cylinder", "box".
std::string_view ShapeTypeName(ShapeType type);
std::optional<ShapeType> ShapeTypeFromName(std::string_view name);

struct Shape {
  ShapeType type = ShapeType::kSphere;
  double radius = 0.0;       ///< sphere, capsule, cylinder [m]
  double half_length = 0.0;  ///< capsule (segment), cylinder (axis) [m]
  /// ellipsoid semi-axes, box half-extents, along the shape frame's x, y, z [m]
  Eigen::Vector3d half_extents = Eigen::Vector3d::Zero();

  static Shape Plane();
  static Shape Sphere(double radius);
  static Shape Capsule(double radius, double half_length);
  static Shape Ellipsoid(const Eigen::Vector3d& semi_axes);
  static Shape Cylinder(double radius, double half_length);
  static Shape Box(const Eigen::Vector3d& half_extents);
};

/// Radius of the smallest sphere about the shape frame's origin that holds the shape [m]
/// (+inf for a plane). Used by the broad phase.
double BoundingRadius(const Shape& shape);

/// Throws std::invalid_argument naming `where` and the bad parameter (every length finite and
/// > 0 where the type uses it; a capsule or cylinder half_length ≥ 0 resp. > 0).
void ValidateShape(const Shape& shape, const std::string& where);

/// Volume [m³] and inertia about the shape frame's origin in its axes per unit density [m⁵]
/// (the plane: not defined, throws std::invalid_argument). Used to build scenes of uniform
/// bodies in code and tests.
double ShapeVolume(const Shape& shape);
Eigen::Matrix3d ShapeUnitInertia(const Shape& shape);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_SHAPE_H_
