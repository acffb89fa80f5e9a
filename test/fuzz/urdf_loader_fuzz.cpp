// libFuzzer target: the input bytes are URDF text, loaded the way the node loads its
// robot_description (scene_io::SceneFromUrdf with the default options, the FCL pairs registered).
//
// Accepted outcomes: a std::exception with a one-line message (the loader's clear error), or a
// scene that then goes the node's way without a fault of its own: the configured start of body 0
// (world::InitialState, as ~initial/... with nothing set), a Simulator constructed from it
// (nothing thrown: "what loads is a simulable rigid body"), the start-up overlap check, the start
// written as initial-state YAML and read back to the same state, and kSteps steps under the
// stepping contract of fuzz_support.h. Anything else (a crash, a sanitizer report, a leak, an
// exception of another kind or from where none is documented, a non-finite state that is not
// reported) is a finding.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "nonsmooth_sim/collision_fcl/fcl_pairs.h"
#include "nonsmooth_sim/core/overlaps.h"
#include "nonsmooth_sim/world/initial_conditions.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace {

using namespace nonsmooth_sim;
using fuzz::Finding;
using fuzz::Require;

constexpr int kSteps = 20;

bool Near(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (a - b).lpNorm<Eigen::Infinity>() <= 1e-9 * (1.0 + a.lpNorm<Eigen::Infinity>());
}

// The start written as YAML reads back as the same state (17 digits; r_S = position + R c and
// the quaternion renormalised cost a few ulps).
void CheckYamlRoundTrip(const Scene& scene) {
  std::string yaml;
  std::vector<BodyState> back;
  try {
    yaml = scene_io::InitialStateToYaml(scene, scene.initial_state);
    back = scene_io::InitialStateFromYaml(scene, yaml);
  } catch (const std::exception& e) {
    Finding(std::string("the loaded scene's start does not survive a YAML round trip: ") +
            e.what());
  }
  Require(back.size() == scene.initial_state.size(), "YAML round trip: body count changed");
  for (std::size_t b = 0; b < back.size(); ++b) {
    const BodyState& s = scene.initial_state[b];
    const BodyState& r = back[b];
    Require(Near(s.position, r.position) && Near(s.linear_velocity, r.linear_velocity) &&
                Near(s.angular_velocity, r.angular_velocity) &&
                std::abs(std::abs(s.orientation.normalized().dot(r.orientation)) - 1.0) <= 1e-12,
            "YAML round trip: body " + scene.bodies[b].name + " changed:\n" + yaml);
  }
}

// The default options with the FCL pairs in the collision table, as the node and simulate load;
// relative and package:// <mesh> paths lead nowhere (no folder, no package path), so an input
// reaches a file of the machine only by its exact absolute path (the dictionary holds none): the
// fuzzed mesh path is the loader's refusals (the mesh reader and the hull have their tests,
// test/scene_io/mesh_*_test.cpp)
const scene_io::UrdfSceneOptions& LoaderOptions() {
  static const scene_io::UrdfSceneOptions options = [] {
    scene_io::UrdfSceneOptions o;
    o.mesh_directory = "/nonexistent/nonsmooth_sim_fuzz_meshes";
    o.ros_package_path = "";
    RegisterFclPairs(&o.collision_table);
    return o;
  }();
  return options;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  scene_io::UrdfScene urdf;
  try {
    urdf = scene_io::SceneFromUrdf(text, LoaderOptions());
  } catch (const std::exception& e) {
    fuzz::RequireClearError(e, "SceneFromUrdf");
    return 0;
  }
  const Scene& loaded = urdf.scene;
  Require(!loaded.bodies.empty(), "a scene without a free body loaded");
  Require(urdf.tippe_top.size() == loaded.bodies.size() &&
              urdf.merged_links.size() == loaded.bodies.size() &&
              loaded.initial_state.size() == loaded.bodies.size(),
          "per-body lists of the UrdfScene do not match its bodies");
  for (const std::string& warning : urdf.warnings) {
    Require(!warning.empty() && warning.find('\n') == std::string::npos,
            "a loader warning that is not one line: " + warning);
  }

  // the node's configured start: body 0 with no ~initial/... set
  Scene scene = loaded;
  try {
    scene.initial_state = world::InitialState(urdf, 0, world::InitialConditions{});
  } catch (const std::exception& e) {
    Finding(std::string("world::InitialState of a loaded scene threw: ") + e.what());
  }
  Require(fuzz::Finite(scene.initial_state), "the configured start is not finite");

  std::unique_ptr<Simulator> sim;
  try {
    sim = std::make_unique<Simulator>(scene, SimulatorOptions{});
  } catch (const std::exception& e) {
    Finding(std::string("a loaded scene does not construct a Simulator: ") + e.what());
  }
  try {
    (void)FindOverlaps(sim->scene(), sim->state(), kOverlapWarningDepth);
  } catch (const std::exception& e) {
    Finding(std::string("FindOverlaps threw: ") + e.what());
  }
  CheckYamlRoundTrip(scene);
  for (int k = 0; k < kSteps; ++k) fuzz::StepUnderContract(*sim, "urdf scene");
  return 0;
}
