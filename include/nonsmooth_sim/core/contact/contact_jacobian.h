// The generalized force directions W_i of one contact over one or two free bodies, (10), (14),
// (16) of Möller, Leine, Glocker (ESMC 2009), for the body coordinates of rigid_body_dynamics.h.
//
// A contact between A and B has a frame (n, t1, t2) in the world: n the unit normal from A to B,
// t1, t2 unit tangents with t1 × t2 = n (contact_frame.h). The percussion Λ = (Λ_N, Λ_T1, Λ_T2,
// Λ_τ) acts on B at its contact point P_B as the force direction Λ_N n + Λ_T1 t1 + Λ_T2 t2 and
// the torque Λ_τ n about the normal (drilling, (50)), and equal and opposite on A at P_A. For
// one body with K_r_SP = Aᵀ(r_P - r_S) (in K) and a world direction d:
//   w_d = ± [d; K_r_SP × Aᵀd],   w_τ = ± [0; Aᵀn]        (+ on B, - on A)
// and the relative velocity γ = Wᵀu is the velocity of P_B minus that of P_A along (n, t1, t2)
// and the spin of B minus that of A about n (χ = 0: the world does not move). A static collider
// (the ground, a wall) contributes no side. Stacking the rows of one side as
//   L = [nᵀ; t1ᵀ; t2ᵀ; 0]  (4 × 3, world)   and   J = [K_r_SP × Aᵀn; K_r_SP × Aᵀt1;
//                                                     K_r_SP × Aᵀt2; Aᵀn]ᵀ  (4 × 3, in K),
//   γ = Σ_sides sign (L v_S + J K_ω),   W Λ on a side = sign (LᵀΛ, JᵀΛ),
//   G_ij = W_iᵀ M⁻¹ W_j = Σ over sides s of i and t of j on the same body
//          sign_s sign_t (L_i L_jᵀ / m + J_s Θ⁻¹ J_tᵀ)                                     (16)
// Rolling resistance adds two rows per side (ContactRollingRows): the rolling percussion
// Λ_R = (Λ_R1, Λ_R2) is the torque Λ_R1 t1 + Λ_R2 t2 on B and its opposite on A, so its rows are
// w_R = ± [0; Aᵀt1], ± [0; Aᵀt2] and γ_R the angular velocity of B minus that of A about t1, t2.
// With the ground as A this is the sphere–ground kinematics of the Tippe-Top: n = ẑ, t1 = x̂,
// t2 = ŷ, one side (B) with sign +1.
#ifndef NONSMOOTH_SIM_CORE_CONTACT_CONTACT_JACOBIAN_H_
#define NONSMOOTH_SIM_CORE_CONTACT_CONTACT_JACOBIAN_H_

#include <Eigen/Core>

#include "nonsmooth_sim/core/rigid_body_dynamics.h"

