// libFuzzer target: the input bytes are an initial-state YAML file (scene_io/initial_state.h; the
// node's ~initial_state and `simulate --initial`), applied the node's way (ConfiguredScene:
// world::InitialState of body 0, then scene_io::ApplyInitialState) to three shipped scenes: the
// Tippe-Top (one body on two spheres), the duel (two bodies that meet) and the die (a box, corners
// on the ground).
//
// Accepted outcomes: a std::exception with a one-line message (InitialStateError), per scene or for
// the text; or a start within the documented bounds (every centre-of-mass coordinate within
// kMaxInitialCoordinate, |v| <= kMaxInitialSpeed, |w| <= kMaxInitialAngularSpeed) that constructs
// a Simulator, is written back as YAML and read back to the same state, and takes kSteps steps
// under the stepping contract of fuzz_support.h.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "nonsmooth_sim/collision_fcl/fcl_pairs.h"
#include "nonsmooth_sim/world/initial_conditions.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace {

using namespace nonsmooth_sim;
using fuzz::Finding;
using fuzz::Require;

constexpr int kSteps = 20;

struct ShippedScene {
  scene_io::UrdfScene urdf;
  std::vector<BodyState> start;  // world::InitialState(urdf, 0, {}): the configured start
};

std::vector<ShippedScene>& Scenes() {
  static std::vector<ShippedScene> scenes;
  return scenes;
}

bool Near(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a - b).lpNorm<Eigen::Infinity>() <= 1e-9 * (1.0 + a.lpNorm<Eigen::Infinity>());
}

void CheckBounds(const Scene& scene, const std::vector<BodyState>& state) {
  for (std::size_t b = 0; b < state.size(); ++b) {
    const BodyState& s = state[b];
    const std::string& name = scene.bodies[b].name;
    Require(s.position.lpNorm<Eigen::Infinity>() <= scene_io::kMaxInitialCoordinate,
            "an accepted start puts the centre of mass of " + name + " beyond the bound");
    Require(s.linear_velocity.norm() <= scene_io::kMaxInitialSpeed,
            "an accepted start gives " + name + " a speed beyond the bound");
    Require(s.angular_velocity.norm() <= scene_io::kMaxInitialAngularSpeed,
            "an accepted start gives " + name + " an angular speed beyond the bound");
    Require(std::abs(s.orientation.norm() - 1.0) <= 1e-12,
            "an accepted start has a quaternion that is not normalised");
  }
}

void RunScene(const ShippedScene& shipped, const scene_io::InitialStateSpec& spec) {
  Scene scene = shipped.urdf.scene;
  try {
    scene.initial_state = scene_io::ApplyInitialState(scene, shipped.start, spec);
  } catch (const std::exception& e) {
    fuzz::RequireClearError(e, "ApplyInitialState");
    return;
  }
  Require(scene.initial_state.size() == scene.bodies.size(), "ApplyInitialState: wrong size");
  CheckBounds(scene, scene.initial_state);
  // bodies the spec does not name keep their configured start bit for bit
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    if (spec.count(scene.bodies[b].name) == 0) {
      Require(fuzz::SameBits(scene.initial_state[b], shipped.start[b]),
              "ApplyInitialState changed a body the YAML does not name");
    }
  }
  std::vector<BodyState> back;
  try {
    back = scene_io::InitialStateFromYaml(scene, scene_io::InitialStateToYaml(scene, scene.initial_state));
  } catch (const std::exception& e) {
    Finding(std::string("an accepted start does not survive a YAML round trip: ") + e.what());
  }
  for (std::size_t b = 0; b < back.size(); ++b) {
    const BodyState& s = scene.initial_state[b];
    Require(Near(s.position, back[b].position) &&
                Near(s.linear_velocity, back[b].linear_velocity) &&
                Near(s.angular_velocity, back[b].angular_velocity) &&
                std::abs(std::abs(s.orientation.dot(back[b].orientation)) - 1.0) <= 1e-12,
            "YAML round trip changed body " + scene.bodies[b].name);
  }
  std::unique_ptr<Simulator> sim;
  try {
    sim = std::make_unique<Simulator>(scene, SimulatorOptions{});
  } catch (const std::exception& e) {
    Finding(std::string("an accepted start does not construct a Simulator: ") + e.what());
  }
  for (int k = 0; k < kSteps; ++k) fuzz::StepUnderContract(*sim, "scene from YAML");
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  scene_io::UrdfSceneOptions options;
  RegisterFclPairs(&options.collision_table);  // as the node and simulate load
  for (const char* name : {"tippe_top", "tippe_top_duel", "die"}) {
    ShippedScene s;
    s.urdf = scene_io::LoadUrdfFile(std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/urdf/" + name +
                                    ".urdf", options);
    s.start = world::InitialState(s.urdf, 0, world::InitialConditions{});
    Scenes().push_back(std::move(s));
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  scene_io::InitialStateSpec spec;
  try {
    spec = scene_io::ParseInitialStateYaml(text);
  } catch (const std::exception& e) {
    fuzz::RequireClearError(e, "ParseInitialStateYaml");
    return 0;
  }
  for (const auto& [name, body] : spec) {
    Require(!body.orientation || std::abs(body.orientation->norm() - 1.0) <= 1e-12,
            "ParseInitialStateYaml: orientation of " + name + " not normalised");
    Require((!body.position || body.position->allFinite()) &&
                (!body.linear_velocity || body.linear_velocity->allFinite()) &&
                (!body.angular_velocity || body.angular_velocity->allFinite()),
            "ParseInitialStateYaml accepted a non-finite value for " + name);
  }
  for (const ShippedScene& shipped : Scenes()) RunScene(shipped, spec);
  return 0;
}
