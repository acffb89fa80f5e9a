// Simulator::SetExternalWrench (simulator_world_support.h): the closed-form accelerations on a
// frictionless plane, momenta changed by the impulse on a free body, static and sliding friction
// against a pushed box, and a wrench on one body leaves the others bit-identical.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "nonsmooth_sim/core/constants.h"
#include "simulator_world_support.h"

namespace nonsmooth_sim {
namespace {

using test::AddGround;
using test::SphereCollider;
using simulator_world_support::Model;
using simulator_world_support::StateDifference;
using simulator_world_support::TopA;
using simulator_world_support::TopB;
using simulator_world_support::World;

// --- external wrench

// A sphere of radius r and mass m resting on the ground (gravity on), law `law`.
Scene SphereOnGround(const ContactLaw& law, const Eigen::Quaterniond& orientation) {
  Scene scene;
  RigidBody ball;
  ball.name = "ball";
  ball.mass = 0.5;
  ball.inertia = Eigen::Matrix3d::Identity() * (0.4 * 0.5 * 0.05 * 0.05);
  scene.bodies = {ball};
  scene.colliders = {SphereCollider("ball", 0, Eigen::Vector3d::Zero(), 0.05, law)};
  AddGround(&scene);
  BodyState state;
  state.position = Eigen::Vector3d(0.0, 0.0, 0.05);
  state.orientation = orientation;
  scene.initial_state = {state};
  return scene;
}

ContactLaw Frictionless() {
  ContactLaw law;
  law.mu = 0.0;
  law.friction_set = FrictionSet::kCoulomb;
  return law;
}

const Eigen::Quaterniond kTilted(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()));

class ExternalWrenchTest : public ::testing::TestWithParam<GyroscopicScheme> {};

TEST_P(ExternalWrenchTest, HorizontalForceOnAFrictionlessPlaneGivesFOverM) {
  SimulatorOptions options;
  options.time_step = 1e-3;
  options.gyroscopic = GetParam();
  Simulator sim(SphereOnGround(Frictionless(), kTilted), options);
  const double m = 0.5;
  const Eigen::Vector3d force(2.0, -1.0, 0.0);
  sim.SetExternalWrench(0, force, Eigen::Vector3d::Zero());
  EXPECT_EQ(sim.ExternalWrench(0).first, force);
  EXPECT_EQ(sim.ExternalWrench(0).second, Eigen::Vector3d::Zero());
  const int n = 1000;
  for (int k = 0; k < n; ++k) {
    const StepStatistics stats = sim.Step();
    ASSERT_EQ(stats.closed_contacts, 1) << k;  // resting on the ground all along
  }
  const double t = n * options.time_step;
  const BodyState& s = sim.state()[0];
  const Eigen::Vector3d v = force / m * t;
  EXPECT_NEAR(s.linear_velocity.x(), v.x(), 1e-9 * v.norm());
  EXPECT_NEAR(s.linear_velocity.y(), v.y(), 1e-9 * v.norm());
  EXPECT_NEAR(s.linear_velocity.z(), 0.0, 1e-12);
  // the midpoint rule integrates a constant acceleration exactly: x = ½ a t²
  const Eigen::Vector3d x = 0.5 * force / m * t * t;
  EXPECT_NEAR(s.position.x(), x.x(), 1e-9 * x.norm());
  EXPECT_NEAR(s.position.y(), x.y(), 1e-9 * x.norm());
  EXPECT_NEAR(s.position.z(), 0.05, 1e-12);
  EXPECT_NEAR(s.angular_velocity.norm(), 0.0, 1e-12);  // frictionless: no torque
  // cleared: no further acceleration, the velocity kept to the bit
  sim.SetExternalWrench(0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  EXPECT_EQ(sim.ExternalWrench(0).first, Eigen::Vector3d::Zero());
  const Eigen::Vector3d kept = s.linear_velocity;
  for (int k = 0; k < n; ++k) sim.Step();
  EXPECT_EQ(sim.state()[0].linear_velocity.x(), kept.x());
  EXPECT_EQ(sim.state()[0].linear_velocity.y(), kept.y());
  EXPECT_NEAR(sim.state()[0].linear_velocity.z(), 0.0, 1e-12);
}

TEST_P(ExternalWrenchTest, VerticalTorqueOnAFrictionlessPlaneGivesTauOverI) {
  // a tilted sphere (its body axes are not the world's: the torque is turned into them)
  SimulatorOptions options;
  options.time_step = 1e-3;
  options.gyroscopic = GetParam();
  Simulator sim(SphereOnGround(Frictionless(), kTilted), options);
  const double inertia = 0.4 * 0.5 * 0.05 * 0.05;
  const Eigen::Vector3d torque(0.0, 0.0, 0.01);
  sim.SetExternalWrench(0, Eigen::Vector3d::Zero(), torque);
  const int n = 1000;
  for (int k = 0; k < n; ++k) {
    const StepStatistics stats = sim.Step();
    ASSERT_EQ(stats.closed_contacts, 1) << k;
  }
  const double t = n * options.time_step;
  const BodyState& s = sim.state()[0];
  const Eigen::Vector3d omega_world = s.orientation * s.angular_velocity;
  const double expected = torque.z() / inertia * t;
  EXPECT_NEAR(omega_world.z(), expected, 1e-9 * expected);
  EXPECT_NEAR(omega_world.x(), 0.0, 1e-9 * expected);
  EXPECT_NEAR(omega_world.y(), 0.0, 1e-9 * expected);
  EXPECT_NEAR(s.linear_velocity.norm(), 0.0, 1e-12);
  EXPECT_NEAR(s.position.z(), 0.05, 1e-12);
  // the angle turned about z: ½ (τ/I) t², up to the first-order quaternion update's O((Δt ω)³)
  // per step
  const Eigen::Quaterniond turned = s.orientation * kTilted.conjugate();
  const Eigen::AngleAxisd axis_angle(turned);
  const double angle = 0.5 * torque.z() / inertia * t * t;
  EXPECT_NEAR(std::remainder(axis_angle.angle() * axis_angle.axis().z() - angle, 2.0 * kPi), 0.0,
              1e-3 * angle);
  sim.SetExternalWrench(0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  const Eigen::Vector3d kept = s.orientation * s.angular_velocity;
  for (int k = 0; k < n; ++k) sim.Step();
  EXPECT_NEAR((sim.state()[0].orientation * sim.state()[0].angular_velocity - kept).norm(), 0.0,
              1e-12 * kept.norm());
}

// An asymmetric body without contact or gravity, spinning up under a constant wrench for 1 s at
// Δt: the error of its world angular momentum against L0 + τ t [N m s], and of its linear momentum
// against F t [N s].
std::pair<double, double> FreeBodyMomentumErrors(GyroscopicScheme scheme, double dt) {
  Scene scene;
  RigidBody body;
  body.name = "brick";
  body.mass = 0.5;
  body.inertia = Eigen::Vector3d(2e-3, 3e-3, 4e-3).asDiagonal();
  scene.bodies = {body};
  scene.gravity.setZero();
  BodyState state;
  state.orientation = kTilted;
  state.angular_velocity = Eigen::Vector3d(1.0, -2.0, 0.5);
  scene.initial_state = {state};
  SimulatorOptions options;
  options.time_step = dt;
  options.gyroscopic = scheme;
  Simulator sim(scene, options);
  const Eigen::Vector3d force(0.3, 0.1, -0.2);
  const Eigen::Vector3d torque(0.02, -0.01, 0.03);
  sim.SetExternalWrench(0, force, torque);
  const int n = static_cast<int>(std::lround(1.0 / dt));
  for (int k = 0; k < n; ++k) sim.Step();
  const double t = n * dt;
  auto world_momentum = [&body](const BodyState& s) {
    return Eigen::Vector3d(s.orientation * (body.inertia * s.angular_velocity));
  };
  const BodyState& end = sim.state()[0];
  return {(world_momentum(end) - world_momentum(state) - torque * t).norm(),
          (body.mass * end.linear_velocity - force * t).norm()};
}

TEST_P(ExternalWrenchTest, WrenchOnAFreeBodyChangesItsMomentaByTheImpulse) {
  // |τ t| = 0.037 N m s, the body spins up from 2.3 to 19 rad/s. Measured (2026-12-02) at
  // Δt = 1e-4: 9.4e-6 (explicit: the explicit gyroscopic term at ω_B is first order in the
  // torque's spin-up) and 1.1e-9 (implicit midpoint: second order, with the torque turned into
  // body axes at the midpoint; at the step's start it would be 4.0e-6, first order); the torque
  // in wrong axes would be off by O(|τ t|).
  const double tau_t = Eigen::Vector3d(0.02, -0.01, 0.03).norm();
  const auto [coarse, coarse_linear] = FreeBodyMomentumErrors(GetParam(), 1e-4);
  const auto [fine, fine_linear] = FreeBodyMomentumErrors(GetParam(), 5e-5);
  EXPECT_LT(coarse_linear, 1e-12);
  EXPECT_LT(fine_linear, 1e-12);
  if (GetParam() == GyroscopicScheme::kExplicit) {
    EXPECT_LT(coarse, 1e-3 * tau_t);
    EXPECT_NEAR(coarse / fine, 2.0, 0.2);  // first order
  } else {
    EXPECT_LT(coarse, 1e-7 * tau_t);
    EXPECT_NEAR(coarse / fine, 4.0, 0.4);  // second order
  }
}

INSTANTIATE_TEST_SUITE_P(Schemes, ExternalWrenchTest,
                         ::testing::Values(GyroscopicScheme::kExplicit,
                                           GyroscopicScheme::kImplicitMidpoint),
                         [](const ::testing::TestParamInfo<GyroscopicScheme>& info) {
                           return std::string(GyroscopicSchemeName(info.param));
                         });

// A 1 kg box of half extents (0.1, 0.1, 0.05) resting on a face on the ground, law (μ, coulomb).
Scene BoxOnGround(double mu) {
  Scene scene;
  RigidBody box;
  box.name = "box";
  box.mass = 1.0;
  const Eigen::Vector3d h(0.1, 0.1, 0.05);
  box.inertia = Eigen::Vector3d(h.y() * h.y() + h.z() * h.z(), h.x() * h.x() + h.z() * h.z(),
                                h.x() * h.x() + h.y() * h.y())
                    .asDiagonal() *
                (box.mass / 3.0);
  scene.bodies = {box};
  ContactLaw law;
  law.mu = mu;
  law.friction_set = FrictionSet::kCoulomb;
  Collider collider;
  collider.name = "box";
  collider.body = 0;
  collider.shape = Shape::Box(h);
  collider.law = law;
  scene.colliders = {collider};
  AddGround(&scene);
  BodyState state;
  state.position = Eigen::Vector3d(0.0, 0.0, h.z());
  scene.initial_state = {state};
  return scene;
}

SimulatorOptions Converged(double dt) {
  SimulatorOptions options;
  options.time_step = dt;
  options.solver.tolerance_rel = 1e-12;
  options.solver.tolerance_abs = 1e-20;
  options.solver.max_iterations = kMaxSimulatorIterations;
  return options;
}

TEST(ExternalWrench, ForceBelowStaticFrictionKeepsABoxAtRest) {
  const double mu = 0.5;
  const double g = 9.81;
  Simulator sim(BoxOnGround(mu), Converged(1e-3));
  // 0.8 μ m g horizontally through S (the tipping moment F h_S = 0.8·0.5·g·0.05 stays below
  // m g·0.1)
  sim.SetExternalWrench(0, Eigen::Vector3d(0.8 * mu * g * 0.6, 0.8 * mu * g * 0.8, 0.0),
                        Eigen::Vector3d::Zero());
  double worst = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const StepStatistics stats = sim.Step();
    ASSERT_GE(stats.closed_contacts, 3) << k;
    const BodyState& s = sim.state()[0];
    worst = std::max({worst, s.linear_velocity.norm(), s.angular_velocity.norm()});
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(sim.state()[0].position.head<2>().norm(), 1e-12);
}

TEST(ExternalWrench, ForceAboveSlidingFrictionAcceleratesByTheExcess) {
  // F = 2 μ m g along x: a = (F - μ m g)/m = μ g
  const double mu = 0.5;
  const double g = 9.81;
  const double dt = 1e-3;
  Simulator sim(BoxOnGround(mu), Converged(dt));
  sim.SetExternalWrench(0, Eigen::Vector3d(2.0 * mu * g, 0.0, 0.0), Eigen::Vector3d::Zero());
  const int n = 500;
  for (int k = 0; k < n; ++k) sim.Step();
  const BodyState& s = sim.state()[0];
  EXPECT_NEAR(s.linear_velocity.x(), mu * g * n * dt, 1e-6 * mu * g * n * dt);
  EXPECT_NEAR(s.linear_velocity.y(), 0.0, 1e-12);
  EXPECT_NEAR(s.linear_velocity.z(), 0.0, 1e-9);
}

TEST(ExternalWrench, AWrenchOnOneBodyLeavesTheOthersBitIdentical) {
  // A pushed sideways and twisted; B, 1 m away, steps as in a world of its own. A zero wrench is
  // no wrench: C's world, with a wrench set and cleared, steps as if never set.
  const Model a = TopA(), b = TopB();
  Simulator w(World({&a, &b}, false), SimulatorOptions{});
  Simulator alone_b(World({&b}, false), SimulatorOptions{});
  Simulator cleared(World({&b}, false), SimulatorOptions{});
  w.SetExternalWrench(0, Eigen::Vector3d(0.01, 0.0, 0.0), Eigen::Vector3d(0.0, 0.0, 1e-5));
  cleared.SetExternalWrench(0, Eigen::Vector3d(0.01, 0.0, 0.0), Eigen::Vector3d(0.0, 0.0, 1e-5));
  cleared.SetExternalWrench(0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  Simulator unpushed_a(World({&a}, false), SimulatorOptions{});
  bool a_differs = false;
  for (int k = 0; k < 2000; ++k) {
    w.Step();
    alone_b.Step();
    cleared.Step();
    unpushed_a.Step();
    ASSERT_EQ(StateDifference(w.state()[1], alone_b.state()[0]), "") << "step " << k;
    ASSERT_EQ(StateDifference(cleared.state()[0], alone_b.state()[0]), "") << "step " << k;
    a_differs = a_differs || StateDifference(w.state()[0], unpushed_a.state()[0]) != "";
  }
  EXPECT_TRUE(a_differs);
  // the wrench follows its body through a removal of a body before it
  Simulator w2(World({&b, &a}, false), SimulatorOptions{});
  w2.SetExternalWrench(1, Eigen::Vector3d(0.01, 0.0, 0.0), Eigen::Vector3d(0.0, 0.0, 1e-5));
  w2.RemoveBodies({0});
  EXPECT_EQ(w2.ExternalWrench(0).first, Eigen::Vector3d(0.01, 0.0, 0.0));
  EXPECT_EQ(w2.ExternalWrench(0).second, Eigen::Vector3d(0.0, 0.0, 1e-5));
  // and a body added has none
  EXPECT_EQ(w2.AddBodies(b.scene, {b.state}), 1);
  EXPECT_EQ(w2.ExternalWrench(1).first, Eigen::Vector3d::Zero());
  EXPECT_EQ(w2.ExternalWrench(1).second, Eigen::Vector3d::Zero());
}

}  // namespace
}  // namespace nonsmooth_sim
