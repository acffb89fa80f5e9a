// The accuracy knob (AdaptiveStepper, simulate --accuracy TOL) is honest: the error it achieves in
// the events the tops are known for stays within 10x of the TOL asked for, against references it
// does not share:
//  - the Tippe-Top's peg touchdown, against moreau2 at a fixed Δt = 2e-6 (its error ≈ 3e-6 s,
//    first order in the step at the event: 2e-6 → 1.371046 s, 1e-6 → 1.371044 s, so ≈ 2e-6 of
//    the time, well inside 10·TOL down to TOL = 1e-6);
//  - the rattleback's first reversal (μ = 10, R = 0), against the independent no-slip reference
//    of test/reference/ (the contact force eliminated, Runge–Kutta–Fehlberg 7(8) at 1e-12).
// And it is cheaper than the default fixed step at the loosest TOL: the estimate sets the step, not
// a noise floor (an estimate dominated by the O(H) difference of the end velocities of one step of
// H and two of H/2 took more steps than Δt = 1e-4 and erred 100-1000x below TOL).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>

#include "nonsmooth_sim/core/adaptive_stepper.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "reference/rolling_reference.h"
#include "rolling_scene.h"

namespace nonsmooth_sim {
namespace {

using scene_test::RattlebackReferenceStart;
using scene_test::RollingScene;
using scene_test::VerticalSpin;

constexpr double kDefaultStep = 1e-4;  // [s], the fixed step the knob is compared with

SimulatorOptions Moreau2(double time_step = kDefaultStep) {
  SimulatorOptions options;
  options.integrator = Integrator::kMoreau2;
  options.time_step = time_step;
  return options;
}

AccuracyOptions Accuracy(double tolerance) {
  AccuracyOptions options;
  options.tolerance = tolerance;
  return options;
}

// The end of the first accepted step that ends with the peg in contact [s].
std::optional<double> AdaptivePegTouchdown(double tolerance, long* simulator_steps) {
  Simulator sim(MakeTippeTopScene(), Moreau2());
  AdaptiveStepper stepper(&sim, Accuracy(tolerance));
  std::optional<double> touchdown;
  stepper.AdvanceTo(1.45, [&](const StepStatistics&, double) {
    if (!touchdown && sim.InContact(kPegSphere)) touchdown = sim.time();
  });
  *simulator_steps = stepper.statistics().simulator_steps;
  return touchdown;
}

TEST(AccuracyKnob, TippeTopTouchdownWithinTenTimesTheTolerance) {
  Simulator reference(MakeTippeTopScene(), Moreau2(2e-6));
  std::optional<double> t_ref;
  while (!t_ref && reference.time() < 1.45) {
    reference.Step();
    if (reference.InContact(kPegSphere)) t_ref = reference.time();
  }
  ASSERT_TRUE(t_ref);
  for (const double tolerance : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
    long steps = 0;
    const std::optional<double> t = AdaptivePegTouchdown(tolerance, &steps);
    ASSERT_TRUE(t) << tolerance;
    const double error = std::abs(*t - *t_ref) / *t_ref;
    std::printf("TOL %.0e: touchdown %.7f s (reference %.7f s), relative error %.2e = %.2f TOL, "
                "%ld steps\n",
                tolerance, *t, *t_ref, error, error / tolerance, steps);
    EXPECT_LE(error, 10.0 * tolerance) << tolerance;
    // the loosest TOL costs less than fixed steps of the default Δt (14 500 steps to 1.45 s)
    if (tolerance == 1e-2) {
      EXPECT_LT(steps, std::lround(1.45 / kDefaultStep)) << tolerance;
    }
  }
}

TEST(AccuracyKnob, RattlebackReversalWithinTenTimesTheTolerance) {
  const Scene scene = RollingScene("rattleback");
  const reference::RollingState start = RattlebackReferenceStart(scene.initial_state[0]);
  const std::optional<double> t_ref =
      reference::FirstSpinReversal(reference::Rattleback(), start, 4.0);
  ASSERT_TRUE(t_ref);
  for (const double tolerance : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
    Simulator sim(scene, Moreau2());
    AdaptiveStepper stepper(&sim, Accuracy(tolerance));
    std::optional<double> reversal;
    double previous = VerticalSpin(sim.state()[0]);
    stepper.AdvanceTo(*t_ref + 0.5, [&](const StepStatistics&, double h) {
      const double spin = VerticalSpin(sim.state()[0]);
      if (!reversal && previous < 0.0 && spin >= 0.0) {
        reversal = sim.time() - h * spin / (spin - previous);  // linear within the step
      }
      previous = spin;
    });
    ASSERT_TRUE(reversal) << tolerance;
    const double error = std::abs(*reversal - *t_ref) / *t_ref;
    std::printf("TOL %.0e: reversal %.6f s (reference %.6f s), relative error %.2e = %.2f TOL, "
                "%ld steps\n",
                tolerance, *reversal, *t_ref, error, error / tolerance,
                stepper.statistics().simulator_steps);
    EXPECT_LE(error, 10.0 * tolerance) << tolerance;
  }
}

}  // namespace
}  // namespace nonsmooth_sim
