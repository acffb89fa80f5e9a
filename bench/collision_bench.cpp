// Narrow phase: ns per call of each pair function at a representative pose (a shallow contact in
// general position), the closed forms and the FCL pairs.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "nonsmooth_sim/collision_fcl/fcl_pairs.h"
#include "nonsmooth_sim/core/collision/capsule_capsule.h"
#include "nonsmooth_sim/core/collision/collision.h"
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

// A pose tilted about a general axis, centre at `centre`.
Eigen::Isometry3d TiltedPose(const Eigen::Vector3d& centre, double angle) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() =
      Eigen::AngleAxisd(angle, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  pose.translation() = centre;
  return pose;
}

Shape Example(ShapeType type) {
  switch (type) {
    case ShapeType::kPlane: return Shape::Plane();
    case ShapeType::kSphere: return Shape::Sphere(0.1);
    case ShapeType::kCapsule: return Shape::Capsule(0.05, 0.1);
    case ShapeType::kEllipsoid: return Shape::Ellipsoid({0.12, 0.08, 0.05});
    case ShapeType::kCylinder: return Shape::Cylinder(0.08, 0.05);
    case ShapeType::kBox: return Shape::Box({0.1, 0.07, 0.05});
    case ShapeType::kConvexHull: {
      // the box above as a hull (a mesh's hull comes from scene_io): 8 vertices, 6 faces
      const Eigen::Vector3d h(0.1, 0.07, 0.05);
      std::vector<Eigen::Vector3d> v;
      for (int i = 0; i < 8; ++i) {
        v.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                       (i & 4) ? h.z() : -h.z());
      }
      return Shape::Hull(MakeConvexHull(v, {4, 0, 2, 3, 1, 4, 4, 5, 7, 6, 4, 0, 4, 6, 2,
                                            4, 1, 3, 7, 5, 4, 0, 1, 5, 4, 4, 2, 6, 7, 3}));
    }
    case ShapeType::kRevolution: {
      // an egg's profile (a mesh's comes from scene_io): 91 points of a half-ellipse
      std::vector<Eigen::Vector2d> meridian;
      for (int i = 0; i <= 90; ++i) {
        const double t = 3.14159265358979323846 * i / 90;
        meridian.emplace_back(0.08 * std::sin(t), 0.12 * std::cos(t));
      }
      return Shape::Revolution(MakeRevolutionProfile(meridian, 1e-5));
    }
  }
  return Shape::Sphere(0.1);
}

// The smallest gap the pair function returns (+inf for none) [m].
double SmallestGap(CollideFunction function, const Shape& a, const Eigen::Isometry3d& pose_a,
                   const Shape& b, const Eigen::Isometry3d& pose_b) {
  ContactGeometry out[kMaxPairContacts];
  const int count = function(a, pose_a, b, pose_b, 1e9, out);
  double gap = std::numeric_limits<double>::infinity();
  for (int i = 0; i < count; ++i) gap = std::min(gap, out[i].gap);
  return gap;
}

// One call of `function` on shapes a, b: A at the origin (tilted unless a plane), B tilted above
// it at the height where the smallest gap is kDepth (bisection, before timing): a shallow
// contact in general position, as in a simulation step.
void BM_Pair(benchmark::State& state, ShapeType type_a, ShapeType type_b,
             CollideFunction function) {
  constexpr double kDepth = -1e-3;
  constexpr double kMargin = 0.01;
  const Shape a = Example(type_a);
  const Shape b = Example(type_b);
  const bool plane = type_a == ShapeType::kPlane;
  const Eigen::Isometry3d pose_a =
      plane ? Eigen::Isometry3d::Identity() : TiltedPose({0, 0, 0}, 0.4);
  const double reach = (plane ? 0.0 : BoundingRadius(a)) + BoundingRadius(b);
  double lo = plane ? -reach : 0.0;
  double hi = reach + 0.1;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double gap = SmallestGap(function, a, pose_a, b, TiltedPose({0.01, 0.02, mid}, 1.1));
    (gap < kDepth ? lo : hi) = mid;
  }
  const Eigen::Isometry3d pose_b = TiltedPose({0.01, 0.02, hi}, 1.1);
  ContactGeometry out[kMaxPairContacts];
  int contacts = 0;
  for (auto _ : state) {
    contacts = function(a, pose_a, b, pose_b, kMargin, out);
    benchmark::DoNotOptimize(out);
  }
  state.counters["contacts"] = contacts;
  state.counters["gap"] = SmallestGap(function, a, pose_a, b, pose_b);
}

#define NONSMOOTH_SIM_PAIR_BENCH(name, a, b, function) \
  BENCHMARK_CAPTURE(BM_Pair, name, ShapeType::a, ShapeType::b, &function)

NONSMOOTH_SIM_PAIR_BENCH(plane_sphere, kPlane, kSphere, CollidePlaneSphere);
NONSMOOTH_SIM_PAIR_BENCH(plane_capsule, kPlane, kCapsule, CollidePlaneCapsule);
NONSMOOTH_SIM_PAIR_BENCH(plane_ellipsoid, kPlane, kEllipsoid, CollidePlaneEllipsoid);
NONSMOOTH_SIM_PAIR_BENCH(plane_cylinder, kPlane, kCylinder, CollidePlaneCylinder);
NONSMOOTH_SIM_PAIR_BENCH(plane_box, kPlane, kBox, CollidePlaneBox);
NONSMOOTH_SIM_PAIR_BENCH(plane_hull, kPlane, kConvexHull, CollidePlaneHull);
NONSMOOTH_SIM_PAIR_BENCH(plane_revolution, kPlane, kRevolution, CollidePlaneRevolution);
NONSMOOTH_SIM_PAIR_BENCH(sphere_sphere, kSphere, kSphere, CollideSphereSphere);
NONSMOOTH_SIM_PAIR_BENCH(sphere_capsule, kSphere, kCapsule, CollideSphereCapsule);
NONSMOOTH_SIM_PAIR_BENCH(sphere_box, kSphere, kBox, CollideSphereBox);
NONSMOOTH_SIM_PAIR_BENCH(capsule_capsule, kCapsule, kCapsule, CollideCapsuleCapsule);
NONSMOOTH_SIM_PAIR_BENCH(fcl_sphere_ellipsoid, kSphere, kEllipsoid, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_sphere_cylinder, kSphere, kCylinder, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_capsule_ellipsoid, kCapsule, kEllipsoid, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_capsule_cylinder, kCapsule, kCylinder, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_capsule_box, kCapsule, kBox, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_ellipsoid_ellipsoid, kEllipsoid, kEllipsoid, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_ellipsoid_cylinder, kEllipsoid, kCylinder, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_ellipsoid_box, kEllipsoid, kBox, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_cylinder_cylinder, kCylinder, kCylinder, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_cylinder_box, kCylinder, kBox, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_box_box, kBox, kBox, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_sphere_hull, kSphere, kConvexHull, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_box_hull, kBox, kConvexHull, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_hull_hull, kConvexHull, kConvexHull, CollideFcl);
// FCL on pairs that have a closed form, for comparison
NONSMOOTH_SIM_PAIR_BENCH(fcl_sphere_sphere, kSphere, kSphere, CollideFcl);
NONSMOOTH_SIM_PAIR_BENCH(fcl_capsule_capsule, kCapsule, kCapsule, CollideFcl);

}  // namespace
}  // namespace nonsmooth_sim
