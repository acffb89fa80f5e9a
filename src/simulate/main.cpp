// `simulate`: the Tippe-Top without ROS. Parses the command line (cli.h), runs the simulator,
// writes the CSV time series and the JSON summary, reports on stdout.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>

#include "cli.h"
#include "contact_csv.h"
#include "monitor.h"
#include "nonsmooth_sim/collision_fcl/fcl_pairs.h"
#include "nonsmooth_sim/core/adaptive_stepper.h"
#include "nonsmooth_sim/core/overlaps.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/schedule.h"
#include "nonsmooth_sim/world/world.h"
#include "schedule_run.h"
#include "nonsmooth_sim/scene_io/one_line.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "progress.h"

namespace nonsmooth_sim::simulate {
namespace {

constexpr int kExitOk = 0;
constexpr int kExitOutputError = 1;
constexpr int kExitUsage = 2;
constexpr int kExitNonFinite = 3;  // the run diverged; outputs end at the last finite state
constexpr int kExitInternal = 4;   // out of memory, or an unexpected error (one line)

// CPU time of this thread [s]: unlike wall time, not inflated when other processes share the core.
double ThreadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Creates (truncates) an output file up front, so that a bad path fails before a long run.
bool CanWrite(const std::string& path) {
  if (path.empty()) return true;
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) return false;
  return std::fclose(file) == 0;
}

std::string Optional(const std::optional<double>& t) {
  if (!t) return "never";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.4f s", *t);
  return buffer;
}

void PrintReport(const RunSummary& s) {
  const RunConfig& c = s.config;
  if (!s.tippe_top) {
    std::printf("%s, integrator %s, solver %s (tolerance %g), dt %g s, %g s, gyroscopic %s\n",
                c.urdf_path.c_str(), std::string(IntegratorName(c.options.integrator)).c_str(),
                std::string(SolverTypeName(c.options.solver.type)).c_str(),
                c.options.solver.tolerance_rel, c.options.time_step, c.duration,
                std::string(GyroscopicSchemeName(c.options.gyroscopic)).c_str());
    std::printf("  %zu bodies; at most %d closed contacts in %d islands; deepest penetration "
                "%.3g m\n",
                s.body_names.size(), s.max_closed_contacts, s.max_islands, s.max_penetration);
    std::printf("  energy %.6g J -> %.6g J, largest step increase %.3g J\n", s.energy_initial,
                s.energy_final, s.max_energy_increase);
    for (std::size_t b = 0; b < s.body_names.size(); ++b) {
      const Eigen::Vector3d& p = s.final_link_position[b];
      std::printf("  %s ends at (%.4f, %.4f, %.4f) m, |v| %.3g m/s, |omega| %.3g rad/s\n",
                  s.body_names[b].c_str(), p.x(), p.y(), p.z(),
                  s.final_state[b].linear_velocity.norm(),
                  s.final_state[b].angular_velocity.norm());
    }
    std::printf("  solver: %.2f iterations per step (max %d), %ld steps unconverged\n",
                s.mean_iterations, s.max_iterations, s.unconverged_steps);
    std::printf("  wall %.4f s (cpu %.4f s) for %ld steps: %.0f steps/s, %.1fx real time\n",
                s.wall_time_s, s.cpu_time_s, s.steps, s.steps / s.wall_time_s,
                c.duration / s.wall_time_s);
    return;
  }
  std::printf("Tippe-Top, integrator %s, friction set %s, solver %s (tolerance %g), dt %g s, "
              "%g s, gyroscopic %s\n",
              std::string(IntegratorName(c.options.integrator)).c_str(),
              std::string(FrictionSetName(c.parameters.friction_set)).c_str(),
              std::string(SolverTypeName(c.options.solver.type)).c_str(),
              c.options.solver.tolerance_rel, c.options.time_step, c.duration,
              std::string(GyroscopicSchemeName(c.options.gyroscopic)).c_str());
  std::printf("  theta > pi/2 at %s, > 2.4 rad (peg touchdown) at %s, > 2.9 rad at %s\n",
              Optional(s.t_theta_above_pi_2).c_str(), Optional(s.t_theta_above_2_4).c_str(),
              Optional(s.t_theta_above_2_9).c_str());
  std::printf("  on the peg alone %.4f s, falls back at %s\n", s.time_on_peg_s,
              Optional(s.t_fall_back).c_str());
  std::printf("  end: theta %.4f rad, z_S %.3f mm, vertical spin %.2f rad/s\n", s.theta_final,
              1e3 * s.z_final, s.vertical_spin_final);
  std::printf("  energy %.6g J -> %.6g J, largest step increase %.3g J\n", s.energy_initial,
              s.energy_final, s.max_energy_increase);
  if (c.options.gap_correction) {
    std::printf("  gap correction: %ld steps lifted, largest lift %.3g m, +%.3g J in total\n",
                s.gap_correction_steps, s.gap_correction_max, s.gap_correction_energy);
  } else {
    std::printf("  gap correction off: smallest gap %.3g m\n", s.min_gap);
  }
  if (!s.state_finite) {
    std::printf("  STOPPED: the state became non-finite at t = %s (values above: last finite "
                "state)\n",
                Optional(s.t_non_finite).c_str());
  }
  std::printf("  solver: %.2f iterations per step (max %d), %ld steps unconverged\n",
              s.mean_iterations, s.max_iterations, s.unconverged_steps);
  std::printf("  wall %.4f s (cpu %.4f s) for %ld steps: %.0f steps/s, %.1fx real time\n",
              s.wall_time_s, s.cpu_time_s, s.steps, s.steps / s.wall_time_s,
              c.duration / s.wall_time_s);
}

// Once per run, at the first step with Δt·|ω| beyond the explicit scheme's safe range.
void WarnExplicitGyroscopicUnsafe(double dt_omega, double t, double dt) {
  std::fprintf(stderr,
               "simulate: warning: explicit gyroscopic term outside its safe range dt*|omega| <= "
               "%g (reached %.2g at t = %.4g s): energy can grow by O((dt*|omega|)^2) per step "
               "and diverge; use --gyroscopic implicit_midpoint or --dt <= %.1e\n",
               kExplicitGyroscopicMaxDtOmega, dt_omega, t,
               kExplicitGyroscopicMaxDtOmega * dt / dt_omega);
}

// The collision table of every scene of a run (the URDF's, the built-in Tippe-Top's, the
// scheduled models'): the core's closed forms, and FCL for the convex pairs without one (box–box,
// cylinder–box, ...).
CollisionTable RunCollisionTable() {
  CollisionTable table = CollisionTable::Defaults();
  RegisterFclPairs(&table);
  return table;
}

// The loader's options of a URDF: the laws the command line overrides, the run's collision table.
scene_io::UrdfSceneOptions UrdfOptions(const RunConfig& config) {
  scene_io::UrdfSceneOptions options;
  options.collision_table = RunCollisionTable();
  if (config.friction_set_given) options.friction_set = config.parameters.friction_set;
  if (config.mu_given) options.mu = config.parameters.mu;
  if (config.contact_radius_given) options.contact_radius = config.parameters.contact_radius;
  if (config.rolling_resistance_given) {
    options.rolling_resistance = config.parameters.rolling_resistance;
  }
  return options;
}

// The scene: a URDF (with the options that override its laws, and a YAML start), or the
// built-in Tippe-Top; `name` its model's name. Throws std::invalid_argument (a bad file) with
// one line.
Scene BuildScene(const RunConfig& config, std::string* name) {
  *name = "tippe_top";
  if (config.urdf_path.empty()) {
    Scene scene = MakeTippeTopScene(config.parameters, config.initial);
    scene.collision_table = RunCollisionTable();  // scheduled models may bring boxes
    return scene;
  }
  scene_io::UrdfSceneOptions options = UrdfOptions(config);
  options.hold_joints = config.hold_joints;  // the --urdf's joints (not the spawned models')
  scene_io::UrdfScene urdf = scene_io::LoadUrdfFile(config.urdf_path, options);
  *name = urdf.robot_name;
  for (const std::string& warning : urdf.warnings) {
    std::fprintf(stderr, "simulate: warning: %s\n", warning.c_str());
  }
  if (config.friction_set_given) {
    // every collision's set, also where the URDF names one
    for (Collider& c : urdf.scene.colliders) c.law.friction_set = config.parameters.friction_set;
  }
  if (!config.initial_path.empty()) {
    urdf.scene.initial_state =
        scene_io::InitialStateFromYamlFile(urdf.scene, config.initial_path);
  }
  return urdf.scene;
}

// Colliders that overlap at the start: one warning each, with the depth (the simulation pushes
// them apart; a deep overlap is a scene error the user should see).
void ReportInitialOverlaps(const Simulator& simulator) {
  const Scene& scene = simulator.scene();
  for (const Overlap& o : FindOverlaps(scene, simulator.state(), kOverlapWarningDepth)) {
    std::fprintf(stderr,
                 "simulate: warning: collisions \"%s\" and \"%s\" overlap by %.3g m at the "
                 "start (resolved by the first steps)\n",
                 scene.colliders[static_cast<std::size_t>(o.collider_a)].name.c_str(),
                 scene.colliders[static_cast<std::size_t>(o.collider_b)].name.c_str(), o.depth);
  }
}

// Bodies that can no longer touch anything (world/lost_bodies.h): one warning each, when first
// found.
void CheckLostBodies(double t, const Simulator& simulator, RunMonitor* monitor,
                     ProgressBar* progress) {
  for (const LostBodyRecord& lost : monitor->CheckLostBodies(t, simulator)) {
    progress->Finish();
    std::fprintf(stderr, "simulate: warning: body \"%s\" %s (found at t = %.4g s)\n",
                 lost.name.c_str(), lost.why.c_str(), lost.t);
  }
}

// `schedule`: the events of --schedule before each step (nullptr: none).
template <typename RecordRow>
void RunFixed(const RunConfig& config, long steps, world::World* world, ScheduleRunner* schedule,
              RunMonitor* monitor, ProgressBar* progress, const RecordRow& record_row) {
  Simulator* simulator = &world->sim();
  const bool record = !config.csv_path.empty() || !config.contacts_csv_path.empty();
  const double dt = config.options.time_step;
  StepStatistics stats;
  bool warned = false;
  const long check_steps = std::max(1L, std::lround(kLostBodyCheckInterval / dt));
  for (long step = 1; step <= steps; ++step) {
    if (schedule != nullptr) schedule->Before(world, static_cast<double>(step - 1) * dt, dt);
    simulator->Step(&stats);
    const double t = static_cast<double>(step) * dt;
    if (!stats.state_finite) {
      monitor->ObserveNonFinite(t);
      progress->Finish();
      std::fprintf(stderr,
                   "simulate: the state became non-finite at t = %.6g s (step %ld of %ld, "
                   "dt*|omega| = %.3g, gyroscopic %s); stopped at the last finite state, the "
                   "outputs end there (summary \"state_finite\": false)\n",
                   t, step, steps, stats.max_dt_omega,
                   std::string(GyroscopicSchemeName(config.options.gyroscopic)).c_str());
      break;
    }
    if (stats.explicit_gyroscopic_unsafe && !warned) {
      warned = true;
      progress->Finish();
      WarnExplicitGyroscopicUnsafe(stats.max_dt_omega, t, dt);
    }
    monitor->Observe(step, t, dt, *simulator, stats);
    if (step % check_steps == 0) CheckLostBodies(t, *simulator, monitor, progress);
    if (record && (step % config.decimate == 0 || step == steps)) record_row(t, stats);
    progress->Update(step);
  }
}

// --accuracy: the adaptive stepper lands on every sample time (decimate x dt) of the CSV; without
// a CSV, every kProgressInterval only (a landing shortens one step), so that the sample time does
// not cap the step
constexpr double kProgressInterval = 0.1;  // [s] of simulated time
template <typename RecordRow>
void RunAdaptive(const RunConfig& config, AdaptiveStepper* stepper, Simulator* simulator,
                 RunMonitor* monitor, ProgressBar* progress, const RecordRow& record_row) {
  const bool record = !config.csv_path.empty() || !config.contacts_csv_path.empty();
  const double csv_sample = static_cast<double>(config.decimate) * config.options.time_step;
  const double sample = record ? csv_sample : std::max(csv_sample, kProgressInterval);
  const long samples = std::max(1L, std::lround(std::ceil(config.duration / sample - 1e-9)));
  const long steps = std::llround(config.duration / config.options.time_step);
  long step = 0;
  bool warned = false;
  double next_check = kLostBodyCheckInterval;
  const auto observe = [&](const StepStatistics& s, double h) {
    ++step;
    if (s.explicit_gyroscopic_unsafe && !warned) {
      warned = true;
      progress->Finish();
      WarnExplicitGyroscopicUnsafe(s.max_dt_omega, simulator->time(), h);
    }
    monitor->Observe(step, simulator->time(), h, *simulator, s);
  };
  for (long k = 1; k <= samples; ++k) {
    const double t = std::min(config.duration, static_cast<double>(k) * sample);
    const StepStatistics stats = stepper->AdvanceTo(t, observe);
    if (!stats.state_finite) {
      monitor->ObserveNonFinite(simulator->time());
      progress->Finish();
      std::fprintf(stderr,
                   "simulate: the state became non-finite near t = %.6g s (adaptive step); "
                   "stopped at the last finite state, the outputs end there (summary "
                   "\"state_finite\": false)\n",
                   simulator->time());
      break;
    }
    if (t >= next_check) {
      CheckLostBodies(t, *simulator, monitor, progress);
      next_check = t + kLostBodyCheckInterval;
    }
    if (record) record_row(t, stats);
    progress->Update(std::min<long>(steps, std::lround(t / config.options.time_step)));
  }
}

int Run(const RunConfig& config) {
  // the world the node serves, over the same Simulator(scene, options)
  std::string name;
  Scene scene = BuildScene(config, &name);
  world::World world(std::move(scene), name, config.options);
  Simulator& simulator = world.sim();
  std::optional<ScheduleRunner> schedule;
  if (!config.schedule_path.empty()) {
    schedule.emplace(scene_io::LoadScheduleFile(config.schedule_path), UrdfOptions(config));
  }
  ReportInitialOverlaps(simulator);
  const long steps = std::llround(config.duration / config.options.time_step);

  for (const std::string* path :
       {&config.csv_path, &config.contacts_csv_path, &config.summary_path}) {
    if (!CanWrite(*path)) {
      std::fprintf(stderr, "simulate: cannot write %s\n", path->c_str());
      return kExitOutputError;
    }
  }

  const bool record = !config.csv_path.empty() || !config.contacts_csv_path.empty();
  // the Tippe-Top keeps its columns; a URDF scene gets per-body ones
  const long rows = record ? steps / config.decimate + 2 : 0;
  std::optional<CsvRecorder> tippe_csv;
  std::optional<BodyCsvRecorder> body_csv;
  if (config.csv_path.empty()) {
    // no time series (--contacts-csv alone)
  } else if (config.urdf_path.empty()) {
    tippe_csv.emplace(simulator, rows);
  } else {
    if (schedule) {
      body_csv.emplace(schedule->BodyColumns(simulator.scene()), rows);
    } else {
      body_csv.emplace(simulator, rows);
    }
  }
  std::optional<ContactCsvRecorder> contact_csv;
  if (!config.contacts_csv_path.empty()) contact_csv.emplace();
  auto record_row = [&](double t, const StepStatistics& s) {
    if (tippe_csv) tippe_csv->Record(t, simulator, s);
    if (body_csv) body_csv->Record(t, simulator, s);
    if (contact_csv) contact_csv->Record(t, simulator);
  };
  RunMonitor monitor(config, simulator);
  ProgressBar progress(steps, config.duration, !config.quiet);
  CheckLostBodies(0.0, simulator, &monitor, &progress);
  StepStatistics stats;
  if (record) record_row(0.0, stats);

  // the timed loop: steps and per-step monitors; CSV rows are only copied here
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = ThreadCpuSeconds();
  if (config.accuracy.tolerance > 0.0) {
    AdaptiveStepper stepper(&simulator, config.accuracy);
    RunAdaptive(config, &stepper, &simulator, &monitor, &progress, record_row);
    monitor.SetAdaptive(stepper.statistics());
  } else {
    RunFixed(config, steps, &world, schedule ? &*schedule : nullptr, &monitor, &progress,
             record_row);
  }
  const auto stop = std::chrono::steady_clock::now();
  const double cpu_time = ThreadCpuSeconds() - cpu_start;
  progress.Finish();

  RunSummary summary = monitor.Finish(simulator);
  summary.wall_time_s = std::chrono::duration<double>(stop - start).count();
  summary.cpu_time_s = cpu_time;
  if (!config.csv_path.empty() && !(tippe_csv ? tippe_csv->Write(config.csv_path)
                                               : body_csv->Write(config.csv_path))) {
    std::fprintf(stderr, "simulate: cannot write %s\n", config.csv_path.c_str());
    return kExitOutputError;
  }
  if (contact_csv && !contact_csv->Write(config.contacts_csv_path)) {
    std::fprintf(stderr, "simulate: cannot write %s\n", config.contacts_csv_path.c_str());
    return kExitOutputError;
  }
  summary.output_wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stop).count();
  if (!config.summary_path.empty() && !WriteSummaryJson(summary, config.summary_path)) {
    std::fprintf(stderr, "simulate: cannot write %s\n", config.summary_path.c_str());
    return kExitOutputError;
  }
  if (!config.quiet) PrintReport(summary);
  return summary.state_finite ? kExitOk : kExitNonFinite;
}

}  // namespace
}  // namespace nonsmooth_sim::simulate

