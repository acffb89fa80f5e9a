// Scene validation and the observables of a state: energy, inclination, Jellett's integral.
#include "nonsmooth_sim/core/scene.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace nonsmooth_sim {
namespace {

// An inertia tensor read from a file or built in code is symmetric up to round-off of its
// entries; a larger asymmetry is an input error.
constexpr double kInertiaSymmetryTolerance = 1e-9;

std::string BodyName(const Scene& scene, std::size_t b) {
  std::ostringstream s;
  s << "scene.bodies[" << b << "]";
  if (!scene.bodies[b].name.empty()) s << " (" << scene.bodies[b].name << ")";
  return s.str();
}

std::string SphereName(const Scene& scene, std::size_t i) {
  std::ostringstream s;
  s << "scene.spheres[" << i << "]";
  if (!scene.spheres[i].name.empty()) s << " (" << scene.spheres[i].name << ")";
  return s.str();
}

[[noreturn]] void Reject(const std::string& what, double value, const std::string& allowed) {
  std::ostringstream s;
  s << what << " = " << value << ": must be " << allowed;
  throw std::invalid_argument(s.str());
}

void RequireFinite(const std::string& what, const Eigen::Ref<const Eigen::MatrixXd>& value) {
  if (!value.allFinite()) throw std::invalid_argument(what + " must be finite (no NaN or inf)");
}

void ValidateInertia(const std::string& where, const Eigen::Matrix3d& inertia) {
  const std::string what = where + ".inertia";
  RequireFinite(what, inertia);
  const double scale = inertia.cwiseAbs().maxCoeff();
  if ((inertia - inertia.transpose()).cwiseAbs().maxCoeff() > kInertiaSymmetryTolerance * scale) {
    throw std::invalid_argument(what + " must be symmetric");
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(inertia);
  if (!(eigen.eigenvalues().minCoeff() > 0.0)) {
    Reject(what + " smallest eigenvalue", eigen.eigenvalues().minCoeff(),
           "> 0 (positive definite) [kg m^2]");
  }
}

void ValidateLaw(const std::string& where, const ContactLaw& law) {
  if (!(std::isfinite(law.mu) && law.mu >= 0.0)) Reject(where + ".law.mu", law.mu, "finite, >= 0");
  if (!(std::isfinite(law.rbar) && law.rbar >= 0.0)) {
    Reject(where + ".law.rbar", law.rbar, "finite, >= 0 [m]");
  }
  if (!(law.restitution >= 0.0 && law.restitution <= 1.0)) {
    Reject(where + ".law.restitution", law.restitution, "in [0, 1]");
  }
  if (FrictionSetName(law.friction_set) == "unknown") {
    throw std::invalid_argument(where + ".law.friction_set is not one of " +
                                FrictionSetNameList());
  }
}

Eigen::Vector3d WorldAngularMomentum(const RigidBody& body, const BodyState& state) {
  return state.orientation.normalized() * (body.inertia * state.angular_velocity);
}

}  // namespace

void ValidateScene(const Scene& scene) {
  if (scene.bodies.empty()) throw std::invalid_argument("scene.bodies must not be empty");
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const RigidBody& body = scene.bodies[b];
    const std::string where = BodyName(scene, b);
    if (!(std::isfinite(body.mass) && body.mass > 0.0)) {
      Reject(where + ".mass", body.mass, "finite, > 0 [kg]");
    }
    ValidateInertia(where, body.inertia);
    RequireFinite(where + ".com_in_link", body.com_in_link);
  }
  for (std::size_t i = 0; i < scene.spheres.size(); ++i) {
    const Sphere& sphere = scene.spheres[i];
    const std::string where = SphereName(scene, i);
    if (sphere.body < 0 || static_cast<std::size_t>(sphere.body) >= scene.bodies.size()) {
      std::ostringstream s;
      s << where << ".body = " << sphere.body << ": must index scene.bodies, in [0, "
        << scene.bodies.size() - 1 << "]";
      throw std::invalid_argument(s.str());
    }
    RequireFinite(where + ".center", sphere.center);
    if (!(std::isfinite(sphere.radius) && sphere.radius > 0.0)) {
      Reject(where + ".radius", sphere.radius, "finite, > 0 [m]");
    }
    ValidateLaw(where, sphere.law);
  }
  RequireFinite("scene.gravity", scene.gravity);
  ValidateState(scene, scene.initial_state);
}

void ValidateState(const Scene& scene, const std::vector<BodyState>& state) {
  if (state.size() != scene.bodies.size()) {
    std::ostringstream s;
    s << "state has " << state.size() << " bodies: must have one per scene body ("
      << scene.bodies.size() << ")";
    throw std::invalid_argument(s.str());
  }
  for (std::size_t b = 0; b < state.size(); ++b) {
    std::ostringstream s;
    s << "state[" << b << "]";
    const std::string where = s.str();
    RequireFinite(where + ".position", state[b].position);
    RequireFinite(where + ".orientation", state[b].orientation.coeffs());
    RequireFinite(where + ".linear_velocity", state[b].linear_velocity);
    RequireFinite(where + ".angular_velocity", state[b].angular_velocity);
    if (!(state[b].orientation.coeffs().squaredNorm() > 0.0)) {
      throw std::invalid_argument(where + ".orientation must be a non-zero quaternion");
    }
  }
}

double MechanicalEnergy(const Scene& scene, const std::vector<BodyState>& state) {
  double energy = 0.0;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const RigidBody& body = scene.bodies[b];
    const BodyState& s = state[b];
    // ½ m|v_S|² + ½ ωᵀΘω - m g·r_S
    energy += 0.5 * body.mass * s.linear_velocity.squaredNorm() +
              0.5 * s.angular_velocity.dot(body.inertia * s.angular_velocity) -
              body.mass * scene.gravity.dot(s.position);
  }
  return energy;
}

double Inclination(const BodyState& state) {
  // e3 in the world frame is the third column of A(p); atan2 stays accurate near 0 and π
  const Eigen::Vector3d e3 = state.orientation.normalized() * Eigen::Vector3d::UnitZ();
  return std::atan2(std::hypot(e3.x(), e3.y()), e3.z());
}

double JellettIntegral(const Scene& scene, const std::vector<BodyState>& state, int sphere) {
  const Sphere& s = scene.spheres.at(static_cast<std::size_t>(sphere));
  const RigidBody& body = scene.bodies.at(static_cast<std::size_t>(s.body));
  const BodyState& b = state.at(static_cast<std::size_t>(s.body));
  // r_S - r_P = ρ ẑ - A K_r_SM, L_S = A Θ K_ω
  const Eigen::Vector3d s_minus_p =
      s.radius * Eigen::Vector3d::UnitZ() - b.orientation.normalized() * s.center;
  return WorldAngularMomentum(body, b).dot(s_minus_p);
}

}  // namespace nonsmooth_sim
