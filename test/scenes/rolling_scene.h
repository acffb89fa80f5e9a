// The shipped scenes made to roll without slip or drilling (μ = 10, R = 0, coulomb), as the
// independent no-slip reference of test/reference/ models them, and the reference's start for the
// rattleback's shipped start.
#ifndef NONSMOOTH_SIM_TEST_SCENES_ROLLING_SCENE_H_
#define NONSMOOTH_SIM_TEST_SCENES_ROLLING_SCENE_H_

#include <string>

#include "reference/rolling_reference.h"
#include "scene_test_support.h"

namespace nonsmooth_sim::scene_test {

inline Scene RollingScene(const std::string& name) {
  scene_io::UrdfSceneOptions options;
  options.mu = 10.0;
  options.contact_radius = 0.0;
  options.friction_set = FrictionSet::kCoulomb;
  Scene scene = LoadShippedScene(name, options);
  for (Collider& c : scene.colliders) {
    if (c.body != kWorld) c.law.friction_set = FrictionSet::kCoulomb;
  }
  return scene;
}

/// The reference's start for a simulator started from `s`: the shipped start slips, and the
/// first step (μ = 10) sticks it impulsively, keeping the angular momentum about the contact point
/// (StickingImpulseStart; a rolling start is left as it is).
inline reference::RollingState RattlebackReferenceStart(const BodyState& s) {
  return reference::StickingImpulseStart(reference::Rattleback(), s.orientation,
                                         s.angular_velocity, s.linear_velocity,
                                         s.position.head<2>());
}

/// The spin about the world vertical [rad/s].
inline double VerticalSpin(const BodyState& s) { return (s.orientation * s.angular_velocity).z(); }

}  // namespace nonsmooth_sim::scene_test

#endif  // NONSMOOTH_SIM_TEST_SCENES_ROLLING_SCENE_H_
