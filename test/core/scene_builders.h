// Small builders and observers shared by the core tests: a sphere collider on a body, the ground
// plane added last, the world pose of a collider at a state and its gap above the ground through
// the scene's collision table (collision_table.h), independent of the simulator's contact report
// (which lists only the contacts closed at the midpoint of the last step).
#ifndef NONSMOOTH_SIM_TEST_CORE_SCENE_BUILDERS_H_
#define NONSMOOTH_SIM_TEST_CORE_SCENE_BUILDERS_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/collision/collision_table.h"
#include "nonsmooth_sim/core/scene.h"

namespace nonsmooth_sim {
namespace test {

/// A sphere of `radius` centred at `center` (in the body frame K, relative to S) on `body`.
inline Collider SphereCollider(const std::string& name, int body, const Eigen::Vector3d& center,
                               double radius, const ContactLaw& law) {
  Collider collider;
  collider.name = name;
  collider.body = body;
  collider.pose = Eigen::Isometry3d::Identity();
  collider.pose.translation() = center;
  collider.shape = Shape::Sphere(radius);
  collider.law = law;
  return collider;
}

/// A scene of one body named `name`: mass `mass` with the inertia of a uniform box of half extents
/// `h`, and one collider `shape` (the box itself, or its hull) at its centre of mass with μ = `mu`
/// and the Coulomb set; no static collider, no initial state.
inline Scene BoxBodyScene(const std::string& name, const Eigen::Vector3d& h, const Shape& shape,
                          double mass, double mu) {
  Scene scene;
  RigidBody body;
  body.name = name;
  body.mass = mass;
  body.inertia = ShapeUnitInertia(Shape::Box(h)) * (mass / ShapeVolume(Shape::Box(h)));
  scene.bodies = {body};
  Collider collider;
  collider.name = name;
  collider.body = 0;
  collider.shape = shape;
  collider.law.mu = mu;
  collider.law.friction_set = FrictionSet::kCoulomb;
  scene.colliders = {collider};
  return scene;
}

/// Appends the ground plane z = 0 with GroundLaw() (μ = 100, R̄ = 0, ε = 0: the body's law
/// decides). Last, so that the contacts of the spheres keep their order.
inline void AddGround(Scene* scene) { scene->colliders.push_back(GroundPlane()); }

/// World pose of a collider's shape frame at `state` (the collider's own pose if static).
inline Eigen::Isometry3d ColliderWorldPose(const Scene& scene, const std::vector<BodyState>& state,
                                           int collider) {
  const Collider& c = scene.colliders.at(static_cast<std::size_t>(collider));
  if (c.body == kWorld) return c.pose;
  Eigen::Isometry3d body = Eigen::Isometry3d::Identity();
  const BodyState& s = state.at(static_cast<std::size_t>(c.body));
  body.linear() = s.orientation.normalized().toRotationMatrix();
  body.translation() = s.position;
  return body * c.pose;
}

/// Gap g of collider `collider` above the static collider `ground` at `state` [m]: the smallest
/// gap the pair function of the collision table returns (no margin: every point is returned).
/// For a sphere on the ground z = 0 this is r_S·ẑ + (A K_r_SM)·ẑ - ρ.
inline double GapAbove(const Scene& scene, const std::vector<BodyState>& state, int collider,
                       int ground) {
  const Collider& a = scene.colliders.at(static_cast<std::size_t>(ground));
  const Collider& b = scene.colliders.at(static_cast<std::size_t>(collider));
  ContactGeometry out[kMaxPairContacts];
  const int count = scene.collision_table.Collide(
      a.shape, ColliderWorldPose(scene, state, ground), b.shape,
      ColliderWorldPose(scene, state, collider), std::numeric_limits<double>::infinity(), out);
  if (count <= 0) throw std::logic_error("no contact geometry for " + a.name + "/" + b.name);
  double gap = std::numeric_limits<double>::infinity();
  for (int k = 0; k < count; ++k) gap = std::min(gap, out[k].gap);
  return gap;
}

/// Index of the collider "ground" (GroundPlane()); throws if there is none.
inline int GroundIndex(const Scene& scene) {
  const int ground = FindCollider(scene, "ground");
  if (ground < 0) throw std::logic_error("scene has no collider named ground");
  return ground;
}

/// Gap of collider `collider` above the ground at `state` [m].
inline double GroundGap(const Scene& scene, const std::vector<BodyState>& state, int collider) {
  return GapAbove(scene, state, collider, GroundIndex(scene));
}

/// Smallest gap above the ground of any collider on a body at `state` [m] (+inf without one).
inline double MinGroundGap(const Scene& scene, const std::vector<BodyState>& state) {
  const int ground = GroundIndex(scene);
  double gap = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < scene.colliders.size(); ++i) {
    if (scene.colliders[i].body == kWorld) continue;
    gap = std::min(gap, GapAbove(scene, state, static_cast<int>(i), ground));
  }
  return gap;
}

}  // namespace test
}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_TEST_CORE_SCENE_BUILDERS_H_
