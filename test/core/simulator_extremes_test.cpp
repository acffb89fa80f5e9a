// States far beyond every scene's scale, set through the C++ API (the node and the loader bound
// every start to |x| ≤ 1e3 m, |v| ≤ 1e3 m/s, |ω| ≤ 1e4 rad/s): the four core findings of the
// service-sequence fuzzer (test/fuzz/corpus/service_sequence_fuzz/finding_*.bin) written out as
// plain C++. A step that reports state_finite leaves a
// finite state, energy and statistics; SetState refuses a state whose energy overflows; a level die
// reset deep under the ground is lifted straight. Fixed states, no timing.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "scene_builders.h"
#include "same_bits.h"

namespace nonsmooth_sim {
namespace {

constexpr double kHalfSide = 0.008;  // the die of urdf/die.urdf: side 0.016 m

// The die of urdf/die.urdf (m = 0.0045 kg, Θ = m s²/6, μ = 0.3, R̄ = 3πR/16 with R = 5e-4 m) on the
// ground, resting level on a face.
Scene DieScene() {
  Scene scene;
  RigidBody die;
  die.name = "die";
  die.mass = 0.0045;
  die.inertia = Eigen::Vector3d::Constant(1.92e-7).asDiagonal();
  scene.bodies = {die};
  ContactLaw law;
  law.mu = 0.3;
  law.rbar = AverageFrictionRadius(5e-4);
  Collider cube;
  cube.name = "cube";
  cube.body = 0;
  cube.shape = Shape::Box(Eigen::Vector3d::Constant(kHalfSide));
  cube.law = law;
  scene.colliders = {cube};
  test::AddGround(&scene);
  BodyState state;
  state.position = Eigen::Vector3d(0.0, 0.0, kHalfSide);
  scene.initial_state = {state};
  return scene;
}

// A simulator of `scene` set to `state` (initial state replaced), with or without gap correction.
Simulator At(Scene scene, const BodyState& state, bool gap_correction = true) {
  scene.initial_state = {state};
  SimulatorOptions options;
  options.gap_correction = gap_correction;
  return Simulator(std::move(scene), options);
}

BodyState DieAt(const Eigen::Vector3d& position) {
  BodyState state;
  state.position = position;
  return state;
}

bool Finite(const std::vector<BodyState>& state) {
  for (const BodyState& s : state) {
    if (!(s.position.allFinite() && s.orientation.coeffs().allFinite() &&
          s.linear_velocity.allFinite() && s.angular_velocity.allFinite())) {
      return false;
    }
  }
  return true;
}

using test::SameBits;

// The contract of a step (fuzz_support.h): finite, or the reported fault with nothing changed.
void ExpectFiniteOrFault(const Simulator& sim, const StepStatistics& stats,
                         const std::vector<BodyState>& before, const std::string& where) {
  if (!stats.state_finite) {
    EXPECT_TRUE(std::isnan(stats.energy)) << where << ": a step not taken reports an energy";
    EXPECT_TRUE(sim.diverged()) << where;
    EXPECT_TRUE(SameBits(sim.state(), before)) << where << ": a step not taken changed the state";
    return;
  }
  EXPECT_TRUE(Finite(sim.state())) << where << ": state_finite, but the state is not";
  EXPECT_TRUE(std::isfinite(sim.Energy())) << where << ": state_finite, but Energy() = "
                                           << sim.Energy();
  // the energy the step summed is the state's, bit for bit (also after an undone correction)
  EXPECT_EQ(stats.energy, sim.Energy()) << where;
  EXPECT_TRUE(std::isfinite(stats.gap_correction))
      << where << ": gap_correction = " << stats.gap_correction;
  EXPECT_TRUE(std::isfinite(stats.gap_correction_energy))
      << where << ": gap_correction_energy = " << stats.gap_correction_energy;
}

// Angle of the rotation q [rad].
double TurnAngle(const Eigen::Quaterniond& q) {
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w()));
}

// Finding 1 (finding_levelling_nan.bin): the die set level 1e300 m deep stepped with state_finite
// to a NaN orientation: the levelling in CorrectGaps ran after the step's finite check.
TEST(SimulatorExtremes, DieFarBelowTheGroundNeverStepsFiniteToANonFiniteState) {
  const BodyState deep = DieAt(Eigen::Vector3d(0.5, 0.5, -1e300));
  Simulator sim = At(DieScene(), deep);
  Simulator uncorrected = At(DieScene(), deep, /*gap_correction=*/false);
  for (int k = 0; k < 3; ++k) {
    const std::vector<BodyState> before = sim.state();
    const StepStatistics stats = sim.Step();
    uncorrected.Step();
    ExpectFiniteOrFault(sim, stats, before, "step " + std::to_string(k));
    ASSERT_TRUE(stats.state_finite) << k;
    // the correction overflowed (a lift of 1e300 m) and was undone: the step without it
    EXPECT_TRUE(stats.gap_correction_undone) << k;
    EXPECT_TRUE(SameBits(sim.state(), uncorrected.state())) << k;
  }
}

