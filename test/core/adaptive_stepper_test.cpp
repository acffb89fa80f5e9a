// The accuracy knob (adaptive_stepper.h) and what it stands on (Simulator::Save / Restore,
// SetTimeStep): a restored checkpoint steps on bit for bit; the stepper lands on the requested
// times and keeps its accepted error estimates within TOL·H (its error against references:
// test/scenes/accuracy_knob_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "nonsmooth_sim/core/adaptive_stepper.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "same_bits.h"

namespace nonsmooth_sim {
namespace {

using test::SameBits;

SimulatorOptions Moreau2() {
  SimulatorOptions options;
  options.integrator = Integrator::kMoreau2;
  return options;
}

TEST(Checkpoint, RestoredSimulatorStepsOnBitForBit) {
  // the Tippe-Top in sliding contact: warm starts, tangent frames and end gaps in the memory
  Simulator sim(MakeTippeTopScene(), Moreau2());
  for (int k = 0; k < 2000; ++k) sim.Step();
  Simulator::Checkpoint checkpoint;
  sim.Save(&checkpoint);
  for (int k = 0; k < 500; ++k) sim.Step();
  const std::vector<BodyState> first = sim.state();
  const double first_time = sim.time();
  // a detour with another step size, then back
  sim.Restore(checkpoint);
  sim.SetTimeStep(3e-5);
  for (int k = 0; k < 77; ++k) sim.Step();
  sim.Restore(checkpoint);
  for (int k = 0; k < 500; ++k) sim.Step();
  EXPECT_TRUE(SameBits(first, sim.state()));
  EXPECT_EQ(sim.time(), first_time);
}

TEST(Checkpoint, RestoreOfAnotherWorldIsRefused) {
  Simulator one(MakeTippeTopScene(), Moreau2());
  Simulator::Checkpoint checkpoint;
  one.Save(&checkpoint);
  checkpoint.state.push_back(checkpoint.state[0]);
  const std::vector<BodyState> before = one.state();
  EXPECT_THROW(one.Restore(checkpoint), std::invalid_argument);
  EXPECT_TRUE(SameBits(before, one.state()));
}

TEST(Checkpoint, RestoreBringsBackTheTimeStepOfTheWarmStarts) {
  // a detour at another Δt, restored: the checkpoint's Δt is back with its warm starts
  Simulator sim(MakeTippeTopScene(), Moreau2());
  for (int k = 0; k < 100; ++k) sim.Step();
  Simulator::Checkpoint checkpoint;
  sim.Save(&checkpoint);
  sim.SetTimeStep(3e-5);
  sim.Step();
  sim.Restore(checkpoint);
  EXPECT_EQ(sim.options().time_step, 1e-4);
  EXPECT_THROW(sim.SetTimeStep(0.5), std::invalid_argument);
  EXPECT_EQ(sim.options().time_step, 1e-4);
}

TEST(AccuracyOptions, OutOfRangeIsRefusedWithTheField) {
  AccuracyOptions o;
  o.tolerance = 2.0;
  EXPECT_THROW(ValidateAccuracyOptions(o), std::invalid_argument);
  o.tolerance = 1e-3;
  o.min_time_step = 1e-3;
  o.max_time_step = 1e-4;
  try {
    ValidateAccuracyOptions(o);
    FAIL() << "min > max accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("min_time_step"), std::string::npos);
  }
}

TEST(AccuracyOptions, SmallestStepHasValidHalves) {
  // a step H is also taken as two of H/2, each a valid SimulatorOptions::time_step (≥ 1e-7)
  AccuracyOptions o;
  o.tolerance = 1e-3;
  o.min_time_step = 1e-7;
  EXPECT_THROW(ValidateAccuracyOptions(o), std::invalid_argument);
  o.min_time_step = 2e-7;
  EXPECT_NO_THROW(ValidateAccuracyOptions(o));
  Simulator sim(MakeTippeTopScene(), Moreau2());
  AdaptiveStepper stepper(&sim, o);
  // remainders down to the smallest step, and below it (absorbed)
  for (const double dt : {3e-7, 2e-7, 1.5e-7, 1e-7, 5e-8}) {
    const double t = sim.time() + dt;
    EXPECT_NO_THROW(stepper.AdvanceTo(t, {})) << dt;
    EXPECT_NEAR(sim.time(), t, 1.01e-7) << dt;
  }
}

TEST(AdaptiveStepper, LandsOnTheRequestedTimesWithAcceptedErrorsWithinTolerance) {
  Simulator sim(MakeTippeTopScene(), Moreau2());
  AccuracyOptions options;
  options.tolerance = 1e-2;
  AdaptiveStepper stepper(&sim, options);
  long calls = 0;
  for (int k = 1; k <= 100; ++k) {
    const double t = 1e-3 * k;
    stepper.AdvanceTo(t, [&](const StepStatistics&, double) { ++calls; });
    EXPECT_NEAR(sim.time(), t, 1e-12);
  }
  const AdaptiveStatistics& s = stepper.statistics();
  EXPECT_EQ(calls, s.accepted_steps);
  EXPECT_EQ(s.simulator_steps, 3 * (s.accepted_steps + s.rejected_steps));
  EXPECT_GE(s.smallest_step, options.min_time_step * (1 - 1e-12));
  EXPECT_LE(s.largest_step, options.max_time_step * (1 + 1e-12));
  // every accepted error within TOL·H (H ≤ largest_step), unless forced at the smallest step
  if (s.forced_steps == 0) {
    EXPECT_LE(s.max_error, options.tolerance * s.largest_step);
  }
  // the contact solver's tolerance was tightened to TOL/100
  EXPECT_LE(sim.options().solver.tolerance_rel, 1e-4);
}

// The knob's honesty against references: test/scenes/accuracy_knob_test.cpp.

}  // namespace
}  // namespace nonsmooth_sim
