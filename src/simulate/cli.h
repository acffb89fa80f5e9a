// Command line of the headless `simulate` executable: the built-in Tippe-Top or any URDF scene
// (--urdf, with initial conditions from a YAML file, --initial), with chosen friction set,
// solver, time step, tolerances and initial conditions.
#ifndef NONSMOOTH_SIM_SIMULATE_CLI_H_
#define NONSMOOTH_SIM_SIMULATE_CLI_H_

#include <string>
#include <variant>
#include <vector>

#include "nonsmooth_sim/core/adaptive_stepper.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"

namespace nonsmooth_sim::simulate {

struct RunConfig {
  TippeTopParameters parameters;     ///< friction set, μ, R (with --urdf: overrides if given)
  TippeTopInitialConditions initial; ///< θ0, spin (the built-in Tippe-Top only)
  std::string urdf_path;             ///< empty: the built-in Tippe-Top (tippe_top.h)
  std::string initial_path;          ///< YAML initial state of a URDF scene; empty: URDF pose
  std::string schedule_path;         ///< --schedule: YAML events of a URDF scene; empty: none
  /// --hold-joint NAME, repeatable: moving joints of the --urdf held rigid (the start-up scene
  /// only, not --schedule's spawned models; UrdfSceneOptions::hold_joints)
  std::vector<std::string> hold_joints;
  bool friction_set_given = false;   ///< --friction-set was given (a URDF's own sets otherwise)
  bool mu_given = false;             ///< --mu was given
  bool contact_radius_given = false; ///< --contact-radius was given
  bool rolling_resistance_given = false;  ///< --rolling-resistance was given
  SimulatorOptions options;          ///< Δt, solver, gyroscopic scheme, integrator
  /// --accuracy (tolerance 0: fixed steps of options.time_step), --min-dt, --max-dt
  AccuracyOptions accuracy;
  double duration = 8.0;             ///< [s], > 0
  std::string csv_path;              ///< empty: no CSV
  std::string contacts_csv_path;     ///< empty: no contacts CSV (contact_csv.h)
  std::string summary_path;          ///< empty: no JSON summary
  long decimate = 10;                ///< CSV row every N steps (of --dt with --accuracy), ≥ 1
  bool quiet = false;                ///< no stdout report, no progress bar
};

/// What the command line asks for: a run, the help text, the friction set names, or an error
/// message (exit code 2).
struct HelpRequest {};
struct FrictionSetsRequest {};
struct UsageError {
  std::string message;
};
using ParseResult = std::variant<RunConfig, HelpRequest, FrictionSetsRequest, UsageError>;

ParseResult ParseCommandLine(int argc, const char* const* argv);
std::string UsageText();
/// The friction set names (the laws table, core/friction_law.h), one per line.
std::string FrictionSetsText();

}  // namespace nonsmooth_sim::simulate

#endif  // NONSMOOTH_SIM_SIMULATE_CLI_H_