// Finding 2 (finding_energy_overflow.bin): the Tippe-Top set 2.8e307 m high has a finite state
// whose Energy() is inf (g·r_S overflows), and stepped "finite" on. SetState refuses it now,
// naming the field and the bound, and changes nothing; so does SetBodyStates.
TEST(SimulatorExtremes, SetStateRefusesAStateWhoseEnergyOverflows) {
  Simulator sim(MakeTippeTopScene(), SimulatorOptions{});
  sim.Step();
  const std::vector<BodyState> before = sim.state();
  struct Case {
    const char* field;
    BodyState state;
  };
  std::vector<Case> cases;
  BodyState high = before[0];
  high.position = Eigen::Vector3d(-8.8234996792925813, -0.0, 2.8089115958841757e307);
  cases.push_back({"state[0].position", high});
  BodyState fast = before[0];
  fast.linear_velocity = Eigen::Vector3d(1e155, 0.0, 0.0);
  cases.push_back({"state[0].linear_velocity", fast});
  BodyState spinning = before[0];
  spinning.angular_velocity = Eigen::Vector3d(0.0, 0.0, 1e160);
  cases.push_back({"state[0].angular_velocity", spinning});
  for (const Case& c : cases) {
    for (int setter = 0; setter < 2; ++setter) {
      try {
        if (setter == 0) {
          sim.SetState({c.state});
        } else {
          sim.SetBodyStates({0}, {c.state});
        }
        ADD_FAILURE() << c.field << " (setter " << setter << "): accepted, Energy() = "
                      << sim.Energy();
        sim.SetState(before);
      } catch (const std::invalid_argument& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(c.field), std::string::npos) << message;
        EXPECT_NE(message.find("must be below"), std::string::npos) << message;
      }
      EXPECT_TRUE(SameBits(sim.state(), before)) << c.field;
      EXPECT_FALSE(sim.diverged());
    }
  }
  // within the bounds of the starts (1e3 m, 1e3 m/s, 1e4 rad/s) every state is accepted
  BodyState bounded = before[0];
  bounded.position = Eigen::Vector3d(1e3, -1e3, 1e3);
  bounded.linear_velocity = Eigen::Vector3d(1e3, 0.0, 0.0);
  bounded.angular_velocity = Eigen::Vector3d(0.0, 0.0, 1e4);
  EXPECT_NO_THROW(sim.SetState({bounded}));
}

