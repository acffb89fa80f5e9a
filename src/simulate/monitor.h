// What `simulate` observes during a run: per-step monitors for the JSON summary (energy, solver,
// penetration, gap correction; for the built-in Tippe-Top also threshold times, contact phases
// and Jellett's integral) and the decimated CSV rows.
#ifndef NONSMOOTH_SIM_SIMULATE_MONITOR_H_
#define NONSMOOTH_SIM_SIMULATE_MONITOR_H_

#include <optional>
#include <string>
#include <vector>

#include "cli.h"
#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim::simulate {

/// A body that could no longer touch anything (world/lost_bodies.h), when it was first seen.
struct LostBodyRecord {
  std::string name;
  double t = 0.0;    ///< [s] the check that found it (every kLostBodyCheckInterval)
  std::string why;  ///< DescribeLostBody
};

/// [s] of simulated time between two checks for lost bodies.
inline constexpr double kLostBodyCheckInterval = 0.1;

struct RunSummary {
  RunConfig config;
  /// The built-in Tippe-Top (its observables below are set); false for a --urdf scene.
  bool tippe_top = true;
  int max_closed_contacts = 0;   ///< most closed contacts in one step
  int max_islands = 0;           ///< most contact problems (islands) in one step
  double max_penetration = 0.0;  ///< deepest penetration of a closed contact at q_M [m]
  /// Per body: link name, and the final state (link frame pose, v_S in the world, ω in the link
  /// axes: the YAML initial-state convention).
  std::vector<std::string> body_names;
  std::vector<Eigen::Vector3d> final_link_position;
  std::vector<BodyState> final_state;
  long steps = 0;  ///< accepted steps (with --accuracy: steps of H, each two half steps)
  /// --accuracy: the stepper's counts (accepted/rejected/forced steps, smallest step, error)
  std::optional<AdaptiveStatistics> adaptive;
  double wall_time_s = 0.0;         ///< stepping and per-step monitors, no file output [s]
  double cpu_time_s = 0.0;          ///< thread CPU time of the same loop [s]
  double output_wall_time_s = 0.0;  ///< formatting and writing CSV [s]
  std::optional<double> t_theta_above_pi_2;
  std::optional<double> t_theta_above_2_4;  ///< peg touchdown
  std::optional<double> t_theta_above_2_9;  ///< inverted
  std::optional<double> t_peg_touchdown;    ///< first step with the peg contact closed
  std::optional<double> t_big_sphere_liftoff;  ///< first step on the peg alone
  /// First step with the big sphere closed again after the top was inverted (θ > 2.9).
  std::optional<double> t_fall_back;
  double time_on_peg_s = 0.0;  ///< total time with the peg closed and the big sphere open
  double theta_final = 0.0;
  double theta_max = 0.0;
  double z_final = 0.0;
  double energy_initial = 0.0;
  double energy_final = 0.0;
  double max_energy_increase = 0.0;  ///< largest E(t+Δt) - E(t) [J]
  double max_energy_increase_time = 0.0;
  double max_energy_above_initial = 0.0;  ///< max_t E(t) - E(0) [J]
  double jellett_initial = 0.0;
  double jellett_final = 0.0;
  double vertical_spin_initial = 0.0;
  double vertical_spin_final = 0.0;
  double min_gap = 0.0;  ///< smallest gap of a closed contact at the midpoint of a step [m]
  double max_dt_omega = 0.0;
  /// No step reported StepStatistics::explicit_gyroscopic_unsafe.
  bool explicit_gyroscopic_safe = true;
  /// First step with explicit_gyroscopic_unsafe: its time [s] and Δt·|ω|.
  std::optional<double> t_explicit_gyroscopic_unsafe;
  double explicit_gyroscopic_unsafe_dt_omega = 0.0;
  double gap_correction_max = 0.0;     ///< largest lift of a body by gap_correction [m]
  double gap_correction_energy = 0.0;  ///< potential energy all lifts added [J]
  long gap_correction_steps = 0;       ///< steps with a lift
  /// false: the run stopped at a step that met a non-finite value (diverged); the summary
  /// describes the last finite state.
  bool state_finite = true;
  std::optional<double> t_non_finite;  ///< end time of the step that was not taken [s]
  double mean_iterations = 0.0;
  int max_iterations = 0;
  long unconverged_steps = 0;
  std::vector<LostBodyRecord> lost_bodies;  ///< in the order they were found
};

/// Accumulates RunSummary step by step without allocating.
class RunMonitor {
 public:
  RunMonitor(const RunConfig& config, const Simulator& simulator);
  /// After every step taken (stats.state_finite): the `step`-th, ending at time t, of size dt.
  void Observe(long step, double t, double dt, const Simulator& simulator,
               const StepStatistics& stats);
  /// The step ending at t met a non-finite value and was not taken.
  void ObserveNonFinite(double t);
  /// At the start and every kLostBodyCheckInterval: the bodies that can no longer touch
  /// anything, recorded once each; returns those found now for the first time.
  std::vector<LostBodyRecord> CheckLostBodies(double t, const Simulator& simulator);
  RunSummary Finish(const Simulator& simulator);
  void SetAdaptive(const AdaptiveStatistics& statistics) { summary_.adaptive = statistics; }

 private:
  RunSummary summary_;
  bool tippe_top_;
  double energy_previous_;
  double min_cos_theta_;
  long total_iterations_ = 0;
  double peg_only_time_ = 0.0;  // [s]
};

/// Decimated CSV rows, stored as numbers during the run and formatted afterwards.
class CsvRecorder {
 public:
  CsvRecorder(const Simulator& simulator, long expected_rows);
  void Record(double time, const Simulator& simulator, const StepStatistics& stats);
  /// Writes header and rows; false if the file cannot be written.
  bool Write(const std::string& path) const;

 private:
  std::vector<std::string> columns_;
  std::vector<int> spheres_;  // the body's sphere colliders, one column group each
  std::vector<char> sphere_rolling_;  // per sphere: its law has rolling (two more columns)
  std::vector<double> values_;
};

/// The CSV of a URDF scene: t, per body <link>/x y z qx qy qz qw vx vy vz wx wy wz (link frame
/// position and orientation in the world, v_S and ω in the world), energy, closed_contacts,
/// islands, max_penetration, iterations, converged.
class BodyCsvRecorder {
 public:
  BodyCsvRecorder(const Simulator& simulator, long expected_rows);
  /// Columns for the bodies named `bodies` (`simulate --schedule`: every body the run will
  /// hold); a body the simulator does not hold at a row writes NaN.
  BodyCsvRecorder(const std::vector<std::string>& bodies, long expected_rows);
  void Record(double time, const Simulator& simulator, const StepStatistics& stats);
  bool Write(const std::string& path) const;

 private:
  std::vector<std::string> columns_;
  std::vector<double> values_;
  std::vector<std::string> bodies_;  ///< by name (second constructor); empty: every body in order
  void AppendBody(const Simulator& simulator, std::size_t b);  ///< its 13 values
};

/// Writes header and rows (numbers with 15 significant digits); false if it cannot.
bool WriteCsv(const std::vector<std::string>& columns, const std::vector<double>& values,
              const std::string& path);

/// Writes the JSON summary; false if the file cannot be written.
bool WriteSummaryJson(const RunSummary& summary, const std::string& path);

/// The vertical spin: world z component of ω [rad/s].
double VerticalSpin(const BodyState& state);

}  // namespace nonsmooth_sim::simulate

#endif  // NONSMOOTH_SIM_SIMULATE_MONITOR_H_
