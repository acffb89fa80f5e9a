// Rigid-body kinematics, mass matrix, gyroscopic term and sphere–ground contact kinematics, see
// rigid_body_dynamics.h.
#include "nonsmooth_sim/core/rigid_body_dynamics.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <limits>

namespace nonsmooth_sim {
namespace {

// Newton on the implicit midpoint equation stops when the update is below this many units of
// round-off relative to |ω|: the quadratic invariants are then kept to round-off.
constexpr double kNewtonRelativeTolerance = 4.0 * std::numeric_limits<double>::epsilon();
// Newton converges quadratically from the explicit guess (error O((Δt|ω|)²)); three iterations
// reach round-off for Δt|ω| up to ~0.5, the cap only guards pathological input.
constexpr int kMaxNewtonIterations = 12;

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return s;
}

}  // namespace

BodyInertia MakeBodyInertia(double mass, const Eigen::Matrix3d& inertia) {
  BodyInertia body;
  body.mass = mass;
  body.inverse_mass = 1.0 / mass;
  // symmetrise: ValidateScene accepts round-off asymmetry
  body.inertia = 0.5 * (inertia + inertia.transpose());
  body.inverse_inertia = body.inertia.inverse();
  body.inverse_inertia = 0.5 * (body.inverse_inertia + body.inverse_inertia.transpose()).eval();
  body.inverse_inertia_factor = body.inverse_inertia.llt().matrixL();
  // a diagonal Θ_S (principal axes, the usual URDF inertia) has the diagonal factor
  // R = diag(Θ_S⁻¹)^½, which J R needs only as a column scaling
  body.principal = body.inertia.isDiagonal(0.0);
  return body;
}

Eigen::Matrix<double, 6, 6> MassMatrix(const BodyInertia& body) {
  Eigen::Matrix<double, 6, 6> m = Eigen::Matrix<double, 6, 6>::Zero();
  m.topLeftCorner<3, 3>().diagonal().setConstant(body.mass);
  m.bottomRightCorner<3, 3>() = body.inertia;
  return m;
}

Eigen::Matrix3d InertiaAboutCenterOfMass(const Eigen::Matrix3d& inertia_about_point, double mass,
                                         const Eigen::Vector3d& point_to_center_of_mass) {
  const Eigen::Vector3d& r = point_to_center_of_mass;
  return inertia_about_point -
         mass * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
}

Eigen::Matrix3d RotateInertia(const Eigen::Matrix3d& inertia_in_b,
                              const Eigen::Matrix3d& rotation_k_from_b) {
  return rotation_k_from_b * inertia_in_b * rotation_k_from_b.transpose();
}

Eigen::Vector3d ImplicitMidpointEuler(const BodyInertia& body, const Eigen::Vector3d& omega_begin,
                                      const Eigen::Vector3d& angular_impulse, double dt,
                                      const Eigen::Vector3d& guess) {
  const Eigen::Matrix3d& theta = body.inertia;
  Eigen::Vector3d omega_end = guess;
  for (int k = 0; k < kMaxNewtonIterations; ++k) {
    const Eigen::Vector3d omega_mid = 0.5 * (omega_begin + omega_end);
    const Eigen::Vector3d spin_mid = theta * omega_mid;
    // residual Θ(ω_E - ω_B) + Δt ω_M × Θω_M - impulse
    const Eigen::Vector3d residual =
        theta * (omega_end - omega_begin) + dt * omega_mid.cross(spin_mid) - angular_impulse;
    // Jacobian Θ + Δt/2 ([ω_M]× Θ - [Θω_M]×)
    const Eigen::Matrix3d jacobian =
        theta + (0.5 * dt) * (Skew(omega_mid) * theta - Skew(spin_mid));
    const Eigen::Vector3d delta = jacobian.inverse() * residual;
    omega_end -= delta;
    if (delta.norm() <= kNewtonRelativeTolerance * omega_end.norm()) break;
  }
  return omega_end;
}

}  // namespace nonsmooth_sim
