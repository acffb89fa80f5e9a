// The rolling equations (R1)–(R7) of rolling_reference.h and their integration.
#include "rolling_reference.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <stdexcept>

#include "reference/odeint.h"

namespace nonsmooth_sim::reference {
namespace {

namespace odeint = boost::numeric::odeint;

// (x_S, y_S, q_w, q_x, q_y, q_z, ω_B)
using OdeState = std::array<double, 9>;

Eigen::Quaterniond Orientation(const OdeState& x) {
  return Eigen::Quaterniond(x[2], x[3], x[4], x[5]).normalized();
}

Eigen::Vector3d Down(const Eigen::Quaterniond& q) {
  return q.conjugate() * Eigen::Vector3d(0.0, 0.0, -1.0);
}

OdeState ToOde(const RollingState& s) {
  const Eigen::Quaterniond q = s.orientation.normalized();
  return {s.position.x(), s.position.y(), q.w(), q.x(), q.y(), q.z(),
          s.omega.x(), s.omega.y(), s.omega.z()};
}

// The full state, with z_S from (R1) and v_S from (R2).
RollingState FromOde(const RollingBody& body, const OdeState& x, double t) {
  const Eigen::Quaterniond q = Orientation(x);
  const Eigen::Vector3d omega(x[6], x[7], x[8]);
  RollingState s = RollingStart(body, q, omega, Eigen::Vector2d(x[0], x[1]));
  s.t = t;
  return s;
}

// The right-hand side: (R2) for ẋ_S, ẏ_S, (R3) for q̇, (R6) for ω̇.
struct RollingOde {
  const RollingBody* body;
  void operator()(const OdeState& x, OdeState& dxdt, double /*t*/) const {
    const Eigen::Quaterniond q = Orientation(x);
    const Eigen::Vector3d omega(x[6], x[7], x[8]);
    const Eigen::Vector3d r = body->contact(Down(q)).r;
    // (R2), world axes
    const Eigen::Vector3d v_w = q * (-omega.cross(r));
    dxdt[0] = v_w.x();
    dxdt[1] = v_w.y();
    // (R3): q̇ = ½ q ⊗ (0, ω) with the integrated (not renormalised) q
    const Eigen::Quaterniond q_raw(x[2], x[3], x[4], x[5]);
    const Eigen::Quaterniond q_dot = q_raw * Eigen::Quaterniond(0.0, omega.x(), omega.y(),
                                                                omega.z());
    dxdt[2] = 0.5 * q_dot.w();
    dxdt[3] = 0.5 * q_dot.x();
    dxdt[4] = 0.5 * q_dot.y();
    dxdt[5] = 0.5 * q_dot.z();
    const Eigen::Vector3d omega_dot = AngularAcceleration(*body, Down(q), omega);
    dxdt[6] = omega_dot.x();
    dxdt[7] = omega_dot.y();
    dxdt[8] = omega_dot.z();
  }
};

auto Stepper(double tolerance) {
  return odeint::make_controlled(tolerance, tolerance,
                                 odeint::runge_kutta_fehlberg78<OdeState>());
}

// First trial step [s]; the controller adapts it at once.
constexpr double kFirstStep = 1e-4;

// Spin about the world vertical, ω_w·ẑ = (A ω)·ẑ = −d·ω.
double VerticalSpin(const OdeState& x) {
  return -Down(Orientation(x)).dot(Eigen::Vector3d(x[6], x[7], x[8]));
}

}  // namespace

RollingState RollingStart(const RollingBody& body, const Eigen::Quaterniond& orientation,
                          const Eigen::Vector3d& omega_body, const Eigen::Vector2d& xy) {
  RollingState s;
  s.orientation = orientation.normalized();
  s.omega = omega_body;
  const Eigen::Vector3d d = Down(s.orientation);
  const Eigen::Vector3d r = body.contact(d).r;
  s.position = Eigen::Vector3d(xy.x(), xy.y(), d.dot(r));  // (R1)
  s.velocity = s.orientation * (-omega_body.cross(r));      // (R2)
  return s;
}

RollingState StickingImpulseStart(const RollingBody& body, const Eigen::Quaterniond& orientation,
                                  const Eigen::Vector3d& omega_body,
                                  const Eigen::Vector3d& velocity, const Eigen::Vector2d& xy) {
  const Eigen::Quaterniond q = orientation.normalized();
  const Eigen::Vector3d r = body.contact(Down(q)).r;
  const Eigen::Vector3d v_body = q.conjugate() * velocity;
  // L_P before = Θ_P ω' after
  const Eigen::Matrix3d theta_p =
      body.inertia +
      body.mass * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  const Eigen::Vector3d omega =
      theta_p.llt().solve(body.inertia * omega_body - body.mass * r.cross(v_body));
  return RollingStart(body, q, omega, xy);
}

double Energy(const RollingBody& body, const RollingState& s) {
  // (R7) in its general form
  return 0.5 * body.mass * s.velocity.squaredNorm() + 0.5 * s.omega.dot(body.inertia * s.omega) +
         body.mass * kGravity * s.position.z();
}

Eigen::Vector3d AngularAcceleration(const RollingBody& body, const Eigen::Vector3d& down,
                                    const Eigen::Vector3d& omega) {
  const SupportPoint p = body.contact(down);
  const Eigen::Vector3d& r = p.r;
  const double m = body.mass;
  // (R3), (R4): P's rate over the surface
  const Eigen::Vector3d rho_dot = p.dr_dd * down.cross(omega);
  // (R6): Θ_P = Θ − m[r]×[r]× = Θ + m(|r|² I − r rᵀ)
  const Eigen::Matrix3d theta_p =
      body.inertia + m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  const Eigen::Vector3d rhs = -omega.cross(body.inertia * omega) -
                              m * r.cross(omega.cross(omega.cross(r) + rho_dot)) -
                              m * kGravity * r.cross(down);
  return theta_p.llt().solve(rhs);
}

std::vector<RollingState> Integrate(const RollingBody& body, const RollingState& start,
                                    const std::vector<double>& times, double tolerance) {
  std::vector<RollingState> out;
  out.reserve(times.size());
  if (times.empty()) return out;
  if (times.front() < start.t) throw std::invalid_argument("Integrate: a time before the start");
  // integrate_times starts at the first time: integrate up to it first
  OdeState x = ToOde(start);
  auto stepper = Stepper(tolerance);
  const RollingOde ode{&body};
  if (times.front() > start.t) {
    odeint::integrate_adaptive(stepper, ode, x, start.t, times.front(),
                               std::min(kFirstStep, times.front() - start.t));
  }
  odeint::integrate_times(stepper, ode, x, times.begin(), times.end(), kFirstStep,
                          [&](const OdeState& xi, double t) {
                            out.push_back(FromOde(body, xi, t));
                          });
  return out;
}

std::optional<double> FirstSpinReversal(const RollingBody& body, const RollingState& start,
                                        double t_end, double tolerance) {
  constexpr double kTimeTolerance = 1e-10;  // [s], the brief asks for 1e-9
  const RollingOde ode{&body};
  auto stepper = Stepper(tolerance);
  OdeState x = ToOde(start);
  double t = start.t;
  double dt = kFirstStep;
  const double sign0 = VerticalSpin(x) < 0.0 ? -1.0 : 1.0;
  while (t < t_end) {
    // one accepted step [t, t_next]
    const OdeState x_prev = x;
    const double t_prev = t;
    dt = std::min(dt, t_end - t);
    while (stepper.try_step(ode, x, t, dt) == odeint::fail) {
    }
    if (sign0 * VerticalSpin(x) > 0.0) continue;
    // the sign changed within [t_prev, t]: bisect, each trial integrated from t_prev
    double lo = t_prev;
    double hi = t;
    while (hi - lo > kTimeTolerance) {
      const double mid = 0.5 * (lo + hi);
      OdeState xm = x_prev;
      odeint::integrate_adaptive(stepper, ode, xm, t_prev, mid, std::min(kFirstStep, mid - t_prev));
      (sign0 * VerticalSpin(xm) > 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  }
  return std::nullopt;
}

Eigen::VectorXcd LinearStabilityExponents(const RollingBody& body, double omega_z) {
  // f(x) = (d × ω, ω̇(d, ω)), x = (d, ω), body axes
  const auto f = [&body](const Eigen::Matrix<double, 6, 1>& x) {
    const Eigen::Vector3d d = x.head<3>();
    const Eigen::Vector3d omega = x.tail<3>();
    Eigen::Matrix<double, 6, 1> out;
    out << d.cross(omega), AngularAcceleration(body, d, omega);
    return out;
  };
  Eigen::Matrix<double, 6, 1> x0;
  x0 << 0.0, 0.0, -1.0, 0.0, 0.0, omega_z;
  // central differences: error O(h²) of the third derivatives, round-off ~1e-16/h relative
  constexpr double kStep = 1e-6;
  Eigen::Matrix<double, 6, 6> jacobian;
  for (int i = 0; i < 6; ++i) {
    Eigen::Matrix<double, 6, 1> e = Eigen::Matrix<double, 6, 1>::Zero();
    e(i) = kStep;
    jacobian.col(i) = (f(x0 + e) - f(x0 - e)) / (2.0 * kStep);
  }
  Eigen::VectorXcd eigenvalues = Eigen::EigenSolver<Eigen::Matrix<double, 6, 6>>(jacobian)
                                     .eigenvalues();
  std::sort(eigenvalues.data(), eigenvalues.data() + eigenvalues.size(),
            [](const std::complex<double>& a, const std::complex<double>& b) {
              return a.real() > b.real() || (a.real() == b.real() && a.imag() > b.imag());
            });
  return eigenvalues;
}

}  // namespace nonsmooth_sim::reference
