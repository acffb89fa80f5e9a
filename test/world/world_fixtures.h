// Tiny URDF fixtures and a snapshot of everything a refused world call must leave as it was.
#ifndef NONSMOOTH_SIM_TEST_WORLD_WORLD_FIXTURES_H_
#define NONSMOOTH_SIM_TEST_WORLD_WORLD_FIXTURES_H_

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "nonsmooth_sim/world/world.h"

namespace nonsmooth_sim::world::testing {

/// One free link "ball" (mass 2 kg, sphere "shell" of radius 0.05 m at the link origin = S).
inline std::string BallUrdf(const std::string& robot = "ball") {
  return "<robot name=\"" + robot + "\"><link name=\"ball\"><inertial><mass value=\"2\"/>"
         "<inertia ixx=\"0.002\" ixy=\"0\" ixz=\"0\" iyy=\"0.002\" iyz=\"0\" izz=\"0.002\"/>"
         "</inertial><collision name=\"shell\"><geometry><sphere radius=\"0.05\"/></geometry>"
         "</collision></link></robot>";
}

inline scene_io::UrdfScene Load(const std::string& urdf, double gravity, bool ground) {
  scene_io::UrdfSceneOptions options;
  options.gravity = gravity;
  options.ground = ground;
  return scene_io::SceneFromUrdf(urdf, options);
}

inline bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Everything observable of a world, bit for bit.
struct WorldSnapshot {
  std::vector<double> numbers;  ///< state, time, external wrenches, scheduled wrenches
  std::vector<std::string> names;  ///< bodies, colliders, models, configured scene

  explicit WorldSnapshot(const World& w) {
    const Simulator& sim = w.sim();
    numbers.push_back(sim.time());
    for (const BodyState& s : sim.state()) {
      for (int k = 0; k < 3; ++k) {
        numbers.push_back(s.position[k]);
        numbers.push_back(s.linear_velocity[k]);
        numbers.push_back(s.angular_velocity[k]);
      }
      for (int k = 0; k < 4; ++k) numbers.push_back(s.orientation.coeffs()[k]);
    }
    for (std::size_t b = 0; b < sim.scene().bodies.size(); ++b) {
      const auto [f, t] = sim.ExternalWrench(static_cast<int>(b));
      for (int k = 0; k < 3; ++k) {
        numbers.push_back(f[k]);
        numbers.push_back(t[k]);
      }
    }
    for (const ExternalWrench& x : w.wrenches().wrenches()) {
      numbers.push_back(x.body);
      numbers.push_back(x.start);
      numbers.push_back(x.end);
      for (int k = 0; k < 3; ++k) numbers.push_back(x.force[k]);
    }
    for (const RigidBody& b : sim.scene().bodies) names.push_back("body " + b.name);
    for (const Collider& c : sim.scene().colliders) names.push_back("collider " + c.name);
    for (const Model& m : w.models().models()) names.push_back("model " + m.name);
    for (const RigidBody& b : w.configured_scene().bodies) names.push_back("configured " + b.name);
    for (const BodyState& s : w.configured_scene().initial_state) {
      for (int k = 0; k < 3; ++k) numbers.push_back(s.position[k]);
    }
  }

  void ExpectSame(const WorldSnapshot& other, const std::string& call) const {
    EXPECT_EQ(names, other.names) << call;
    ASSERT_EQ(numbers.size(), other.numbers.size()) << call;
    for (std::size_t i = 0; i < numbers.size(); ++i) {
      EXPECT_TRUE(SameBits(numbers[i], other.numbers[i])) << call << ": number " << i;
    }
  }
};

}  // namespace nonsmooth_sim::world::testing

#endif  // NONSMOOTH_SIM_TEST_WORLD_WORLD_FIXTURES_H_
