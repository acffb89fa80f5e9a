// The scenes and options several dynamics tests share (free_fall_test.cpp, restitution_test.cpp,
// torque_free_test.cpp, sliding_block_test.cpp, validation_test.cpp): a ball above the ground and
// the simulator's options with a time step and a gyroscopic scheme.
#ifndef NONSMOOTH_SIM_TEST_CORE_DYNAMICS_SCENES_H_
#define NONSMOOTH_SIM_TEST_CORE_DYNAMICS_SCENES_H_

#include <Eigen/Core>

#include "nonsmooth_sim/core/scene.h"
#include "nonsmooth_sim/core/simulator_options.h"
#include "scene_builders.h"

namespace nonsmooth_sim {
namespace test {

inline constexpr double kGravity = 9.81;  ///< [m/s²], the default Scene::gravity's magnitude

/// A ball of `radius` whose lowest point is `height` above the ground, at rest, with a Coulomb
/// law of `mu` and `restitution`.
inline Scene BallScene(double radius, double height, double restitution, double mu) {
  Scene scene;
  RigidBody ball;
  ball.name = "ball";
  ball.mass = 0.2;
  ball.inertia = Eigen::Matrix3d::Identity() * (0.4 * ball.mass * radius * radius);
  scene.bodies = {ball};
  ContactLaw law;
  law.mu = mu;
  law.restitution = restitution;
  law.friction_set = FrictionSet::kCoulomb;
  scene.colliders = {SphereCollider("ball", 0, Eigen::Vector3d::Zero(), radius, law)};
  AddGround(&scene);
  BodyState state;
  state.position = Eigen::Vector3d(0.0, 0.0, radius + height);
  scene.initial_state = {state};
  return scene;
}

/// The default options with time step `dt` and gyroscopic scheme `scheme`.
inline SimulatorOptions Options(double dt, GyroscopicScheme scheme = GyroscopicScheme::kExplicit) {
  SimulatorOptions options;
  options.time_step = dt;
  options.gyroscopic = scheme;
  return options;
}

}  // namespace test
}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_TEST_CORE_DYNAMICS_SCENES_H_
