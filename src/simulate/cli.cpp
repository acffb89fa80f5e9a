// Parsing and range checks of the `simulate` command line. Every bad value is reported with the
// option, the value and what is allowed, before anything runs or is written.
#include "cli.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <sstream>

#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/scene_io/format.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace nonsmooth_sim::simulate {
namespace {

using scene_io::Format;

constexpr double kMinTimeStep = 1e-7;   // [s], as ValidateSimulatorOptions
constexpr double kMaxTimeStep = 1e-2;   // [s]
constexpr double kMaxDuration = 1e5;    // [s], keeps the step count far inside a long
// The core's bounds (ValidateSimulatorOptions, the loader's and the initial state's, see
// docs/settings.md and docs/urdf.md), checked here too so that the message names the option.
constexpr long kMaxIterationsLimit = kMaxSimulatorIterations;

struct Error {
  std::string message;
};

Error BadValue(const std::string& option, const std::string& value, const std::string& allowed) {
  return {"invalid value '" + value + "' for " + option + ": expected " + allowed};
}

// A finite number in [low, high] (open ends where the flags say so).
double ParseNumber(const std::string& option, const std::string& value, double low, double high,
                   bool low_open, bool high_open, const std::string& allowed) {
  const char* begin = value.c_str();
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(begin, &end);
  const bool parsed = !value.empty() && end == begin + value.size() && errno == 0;
  const bool in_range = std::isfinite(x) && (low_open ? x > low : x >= low) &&
                        (high_open ? x < high : x <= high);
  if (!parsed || !in_range) throw BadValue(option, value, allowed);
  return x;
}

long ParseInteger(const std::string& option, const std::string& value, long low, long high,
                  const std::string& allowed) {
  const char* begin = value.c_str();
  char* end = nullptr;
  errno = 0;
  const long x = std::strtol(begin, &end, 10);
  const bool parsed = !value.empty() && end == begin + value.size() && errno == 0;
  if (!parsed || x < low || x > high) throw BadValue(option, value, allowed);
  return x;
}

std::string ParsePath(const std::string& option, const std::string& value) {
  if (value.empty()) throw BadValue(option, value, "a file path");
  return value;
}

using Setter = std::function<void(RunConfig&, const std::string& option, const std::string&)>;

const std::map<std::string, Setter>& ValueOptions() {
  static const std::map<std::string, Setter> options = {
      {"--friction-set",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         const auto set = FrictionSetFromName(v);
         if (!set) throw BadValue(o, v, "one of " + FrictionSetNameList());
         c.parameters.friction_set = *set;
         c.friction_set_given = true;
       }},
      {"--solver",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         const auto type = SolverTypeFromName(v);
         if (!type) throw BadValue(o, v, "one of " + SolverTypeNameList());
         c.options.solver.type = *type;
       }},
      {"--gyroscopic",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         const auto scheme = GyroscopicSchemeFromName(v);
         if (!scheme) throw BadValue(o, v, "one of auto, explicit, implicit_midpoint");
         c.options.gyroscopic = *scheme;
       }},
      {"--integrator",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         const auto integrator = IntegratorFromName(v);
         if (!integrator) throw BadValue(o, v, "one of moreau2, moreau");
         c.options.integrator = *integrator;
       }},
      {"--accuracy",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.accuracy.tolerance = ParseNumber(o, v, 0.0, 1.0, false, false,
                                            "0 (fixed steps) or a tolerance in [1e-09, 1]");
         if (c.accuracy.tolerance != 0.0 && c.accuracy.tolerance < 1e-9) {
           throw BadValue(o, v, "0 (fixed steps) or a tolerance in [1e-09, 1]");
         }
       }},
      {"--min-dt",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.accuracy.min_time_step = ParseNumber(o, v, 2.0 * kMinTimeStep, kMaxTimeStep, false,
                                                false, "a time step in [2e-07, 0.01] s");
       }},
      {"--max-dt",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.accuracy.max_time_step = ParseNumber(o, v, 2.0 * kMinTimeStep, kMaxTimeStep, false,
                                                false, "a time step in [2e-07, 0.01] s");
       }},
      {"--dt",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.options.time_step = ParseNumber(o, v, kMinTimeStep, kMaxTimeStep, false, false,
                                           "a time step in [1e-07, 0.01] s");
       }},
      {"--duration",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.duration = ParseNumber(o, v, 0.0, kMaxDuration, true, false,
                                  "a duration in (0, 100000] s");
       }},
      {"--tolerance",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.options.solver.tolerance_rel = ParseNumber(
             o, v, 0.0, std::numeric_limits<double>::max(), false, false,
             "a finite relative tolerance >= 0");
       }},
      {"--tolerance-abs",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.options.solver.tolerance_abs = ParseNumber(
             o, v, 0.0, std::numeric_limits<double>::max(), false, false,
             "a finite absolute tolerance >= 0 N s");
       }},
      {"--max-iterations",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.options.solver.max_iterations = static_cast<int>(ParseInteger(
             o, v, 1, kMaxIterationsLimit,
             "an integer in [1, " + std::to_string(kMaxIterationsLimit) + "]"));
       }},
      {"--relaxation",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.options.solver.relaxation =
             ParseNumber(o, v, kMinRelaxation, 2.0, false, true,
                         "a relaxation alpha in [" + Format(kMinRelaxation) + ", 2)");
       }},
      {"--mu",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.parameters.mu = ParseNumber(o, v, 0.0, scene_io::kMaxFriction, false, false,
                                       "a friction coefficient in [0, " +
                                           Format(scene_io::kMaxFriction) + "]");
         c.mu_given = true;
       }},
      {"--rolling-resistance",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.parameters.rolling_resistance =
             ParseNumber(o, v, 0.0, scene_io::kMaxLength, false, false,
                         "a rolling-resistance length in [0, " + Format(scene_io::kMaxLength) +
                             "] m");
         c.rolling_resistance_given = true;
       }},
      {"--contact-radius",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.parameters.contact_radius =
             ParseNumber(o, v, 0.0, scene_io::kMaxLength, false, false,
                         "a contact radius R in [0, " + Format(scene_io::kMaxLength) +
                             "] m, at most the size of every shape it applies to");
         c.contact_radius_given = true;
       }},
      {"--inclination",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.initial.inclination =
             ParseNumber(o, v, 0.0, kPi, false, false, "an angle in [0, 3.14159] rad");
       }},
      {"--spin",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.initial.spin = ParseNumber(o, v, -scene_io::kMaxInitialAngularSpeed,
                                      scene_io::kMaxInitialAngularSpeed, false, false,
                                      "a spin in [-" + Format(scene_io::kMaxInitialAngularSpeed) +
                                          ", " + Format(scene_io::kMaxInitialAngularSpeed) +
                                          "] rad/s");
       }},
      {"--urdf",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.urdf_path = ParsePath(o, v);
       }},
      {"--hold-joint",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         if (v.empty()) throw BadValue(o, v, "the name of a joint of the --urdf that moves");
         c.hold_joints.push_back(v);
       }},
      {"--initial",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.initial_path = ParsePath(o, v);
       }},
      {"--schedule",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.schedule_path = ParsePath(o, v);
       }},
      {"--csv",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.csv_path = ParsePath(o, v);
       }},
      {"--contacts-csv",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.contacts_csv_path = ParsePath(o, v);
       }},
      {"--summary",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.summary_path = ParsePath(o, v);
       }},
      {"--decimate",
       [](RunConfig& c, const std::string& o, const std::string& v) {
         c.decimate = ParseInteger(o, v, 1, std::numeric_limits<long>::max(), "an integer >= 1");
       }},
  };
  return options;
}

}  // namespace

