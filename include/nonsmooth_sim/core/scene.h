// A scene (the model, immutable while it runs except through the Simulator's setters): free rigid
// bodies, colliders (a convex shape fixed on a body or in the world, with its contact law),
// gravity and the initial state. A plain data structure: built in code (tippe_top.h), or from a
// URDF by the scene loader (scene_io/urdf_scene.h).
//
// Contact laws of a pair of colliders (CombineLaws): μ = min(μ_a, μ_b) (Gazebo/ODE), R̄ =
// max(R̄_a, R̄_b) (the larger patch: the ground has none), ε = max(ε_a, ε_b) (Gazebo), μ_r =
// min(μ_r,a, μ_r,b) (as μ), and the friction set of the collider that comes first in
// Scene::colliders among those on a body (the ground has no say). The ground's default law
// (GroundLaw) is neutral under these rules: μ = the largest double, μ_r the largest float, R̄ = 0,
// ε = 0, so that a body's own law decides (Gazebo's ground_plane model has μ = 100, which would
// cap a body's μ).
#ifndef NONSMOOTH_SIM_CORE_SCENE_H_
#define NONSMOOTH_SIM_CORE_SCENE_H_

#include <Eigen/Core>
#include <algorithm>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/collision/collision_table.h"
#include "nonsmooth_sim/core/friction_law.h"
#include "nonsmooth_sim/core/shape.h"

namespace nonsmooth_sim {

/// A free rigid body. Its body frame K has its origin at the centre of mass S and the axes of the
/// link frame it was described in.
struct RigidBody {
  std::string name;
  double mass = 1.0;                                   ///< [kg], > 0
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();  ///< Θ_S in K [kg m²], symmetric PD
  /// Position of S in the link frame [m] (the URDF <inertial><origin>); the link frame's pose is
  /// the body pose composed with the translation -com_in_link. Zero for scenes built in code.
  Eigen::Vector3d com_in_link = Eigen::Vector3d::Zero();
};

/// Body index of a collider fixed in the world (static environment: the ground, walls, a table).
inline constexpr int kWorld = -1;

/// A convex shape fixed on a body (in its frame K, origin at S) or in the world.
struct Collider {
  std::string name;  ///< unique in the scene; contacts are named "<name a>/<name b>"
  int body = kWorld;  ///< index into Scene::bodies, or kWorld
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< shape frame → K (or → world)
  Shape shape;
  ContactLaw law;
};

/// The state of one body: q = (r_S, p) with f = 7 and u = (v_S, K_ω) with k = 6.
struct BodyState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();     ///< r_S in the world frame [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< unit, K → world
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   ///< v_S in the world frame [m/s]
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  ///< K_ω, in the body frame [rad/s]
};

struct Scene {
  std::vector<RigidBody> bodies;
  std::vector<Collider> colliders;
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};  ///< [m/s²]
  std::vector<BodyState> initial_state;      ///< one per body
  /// The pair functions every stage collides this scene's colliders with (collision_table.h):
  /// the core's closed forms, unless its builder registers more (RegisterFclPairs,
  /// collision_fcl/fcl_pairs.h; the scene loader takes it from its options).
  CollisionTable collision_table = CollisionTable::Defaults();
};

/// μ = largest double, μ_r = largest float, R̄ = 0, ε = 0: a body's own law decides (CombineLaws).
ContactLaw GroundLaw();
/// The ground plane z = 0 (normal +z), named "ground".
Collider GroundPlane(const ContactLaw& law = GroundLaw());

/// The law of a contact between colliders a and b (see the top of this file). Inline: the
/// contact pipeline asks for it per pair and step.
inline ContactLaw CombineLaws(const Collider& a, const Collider& b) {
  ContactLaw law;
  law.mu = std::min(a.law.mu, b.law.mu);
  law.rbar = std::max(a.law.rbar, b.law.rbar);
  law.restitution = std::max(a.law.restitution, b.law.restitution);
  law.rolling_resistance = std::min(a.law.rolling_resistance, b.law.rolling_resistance);
  // the set of the first collider on a body (a comes first in the scene unless it is static)
  law.friction_set = a.body != kWorld ? a.law.friction_set : b.law.friction_set;
  return law;
}

/// Index of the collider named `name`, or -1.
int FindCollider(const Scene& scene, const std::string& name);

/// Appends `model` to `world`: its bodies with their initial_state, its colliders (indices of its
/// bodies shifted to where they land); `world` keeps its collision_table. Returns the index of
/// its first body. Checks nothing (ValidateScene does); Simulator::AddBodies is this on the
/// simulator's scene.
int AppendScene(const Scene& model, Scene* world);
/// Removes from `world` the bodies b with remove_body[b] (and the colliders on them) and the
/// static colliders i with remove_collider[i], keeping the order of the rest. body_map and
/// collider_map (old → new index, -1: removed) are increasing over what remains.
/// Simulator::RemoveBodies is this on the simulator's scene.
void RemoveFromScene(const std::vector<char>& remove_body, const std::vector<char>& remove_collider,
                     Scene* world, std::vector<int>* body_map, std::vector<int>* collider_map);

/// Throws std::invalid_argument naming the element and the reason (non-positive mass, inertia not
/// symmetric positive definite, a bad shape, a plane on a body, μ < 0, R̄ < 0, ε ∉ [0, 1], NaN
/// anywhere, a collider on a missing body, two colliders with one name, initial_state of the wrong
/// size or not finite).
void ValidateScene(const Scene& scene);
/// Throws std::invalid_argument unless every entry is finite and the quaternions are non-zero.
void ValidateState(const Scene& scene, const std::vector<BodyState>& state);
/// Throws std::invalid_argument naming `where` (μ, R̄, μ_r finite ≥ 0, ε in [0, 1], a known set).
void ValidateLaw(const std::string& where, const ContactLaw& law);

/// Mechanical energy E = Σ ½ m|v_S|² + ½ ωᵀΘω - m g·r_S [J].
double MechanicalEnergy(const Scene& scene, const std::vector<BodyState>& state);

/// Angle between the body's e3 axis and the world z axis [rad], in [0, π].
double Inclination(const BodyState& state);

/// World pose of a body's frame K (origin S) from its state.
Eigen::Isometry3d BodyPose(const BodyState& state);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_SCENE_H_
