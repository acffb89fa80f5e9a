// Stability at the extremes of the parameters (stability_support.h): invalid ones rejected before
// the run; μ, the patch radius, Λ_N → 0 and the spin from zero to very fast.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "stability_support.h"

namespace nonsmooth_sim {
namespace {

using namespace stability;  // NOLINT(build/namespaces)

// ---------------------------------------------------------------------------------------------
// Invalid parameters are rejected before the run

void ExpectRejected(const std::function<void()>& action,
                    const std::vector<std::string>& fragments) {
  try {
    action();
    ADD_FAILURE() << "accepted; expected std::invalid_argument naming " << fragments[0];
  } catch (const std::invalid_argument& e) {
    for (const std::string& f : fragments) {
      EXPECT_NE(std::string(e.what()).find(f), std::string::npos)
          << "message \"" << e.what() << "\" lacks \"" << f << "\"";
    }
  }
}

TEST(Validation, BadParametersAreRejectedWithNameAndRangeBeforeTheRun) {
  const Scene top = TippeTop({});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto construct = [&](const Scene& scene, const SimulatorOptions& options) {
    return [scene, options] { Simulator sim(scene, options); };
  };
  SimulatorOptions o;
  o.time_step = -1e-4;
  ExpectRejected(construct(top, o), {"time_step", "[1e-07, 0.01]"});
  o.time_step = nan;
  ExpectRejected(construct(top, o), {"time_step", "[1e-07, 0.01]"});
  o.time_step = 0.1;
  ExpectRejected(construct(top, o), {"time_step", "[1e-07, 0.01]"});
  for (const double alpha : {0.0, 2.0, -1.0, nan}) {
    o = SimulatorOptions{};
    o.solver.relaxation = alpha;
    ExpectRejected(construct(top, o), {"relaxation", "(0, 2)"});
  }
  o = SimulatorOptions{};
  o.solver.tolerance_rel = -1e-6;
  ExpectRejected(construct(top, o), {"tolerance_rel", ">= 0"});
  o.solver.tolerance_rel = nan;
  ExpectRejected(construct(top, o), {"tolerance_rel", ">= 0"});
  o = SimulatorOptions{};
  o.solver.max_iterations = 0;
  ExpectRejected(construct(top, o), {"max_iterations", ">= 1"});

  for (const double mu : {-0.3, nan}) {
    Scene s = top;
    s.colliders[kPeg].law.mu = mu;
    ExpectRejected(construct(s, SimulatorOptions{}),
                   {"colliders[1] (peg_sphere)", "law.mu", ">= 0"});
  }
  Scene s = top;
  s.colliders[kBig].law.rbar = -1e-4;
  ExpectRejected(construct(s, SimulatorOptions{}),
                 {"colliders[0] (big_sphere)", "law.rbar", ">= 0"});
  s = top;
  s.colliders[kBig].law.restitution = 1.5;
  ExpectRejected(construct(s, SimulatorOptions{}),
                 {"colliders[0] (big_sphere)", "law.restitution", "[0, 1]"});
  s = top;
  s.colliders[kBig].shape.radius = nan;
  ExpectRejected(construct(s, SimulatorOptions{}),
                 {"colliders[0] (big_sphere)", "radius", "> 0"});
  s = top;
  s.initial_state[0].position.z() = nan;
  ExpectRejected(construct(s, SimulatorOptions{}), {"position", "finite"});

  // on a running simulator the setters reject the same values and leave everything unchanged
  Simulator sim(top, SimulatorOptions{});
  for (int k = 0; k < 100; ++k) sim.Step();
  const BodyState before = sim.state()[0];
  o = SimulatorOptions{};
  o.time_step = -1e-4;
  ExpectRejected([&] { sim.SetOptions(o); }, {"time_step"});
  ContactLaw law = sim.scene().colliders[kBig].law;
  law.mu = -1.0;
  // "law of collider big_sphere.mu = -1: must be finite, >= 0"
  ExpectRejected([&] { sim.SetContactLaw(kBig, law); }, {"big_sphere", "mu", ">= 0"});
  ExpectRejected([&] { sim.SetFrictionSet(FrictionSet::kExact, "no_such_collider"); },
                 {"no_such_collider"});
  EXPECT_EQ(sim.options().time_step, 1e-4);
  EXPECT_EQ(sim.scene().colliders[kBig].law.mu, 0.3);
  EXPECT_EQ(sim.scene().colliders[kBig].law.friction_set, FrictionSet::kSphere);
  EXPECT_EQ(sim.state()[0].position, before.position);
  sim.Step();  // and it still runs
  EXPECT_TRUE(StateIsFinite(sim.state()));
}

// ---------------------------------------------------------------------------------------------
// Friction coefficient μ: 0, 1e-6, 5, 1e3

TEST(FrictionCoefficient, FrictionlessTopKeepsItsEnergyAndDoesNotInvert) {
  // μ = 0: only normal percussions (ContactDimension 1), so no torque can lift the centre of mass
  // towards inversion: θ only nutates (measured θ_max 0.1000 rad over 3 s). With ε = 1 every
  // contact percussion does zero work in Moreau's midpoint rule (Λ_N(γ_B + γ_E)/2 = 0) and the
  // implicit-midpoint gyroscopic term none either: energy is conserved to round-off (measured
  // max step gain 3e-16 J, |E(3 s) - E0| 7e-18 J of 0.012 J). With ε = 0 steps only lose energy
  // (measured max step gain -1.7e-18 J).
  for (const double restitution : {1.0, 0.0}) {
    TopSetup setup;
    setup.mu = 0.0;
    setup.restitution = restitution;
    SimulatorOptions options = Options();
    options.solver.tolerance_rel = 1e-12;
    Simulator sim(TippeTop(setup), options);
    const double e0 = sim.Energy();
    double max_friction = 0.0;
    const RunReport r = RunChecked(&sim, Steps(3.0, 1e-4), 1e-6, [&](long, const StepStatistics&) {
      for (const ContactState& c : sim.contacts()) {
        max_friction = std::max(max_friction, c.percussion.tail<3>().cwiseAbs().maxCoeff());
      }
    });
    const std::string what = "eps = " + std::to_string(restitution);
    ExpectSane(r, -2e-6, what);  // measured -4.9e-8 m (ε = 1), -1.1e-6 m (ε = 0)
    EXPECT_EQ(max_friction, 0.0) << what;
    EXPECT_LT(r.theta_max, 0.11) << what;
    EXPECT_LT(r.max_step_energy_gain, kEnergyRoundOff) << what;
    EXPECT_EQ(r.unconverged_steps, 0) << what;
    if (restitution == 1.0) {
      EXPECT_NEAR(sim.Energy(), e0, 1e-12 * e0) << what;
    }
  }
}

TEST(FrictionCoefficient, TinyMuIsAlmostFrictionless) {
  // μ = 1e-6: friction is bounded by μΛ_N, so over 1 s θ(t) stays within a hair of the μ = 0 run
  // (measured max |Δθ| = 5.4e-6 rad) and the top is far from inverting.
  TopSetup setup;
  setup.mu = 1e-6;
  Simulator tiny(TippeTop(setup), Options());
  setup.mu = 0.0;
  Simulator none(TippeTop(setup), Options());
  double max_difference = 0.0;
  const RunReport r = RunChecked(&tiny, Steps(1.0, 1e-4), 1e-6, [&](long, const StepStatistics&) {
    none.Step();
    max_difference = std::max(
        max_difference, std::abs(Inclination(tiny.state()[0]) - Inclination(none.state()[0])));
  });
  ExpectSane(r, -2e-6, "mu = 1e-6");
  EXPECT_LT(max_difference, 1e-4);
  EXPECT_LT(r.theta_max, 0.11);
  EXPECT_LT(r.max_step_energy_gain, kEnergyRoundOff);
  EXPECT_EQ(r.unconverged_steps, 0);
}

// Time after which the big sphere's contact stays sticking (|γ_T| and |γ_τ| below the bounds)
// for the rest of the run, -1 if never.
struct StickReport {
  RunReport run;
  double stick_time = -1.0;  // [s]
  double contact_mu = -1.0;  // μ of the big sphere's contact (its pair's law)
};
StickReport RunUntilStuck(const TopSetup& setup, double duration) {
  Simulator sim(TippeTop(setup), Options());
  StickReport report;
  constexpr double kSlipSpeed = 1e-6;   // [m/s]
  constexpr double kDrillSpeed = 1e-6;  // [rad/s]
  report.run = RunChecked(&sim, Steps(duration, 1e-4), 1e-6, [&](long k, const StepStatistics&) {
    const ContactState* c = sim.FindContact(kBig);
    const bool closed = c != nullptr;
    if (closed) report.contact_mu = c->law.mu;
    const bool stuck = closed && c->relative_velocity.segment<2>(1).norm() < kSlipSpeed &&
                       (ContactDimension(sim.scene().colliders[kBig].law) < 4 ||
                        std::abs(c->relative_velocity[3]) < kDrillSpeed);
    if (!stuck && closed) report.stick_time = -1.0;
    if (stuck && report.stick_time < 0.0) report.stick_time = k * 1e-4;
  });
  return report;
}

TEST(FrictionCoefficient, HugeMuSticksAlmostAtOnceAndDoesNotInvert) {
  // μ = 1e3 with the coupled law: the contact can supply any force and any drilling torque the
  // motion asks for, so sliding (0.27 m/s) and drilling (179 rad/s) stop within a few steps
  // (measured: stuck for good from t = 0.0073 s) and the vertical spin is gone. Inversion needs
  // sliding friction (tippe-top.md): θ only rises to 0.75 rad (the 18 rad/s of horizontal
  // angular velocity the initial spin had about the tilted axis rolls the top over; measured
  // 0.752) and rocks back. μ = 5 behaves alike, slower: drilling torque R̄μΛ_N drains the spin
  // and the contact sticks for good from 1.446 s (θ_max 0.741 rad). Measured smallest gap
  // -1.2e-5 m, no step gains energy, every step converges.
  for (const double mu : {1e3, 5.0}) {
    TopSetup setup;
    setup.mu = mu;
    const StickReport s = RunUntilStuck(setup, 3.0);
    const std::string what = "mu = " + std::to_string(mu);
    ExpectSane(s.run, -2e-5, what);
    EXPECT_EQ(s.contact_mu, mu) << what;
    ASSERT_GT(s.stick_time, 0.0) << what;
    EXPECT_LT(s.stick_time, mu > 10.0 ? 0.02 : 2.0) << what;
    EXPECT_LT(s.run.theta_max, 0.8) << what;
    EXPECT_LT(s.run.max_step_energy_gain, kEnergyRoundOff) << what;
    EXPECT_EQ(s.run.unconverged_steps, 0) << what;
  }
}

// ---------------------------------------------------------------------------------------------
// Contact radius R: 0, 1e-9, R1

// max |θ_a(t) - θ_b(t)| of two Tippe-Tops over `steps` steps; `a` is checked by RunChecked.
struct Comparison {
  RunReport run;
  double max_theta_difference = 0.0;
  double max_drilling = 0.0;  // max |Λ_τ| of `a` [N m s]
};
Comparison Compare(const TopSetup& a, const TopSetup& b, long steps,
                   const SimulatorOptions& options = Options()) {
  Simulator sim_a(TippeTop(a), options);
  Simulator sim_b(TippeTop(b), options);
  Comparison c;
  c.run = RunChecked(&sim_a, steps, 1e-6, [&](long, const StepStatistics&) {
    sim_b.Step();
    c.max_theta_difference =
        std::max(c.max_theta_difference,
                 std::abs(Inclination(sim_a.state()[0]) - Inclination(sim_b.state()[0])));
    for (const ContactState& contact : sim_a.contacts()) {
      c.max_drilling = std::max(c.max_drilling, std::abs(contact.percussion[3]));
    }
  });
  return c;
}

TEST(ContactRadius, ZeroRadiusHasNoDrillingComponentWithAnySet) {
  // R = 0: every law has 3 components (ContactDimension), Λ_τ is identically 0 and every
  // drilling set gives the trajectory of `coulomb` (measured max |Δθ| = 0 over 1 s)
  TopSetup coulomb;
  coulomb.set = FrictionSet::kCoulomb;
  coulomb.contact_radius = 0.0;
  for (const FrictionSet set : {FrictionSet::kCylinder, FrictionSet::kEllipsoid,
                                FrictionSet::kSphere, FrictionSet::kExact}) {
    TopSetup setup = coulomb;
    setup.set = set;
    const std::string what(FrictionSetName(set));
    EXPECT_EQ(ContactDimension(TippeTop(setup).colliders[kBig].law), 3) << what;
    const Comparison c = Compare(setup, coulomb, Steps(1.0, 1e-4));
    ExpectSane(c.run, -1e-6, what);  // measured -1.6e-7 m
    EXPECT_EQ(c.max_drilling, 0.0) << what;
    EXPECT_LE(c.max_theta_difference, 1e-15) << what;
    EXPECT_EQ(c.run.unconverged_steps, 0) << what;
    EXPECT_LT(c.run.max_step_energy_gain, kContactWorkPerStep) << what;  // measured 1.8e-12 J
  }
}

TEST(ContactRadius, TinyRadiusIsCloseToZeroRadius) {
  // R = 1e-9 m (R̄ = 5.9e-10 m): the drilling torque is bounded by R̄μΛ_N, so θ(t) follows the
  // R = 0 run. `sphere` iterates Λ_τ/R̄ (56) and converges every step (measured max |Δθ| over 1 s
  // 4.2e-7 rad; cylinder 1.1e-10 and exact 5.1e-11 rad over 0.1 s, both converged). A set
  // iterated in its own coordinates (ellipsoid, (37)) sees G_ττ = 1/C = 1.4e6 next to
  // G_TT ≈ 450 in one contact: the friction block's step r = α/G_ττ makes the sliding tangential
  // components creep and steps end unconverged at max_iterations (measured 645 of 999 contact
  // steps) — reported, never silently: the percussions stay in their sets, E(t) ≤ E(0), and the
  // trajectory stays within 9.3e-6 rad of R = 0 over 0.1 s.
  TopSetup zero;
  zero.contact_radius = 0.0;
  for (const FrictionSet set : {FrictionSet::kSphere, FrictionSet::kCylinder,
                                FrictionSet::kEllipsoid, FrictionSet::kExact}) {
    TopSetup tiny = zero;
    tiny.contact_radius = 1e-9;
    tiny.set = set;
    const bool transformed = set == FrictionSet::kSphere;
    const Comparison c = Compare(tiny, zero, Steps(transformed ? 1.0 : 0.1, 1e-4));
    const std::string what(FrictionSetName(set));
    ExpectSane(c.run, -1e-6, what);
    EXPECT_LT(c.max_theta_difference, transformed ? 1e-6 : 1e-4) << what;
    EXPECT_LE(c.run.max_energy_above_start, 0.0) << what;
    if (transformed) {
      EXPECT_EQ(c.run.unconverged_steps, 0) << what;
      EXPECT_LT(c.run.max_step_energy_gain, kContactWorkPerStep) << what;
    }
  }
}

TEST(ContactRadius, HugePatchDrainsTheSpinQuickly) {
  // R = R1 = 15 mm (R̄ = 8.8 mm, 30 times the default): drilling friction μmgR̄ drains the
  // vertical spin at up to μgmR̄/C ≈ 220 rad/s² (measured: below 4e-8 rad/s after 1 s with every
  // set, from 179 rad/s; with the default R it keeps ~120 rad/s); finite, no energy gained.
  TopSetup setup;
  setup.contact_radius = 0.015;
  for (const FrictionSet set : {FrictionSet::kSphere, FrictionSet::kEllipsoid, FrictionSet::kExact,
                                FrictionSet::kCylinder}) {
    setup.set = set;
    Simulator sim(TippeTop(setup), Options());
    const RunReport r = RunChecked(&sim, Steps(1.0, 1e-4));
    const std::string what(FrictionSetName(set));
    ExpectSane(r, -1e-5, what);
    EXPECT_LT(std::abs(VerticalSpin(sim)), 1.0) << what;
    EXPECT_LT(r.max_step_energy_gain, kEnergyRoundOff) << what;
  }
}

// ---------------------------------------------------------------------------------------------
// Λ_N → 0: just touching, lifting off, many closed contacts at rest


TEST(NormalForceToZero, TouchingWithoutLoadCarriesNoForce) {
  // no gravity, the ball touches the floor (gap 0, closed by (12)) while sliding at 1 m/s and
  // spinning: nothing presses it on the floor, so Λ_N = 0 and the friction set of radius μΛ_N
  // is the point 0: the ball slides on unchanged, with every set (measured |Δv| = 0)
  for (const FrictionSet set : kAllFrictionSets) {
    Scene scene = BallScene(Eigen::Vector3d::Zero(), set);
    scene.initial_state[0].linear_velocity = Eigen::Vector3d(1.0, 0.0, 0.0);
    scene.initial_state[0].angular_velocity = Eigen::Vector3d(0.0, 2.0, 30.0);
    const BodyState start = scene.initial_state[0];
    Simulator sim(scene, Options());
    double max_percussion = 0.0;
    const RunReport r = RunChecked(&sim, 1000, 1e-12, [&](long, const StepStatistics& stats) {
      EXPECT_EQ(stats.closed_contacts, 1);
      const ContactState* c = sim.FindContact(0);
      ASSERT_NE(c, nullptr);
      max_percussion = std::max(max_percussion, c->percussion.cwiseAbs().maxCoeff());
    });
    const std::string what(FrictionSetName(set));
    ExpectSane(r, -1e-15, what);
    EXPECT_LT(max_percussion, 1e-15) << what;  // round-off of m|v| = 0.2 N s; measured 1.6e-19
    EXPECT_EQ(r.unconverged_steps, 0) << what;
    EXPECT_LT((sim.state()[0].linear_velocity - start.linear_velocity).norm(), 1e-15) << what;
    EXPECT_LT((sim.state()[0].angular_velocity - start.angular_velocity).norm(), 1e-12) << what;
  }
}

TEST(NormalForceToZero, BigSphereLiftsOffCleanly) {
  // the Tippe-Top's inversion: once the peg touches down (θ ≈ 140°) the big sphere's load goes
  // to 0 and it lifts off. Through that phase every step converges, Λ_N ≥ 0 (in the set check)
  // and energy is never gained; after lift-off its gap opens (2.8 mm at 1.7 s) and it does not
  // touch again. Without the gap correction the big sphere, sunk ~30 μm, stayed closed until
  // after the peg touched (measured: peg down at 1.3690 s, big sphere last closed at 1.3712 s).
  // With it the big sphere hops just before and comes down in the step the peg touches
  // (measured: both at 1.3703 s, a double impact with Λ_N = 1.3e-4 N s on the peg, 28 times the
  // resting load). There a converged step shows γ_N = -5.1e-6 m/s: the solver's increment test
  // stops at an error of tolerance_rel·Λ_N·G/(1 - contraction), 10 times the usual 1e-6 m/s.
  Simulator sim(TippeTop({}), Options());
  double last_closed = -1.0, first_peg = -1.0;
  const RunReport r = RunChecked(&sim, Steps(1.7, 1e-4), 1e-5, [&](long k, const StepStatistics&) {
    if (sim.InContact(kPeg) && first_peg < 0.0) first_peg = k * 1e-4;
    if (sim.InContact(kBig)) last_closed = k * 1e-4;
  });
  ExpectSane(r, -1e-4, "lift-off");
  EXPECT_EQ(r.unconverged_steps, 0);
  EXPECT_LT(r.max_step_energy_gain, kEnergyRoundOff);
  ASSERT_GT(first_peg, 0.0);
  EXPECT_GE(last_closed, first_peg);
  EXPECT_LT(last_closed, 1.6);
  EXPECT_GT(test::GroundGap(sim.scene(), sim.state(), kBig), 1e-3);
}

// A 1 kg disc resting on `feet` spheres (radius 1 cm) on a circle of radius 0.1 m, 2 cm below its
// centre of mass: a redundant support (4·feet percussion components against 6 degrees of
// freedom).
Scene DiscOnFeet(int feet, FrictionSet set) {
  Scene scene;
  RigidBody disc;
  disc.name = "disc";
  disc.mass = 1.0;
  disc.inertia = Eigen::Vector3d(2.5e-3, 2.5e-3, 5e-3).asDiagonal();
  scene.bodies = {disc};
  ContactLaw law;
  law.mu = 0.3;
  law.rbar = AverageFrictionRadius(2e-3);
  law.friction_set = set;
  for (int i = 0; i < feet; ++i) {
    const double angle = 2.0 * kPi * i / feet;
    scene.colliders.push_back(SphereCollider(
        "foot" + std::to_string(i), 0,
        Eigen::Vector3d(0.1 * std::cos(angle), 0.1 * std::sin(angle), -0.02), 0.01, law));
  }
  AddGround(&scene);
  BodyState state;
  state.position = Eigen::Vector3d(0.0, 0.0, 0.03);  // every foot touches
  scene.initial_state = {state};
  return scene;
}

TEST(NormalForceToZero, RestingOnTwelveClosedContacts) {
  // 12 closed contacts share m g Δt: the single Λ_N are not unique (G is singular), only their
  // sum and moments are. Gauss-Seidel converges with α = 1, the Jacobi schemes with α below
  // 2/λ_max of the coupled problem (contact_solver.h): here (43) with α = 0.2 and (46), whose
  // steps are larger, with α = 0.05. Then the disc stays put (gap ≥ -1e-9 m, no horizontal creep,
  // measured smallest gap -3e-9 m) and the loads sum to m g Δt. With α = 1 both Jacobi schemes
  // diverge: every step ends unconverged — and says so (measured 1000 of 1000 steps flagged; the
  // percussions they return do not hold the disc, which falls freely). Whatever the setting, a
  // step whose loads miss m g Δt by more than 0.1 % must not claim convergence.
  struct Setting {
    SolverType type;
    double relaxation;
    bool converges;
  };
  for (const Setting setting :
       {Setting{SolverType::kGaussSeidel, 1.0, true}, Setting{SolverType::kJacobi, 0.2, true},
        Setting{SolverType::kModifiedJacobi, 0.05, true}, Setting{SolverType::kJacobi, 1.0, false},
        Setting{SolverType::kModifiedJacobi, 1.0, false}}) {
    SimulatorOptions options = Options(1e-3);
    options.solver.type = setting.type;
    options.solver.relaxation = setting.relaxation;
    Simulator sim(DiscOnFeet(12, FrictionSet::kSphere), options);
    const double weight = 1.0 * 9.81 * 1e-3;  // m g Δt [N s]
    double max_load_error = 0.0;
    long wrong_but_converged = 0;
    long feet_dropped = 0;  // steps whose index set lost a foot
    const RunReport r = RunChecked(&sim, 1000, 1e-6, [&](long, const StepStatistics& stats) {
      if (stats.closed_contacts != 12) ++feet_dropped;
      double load = 0.0;
      for (const ContactState& c : sim.contacts()) load += c.percussion[0];
      const double error = std::abs(load - weight) / weight;
      if (stats.solver.converged) {
        max_load_error = std::max(max_load_error, error);
        if (error > 1e-3) ++wrong_but_converged;
      }
    });
    const std::string what =
        std::string(SolverTypeName(setting.type)) + ", alpha " + std::to_string(setting.relaxation);
    EXPECT_TRUE(r.finite) << what;
    EXPECT_EQ(r.dishonest_steps, 0) << what;
    EXPECT_EQ(wrong_but_converged, 0) << what;
    EXPECT_LE(r.max_set_violation, kSetRoundOff) << what;
    if (setting.converges) {
      ExpectSane(r, -1e-8, what);
      EXPECT_EQ(r.unconverged_steps, 0) << what;
      // measured 3e-12 (Gauss-Seidel), 7.7e-6 (Jacobi), 6.9e-5 ((46) at α = 0.05: small steps
      // stop the increment test early, at ~tolerance / α)
      EXPECT_LT(max_load_error, 1e-3) << what;
      EXPECT_LT(sim.state()[0].position.head<2>().norm(), 1e-12) << what;
      // every foot stays in the index set (12): the ends of a step leave round-off-level gaps of
      // either sign (±1e-17 m), and a foot closed in the last step stays closed up to
      // kContactHysteresis. The broad phase once cut at the unpadded bounding sphere (= the
      // foot): Gauss-Seidel dropped to 7 of 12 feet every other step, 170 iterations each time
      EXPECT_EQ(feet_dropped, 0) << what;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Spin: 0, 1 rad/s, 5000 rad/s

TEST(Spin, WithoutSpinTheTopRocksOnItsBigSphereWithoutGainingHeight) {
  // spin 0 from θ0 = 0.1: the bottom-heavy top falls back towards upright and rocks. It rolls
  // without sliding and without drilling (nothing spins), so nothing dissipates: it keeps
  // rocking (measured: θ back above 0.099 rad in the last second) — and since energy is never
  // gained, θ exceeds θ0 only by what the sinking of the contact allows (measured 1.05e-7 rad,
  // gap -2.4e-7 m); the contact does not slide (measured |γ_T| ≤ 3.7e-12 m/s).
  TopSetup setup;
  setup.spin = 0.0;
  Simulator sim(TippeTop(setup), Options());
  double late_theta_max = 0.0, max_slip = 0.0;
  const RunReport r = RunChecked(&sim, Steps(3.0, 1e-4), 1e-6, [&](long k, const StepStatistics&) {
    if (k > 20000) late_theta_max = std::max(late_theta_max, Inclination(sim.state()[0]));
    const ContactState* big = sim.FindContact(kBig);
    if (k > 10 && big != nullptr) {
      max_slip = std::max(max_slip, big->relative_velocity.segment<2>(1).norm());
    }
  });
  ExpectSane(r, -1e-6, "spin 0");
  // z_S = R1 - a1 cos θ + g: sinking by |g| lets θ grow by |g| / (a1 sin θ0) at the same energy
  EXPECT_LE(r.theta_max, 0.1 - r.min_gap / (0.003 * std::sin(0.1)) + 1e-12);
  EXPECT_GT(late_theta_max, 0.099);
  EXPECT_LT(max_slip, 1e-6);
  EXPECT_LT(r.max_step_energy_gain, kEnergyRoundOff);
  EXPECT_EQ(r.unconverged_steps, 0);
}

TEST(Spin, SlowSpinIsDrainedByDrillingAndStaysStopped) {
  // spin 1 rad/s: drilling friction (≤ μmgR̄/C ≈ 7.4 rad/s²) stops the vertical spin within
  // ~0.15 s (measured |ω_z| < 1e-6 rad/s from 0.134 s on, at most 5e-11 rad/s after); once stuck
  // it does not restart or reverse.
  TopSetup setup;
  setup.spin = 1.0;
  Simulator sim(TippeTop(setup), Options());
  double stopped_at = -1.0, max_after = 0.0;
  const RunReport r = RunChecked(&sim, Steps(1.0, 1e-4), 1e-6, [&](long k, const StepStatistics&) {
    const double spin = std::abs(VerticalSpin(sim));
    if (stopped_at < 0.0 && spin < 1e-6) stopped_at = k * 1e-4;
    if (stopped_at > 0.0) max_after = std::max(max_after, spin);
  });
  ExpectSane(r, -1e-6, "spin 1");
  ASSERT_GT(stopped_at, 0.0);
  EXPECT_LT(stopped_at, 0.3);
  EXPECT_LT(max_after, 1e-6);
  EXPECT_LT(r.max_step_energy_gain, kEnergyRoundOff);
}

TEST(Spin, VeryFastSpinStaysBounded) {
  // spin 5000 rad/s at Δt = 1e-4 (Δt·|ω| = 0.5): 9 J of spin energy. With the implicit midpoint
  // term no step gains energy (measured largest step gain 0 J, E(t) - E(0) ≤ -1.4e-5 J after the
  // first contact) and the top is gyroscopically stiff (measured θ_max = θ0 = 0.1000 rad).
  TopSetup setup;
  setup.spin = 5000.0;
  Simulator sim(TippeTop(setup), Options());
  const RunReport r = RunChecked(&sim, Steps(1.0, 1e-4));
  ExpectSane(r, -1e-6, "spin 5000");
  EXPECT_LT(r.max_step_energy_gain, 1e-15 * 1e3);
  EXPECT_LE(r.max_energy_above_start, 0.0);
  EXPECT_EQ(r.unconverged_steps, 0);
}


}  // namespace
}  // namespace nonsmooth_sim
