// One step of each shipped scene (urdf/<scene>.urdf with config/<scene>.yaml): ns per step and
// closed contacts and solver iterations per step, after a warm-up into the scene's typical
// contact phase. Timing lives here, never in the tests. Run through scripts/dev/bench.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <string>

#include "nonsmooth_sim/collision_fcl/fcl_pairs.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace nonsmooth_sim {
namespace {

// warm-up before timing [s of sim time]: past the first touch-down of every scene
constexpr double kWarmUp = 0.2;

Scene LoadShipped(const std::string& name) {
  const std::string root = NONSMOOTH_SIM_SOURCE_DIR;
  scene_io::UrdfSceneOptions options;
  RegisterFclPairs(&options.collision_table);  // as simulate and the node load
  scene_io::UrdfScene urdf = scene_io::LoadUrdfFile(root + "/urdf/" + name + ".urdf", options);
  const std::string yaml = root + "/config/" + name + ".yaml";
  // a scene without a config file starts at its URDF pose
  if (std::filesystem::exists(yaml)) {
    urdf.scene.initial_state = scene_io::InitialStateFromYamlFile(urdf.scene, yaml);
  }
  return urdf.scene;
}

void BM_SceneStep(benchmark::State& state, const char* name) {
  Simulator sim(LoadShipped(name), SimulatorOptions{});
  StepStatistics stats;
  const long warm_up = static_cast<long>(kWarmUp / sim.options().time_step);
  for (long k = 0; k < warm_up; ++k) sim.Step(&stats);
  long contacts = 0;
  long iterations = 0;
  long steps = 0;
  for (auto _ : state) {
    sim.Step(&stats);
    contacts += stats.closed_contacts;
    iterations += stats.solver.iterations;
    ++steps;
  }
  state.counters["contacts_per_step"] = static_cast<double>(contacts) / static_cast<double>(steps);
  state.counters["solver_iterations"] = static_cast<double>(iterations) / static_cast<double>(steps);
}

#define NONSMOOTH_SIM_SCENE_BENCHMARK(name) BENCHMARK_CAPTURE(BM_SceneStep, name, #name)
NONSMOOTH_SIM_SCENE_BENCHMARK(tippe_top);
NONSMOOTH_SIM_SCENE_BENCHMARK(euler_disk);
NONSMOOTH_SIM_SCENE_BENCHMARK(rattleback);
NONSMOOTH_SIM_SCENE_BENCHMARK(spinning_egg);
NONSMOOTH_SIM_SCENE_BENCHMARK(classic_top);
NONSMOOTH_SIM_SCENE_BENCHMARK(tippe_top_duel);
NONSMOOTH_SIM_SCENE_BENCHMARK(coin);
NONSMOOTH_SIM_SCENE_BENCHMARK(die);

}  // namespace
}  // namespace nonsmooth_sim
