// Free rigid bodies and sphere–ground contacts: the ingredients of (10)-(18) of Möller, Leine,
// Glocker (ESMC 2009) for the scenes of scene.h.
//
// Coordinates of one body (f = 7, k = 6), body frame K with its origin at the centre of mass S:
//   q = (r_S, p):    r_S position of S in the world frame, p unit quaternion K → world, A = A(p)
//   u = (v_S, K_ω):  velocity of S in the world frame, angular velocity in K
//   q̇ = F(q) u  (10):  ṙ_S = v_S,  ṗ = ½ p ⊗ (0, K_ω)
//   M = diag(m I, Θ_S)    constant, so M⁻¹ = diag(I/m, Θ_S⁻¹) is precomputed once
//   h(q, u) = (m g, -K_ω × Θ_S K_ω)       gravity and gyroscopic term (14)
//
// Sphere with centre K_r_SM (in K, from S) and radius ρ against the ground plane z = 0 (normal ẑ):
//   g = (r_S + A K_r_SM)·ẑ - ρ                               gap (12)
//   P = r_S + A K_r_SM - ρ ẑ,  K_r_SP = K_r_SM - ρ Aᵀẑ         lowest point of the sphere
//   w_d = [d; K_r_SP × Aᵀd]       generalized force direction of a world force direction d at P
//   W = [w_N w_T1 w_T2 w_τ] with N = ẑ, T1 = x̂, T2 = ŷ, and the drilling direction
//   w_τ = [0; Aᵀẑ] (a torque about the ground normal) when the law has R̄ > 0 (50)
//   γ = Wᵀu + χ, χ = 0 for the fixed ground (10)
// Every direction's translational part is a world unit vector and the three are orthonormal, so
//   W_iᵀ M⁻¹ W_j = (1/m) diag(1, 1, 1, 0) + J_i Θ_S⁻¹ J_jᵀ    (16), same body,
// with J the 4×3 matrix of the rotational parts, rows K_r_SP × Aᵀẑ, K_r_SP × Aᵀx̂, K_r_SP × Aᵀŷ
// and Aᵀẑ.
//
// The Tippe-Top's numbers (tippe_top.h, ../shared/reference/tippe-top.md): m = 6 g,
// Θ_S = diag(8, 8, 7)·10⁻⁷ kg m², big sphere ρ = 15 mm at K_r_SM = (0, 0, 3 mm), peg sphere
// ρ = 5 mm at (0, 0, 16 mm), μ = 0.3, R = 0.5 mm (R̄ = 3πR/16 ≈ 0.2945 mm), ε = 0, g = 9.81 m/s².
#ifndef NONSMOOTH_SIM_CORE_RIGID_BODY_DYNAMICS_H_
#define NONSMOOTH_SIM_CORE_RIGID_BODY_DYNAMICS_H_

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace nonsmooth_sim {

/// Percussion / relative-velocity components of a sphere–ground contact, in this order.
enum ContactComponent : int { kNormal = 0, kTangent1 = 1, kTangent2 = 2, kDrilling = 3 };

/// Mass and inertia of one body with the inverses M⁻¹ needs, computed once.
struct BodyInertia {
  double mass = 1.0;          ///< m [kg], > 0
  double inverse_mass = 1.0;  ///< 1/m [1/kg]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();          ///< Θ_S in K [kg m²]
  Eigen::Matrix3d inverse_inertia = Eigen::Matrix3d::Identity();  ///< Θ_S⁻¹ [1/(kg m²)]
};
/// Requires mass > 0 and inertia symmetric positive definite (see ValidateScene).
BodyInertia MakeBodyInertia(double mass, const Eigen::Matrix3d& inertia);

/// M = diag(m I, Θ_S) (10), 6 × 6.
Eigen::Matrix<double, 6, 6> MassMatrix(const BodyInertia& body);

/// Inertia about S from the inertia about another point O: Θ_S = Θ_O - m(|r|² I - r rᵀ),
/// r = r_OS (parallel-axis theorem), all in the same frame [kg m², kg, m].
Eigen::Matrix3d InertiaAboutCenterOfMass(const Eigen::Matrix3d& inertia_about_point, double mass,
                                         const Eigen::Vector3d& point_to_center_of_mass);
/// Re-expresses an inertia tensor given in frame B in frame K: Θ_K = R Θ_B Rᵀ with R = A_KB.
Eigen::Matrix3d RotateInertia(const Eigen::Matrix3d& inertia_in_b,
                              const Eigen::Matrix3d& rotation_k_from_b);

/// The orientation part of q + h F(q) u (10), (13), (15): p + h · ½ p ⊗ (0, K_ω) (not normalised).
inline Eigen::Quaterniond AdvanceOrientation(const Eigen::Quaterniond& orientation,
                                             const Eigen::Vector3d& angular_velocity_body,
                                             double h) {
  // ½ h p ⊗ (0, ω): scalar part -½h p_v·ω, vector part ½h (p_w ω + p_v × ω)
  const double half_h = 0.5 * h;
  const Eigen::Vector3d p_v = orientation.vec();
  const Eigen::Vector3d& w = angular_velocity_body;
  const Eigen::Vector3d vec = p_v + half_h * (orientation.w() * w + p_v.cross(w));
  return Eigen::Quaterniond(orientation.w() - half_h * p_v.dot(w), vec.x(), vec.y(), vec.z());
}

/// Gyroscopic torque -K_ω × Θ_S K_ω of h (10) [N m], in K.
inline Eigen::Vector3d GyroscopicTorque(const Eigen::Matrix3d& inertia,
                                        const Eigen::Vector3d& angular_velocity_body) {
  return -angular_velocity_body.cross(inertia * angular_velocity_body);
}

/// Implicit midpoint rule on Euler's equations over one step:
///   Θ(ω_E - ω_B) = -Δt ω_M × Θ ω_M + angular_impulse,  ω_M = (ω_B + ω_E)/2,
/// solved by Newton's method to round-off. Without impulse it conserves ½ωᵀΘω and |Θω| exactly
/// (multiply by ω_Mᵀ resp. (Θω_M)ᵀ: the gyroscopic term drops out). angular_impulse in K [N m s],
/// Δt [s] > 0; `guess` starts the iteration (e.g. the explicit step).
Eigen::Vector3d ImplicitMidpointEuler(const BodyInertia& body, const Eigen::Vector3d& omega_begin,
                                      const Eigen::Vector3d& angular_impulse, double dt,
                                      const Eigen::Vector3d& guess);

/// Gap g of a sphere against the ground z = 0 (12) [m]; rotation = A(p) K → world.
inline double SphereGroundGap(const Eigen::Vector3d& position, const Eigen::Matrix3d& rotation,
                              const Eigen::Vector3d& center_body, double radius) {
  return position.z() + rotation.row(2).dot(center_body) - radius;
}

/// Kinematics of a sphere–ground contact at one configuration (see the top of this file).
struct GroundContactKinematics {
  double gap = 0.0;                                  ///< g [m]
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< P in the world frame [m]
  /// Rotational parts of w_N, w_T1, w_T2, w_τ (rows), in K [m, m, m, 1]. The translational parts
  /// are ẑ, x̂, ŷ and 0.
  Eigen::Matrix<double, 4, 3> angular = Eigen::Matrix<double, 4, 3>::Zero();
};
inline GroundContactKinematics SphereGroundKinematics(const Eigen::Vector3d& position,
                                                      const Eigen::Matrix3d& rotation,
                                                      const Eigen::Vector3d& center_body,
                                                      double radius) {
  GroundContactKinematics contact;
  // Aᵀx̂, Aᵀŷ, Aᵀẑ are the rows of A
  const Eigen::Vector3d x_body = rotation.row(0).transpose();
  const Eigen::Vector3d y_body = rotation.row(1).transpose();
  const Eigen::Vector3d z_body = rotation.row(2).transpose();
  // K_r_SP = K_r_SM - ρ Aᵀẑ
  const Eigen::Vector3d r_sp = center_body - radius * z_body;
  contact.point = position + rotation * r_sp;
  contact.gap = contact.point.z();
  // rotational parts of w_d = [d; K_r_SP × Aᵀd] and of w_τ = [0; Aᵀẑ]
  contact.angular.row(kNormal) = r_sp.cross(z_body);
  contact.angular.row(kTangent1) = r_sp.cross(x_body);
  contact.angular.row(kTangent2) = r_sp.cross(y_body);
  contact.angular.row(kDrilling) = z_body;
  return contact;
}

/// γ = Wᵀu (χ = 0) for the four directions (N, T1, T2, τ) [m/s, m/s, m/s, rad/s].
inline Eigen::Vector4d ContactVelocity(const GroundContactKinematics& contact,
                                       const Eigen::Vector3d& linear_velocity,
                                       const Eigen::Vector3d& angular_velocity_body) {
  Eigen::Vector4d gamma = contact.angular * angular_velocity_body;
  gamma[kNormal] += linear_velocity.z();
  gamma[kTangent1] += linear_velocity.x();
  gamma[kTangent2] += linear_velocity.y();
  return gamma;
}

/// Linear part of W Λ (a world force/percussion): (Λ_T1, Λ_T2, Λ_N).
inline Eigen::Vector3d ContactLinearImpulse(const Eigen::Vector4d& percussion) {
  return {percussion[kTangent1], percussion[kTangent2], percussion[kNormal]};
}
/// Rotational part of W Λ, in K: Jᵀ Λ.
inline Eigen::Vector3d ContactAngularImpulse(const GroundContactKinematics& contact,
                                             const Eigen::Vector4d& percussion) {
  return contact.angular.transpose() * percussion;
}

/// Delassus block W_iᵀ M⁻¹ W_j (16) of two contacts on the same body, all four directions.
inline Eigen::Matrix4d DelassusBlock(const BodyInertia& body, const GroundContactKinematics& a,
                                     const GroundContactKinematics& b) {
  Eigen::Matrix4d block = a.angular * body.inverse_inertia * b.angular.transpose();
  block(kNormal, kNormal) += body.inverse_mass;
  block(kTangent1, kTangent1) += body.inverse_mass;
  block(kTangent2, kTangent2) += body.inverse_mass;
  return block;
}

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_RIGID_BODY_DYNAMICS_H_
