// Shared by the fuzz targets of test/fuzz: the contract every input is held to once a scene loads
// or a request is accepted, and how a broken contract is reported (abort: libFuzzer keeps the
// input as a crash file, scripts/dev/fuzz prints its path).
//
// The contract of stepping (core/simulator.h, and what the node does with it in StepOnce):
//  - Step() throws nothing (the node would turn an exception into a fault, but none is
//    documented);
//  - a step with state_finite leaves a finite state, time advanced by Δt, and a finite energy,
//    contact report and statistics (but the solver's residual, which may be +inf by design);
//  - a step without state_finite is the reported fault: diverged() is set, state and time are
//    bit for bit those before the step, and every later step does nothing until SetState().
#ifndef NONSMOOTH_SIM_TEST_FUZZ_FUZZ_SUPPORT_H_
#define NONSMOOTH_SIM_TEST_FUZZ_FUZZ_SUPPORT_H_

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/scene.h"
#include "nonsmooth_sim/core/simulator.h"

namespace nonsmooth_sim::fuzz {

[[noreturn]] inline void Finding(const std::string& what) {
  std::fprintf(stderr, "FUZZ FINDING: %s\n", what.c_str());
  std::fflush(stderr);
  std::abort();
}

inline void Require(bool ok, const std::string& what) {
  if (!ok) Finding(what);
}

/// A loader error is "clear" when it has a message of one line (urdf_scene.h, initial_state.h).
inline void RequireClearError(const std::exception& e, const char* where) {
  const std::string message = e.what();
  Require(!message.empty(), std::string(where) + ": an exception without a message");
  Require(message.find('\n') == std::string::npos,
          std::string(where) + ": an error of more than one line: " + message);
}

/// The core's setters promise a std::invalid_argument / std::out_of_range with a message, not one
/// line (SetFrictionSet quotes the contact name as given, newlines included; the node returns it in
/// the response's status_message).
inline void RequireMessage(const std::exception& e, const char* where) {
  Require(e.what() != nullptr && e.what()[0] != '\0',
          std::string(where) + ": an exception without a message");
}

inline bool Finite(const BodyState& s) {
  return s.position.allFinite() && s.orientation.coeffs().allFinite() &&
         s.linear_velocity.allFinite() && s.angular_velocity.allFinite();
}

inline bool Finite(const std::vector<BodyState>& state) {
  for (const BodyState& s : state) {
    if (!Finite(s)) return false;
  }
  return true;
}

/// Bit-for-bit equality (a rejected request must not have touched anything).
inline bool SameBits(const BodyState& a, const BodyState& b) {
  return std::memcmp(a.position.data(), b.position.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.orientation.coeffs().data(), b.orientation.coeffs().data(),
                     4 * sizeof(double)) == 0 &&
         std::memcmp(a.linear_velocity.data(), b.linear_velocity.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.angular_velocity.data(), b.angular_velocity.data(), 3 * sizeof(double)) == 0;
}

inline bool SameBits(const std::vector<BodyState>& a, const std::vector<BodyState>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!SameBits(a[i], b[i])) return false;
  }
  return true;
}

inline bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// The state of a simulator that is not diverged is finite (and, after a step, so is its energy:
/// the step checks the squared norms of the velocities; SetState accepts any finite state).
inline void RequireFiniteOrFault(const Simulator& sim, const char* where, bool energy = false) {
  if (sim.diverged()) return;
  if (!Finite(sim.state())) {
    std::string state;
    for (const BodyState& b : sim.state()) {
      char line[512];
      std::snprintf(line, sizeof line, " [r %g %g %g | q %g %g %g %g | v %g %g %g | w %g %g %g]",
                    b.position.x(), b.position.y(), b.position.z(), b.orientation.x(),
                    b.orientation.y(), b.orientation.z(), b.orientation.w(),
                    b.linear_velocity.x(), b.linear_velocity.y(), b.linear_velocity.z(),
                    b.angular_velocity.x(), b.angular_velocity.y(), b.angular_velocity.z());
      state += line;
    }
    Finding(std::string(where) + ": non-finite state without a reported fault:" + state);
  }
  Require(!energy || std::isfinite(sim.Energy()),
          std::string(where) + ": finite step to a state of non-finite energy (no fault reported)");
  Require(std::isfinite(sim.time()), std::string(where) + ": non-finite time");
}

/// One step under the contract at the top of this file: finite or a reported fault, and a finite
/// step has a finite energy, contact report and statistics, whatever state was set before (the
/// core refuses states whose energy overflows and undoes a gap correction that is not finite).
inline void StepUnderContract(Simulator& sim, const char* where) {
  const std::vector<BodyState> before = sim.state();
  const double time_before = sim.time();
  const bool diverged_before = sim.diverged();
  StepStatistics stats;
  try {
    sim.Step(&stats);
  } catch (const std::exception& e) {
    Finding(std::string(where) + ": Step() threw: " + e.what());
  }
  if (!stats.state_finite) {
    Require(sim.diverged(), std::string(where) + ": state_finite = false but diverged() is not");
    Require(SameBits(sim.state(), before),
            std::string(where) + ": a step that was not taken changed the state");
    Require(SameBits(sim.time(), time_before),
            std::string(where) + ": a step that was not taken changed the time");
    return;
  }
  Require(!diverged_before, std::string(where) + ": a diverged simulator reported a finite step");
  Require(!sim.diverged(), std::string(where) + ": a finite step left diverged() set");
  Require(sim.time() > time_before || time_before + sim.options().time_step == time_before,
          std::string(where) + ": a finite step did not advance the time");
  RequireFiniteOrFault(sim, where, /*energy=*/true);
  for (const ContactState& c : sim.contacts()) {
    Require(c.percussion.allFinite() && c.relative_velocity.allFinite() && c.point.allFinite() &&
                std::isfinite(c.gap),
            std::string(where) + ": a finite step reported a non-finite contact");
  }
  // not the solver's residual: +inf is documented data (contact_solver.h: tolerance_abs =
  // tolerance_rel = 0 makes every bound zero, a diverging Jacobi iteration stops at +inf)
  Require(std::isfinite(stats.max_penetration) &&
              std::isfinite(stats.max_dt_omega) && std::isfinite(stats.gap_correction_energy),
          std::string(where) + ": a finite step reported non-finite statistics: max_penetration " +
              std::to_string(stats.max_penetration) + ", max_dt_omega " +
              std::to_string(stats.max_dt_omega) + ", gap_correction_energy " +
              std::to_string(stats.gap_correction_energy));
}

}  // namespace nonsmooth_sim::fuzz

#endif  // NONSMOOTH_SIM_TEST_FUZZ_FUZZ_SUPPORT_H_
