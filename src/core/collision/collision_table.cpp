// The [type][type] table of pair functions (collision.h), and Collide(), which orders a pair.
// A new closed form is one line in DefaultTable().
#include <array>
#include <stdexcept>
#include <string>
#include <utility>

#include "nonsmooth_sim/core/collision/capsule_capsule.h"
#include "nonsmooth_sim/core/collision/collision.h"
#include "nonsmooth_sim/core/collision/plane_box.h"
#include "nonsmooth_sim/core/collision/plane_capsule.h"
#include "nonsmooth_sim/core/collision/plane_cylinder.h"
#include "nonsmooth_sim/core/collision/plane_ellipsoid.h"
#include "nonsmooth_sim/core/collision/plane_sphere.h"
#include "nonsmooth_sim/core/collision/sphere_box.h"
#include "nonsmooth_sim/core/collision/sphere_capsule.h"
#include "nonsmooth_sim/core/collision/sphere_sphere.h"

namespace nonsmooth_sim {
namespace {

// table[a][b] with a ≤ b in ShapeType order; the entries below the diagonal stay empty
using Table = std::array<std::array<CollideFunction, kShapeTypeCount>, kShapeTypeCount>;

int Index(ShapeType type) { return static_cast<int>(type); }

Table DefaultTable() {
  Table table{};
  const auto set = [&table](ShapeType a, ShapeType b, CollideFunction function) {
    table[Index(a)][Index(b)] = function;
  };
  set(ShapeType::kPlane, ShapeType::kSphere, &CollidePlaneSphere);
  set(ShapeType::kPlane, ShapeType::kCapsule, &CollidePlaneCapsule);
  set(ShapeType::kPlane, ShapeType::kEllipsoid, &CollidePlaneEllipsoid);
  set(ShapeType::kPlane, ShapeType::kCylinder, &CollidePlaneCylinder);
  set(ShapeType::kPlane, ShapeType::kBox, &CollidePlaneBox);
  set(ShapeType::kSphere, ShapeType::kSphere, &CollideSphereSphere);
  set(ShapeType::kSphere, ShapeType::kCapsule, &CollideSphereCapsule);
  set(ShapeType::kSphere, ShapeType::kBox, &CollideSphereBox);
  set(ShapeType::kCapsule, ShapeType::kCapsule, &CollideCapsuleCapsule);
  return table;
}

Table& RegisteredTable() {
  static Table table = DefaultTable();
  return table;
}

bool IsShapeType(ShapeType type) { return Index(type) >= 0 && Index(type) < kShapeTypeCount; }

}  // namespace

CollideFunction FindCollideFunction(ShapeType a, ShapeType b) {
  if (!IsShapeType(a) || !IsShapeType(b)) return nullptr;
  if (Index(a) > Index(b)) std::swap(a, b);
  return RegisteredTable()[Index(a)][Index(b)];
}

void RegisterCollideFunction(ShapeType a, ShapeType b, CollideFunction function) {
  if (!IsShapeType(a) || !IsShapeType(b) || Index(a) > Index(b)) {
    throw std::invalid_argument("RegisterCollideFunction: types (" + std::to_string(Index(a)) +
                                ", " + std::to_string(Index(b)) +
                                ") must be ShapeTypes in order, a <= b");
  }
  RegisteredTable()[Index(a)][Index(b)] = function;
}

int Collide(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
            const Eigen::Isometry3d& pose_b, double margin, ContactGeometry* out) {
  const CollideFunction function = FindCollideFunction(a.type, b.type);
  if (function == nullptr) return -1;
  if (Index(a.type) <= Index(b.type)) return function(a, pose_a, b, pose_b, margin, out);
  // swapped: back to "from a to b" as passed here
  const int count = function(b, pose_b, a, pose_a, margin, out);
  for (int i = 0; i < count; ++i) {
    std::swap(out[i].point_a, out[i].point_b);
    out[i].normal = -out[i].normal;
  }
  return count;
}

}  // namespace nonsmooth_sim
