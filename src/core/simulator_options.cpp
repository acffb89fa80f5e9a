// The ranges of SimulatorOptions and the names of its choices, see simulator_options.h.
#include "nonsmooth_sim/core/simulator_options.h"

#include <sstream>
#include <stdexcept>
#include <string>

#include "nonsmooth_sim/core/enum_names.h"

namespace nonsmooth_sim {
namespace {

constexpr double kMinTimeStep = 1e-7;  // [s]
constexpr double kMaxTimeStep = 1e-2;  // [s]

}  // namespace

void ValidateSimulatorOptions(const SimulatorOptions& options) {
  if (!(options.time_step >= kMinTimeStep && options.time_step <= kMaxTimeStep)) {
    std::ostringstream s;
    s << "SimulatorOptions.time_step = " << options.time_step << ": must be in [" << kMinTimeStep
      << ", " << kMaxTimeStep << "] s";
    throw std::invalid_argument(s.str());
  }
  // the tighter cap of a simulation first, so that the message names it
  if (options.solver.max_iterations > kMaxSimulatorIterations) {
    throw std::invalid_argument("SimulatorOptions.solver.max_iterations: must be >= 1 and <= " +
                                std::to_string(kMaxSimulatorIterations) +
                                " in a simulation (the cap multiplies the work of every step), "
                                "got " + std::to_string(options.solver.max_iterations));
  }
  ValidateSolverOptions(options.solver);
  if (!IsOneOf(options.gyroscopic, kAllGyroscopicSchemes)) {
    throw std::invalid_argument(
        "SimulatorOptions.gyroscopic must be kExplicit, kImplicitMidpoint or kAuto");
  }
  if (!IsOneOf(options.integrator, kAllIntegrators)) {
    throw std::invalid_argument("SimulatorOptions.integrator must be kMoreau or kMoreau2");
  }
}

std::string_view GyroscopicSchemeName(GyroscopicScheme scheme) {
  switch (scheme) {
    case GyroscopicScheme::kExplicit: return "explicit";
    case GyroscopicScheme::kImplicitMidpoint: return "implicit_midpoint";
    case GyroscopicScheme::kAuto: return "auto";
  }
  return "";
}
std::optional<GyroscopicScheme> GyroscopicSchemeFromName(std::string_view name) {
  return EnumFromName(name, kAllGyroscopicSchemes, &GyroscopicSchemeName);
}

std::string_view IntegratorName(Integrator integrator) {
  switch (integrator) {
    case Integrator::kMoreau: return "moreau";
    case Integrator::kMoreau2: return "moreau2";
  }
  return "";
}
std::optional<Integrator> IntegratorFromName(std::string_view name) {
  return EnumFromName(name, kAllIntegrators, &IntegratorName);
}

}  // namespace nonsmooth_sim
