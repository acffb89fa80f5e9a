// The Tippe-Top scene, see tippe_top.h.
#include "nonsmooth_sim/core/tippe_top.h"

#include <cmath>

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

  Sphere big;
  big.name = "big_sphere";
  big.body = 0;
  big.center = Eigen::Vector3d(0.0, 0.0, parameters.big_offset);
  big.radius = parameters.big_radius;
  big.law = law;
  Sphere peg = big;
  peg.name = "peg_sphere";
  peg.center = Eigen::Vector3d(0.0, 0.0, parameters.peg_offset);
  peg.radius = parameters.peg_radius;
  scene.spheres = {big, peg};

  scene.gravity = Eigen::Vector3d(0.0, 0.0, -parameters.gravity);
  scene.initial_state = {TippeTopInitialState(parameters, initial)};
  return scene;
}

}  // namespace nonsmooth_sim
