// Free rigid bodies: the ingredients of (10)-(18) of Möller, Leine,
// Glocker (ESMC 2009) for the scenes of scene.h.
//
// Coordinates of one body (f = 7, k = 6), body frame K with its origin at the centre of mass S:
//   q = (r_S, p):    r_S position of S in the world frame, p unit quaternion K → world, A = A(p)
//   u = (v_S, K_ω):  velocity of S in the world frame, angular velocity in K
//   q̇ = F(q) u  (10):  ṙ_S = v_S,  ṗ = ½ p ⊗ (0, K_ω)
//   M = diag(m I, Θ_S)    constant, so M⁻¹ = diag(I/m, Θ_S⁻¹) is precomputed once
//   h(q, u) = (m g, -K_ω × Θ_S K_ω)       gravity and gyroscopic term (14)
//
// Contacts over one or two bodies: contact/contact_jacobian.h.
//
// The Tippe-Top's numbers (tippe_top.h, ../shared/reference/tippe-top.md): m = 6 g,
// Θ_S = diag(8, 8, 7)·10⁻⁷ kg m², big sphere ρ = 15 mm at K_r_SM = (0, 0, 3 mm), peg sphere
// ρ = 5 mm at (0, 0, 16 mm), μ = 0.3, R = 0.5 mm (R̄ = 3πR/16 ≈ 0.2945 mm), ε = 0, g = 9.81 m/s².
#ifndef NONSMOOTH_SIM_CORE_RIGID_BODY_DYNAMICS_H_
#define NONSMOOTH_SIM_CORE_RIGID_BODY_DYNAMICS_H_

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace nonsmooth_sim {

/// Percussion / relative-velocity components of a contact, in this order.
enum ContactComponent : int { kNormal = 0, kTangent1 = 1, kTangent2 = 2, kDrilling = 3 };

/// Mass and inertia of one body with the inverses M⁻¹ needs, computed once.
struct BodyInertia {
  double mass = 1.0;          ///< m [kg], > 0
  double inverse_mass = 1.0;  ///< 1/m [1/kg]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();          ///< Θ_S in K [kg m²]
  Eigen::Matrix3d inverse_inertia = Eigen::Matrix3d::Identity();  ///< Θ_S⁻¹ [1/(kg m²)]
  /// R with Θ_S⁻¹ = R Rᵀ, lower triangular (Cholesky): J Θ⁻¹ Jᵀ = (J R)(J R)ᵀ
  Eigen::Matrix3d inverse_inertia_factor = Eigen::Matrix3d::Identity();
  bool principal = true;  ///< Θ_S diagonal in K (then so is R)
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

/// Θ_S⁻¹ x in K, three products where Θ_S is diagonal (BodyInertia::principal, most bodies):
/// the same values as the full product, whose other terms are zeros.
inline Eigen::Vector3d InverseInertiaTimes(const BodyInertia& body, const Eigen::Vector3d& x) {
  if (body.principal) return body.inverse_inertia.diagonal().cwiseProduct(x);
  return body.inverse_inertia * x;
}

/// GyroscopicTorque of a body, with the diagonal product where Θ_S is diagonal.
inline Eigen::Vector3d GyroscopicTorque(const BodyInertia& body,
                                        const Eigen::Vector3d& angular_velocity_body) {
  if (!body.principal) return GyroscopicTorque(body.inertia, angular_velocity_body);
  return -angular_velocity_body.cross(body.inertia.diagonal().cwiseProduct(angular_velocity_body));
}

/// Implicit midpoint rule on Euler's equations over one step:
///   Θ(ω_E - ω_B) = -Δt ω_M × Θ ω_M + angular_impulse,  ω_M = (ω_B + ω_E)/2,
/// solved by Newton's method to round-off. Without impulse it conserves ½ωᵀΘω and |Θω| exactly
/// (multiply by ω_Mᵀ resp. (Θω_M)ᵀ: the gyroscopic term drops out). angular_impulse in K [N m s],
/// Δt [s] > 0; `guess` starts the iteration (e.g. the explicit step).
Eigen::Vector3d ImplicitMidpointEuler(const BodyInertia& body, const Eigen::Vector3d& omega_begin,
                                      const Eigen::Vector3d& angular_impulse, double dt,
                                      const Eigen::Vector3d& guess);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_RIGID_BODY_DYNAMICS_H_
