// Initial conditions -> core BodyState. See initial_conditions.h.
#include "nonsmooth_sim/world/initial_conditions.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "nonsmooth_sim/world/placement.h"

namespace nonsmooth_sim::world {
namespace {

template <typename T>
std::optional<T> Pick(const std::optional<T>& over, const std::optional<T>& def) {
  return over ? over : def;
}

void RequireFinite(const char* field, bool finite) {
  if (!finite) throw std::invalid_argument(std::string(field) + " must be finite");
}

}  // namespace

InitialConditions Merge(const InitialConditions& defaults, const InitialConditions& overrides) {
  InitialConditions m;
  m.inclination = Pick(overrides.inclination, defaults.inclination);
  m.spin = Pick(overrides.spin, defaults.spin);
  m.position = Pick(overrides.position, defaults.position);
  m.orientation = Pick(overrides.orientation, defaults.orientation);
  m.linear_velocity = Pick(overrides.linear_velocity, defaults.linear_velocity);
  m.angular_velocity = Pick(overrides.angular_velocity, defaults.angular_velocity);
  return m;
}

void ValidateInitialConditions(const InitialConditions& initial) {
  if (initial.inclination) {
    RequireFinite("inclination", std::isfinite(*initial.inclination));
    if (*initial.inclination < 0.0 || *initial.inclination > kPi) {
      throw std::invalid_argument("inclination must be in [0, pi] rad, got " +
                                  std::to_string(*initial.inclination));
    }
  }
  if (initial.spin) {
    RequireFinite("spin", std::isfinite(*initial.spin));
    if (std::abs(*initial.spin) > scene_io::kMaxInitialAngularSpeed) {
      std::ostringstream s;
      s << "spin = " << *initial.spin << " rad/s: |spin| must be <= "
        << scene_io::kMaxInitialAngularSpeed << " rad/s (finite kinetic energy, bounded dt*|w|)";
      throw std::invalid_argument(s.str());
    }
  }
  if (initial.position) {
    RequireFinite("position", initial.position->allFinite());
    scene_io::CheckInitialPosition("position", *initial.position);
  }
  if (initial.orientation) {
    RequireFinite("orientation", initial.orientation->coeffs().allFinite());
    // |q|² overflows for components near 1e154 and underflows near 1e-162: either way it
    // cannot be normalised
    const double norm2 = initial.orientation->coeffs().squaredNorm();
    if (norm2 == 0.0 || !std::isfinite(norm2)) {
      throw std::invalid_argument(
          "orientation must be a quaternion that can be normalised (non-zero, |q|^2 finite)");
    }
  }
  if (initial.linear_velocity) {
    RequireFinite("linear_velocity", initial.linear_velocity->allFinite());
    scene_io::CheckInitialLinearVelocity("linear_velocity", *initial.linear_velocity);
  }
  if (initial.angular_velocity) {
    RequireFinite("angular_velocity", initial.angular_velocity->allFinite());
    scene_io::CheckInitialAngularVelocity("angular_velocity", *initial.angular_velocity);
  }
}

std::vector<BodyState> InitialState(const scene_io::UrdfScene& urdf, int body,
                                    const InitialConditions& initial) {
  ValidateInitialConditions(initial);
  const Scene& scene = urdf.scene;
  if (body < 0 || body >= static_cast<int>(scene.bodies.size())) {
    throw std::out_of_range("body index " + std::to_string(body) + " out of range");
  }
  const TippeTopInitialConditions defaults;
  const TippeTopInitialConditions tilt{initial.inclination.value_or(defaults.inclination),
                                       initial.spin.value_or(defaults.spin)};

  std::vector<BodyState> state = scene.initial_state;
  const bool any = initial.inclination || initial.spin || initial.position ||
                   initial.orientation || initial.linear_velocity || initial.angular_velocity;
  // a scene that is not a Tippe-Top starts at its URDF pose (and ~initial_state) unless asked
  if (!urdf.tippe_top[body] && !any) return state;
  BodyState& s = state[body];
  if (urdf.tippe_top[body]) {
    // the core's own start for the Tippe-Top, bit for bit
    s = TippeTopInitialState(*urdf.tippe_top[body], tilt);
  } else {
    const double x = s.position.x();
    const double y = s.position.y();
    s.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(tilt.inclination, Eigen::Vector3d::UnitX()));
    s.angular_velocity = Eigen::Vector3d(0.0, 0.0, tilt.spin);
    s.linear_velocity.setZero();
    s.position = Eigen::Vector3d(x, y, TouchingHeight(scene, body, s.orientation, s.position.z()));
  }
  if (initial.orientation) {
    s.orientation = initial.orientation->normalized();
    s.position.z() = TouchingHeight(scene, body, s.orientation, s.position.z());
  }
  if (initial.position) s.position = *initial.position;
  if (initial.linear_velocity) s.linear_velocity = *initial.linear_velocity;
  if (initial.angular_velocity) s.angular_velocity = *initial.angular_velocity;
  return state;
}

std::vector<BodyState> StartState(const scene_io::UrdfScene& urdf, const StartSpec& start) {
  std::vector<BodyState> state = InitialState(urdf, start.body, start.conditions);
  if (!start.bodies.empty()) state = scene_io::ApplyInitialState(urdf.scene, state, start.bodies);
  return state;
}

}  // namespace nonsmooth_sim::world