namespace nonsmooth_sim {

/// The unit normal n (from A to B) and tangents t1, t2 (t1 × t2 = n) of a contact, world.
struct ContactFrame {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d tangent1 = Eigen::Vector3d::UnitX();
  Eigen::Vector3d tangent2 = Eigen::Vector3d::UnitY();
};

/// One body's part of W_i.
struct ContactSide {
  int body = -1;      ///< body index; -1 = no side (static collider)
  double sign = 1.0;  ///< +1 on B, -1 on A
  Eigen::Matrix<double, 4, 3> angular = Eigen::Matrix<double, 4, 3>::Zero();  ///< J, in K
  /// J R with Θ⁻¹ = R Rᵀ of the body (BodyInertia): J Θ⁻¹ Jᵀ of G as a product of two
  /// (SetAngularRows sets both)
  Eigen::Matrix<double, 4, 3> angular_metric = Eigen::Matrix<double, 4, 3>::Zero();
};

struct ContactJacobian {
  Eigen::Matrix<double, 4, 3> linear = Eigen::Matrix<double, 4, 3>::Zero();  ///< L, world
  ContactSide side[2];  ///< side[0] on B, side[1] on A (body -1 where static)
};

/// J of one side: point P (world), body position r_S, rotation A = A(p) (K → world).
inline Eigen::Matrix<double, 4, 3> ContactAngularRows(const ContactFrame& frame,
                                                      const Eigen::Vector3d& point,
                                                      const Eigen::Vector3d& body_position,
                                                      const Eigen::Matrix3d& rotation) {
  // K_r_SP = Aᵀ(r_P - r_S); Aᵀd for d = n, t1, t2
  const Eigen::Vector3d r_sp = rotation.transpose() * (point - body_position);
  const Eigen::Vector3d n_body = rotation.transpose() * frame.normal;
  Eigen::Matrix<double, 4, 3> angular;
  angular.row(kNormal) = r_sp.cross(n_body);
  angular.row(kTangent1) = r_sp.cross(rotation.transpose() * frame.tangent1);
  angular.row(kTangent2) = r_sp.cross(rotation.transpose() * frame.tangent2);
  angular.row(kDrilling) = n_body;
  return angular;
}

/// The rolling rows of one side, in K: Aᵀt1, Aᵀt2 (a torque about each tangent); sign times
/// these rows applied to K_ω is the side's part of γ_R.
inline Eigen::Matrix<double, 2, 3> ContactRollingRows(const ContactFrame& frame,
                                                      const Eigen::Matrix3d& rotation) {
  Eigen::Matrix<double, 2, 3> rows;
  rows.row(0) = rotation.transpose() * frame.tangent1;
  rows.row(1) = rotation.transpose() * frame.tangent2;
  return rows;
}

/// The rolling rows of a contact's two sides (ContactRollingRows, in K; side[k] as
/// ContactJacobian::side[k]) and J_R R with them (Θ⁻¹ = R Rᵀ): set only where the contact has
/// rolling components.
struct RollingSide {
  Eigen::Matrix<double, 2, 3> rows = Eigen::Matrix<double, 2, 3>::Zero();
  Eigen::Matrix<double, 2, 3> metric = Eigen::Matrix<double, 2, 3>::Zero();
};
struct RollingJacobian {
  RollingSide side[2];
};

/// Sets the rolling rows of a side and J_R R with them.
inline void SetRollingRows(const Eigen::Matrix<double, 2, 3>& rows, const BodyInertia& body,
                           RollingSide* side) {
  side->rows = rows;
  if (body.principal) {
    side->metric.noalias() = rows * body.inverse_inertia_factor.diagonal().asDiagonal();
  } else {
    side->metric.noalias() = rows * body.inverse_inertia_factor;
  }
}

/// Sets J of a side and J R with it (the side's body's inertia).
inline void SetAngularRows(const Eigen::Matrix<double, 4, 3>& angular, const BodyInertia& body,
                           ContactSide* side) {
  side->angular = angular;
  if (body.principal) {
    side->angular_metric.noalias() = angular * body.inverse_inertia_factor.diagonal().asDiagonal();
  } else {
    side->angular_metric.noalias() = angular * body.inverse_inertia_factor;
  }
}

/// L of the frame: rows n, t1, t2, 0.
inline Eigen::Matrix<double, 4, 3> ContactLinearRows(const ContactFrame& frame) {
  Eigen::Matrix<double, 4, 3> linear;
  linear.row(kNormal) = frame.normal;
  linear.row(kTangent1) = frame.tangent1;
  linear.row(kTangent2) = frame.tangent2;
  linear.row(kDrilling).setZero();
  return linear;
}

/// One side's part of γ = Wᵀu: sign (L v_S + J K_ω).
inline Eigen::Vector4d SideVelocity(const ContactJacobian& jacobian, const ContactSide& side,
                                    const Eigen::Vector3d& linear_velocity,
                                    const Eigen::Vector3d& angular_velocity_body) {
  return side.sign * (jacobian.linear * linear_velocity + side.angular * angular_velocity_body);
}

/// The block sign_s sign_t (L_i L_jᵀ/m + J_s Θ⁻¹ J_tᵀ) of G_ij (16) for two sides on one body,
/// J_s Θ⁻¹ J_tᵀ = (J_s R)(J_t R)ᵀ. L has a zero drilling row: only its 3 × 3 part is formed.
inline Eigen::Matrix4d SideDelassusBlock(const BodyInertia& body, const ContactJacobian& i,
                                         const ContactSide& s, const ContactJacobian& j,
                                         const ContactSide& t) {
  Eigen::Matrix4d block;
  block.noalias() = s.angular_metric * t.angular_metric.transpose();
  block.topLeftCorner<3, 3>().noalias() +=
      body.inverse_mass * (i.linear.topRows<3>() * j.linear.topRows<3>().transpose());
  if (s.sign * t.sign < 0.0) block = -block;
  return block;
}

/// The rolling rows' part of G_ij (16) for sides s (of contact i) and t (of contact j) on one
/// body, beside SideDelassusBlock's 4 × 4 (rows and columns N, T1, T2, τ): the 4 × 2 block
/// sign_s sign_t (J_s R)(J_R,t R)ᵀ of (i's 4 rows, j's rolling rows), the 2 × 4 block of (i's
/// rolling rows, j's 4 rows) and the 2 × 2 block (J_R,s R)(J_R,t R)ᵀ; the rolling rows have no
/// linear part. A contact without rolling rows passes zero rows (its blocks come out zero).
inline void RollingDelassusParts(const ContactSide& s, const RollingSide& rs, const ContactSide& t,
                                 const RollingSide& rt, Eigen::Matrix<double, 6, 6>* block) {
  const double sign = s.sign * t.sign;
  block->topRightCorner<4, 2>().noalias() += sign * (s.angular_metric * rt.metric.transpose());
  block->bottomLeftCorner<2, 4>().noalias() += sign * (rs.metric * t.angular_metric.transpose());
  block->bottomRightCorner<2, 2>().noalias() += sign * (rs.metric * rt.metric.transpose());
}

/// The same for one side with itself, the part of G_ii its body gives: L Lᵀ = diag(1, 1, 1, 0)
/// (n, t1, t2 orthonormal), so only (J R)(J R)ᵀ is a product.
inline Eigen::Matrix4d OwnDelassusBlock(const BodyInertia& body, const ContactSide& s) {
  Eigen::Matrix4d block;
  block.noalias() = s.angular_metric * s.angular_metric.transpose();
  block(0, 0) += body.inverse_mass;
  block(1, 1) += body.inverse_mass;
  block(2, 2) += body.inverse_mass;
  return block;
}

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_CONTACT_CONTACT_JACOBIAN_H_