std::string UsageText() {
  std::ostringstream s;
  s << "usage: simulate [options]\n"
       "Runs a scene headless with Moreau's midpoint time-stepping and writes a CSV time series\n"
       "and a JSON summary: the built-in Tippe-Top (Leine & Glocker 2003 parameters), or any\n"
       "URDF scene with --urdf.\n\n"
       "  --urdf FILE           the scene: free bodies, their collisions and laws, static\n"
       "                        links, the ground (docs/urdf.md); default: the Tippe-Top\n"
       "  --initial FILE        initial state of a --urdf scene (YAML, bodies: {<link>:\n"
       "                        {position, orientation, linear_velocity, angular_velocity}});\n"
       "                        default: the URDF pose, at rest\n"
       "  --hold-joint NAME     hold the moving joint NAME of the --urdf rigid (at 0, or at the\n"
       "                        position of its <nonsmooth_sim joint=...><hold>): its link is\n"
       "                        merged into its parent (docs/urdf.md); repeatable\n"
       "  --schedule FILE       timed events of a --urdf scene (YAML: spawn, wrench,\n"
       "                        set_state, delete; docs/simulate.md); fixed steps only\n"
       "  --friction-set NAME   "
    << FrictionSetNameList()
    << " (default sphere)\n"
       "  --solver NAME         "
    << SolverTypeNameList()
    << " (default "
    << SolverTypeName(SolverOptions{}.type)
    << ")\n"
       "  --dt SECONDS          time step in [1e-7, 1e-2] (default 1e-4)\n"
       "  --duration SECONDS    simulated time (default 8)\n"
       "  --tolerance REL       solver relative tolerance on the change of the percussions"
       " (default "
    << SolverOptions{}.tolerance_rel
    << ")\n"
       "  --tolerance-abs ABS   solver absolute tolerance on the change [N s] (default "
    << SolverOptions{}.tolerance_abs
    << ")\n"
       "  --max-iterations N    solver iteration cap per step, in [1, "
    << kMaxSimulatorIterations << "] (default "
    << SolverOptions{}.max_iterations
    << ")\n"
       "  --relaxation ALPHA    alpha of (43), in ["
    << kMinRelaxation << ", 2) (default 1)\n"
       "  --unmapped-drilling-sets\n"
       "                        iterate exact and cylinder on their original sets (37), as the\n"
       "                        paper timed B_F, instead of on the A-mapped sets (40)-(47)\n"
       "  --no-direct-solve     the iteration alone: no direct solve of ball-set contacts\n"
       "                        whose iteration has not converged after "
    << kDirectSolveAfter << " iterations\n"
       "  --mu MU               friction coefficient of every contact (default: 0.3 for the\n"
       "                        Tippe-Top, the URDF's for --urdf)\n"
       "  --rolling-resistance METRES\n"
       "                        rolling-resistance length mu_r of every contact (default 0:\n"
       "                        none, or the URDF's); acts with the rolling friction sets\n"
       "  --contact-radius R    contact-disc radius [m], Rbar = 3 pi R / 16 (default 5e-4 for\n"
       "                        the Tippe-Top, the URDF's patch_radius for --urdf)\n"
       "  --inclination THETA   Tippe-Top: initial inclination [rad] in [0, pi] (default 0.1)\n"
       "  --spin OMEGA          Tippe-Top: initial spin about the symmetry axis [rad/s]\n"
       "                        (default 180)\n"
       "  --integrator NAME     moreau2 (default): second order without impacts, contacts held\n"
       "                        on position level (docs/theory.md); moreau: the paper's midpoint\n"
       "                        rule (13)-(18) bit for bit, first order\n"
       "  --accuracy TOL        choose each step from an error estimate (step doubling) so that\n"
       "                        the error per second of simulated time stays below TOL, relative\n"
       "                        to each body's size and speeds (docs/accuracy.md); 0 (default):\n"
       "                        fixed steps of --dt. CSV rows stay every --decimate x --dt\n"
       "  --min-dt DT           smallest step of --accuracy [s] (default 1e-6)\n"
       "  --max-dt DT           largest step of --accuracy [s] (default 1e-2)\n"
       "  --gyroscopic SCHEME   moreau only (moreau2 takes implicit_midpoint): auto (default),\n"
       "                        explicit (the paper's) or implicit_midpoint;\n"
       "                        explicit is safe for dt*|omega| <= "
    << kExplicitGyroscopicMaxDtOmega
    << " (warned on stderr\n"
       "                        beyond); auto takes it there and implicit_midpoint beyond\n"
       "  --no-gap-correction   the paper's scheme exactly: no lift of penetrating bodies (by\n"
       "                        default a body whose closed contact sinks below -"
    << kGapCorrectionSlop
    << " m is\n"
       "                        lifted back to it; the lifts are reported in the summary)\n"
       "  --plain-warm-start    start each contact's solve from the last step's percussion (by\n"
       "                        default it is extrapolated from the last two or three steps where\n"
       "                        that is safe: the same motion within the tolerance, fewer\n"
       "                        iterations)\n"
       "  --csv FILE            time series. Tippe-Top: t, position, quaternion, theta, energy,\n"
       "                        Jellett, vertical spin, per sphere closed/percussions,\n"
       "                        iterations. --urdf: t, per body <link>/x y z qx qy qz qw vx vy\n"
       "                        vz wx wy wz (link frame; v of the centre of mass and omega in\n"
       "                        the world), energy, closed contacts, islands, deepest\n"
       "                        penetration, iterations, converged\n"
       "  --contacts-csv FILE   the closed contacts of every CSV sample, one row each: t, dt,\n"
       "                        contact (A/B), feature, point, normal, t1, gap, percussions\n"
       "                        (n, t1, t2, tau, r1, r2; force = percussion/dt)\n"
       "  --summary FILE        JSON summary\n"
       "  --decimate N          write every N-th step to the CSVs (default 10)\n"
       "  --quiet               no report on stdout, no progress bar\n"
       "  --list-friction-sets  print the friction set names, one per line, and exit\n"
       "  --help                this text\n"
       "Exit status: 0 ok, 1 an output file could not be written, 2 invalid command line,\n"
       "3 the state became non-finite (the run diverged; CSV and summary end at the last\n"
       "finite state, summary field \"state_finite\": false).\n";
  return s.str();
}

