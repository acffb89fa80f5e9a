// The two rolling bodies of the reference (rolling_reference.h): Euler's disk on its rim and the
// rattleback's ellipsoid. Their numbers are typed here from the URDFs (nothing is read from files,
// so that the reference stays independent of the package's loader).
#include <cmath>

#include "rolling_reference.h"

namespace nonsmooth_sim::reference {
namespace {

// Support point of the ellipsoid |D⁻¹(p − O)| = 1, D = diag(s), for the direction d:
//   r = O + D² d / |D d|,   ∂r/∂d = D²/|D d| − (D² d)(D² d)ᵀ/|D d|³        (E1)
SupportPoint EllipsoidSupport(const Eigen::Vector3d& semi_axes, const Eigen::Vector3d& centre,
                              const Eigen::Vector3d& d) {
  const Eigen::Vector3d d2d = semi_axes.array().square().matrix().cwiseProduct(d);  // D² d
  const double norm = semi_axes.cwiseProduct(d).norm();                              // |D d|
  SupportPoint p;
  p.r = centre + d2d / norm;
  p.dr_dd = Eigen::Matrix3d(semi_axes.array().square().matrix().asDiagonal()) / norm -
            d2d * d2d.transpose() / (norm * norm * norm);
  return p;
}

// Lowest point of the two rim circles (radius a at z = ±h/2) of a cylinder: on the face towards
// d (sign of d_z), in the direction n of d's part in the face plane, d⊥ = (d_x, d_y, 0):
//   r = a n + (h/2) sign(d_z) e3,   n = d⊥/|d⊥|,   ∂r/∂d = a (P⊥ − n nᵀ)/|d⊥|,  P⊥ = diag(1,1,0)   (E2)
// (the sign does not change while the disc rolls on one face, so ∂/∂d of it is 0).
SupportPoint RimSupport(double radius, double thickness, const Eigen::Vector3d& d) {
  const Eigen::Vector3d d_perp(d.x(), d.y(), 0.0);
  const double norm = d_perp.norm();
  const Eigen::Vector3d n = d_perp / norm;
  SupportPoint p;
  p.r = radius * n + Eigen::Vector3d(0.0, 0.0, 0.5 * thickness * (d.z() < 0.0 ? -1.0 : 1.0));
  p.dr_dd = radius / norm *
            (Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal().toDenseMatrix() - n * n.transpose());
  return p;
}

}  // namespace

RollingBody EulerDisk() {
  // urdf/euler_disk.urdf: cylinder radius 0.0375 m, length 0.012 m; steel, ρ = 7850 kg/m³:
  // m = ρπa²h, A = B = m(3a² + h²)/12, C = m a²/2 (the URDF's <inertial>).
  constexpr double kRadius = 0.0375;
  constexpr double kThickness = 0.012;
  RollingBody body;
  body.name = "euler_disk";
  body.mass = 0.41616285183022284;
  body.inertia = Eigen::Vector3d(1.5130120681852537e-4, 1.5130120681852537e-4,
                                 2.926145051931254e-4).asDiagonal();
  body.contact = [](const Eigen::Vector3d& d) { return RimSupport(kRadius, kThickness, d); };
  return body;
}

RollingBody Rattleback(double theta_xy) {
  // urdf/rattleback.urdf (Kane & Levinson 1982): <inertial> m = 1, ixx = 2e-4, iyy = 1.6e-3,
  // izz = 1.7e-3, ixy = −2e-5 (the tensor entry Θ_xy, docs/scenes.md §2: URDF's ixy is the
  // off-diagonal element of the inertia matrix, not the product of inertia with its minus sign);
  // <nonsmooth_sim> ellipsoid semi_axes 0.20 0.03 0.02 on the collision origin z = +0.01 m.
  RollingBody body;
  body.name = "rattleback";
  body.mass = 1.0;
  body.inertia << 2.0e-4, theta_xy, 0.0,
                  theta_xy, 1.6e-3, 0.0,
                  0.0, 0.0, 1.7e-3;
  const Eigen::Vector3d semi_axes(0.20, 0.03, 0.02);
  const Eigen::Vector3d centre(0.0, 0.0, 0.01);
  body.contact = [semi_axes, centre](const Eigen::Vector3d& d) {
    return EllipsoidSupport(semi_axes, centre, d);
  };
  return body;
}

}  // namespace nonsmooth_sim::reference
