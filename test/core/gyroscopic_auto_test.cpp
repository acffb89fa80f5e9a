// GyroscopicScheme::kAuto: the paper's explicit gyroscopic term while every body has
// Δt·|ω_B| ≤ kExplicitGyroscopicMaxDtOmega, the implicit midpoint rule for a step where one
// exceeds it. Checked on the Tippe-Top against the two fixed schemes, bit for bit:
// - at the default Δt = 1e-4 (Δt·|ω| ≈ 0.018) every step equals kExplicit's;
// - at Δt = 1e-2, the largest step `simulate` and the node allow (Δt·|ω| = 1.8), every step
//   above the threshold equals kImplicitMidpoint's;
// - at Δt = 1e-2 the explicit term gains energy over 8 s (the control), kAuto none:
//   E(t) − E(0) minus the potential energy the gap correction added stays ≤ 0 (the explicit
//   term: 6.9e-4 J = 5.7 % of E0 beyond the lifts).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"

namespace nonsmooth_sim {
namespace {

SimulatorOptions Options(GyroscopicScheme scheme, double dt) {
  SimulatorOptions options;
  options.gyroscopic = scheme;
  options.time_step = dt;
  return options;
}

bool SameState(const BodyState& a, const BodyState& b) {
  return a.position == b.position && a.orientation.coeffs() == b.orientation.coeffs() &&
         a.linear_velocity == b.linear_velocity && a.angular_velocity == b.angular_velocity;
}

// The largest E(t) − E(0) − Σ ΔE_lift over `duration` [J], and E(0).
std::pair<double, double> EnergyGain(GyroscopicScheme scheme, double dt, double duration) {
  Simulator sim(MakeTippeTopScene(), Options(scheme, dt));
  const double e0 = sim.Energy();
  double lifted = 0.0;
  double gain = -e0;
  StepStatistics stats;
  const long steps = std::lround(duration / dt);
  for (long k = 0; k < steps; ++k) {
    sim.Step(&stats);
    EXPECT_TRUE(stats.state_finite) << k;
    lifted += stats.gap_correction_energy;
    gain = std::max(gain, sim.Energy() - e0 - lifted);
  }
  return {gain, e0};
}

TEST(GyroscopicAuto, BelowTheThresholdEveryStepIsTheExplicitOne) {
  Simulator automatic(MakeTippeTopScene(), Options(GyroscopicScheme::kAuto, 1e-4));
  Simulator explicit_(MakeTippeTopScene(), Options(GyroscopicScheme::kExplicit, 1e-4));
  StepStatistics a, e;
  double max_dt_omega = 0.0;
  for (int k = 0; k < 20000; ++k) {  // 2 s: spinning, rising, the peg touching down
    automatic.Step(&a);
    explicit_.Step(&e);
    ASSERT_TRUE(SameState(automatic.state()[0], explicit_.state()[0])) << "step " << k;
    ASSERT_EQ(a.solver.iterations, e.solver.iterations) << "step " << k;
    EXPECT_FALSE(a.explicit_gyroscopic_unsafe);
    max_dt_omega = std::max(max_dt_omega, a.max_dt_omega);
  }
  EXPECT_LT(max_dt_omega, kExplicitGyroscopicMaxDtOmega);
}

TEST(GyroscopicAuto, AboveTheThresholdEveryStepIsTheImplicitOne) {
  Simulator automatic(MakeTippeTopScene(), Options(GyroscopicScheme::kAuto, 1e-2));
  Simulator implicit(MakeTippeTopScene(), Options(GyroscopicScheme::kImplicitMidpoint, 1e-2));
  StepStatistics a, i;
  int above = 0;
  for (int k = 0; k < 800; ++k) {
    automatic.Step(&a);
    implicit.Step(&i);
    if (a.max_dt_omega <= kExplicitGyroscopicMaxDtOmega) break;  // from here they may differ
    ++above;
    ASSERT_TRUE(SameState(automatic.state()[0], implicit.state()[0])) << "step " << k;
    EXPECT_EQ(a.gyroscopic_passes, i.gyroscopic_passes) << "step " << k;
    EXPECT_FALSE(a.explicit_gyroscopic_unsafe);
  }
  EXPECT_GT(above, 100);  // the spin stays above 10 rad/s for more than a second
}

TEST(GyroscopicAuto, TheLargestAllowedStepGainsNoEnergy) {
  const auto [explicit_gain, e0] = EnergyGain(GyroscopicScheme::kExplicit, 1e-2, 8.0);
  const auto automatic_gain = EnergyGain(GyroscopicScheme::kAuto, 1e-2, 8.0).first;
  EXPECT_GT(explicit_gain, 0.02 * e0);  // the control (5.7 % of E0): the comparison can tell
  EXPECT_LE(automatic_gain, 1e-12 * e0);
}

}  // namespace
}  // namespace nonsmooth_sim