std::string FrictionSetsText() {
  std::string text;
  for (const FrictionLaw& law : kFrictionLaws) {
    text += law.name;
    text += '\n';
  }
  return text;
}

ParseResult ParseCommandLine(int argc, const char* const* argv) {
  RunConfig config;
  // the paper's explicit gyroscopic term, the implicit midpoint rule in the steps where
  // Δt·|ω| exceeds its safe range (an explicit run that stays inside is bit-identical)
  config.options.gyroscopic = GyroscopicScheme::kAuto;
  // the second-order scheme: the tops' rolling right at the default step (docs/accuracy.md)
  config.options.integrator = Integrator::kMoreau2;
  try {
    for (int k = 1; k < argc; ++k) {
      std::string arg = argv[k];
      if (arg == "--help" || arg == "-h") return HelpRequest{};
      if (arg == "--list-friction-sets") return FrictionSetsRequest{};
      if (arg == "--quiet") {
        config.quiet = true;
        continue;
      }
      if (arg == "--unmapped-drilling-sets") {
        config.options.solver.map_drilling_sets = false;
        continue;
      }
      if (arg == "--no-direct-solve") {
        config.options.solver.direct_solve = false;
        continue;
      }
      if (arg == "--no-gap-correction") {
        config.options.gap_correction = false;
        continue;
      }
      if (arg == "--plain-warm-start") {
        config.options.extrapolate_warm_start = false;
        continue;
      }
      std::string value;
      bool has_value = false;
      if (const auto eq = arg.find('='); arg.rfind("--", 0) == 0 && eq != std::string::npos) {
        value = arg.substr(eq + 1);
        arg = arg.substr(0, eq);
        has_value = true;
      }
      const auto option = ValueOptions().find(arg);
      if (option == ValueOptions().end()) {
        throw Error{"unknown option '" + arg + "' (see --help)"};
      }
      if (!has_value) {
        if (k + 1 >= argc) throw Error{"missing value for " + arg + " (see --help)"};
        value = argv[++k];
      }
      option->second(config, arg, value);
    }
    if (config.accuracy.min_time_step > config.accuracy.max_time_step) {
      throw Error{"--min-dt must not exceed --max-dt"};
    }
    if (!config.schedule_path.empty() &&
        (config.urdf_path.empty() || config.accuracy.tolerance > 0.0)) {
      throw Error{"--schedule needs --urdf and fixed steps (not --accuracy)"};
    }
    if (!config.hold_joints.empty() && config.urdf_path.empty()) {
      throw Error{"--hold-joint needs --urdf (the built-in Tippe-Top has no joints)"};
    }
    if (!config.initial_path.empty() && config.urdf_path.empty()) {
      throw Error{"--initial needs --urdf (the built-in Tippe-Top takes --inclination, --spin)"};
    }
    if (!config.urdf_path.empty()) {
      for (int k = 1; k < argc; ++k) {
        const std::string arg = argv[k];
        for (const char* tippe : {"--inclination", "--spin"}) {
          if (arg.rfind(tippe, 0) == 0) {
            throw Error{std::string(tippe) +
                        " is for the built-in Tippe-Top; a --urdf scene starts from --initial "
                        "FILE.yaml"};
          }
        }
      }
    }
    // the loader checks a --urdf scene's shapes; the built-in Tippe-Top's are its two spheres
    const double smallest_sphere =
        std::min(config.parameters.big_radius, config.parameters.peg_radius);
    if (config.urdf_path.empty() && config.contact_radius_given &&
        config.parameters.contact_radius > smallest_sphere) {
      throw BadValue("--contact-radius", Format(config.parameters.contact_radius),
                     "for the built-in Tippe-Top a contact radius R of at most its peg radius " +
                         Format(smallest_sphere) + " m (a contact patch lies on the sphere)");
    }
    if (std::llround(config.duration / config.options.time_step) < 1) {
      throw Error{"--duration " + std::to_string(config.duration) +
                  " is shorter than one time step --dt " +
                  std::to_string(config.options.time_step)};
    }
  } catch (const Error& error) {
    return UsageError{error.message};
  }
  return config;
}

}  // namespace nonsmooth_sim::simulate
