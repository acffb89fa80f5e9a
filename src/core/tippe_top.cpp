// The Tippe-Top scene, see tippe_top.h.
#include "nonsmooth_sim/core/tippe_top.h"

#include <cmath>
#include <stdexcept>

namespace nonsmooth_sim {

BodyState TippeTopInitialState(const TippeTopParameters& parameters,
                               const TippeTopInitialConditions& initial) {
  BodyState state;
  // e3 tilted by θ0 about the world x axis
  state.orientation =
      Eigen::Quaterniond(Eigen::AngleAxisd(initial.inclination, Eigen::Vector3d::UnitX()));
  // the big sphere touches the floor: z_S0 = R1 - a1 cos θ0
  state.position = Eigen::Vector3d(
      0.0, 0.0, parameters.big_radius - parameters.big_offset * std::cos(initial.inclination));
  state.linear_velocity.setZero();
  // spin about the tilted symmetry axis e3
  state.angular_velocity = Eigen::Vector3d(0.0, 0.0, initial.spin);
  return state;
}

Scene MakeTippeTopScene(const TippeTopParameters& parameters,
                        const TippeTopInitialConditions& initial) {
  Scene scene;
  RigidBody body;
  body.name = "tippe_top";
  body.mass = parameters.mass;
  body.inertia = Eigen::Vector3d(parameters.inertia_equatorial, parameters.inertia_equatorial,
                                 parameters.inertia_axial)
                     .asDiagonal();
  scene.bodies.push_back(body);

  ContactLaw law;
  law.mu = parameters.mu;
  law.rbar = AverageFrictionRadius(parameters.contact_radius);  // (50)
  law.restitution = parameters.restitution;
  law.friction_set = parameters.friction_set;
  law.rolling_resistance = static_cast<float>(parameters.rolling_resistance);

  Collider big;
  big.name = "big_sphere";
  big.body = 0;
  big.pose.translation() = Eigen::Vector3d(0.0, 0.0, parameters.big_offset);
  big.shape = Shape::Sphere(parameters.big_radius);
  big.law = law;
  Collider peg = big;
  peg.name = "peg_sphere";
  peg.pose.translation() = Eigen::Vector3d(0.0, 0.0, parameters.peg_offset);
  peg.shape = Shape::Sphere(parameters.peg_radius);
  scene.colliders = {big, peg, GroundPlane()};

  scene.gravity = Eigen::Vector3d(0.0, 0.0, -parameters.gravity);
  scene.initial_state = {TippeTopInitialState(parameters, initial)};
  return scene;
}

double JellettIntegral(const Scene& scene, const std::vector<BodyState>& state, int sphere) {
  const Collider& s = scene.colliders.at(static_cast<std::size_t>(sphere));
  if (s.shape.type != ShapeType::kSphere || s.body == kWorld) {
    throw std::invalid_argument("JellettIntegral: collider " + s.name +
                                " is not a sphere on a body");
  }
  const RigidBody& body = scene.bodies.at(static_cast<std::size_t>(s.body));
  const BodyState& b = state.at(static_cast<std::size_t>(s.body));
  const Eigen::Quaterniond p = b.orientation.normalized();
  // r_S - r_P = ρ ẑ - A K_r_SM, L_S = A Θ K_ω
  const Eigen::Vector3d s_minus_p =
      s.shape.radius * Eigen::Vector3d::UnitZ() - p * s.pose.translation();
  return (p * (body.inertia * b.angular_velocity)).dot(s_minus_p);
}

}  // namespace nonsmooth_sim