int main(int argc, char** argv) {
  using namespace nonsmooth_sim::simulate;
  const ParseResult parsed = ParseCommandLine(argc, argv);
  if (std::holds_alternative<HelpRequest>(parsed)) {
    std::fputs(UsageText().c_str(), stdout);
    return kExitOk;
  }
  if (std::holds_alternative<FrictionSetsRequest>(parsed)) {
    std::fputs(FrictionSetsText().c_str(), stdout);
    return kExitOk;
  }
  if (const auto* error = std::get_if<UsageError>(&parsed)) {
    std::fprintf(stderr, "simulate: %s\n", error->message.c_str());
    return kExitUsage;
  }
  try {
    return Run(std::get<RunConfig>(parsed));
  } catch (const std::invalid_argument& e) {
    // a bad file, or a combination the core rejects (all single values are range-checked by the
    // parser)
    std::fprintf(stderr, "simulate: %s\n", e.what());
    return kExitUsage;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "simulate: out of memory (the scene or the run needs more memory than "
                         "the system gives)\n");
    return kExitInternal;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "simulate: internal error: %s\n",
                 nonsmooth_sim::scene_io::OneLine(e.what()).c_str());
    return kExitInternal;
  } catch (...) {
    std::fprintf(stderr, "simulate: internal error (an exception of unknown type)\n");
    return kExitInternal;
  }
}
