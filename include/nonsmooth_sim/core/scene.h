// A scene: free rigid bodies, spheres fixed on them that touch the ground plane z = 0, each with
// its own contact law, gravity, and the initial state. A plain data structure: the headless
// simulator builds it in code (tippe_top.h), the ROS node from a URDF.
#ifndef NONSMOOTH_SIM_CORE_SCENE_H_
#define NONSMOOTH_SIM_CORE_SCENE_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/contact_solver.h"

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

/// A sphere fixed on a body; it makes a contact with the ground plane z = 0 (normal +z).
struct Sphere {
  std::string name;
  int body = 0;                                   ///< index into Scene::bodies
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< centre in K, relative to S [m]
  double radius = 0.0;                            ///< [m], > 0
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
  std::vector<Sphere> spheres;
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};  ///< [m/s²]
  std::vector<BodyState> initial_state;      ///< one per body
};

/// Throws std::invalid_argument naming the element and the reason (non-positive mass, inertia not
/// symmetric positive definite, radius ≤ 0, μ < 0, R̄ < 0, ε ∉ [0, 1], NaN anywhere, a sphere on a
/// missing body, initial_state of the wrong size or not finite).
void ValidateScene(const Scene& scene);
/// Throws std::invalid_argument unless every entry is finite and the quaternions are non-zero.
void ValidateState(const Scene& scene, const std::vector<BodyState>& state);

/// Mechanical energy E = Σ ½ m|v_S|² + ½ ωᵀΘω - m g·r_S [J].
double MechanicalEnergy(const Scene& scene, const std::vector<BodyState>& state);

/// Angle between the body's e3 axis and the world z axis [rad], in [0, π].
double Inclination(const BodyState& state);

/// Jellett's integral for sphere `sphere` touching the ground: J = L_S · (r_S - r_P) with P the
/// lowest point of the sphere [kg m³/s] (Tippe-Top: J = L_S · (R1 ẑ - a1 e3)).
double JellettIntegral(const Scene& scene, const std::vector<BodyState>& state, int sphere);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_SCENE_H_
