// (L1)–(L4) of rolling_lagrange.h: the world-axes, Lagrange-multiplier form of rolling.
#include "rolling_lagrange.h"

#include <array>
#include <stdexcept>

#include "reference/odeint.h"

namespace nonsmooth_sim::reference {
namespace {

namespace odeint = boost::numeric::odeint;

// (r_S, v_S, q_w, q_x, q_y, q_z, ω_w)
using OdeState = std::array<double, 13>;

Eigen::Matrix3d Hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(),
       v.z(), 0.0, -v.x(),
       -v.y(), v.x(), 0.0;
  return m;
}

struct LagrangeOde {
  const RollingBody* body;
  void operator()(const OdeState& x, OdeState& dxdt, double /*t*/) const {
    const Eigen::Vector3d v(x[3], x[4], x[5]);
    const Eigen::Quaterniond q_raw(x[6], x[7], x[8], x[9]);
    const Eigen::Matrix3d a = q_raw.normalized().toRotationMatrix();
    const Eigen::Vector3d omega(x[10], x[11], x[12]);
    const Eigen::Vector3d z_hat = Eigen::Vector3d::UnitZ();
    const double m = body->mass;
    // the contact point in world axes and its rate (L2)
    const Eigen::Vector3d d_body = a.transpose() * -z_hat;
    const SupportPoint p = body->contact(d_body);
    const Eigen::Vector3d r = a * p.r;
    const Eigen::Vector3d omega_body = a.transpose() * omega;
    const Eigen::Vector3d r_dot = omega.cross(r) + a * (p.dr_dd * d_body.cross(omega_body));
    // (L3): the contact force
    const Eigen::Matrix3d theta_w = a * body->inertia * a.transpose();
    const Eigen::Matrix3d theta_w_inv = theta_w.inverse();
    const Eigen::Vector3d gyro = omega.cross(theta_w * omega);
    const Eigen::Matrix3d w = Eigen::Matrix3d::Identity() / m +
                              Hat(r).transpose() * theta_w_inv * Hat(r);
    const Eigen::Vector3d force =
        w.llt().solve(kGravity * z_hat - omega.cross(r_dot) - Hat(r) * theta_w_inv * gyro);
    // (L1)
    const Eigen::Vector3d v_dot = force / m - kGravity * z_hat;
    const Eigen::Vector3d omega_dot = theta_w_inv * (r.cross(force) - gyro);
    // (L4)
    const Eigen::Quaterniond q_dot =
        Eigen::Quaterniond(0.0, omega.x(), omega.y(), omega.z()) * q_raw;
    for (int i = 0; i < 3; ++i) {
      dxdt[i] = v(i);
      dxdt[3 + i] = v_dot(i);
      dxdt[10 + i] = omega_dot(i);
    }
    dxdt[6] = 0.5 * q_dot.w();
    dxdt[7] = 0.5 * q_dot.x();
    dxdt[8] = 0.5 * q_dot.y();
    dxdt[9] = 0.5 * q_dot.z();
  }
};

}  // namespace

std::vector<RollingState> IntegrateLagrange(const RollingBody& body, const RollingState& start,
                                            const std::vector<double>& times, double tolerance) {
  std::vector<RollingState> out;
  out.reserve(times.size());
  if (times.empty()) return out;
  if (times.front() < start.t) {
    throw std::invalid_argument("IntegrateLagrange: a time before the start");
  }
  const Eigen::Quaterniond q0 = start.orientation.normalized();
  const Eigen::Vector3d omega0 = q0 * start.omega;
  OdeState x = {start.position.x(), start.position.y(), start.position.z(),
                start.velocity.x(), start.velocity.y(), start.velocity.z(),
                q0.w(), q0.x(), q0.y(), q0.z(), omega0.x(), omega0.y(), omega0.z()};
  auto stepper = odeint::make_controlled(tolerance, tolerance,
                                         odeint::runge_kutta_fehlberg78<OdeState>());
  const LagrangeOde ode{&body};
  constexpr double kFirstStep = 1e-4;  // [s], adapted at once
  if (times.front() > start.t) {
    odeint::integrate_adaptive(stepper, ode, x, start.t, times.front(),
                               std::min(kFirstStep, times.front() - start.t));
  }
  odeint::integrate_times(stepper, ode, x, times.begin(), times.end(), kFirstStep,
                          [&](const OdeState& xi, double t) {
                            RollingState s;
                            s.t = t;
                            s.position = Eigen::Vector3d(xi[0], xi[1], xi[2]);
                            s.velocity = Eigen::Vector3d(xi[3], xi[4], xi[5]);
                            s.orientation =
                                Eigen::Quaterniond(xi[6], xi[7], xi[8], xi[9]).normalized();
                            s.omega = s.orientation.conjugate() *
                                      Eigen::Vector3d(xi[10], xi[11], xi[12]);
                            out.push_back(s);
                          });
  return out;
}

}  // namespace nonsmooth_sim::reference
