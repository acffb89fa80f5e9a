// Bounded work: every knob that multiplies the work of a solve or a step has an upper
// bound in the core's validation, so that no accepted setting can make one step run for minutes.
// A hostile-user run set max_iterations = 2147483647 and relaxation = 4.9e-324 through
// ~set_solver_properties: both were accepted, and the next step iterated 2^31 times. Each
// assertion below holds the bound itself (values just inside are accepted, just outside and the
// hostile values rejected with the field and the range in the message) or what it protects (a
// simulation at the bounds steps in bounded time).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "nonsmooth_sim/core/contact_solver.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"

namespace nonsmooth_sim {
namespace {

constexpr int kHostileIterations = std::numeric_limits<int>::max();  // 2147483647
constexpr double kDenormal = 4.9e-324;                                // the smallest double > 0

// The message of the std::invalid_argument `f` throws ("" and a failure if it does not).
template <typename F>
std::string Rejection(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted";
  return "";
}

void ExpectContains(const std::string& message, const std::string& part) {
  EXPECT_NE(message.find(part), std::string::npos) << "\"" << part << "\" not in: " << message;
}

TEST(BoundedWork, SolverIterationCapIsBounded) {
  SolverOptions options;
  options.max_iterations = kHostileIterations;
  std::string message = Rejection([&] { ValidateSolverOptions(options); });
  ExpectContains(message, "max_iterations");
  ExpectContains(message, "<= 1000000");
  options.max_iterations = 1000001;
  EXPECT_THROW(ValidateSolverOptions(options), std::invalid_argument);
  options.max_iterations = 1000000;  // the converged references of single problems need it
  EXPECT_NO_THROW(ValidateSolverOptions(options));
}

TEST(BoundedWork, RelaxationIsBoundedAwayFromZero) {
  // α → 0 contracts the error by only 1 - α per iteration; 4.9e-324 moves nothing at all
  SolverOptions options;
  for (const double alpha : {kDenormal, 1e-300, 1e-4, 9.99e-4}) {
    options.relaxation = alpha;
    const std::string message = Rejection([&] { ValidateSolverOptions(options); });
    ExpectContains(message, "relaxation");
    ExpectContains(message, "[0.001, 2)");
  }
  options.relaxation = 1e-3;
  EXPECT_NO_THROW(ValidateSolverOptions(options));
  options.relaxation = 1.999;
  EXPECT_NO_THROW(ValidateSolverOptions(options));
}

TEST(BoundedWork, SimulatorRejectsTheHostileSettings) {
  SimulatorOptions options;
  options.solver.max_iterations = kHostileIterations;
  std::string message = Rejection([&] { ValidateSimulatorOptions(options); });
  ExpectContains(message, "max_iterations");
  ExpectContains(message, "<= 100000 in a simulation");
  // the same through the constructor and SetOptions, which the node and `simulate` use
  EXPECT_THROW(Simulator(MakeTippeTopScene(), options), std::invalid_argument);
  Simulator sim(MakeTippeTopScene(), SimulatorOptions{});
  EXPECT_THROW(sim.SetOptions(options), std::invalid_argument);
  EXPECT_EQ(sim.options().solver.max_iterations, SimulatorOptions{}.solver.max_iterations);

  options = SimulatorOptions{};
  options.solver.relaxation = kDenormal;
  message = Rejection([&] { ValidateSimulatorOptions(options); });
  ExpectContains(message, "relaxation");
  EXPECT_THROW(sim.SetOptions(options), std::invalid_argument);
  EXPECT_EQ(sim.options().solver.relaxation, 1.0);

  // a simulation repeats the solve every step: a tighter cap than a single solve's
  options = SimulatorOptions{};
  options.solver.max_iterations = 100001;
  message = Rejection([&] { ValidateSimulatorOptions(options); });
  ExpectContains(message, "max_iterations");
  ExpectContains(message, "<= 100000 in a simulation");
  options.solver.max_iterations = 100000;
  EXPECT_NO_THROW(ValidateSimulatorOptions(options));
}

TEST(BoundedWork, StepsAtTheLargestAcceptedSettingsEndInBoundedTime) {
  // the worst accepted combination for the Tippe-Top: the most iterations, the slowest accepted
  // relaxation, a tolerance of 0 that stops only on an exact fixed point. Its steps iterate tens
  // of thousands of times up to the cap (measured 2026-12-02, Release: 30 134 to 100 000
  // iterations, the slowest step 4.4 ms on an idle core, 8-17 ms with both cores shared); the
  // time bound leaves a factor of 50 or more for slow machines and debug builds.
  SimulatorOptions options;
  options.solver.max_iterations = 100000;  // kMaxSimulatorIterations
  options.solver.relaxation = 1e-3;        // kMinRelaxation
  options.solver.tolerance_rel = 0.0;
  options.solver.tolerance_abs = 0.0;
  // the iteration alone: the direct solve of a lone contact ends these steps after ~105
  // iterations (it reaches the exact fixed point), the worst case is without it
  options.solver.direct_solve = false;
  Simulator sim(MakeTippeTopScene(), options);
  int most = 0;
  double slowest = 0.0;
  for (int k = 0; k < 10; ++k) {
    const auto start = std::chrono::steady_clock::now();
    const StepStatistics stats = sim.Step();
    slowest = std::max(
        slowest,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    ASSERT_TRUE(stats.state_finite) << "step " << k;
    EXPECT_LE(stats.solver.iterations, 100000) << "step " << k;
    most = std::max(most, stats.solver.iterations);
  }
  EXPECT_GT(most, 10000);  // the solver did work hard
  EXPECT_LT(slowest, 1.0) << "the slowest step took " << slowest << " s";
  std::printf("most iterations in a step: %d, slowest step: %.2f ms (%.0f ns per iteration)\n",
              most, 1e3 * slowest, 1e9 * slowest / most);
}

}  // namespace
}  // namespace nonsmooth_sim