// Finding 2 through the other doors: a scene whose start's energy overflows is refused by the
// constructor, and a model whose state's energy overflows by AddBodies (the world unchanged).
TEST(SimulatorExtremes, ConstructorAndAddBodiesRefuseAnOverflowingEnergy) {
  Scene far = MakeTippeTopScene();
  far.initial_state[0].position.z() = 2.8089115958841757e307;
  try {
    Simulator sim(far, SimulatorOptions{});
    ADD_FAILURE() << "constructed, Energy() = " << sim.Energy();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("state[0].position"), std::string::npos) << e.what();
  }

  Simulator sim(MakeTippeTopScene(), SimulatorOptions{});
  sim.Step();
  const std::vector<BodyState> before = sim.state();
  Scene model = MakeTippeTopScene();
  model.colliders.erase(std::remove_if(model.colliders.begin(), model.colliders.end(),
                                       [](const Collider& c) { return c.body == kWorld; }),
                        model.colliders.end());
  for (RigidBody& body : model.bodies) body.name = "second_" + body.name;
  for (Collider& collider : model.colliders) collider.name = "second_" + collider.name;
  BodyState fast = model.initial_state[0];
  fast.linear_velocity = Eigen::Vector3d(1e155, 0.0, 0.0);
  try {
    sim.AddBodies(model, {fast});
    ADD_FAILURE() << "added, Energy() = " << sim.Energy();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("state[1].linear_velocity"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(sim.state().size(), 1u);
  EXPECT_TRUE(SameBits(sim.state(), before));
  // the same model at a bounded speed is added
  fast.linear_velocity = Eigen::Vector3d(1.0, 0.0, 0.0);
  EXPECT_NO_THROW(sim.AddBodies(model, {fast}));
  EXPECT_EQ(sim.state().size(), 2u);
}

// Finding 2, in a step: a state of finite energy that steps to one whose energy overflows (a
// 100 kg ball at 1e153 m/s pushed to 2e153 m/s: |v|² is finite, ½m|v|² is not) is the reported
// fault, not a finite step to Energy() = inf.
TEST(SimulatorExtremes, AStepToAnOverflowingEnergyIsNotTaken) {
  Scene scene;
  RigidBody ball;
  ball.name = "ball";
  ball.mass = 100.0;
  ball.inertia = Eigen::Vector3d::Constant(0.4 * 100.0 * 0.01).asDiagonal();
  scene.bodies = {ball};
  scene.colliders = {test::SphereCollider("ball", 0, Eigen::Vector3d::Zero(), 0.1, ContactLaw{})};
  test::AddGround(&scene);
  BodyState state;
  state.position = Eigen::Vector3d(0.0, 0.0, 1.0);
  state.linear_velocity = Eigen::Vector3d(1e153, 0.0, 0.0);
  scene.initial_state = {state};
  Simulator sim(scene, SimulatorOptions{});
  ASSERT_TRUE(std::isfinite(sim.Energy()));
  sim.SetExternalWrench(0, Eigen::Vector3d(100.0 * 1e153 / sim.options().time_step, 0.0, 0.0),
                        Eigen::Vector3d::Zero());
  const std::vector<BodyState> before = sim.state();
  const StepStatistics stats = sim.Step();
  ExpectFiniteOrFault(sim, stats, before, "push");
  EXPECT_FALSE(stats.state_finite);
  EXPECT_EQ(sim.time(), 0.0);
}

// Finding 3 (finding_deep_lift_energy.bin): a body set absurdly deep was lifted with
// gap_correction_energy (or gap_correction, the lift's norm) = inf in a finite step. The lift is
// undone now.
TEST(SimulatorExtremes, ALiftThatOverflowsIsUndone) {
  // the lift group rule (one point per sphere) and the levelling (the die's points)
  BodyState top = TippeTopInitialState(TippeTopParameters{}, TippeTopInitialConditions{});
  top.position.z() = -1e200;
  const BodyState die = DieAt(Eigen::Vector3d(0.0, 0.0, -1.5e307));
  const std::vector<std::pair<Scene, BodyState>> cases = {{MakeTippeTopScene(), top},
                                                          {DieScene(), die}};
  for (std::size_t c = 0; c < cases.size(); ++c) {
    Simulator sim = At(cases[c].first, cases[c].second);
    Simulator uncorrected = At(cases[c].first, cases[c].second, /*gap_correction=*/false);
    const std::vector<BodyState> before = sim.state();
    const StepStatistics stats = sim.Step();
    uncorrected.Step();
    ExpectFiniteOrFault(sim, stats, before, "case " + std::to_string(c));
    ASSERT_TRUE(stats.state_finite) << c;
    EXPECT_TRUE(stats.gap_correction_undone) << c;
    EXPECT_EQ(stats.gap_correction, 0.0) << c;
    EXPECT_EQ(stats.gap_correction_energy, 0.0) << c;
    EXPECT_TRUE(SameBits(sim.state(), uncorrected.state())) << c;
  }
  // the reproducer's state, 1.56e308 m deep: -m g·r_S overflows; SetState (above) and AddBodies
  // (ConstructorAndAddBodiesRefuseAnOverflowingEnergy) refuse it
  Simulator sim(DieScene(), SimulatorOptions{});
  Scene model = MakeTippeTopScene();
  model.colliders.pop_back();  // the ground is the world's
  BodyState deepest = TippeTopInitialState(TippeTopParameters{}, TippeTopInitialConditions{});
  deepest.position.z() = -1.5589370091066778e308;
  EXPECT_THROW(sim.AddBodies(model, {deepest}), std::invalid_argument);
}

// Finding 4: a level die reset 10 m (and 1 km) under the ground came up turned by 33° (25°) in
// one step: the levelling's sweeps gave the lift to its upper corners first. It is lifted straight
// now, up to its face at -kGapCorrectionSlop, and stays level.
TEST(SimulatorExtremes, ALevelDieResetDeepIsLiftedStraight) {
  for (const double depth : {10.0, 1000.0}) {
    Simulator sim = At(DieScene(), DieAt(Eigen::Vector3d(0.0, 0.0, -depth)));
    const StepStatistics stats = sim.Step();
    ASSERT_TRUE(stats.state_finite) << depth;
    const BodyState& s = sim.state()[0];
    EXPECT_LT(TurnAngle(s.orientation), 1e-9) << depth;
    EXPECT_NEAR(s.position.z(), kHalfSide - kGapCorrectionSlop, 1e-9) << depth;
    EXPECT_LT(s.position.head<2>().norm(), 1e-12) << depth;
    EXPECT_NEAR(stats.gap_correction, depth + kHalfSide - kGapCorrectionSlop, 1e-9 * depth)
        << depth;
    // turned about the vertical it is level too, and lifted the same way
    BodyState turned = DieAt(Eigen::Vector3d(0.0, 0.0, -depth));
    turned.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
    Simulator sim_turned = At(DieScene(), turned);
    sim_turned.Step();
    EXPECT_LT(sim_turned.state()[0].orientation.angularDistance(turned.orientation), 1e-9)
        << depth;
    EXPECT_NEAR(sim_turned.state()[0].position.z(), kHalfSide - kGapCorrectionSlop, 1e-9)
        << depth;
  }
}

}  // namespace
}  // namespace nonsmooth_sim
