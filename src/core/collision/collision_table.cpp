// The collision table (collision_table.h): the core's closed forms, and Collide(), which orders a
// pair. A new closed form is one line in Defaults().
#include "nonsmooth_sim/core/collision/collision_table.h"

#include <stdexcept>
#include <string>
#include <utility>

#include "nonsmooth_sim/core/collision/capsule_capsule.h"
#include "nonsmooth_sim/core/collision/plane_box.h"
#include "nonsmooth_sim/core/collision/plane_capsule.h"
#include "nonsmooth_sim/core/collision/plane_cylinder.h"
#include "nonsmooth_sim/core/collision/plane_ellipsoid.h"
#include "nonsmooth_sim/core/collision/plane_hull.h"
#include "nonsmooth_sim/core/collision/plane_revolution.h"
#include "nonsmooth_sim/core/collision/plane_sphere.h"
#include "nonsmooth_sim/core/collision/sphere_box.h"
#include "nonsmooth_sim/core/collision/sphere_capsule.h"
#include "nonsmooth_sim/core/collision/sphere_sphere.h"

namespace nonsmooth_sim {
namespace {

int Index(ShapeType type) { return static_cast<int>(type); }

bool IsShapeType(ShapeType type) { return Index(type) >= 0 && Index(type) < kShapeTypeCount; }

}  // namespace

CollisionTable CollisionTable::Defaults() {
  CollisionTable table;
  table.Register(ShapeType::kPlane, ShapeType::kSphere, &CollidePlaneSphere);
  table.Register(ShapeType::kPlane, ShapeType::kCapsule, &CollidePlaneCapsule);
  table.Register(ShapeType::kPlane, ShapeType::kEllipsoid, &CollidePlaneEllipsoid);
  table.Register(ShapeType::kPlane, ShapeType::kCylinder, &CollidePlaneCylinder);
  table.Register(ShapeType::kPlane, ShapeType::kBox, &CollidePlaneBox);
  table.Register(ShapeType::kPlane, ShapeType::kConvexHull, &CollidePlaneHull);
  table.Register(ShapeType::kPlane, ShapeType::kRevolution, &CollidePlaneRevolution);
  table.Register(ShapeType::kSphere, ShapeType::kSphere, &CollideSphereSphere);
  table.Register(ShapeType::kSphere, ShapeType::kCapsule, &CollideSphereCapsule);
  table.Register(ShapeType::kSphere, ShapeType::kBox, &CollideSphereBox);
  table.Register(ShapeType::kCapsule, ShapeType::kCapsule, &CollideCapsuleCapsule);
  return table;
}

CollideFunction CollisionTable::Find(ShapeType a, ShapeType b) const {
  if (!IsShapeType(a) || !IsShapeType(b)) return nullptr;
  if (Index(a) > Index(b)) std::swap(a, b);
  return functions_[Index(a)][Index(b)];
}

void CollisionTable::Register(ShapeType a, ShapeType b, CollideFunction function) {
  if (!IsShapeType(a) || !IsShapeType(b) || Index(a) > Index(b)) {
    throw std::invalid_argument("CollisionTable::Register: types (" + std::to_string(Index(a)) +
                                ", " + std::to_string(Index(b)) +
                                ") must be ShapeTypes in order, a <= b");
  }
  functions_[Index(a)][Index(b)] = function;
}

int CollisionTable::CollideOther(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                                 const Eigen::Isometry3d& pose_b, double margin,
                                 ContactGeometry* out) const {
  const CollideFunction function = Find(a.type, b.type);
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
