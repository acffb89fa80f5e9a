// The collision table: the pair function (collision.h) of each pair of shape types, a
// [type][type] array as MuJoCo's mjCOLLISIONFUNC and Bullet's dispatcher. A value, not a
// process-wide registry: each Scene carries its own (Scene::collision_table, the closed forms of
// Defaults() unless the scene's builder adds more, e.g. RegisterFclPairs in collision_fcl/), and
// every stage that collides reads the table of the scene it works on. Two simulators with
// different tables do not affect each other, and a table is read-only while a simulator steps.
//
// A new closed form is one line in Defaults() (collision_table.cpp).
#ifndef NONSMOOTH_SIM_CORE_COLLISION_COLLISION_TABLE_H_
#define NONSMOOTH_SIM_CORE_COLLISION_COLLISION_TABLE_H_

#include <Eigen/Geometry>
#include <array>

#include "nonsmooth_sim/core/collision/collision.h"
#include "nonsmooth_sim/core/shape.h"

namespace nonsmooth_sim {

class CollisionTable {
 public:
  /// An empty table: no pair has a function.
  CollisionTable() = default;

  /// The core's closed forms: plane against sphere, capsule, ellipsoid, cylinder, box, convex
  /// hull and body of revolution; sphere
  /// against sphere, capsule and box; capsule against capsule.
  static CollisionTable Defaults();

  /// The function of a pair of types in either order (nullptr: no function; the pair is skipped
  /// and reported by the scene loader).
  CollideFunction Find(ShapeType a, ShapeType b) const;

  /// Registers (or replaces) the function of a pair; `a` ≤ `b` in ShapeType order (throws
  /// std::invalid_argument otherwise: the function is called with its shapes in that order).
  /// nullptr removes the pair's function.
  void Register(ShapeType a, ShapeType b, CollideFunction function);

  /// Collides two shapes in any order: calls the pair function with the shapes in ShapeType order
  /// and, if it swapped them, swaps point_a/point_b and flips the normal, so that the result is
  /// always "from a to b" as passed here. Returns -1 if no function is registered for the pair.
  int Collide(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
              const Eigen::Isometry3d& pose_b, double margin, ContactGeometry* out) const {
    // inline for the pairs already in order (a body's shape against a static plane, every step)
    const unsigned ia = static_cast<unsigned>(a.type);
    const unsigned ib = static_cast<unsigned>(b.type);
    if (ia <= ib && ib < static_cast<unsigned>(kShapeTypeCount) && functions_[ia][ib] != nullptr) {
      return functions_[ia][ib](a, pose_a, b, pose_b, margin, out);
    }
    return CollideOther(a, pose_a, b, pose_b, margin, out);
  }

 private:
  // Collide for pairs out of ShapeType order, without a function or with an invalid type
  int CollideOther(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                   const Eigen::Isometry3d& pose_b, double margin, ContactGeometry* out) const;

  // functions_[a][b] with a ≤ b in ShapeType order; the entries below the diagonal stay empty
  std::array<std::array<CollideFunction, kShapeTypeCount>, kShapeTypeCount> functions_{};
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_COLLISION_TABLE_H_
