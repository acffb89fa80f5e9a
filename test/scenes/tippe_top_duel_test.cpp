// Two Tippe-Tops that collide (urdf/tippe_top_duel.urdf, config/tippe_top_duel.yaml;
// docs/scenes.md section 5), and the body–body contact on its own: two free spheres head-on.
//
// The duel: upright, 180 rad/s in opposite senses, 0.1 m/s each towards the other, big spheres
// 10 mm apart. What must hold:
//  - the big spheres touch (a sphere–sphere contact between the two free bodies);
//  - momentum: per step, P_E − P_B = (m1 + m2) g Δt + Σ (impulses of the ground contacts) exactly
//    (the top–top percussion enters both bodies with opposite signs): checked to round-off from the
//    reported percussions and frames;
//  - energy never increases (Runner: with the implicit-midpoint gyroscopic scheme the allowance is
//    the gap-correction lifts only);
//  - no penetration beyond 0.1 mm at any contact, top–top included.
// Δt = 1e-4 s (Δt|ω| = 0.018), implicit midpoint; 2 s cover the approach (~0.08 s), the
// collision and the tops running apart. Measured: first touch at 0.0764 s, 130 steps in contact,
// ΣΛ_N = 5.7e-4 N s; momentum balance ≤ 2e-19 N s per step; afterwards v_x = ∓0.022 m/s (they
// run apart); max penetration 7.6e-6 m (at the top–top contact); no energy gain.
//
// Head-on spheres (built in code, no ground, no gravity, μ = 0): equal masses, ε = 1 exchange
// their velocities, ε = 0 move on together at the mean velocity, momentum conserved to round-off.
// With Newton's law on γ_E + ε γ_B (14) and one contact both are exact in one step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "scene_test_support.h"

namespace nonsmooth_sim {
namespace {

using scene_test::LoadShippedScene;
using scene_test::Runner;

SimulatorOptions DuelOptions() {
  SimulatorOptions options;
  options.time_step = 1e-4;
  options.gyroscopic = GyroscopicScheme::kImplicitMidpoint;
  return options;
}

// The world-frame impulse a contact applies to its body B [N s].
Eigen::Vector3d ImpulseOnB(const ContactState& c) {
  return c.percussion[0] * c.frame.normal + c.percussion[1] * c.frame.tangent1 +
         c.percussion[2] * c.frame.tangent2;
}

Eigen::Vector3d Momentum(const Simulator& sim) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (std::size_t b = 0; b < sim.scene().bodies.size(); ++b) {
    p += sim.scene().bodies[b].mass * sim.state()[b].linear_velocity;
  }
  return p;
}

TEST(TippeTopDuel, CollideWithoutEnergyGainOrPenetration) {
  Simulator sim(LoadShippedScene("tippe_top_duel"), DuelOptions());
  Runner run(&sim);
  const int big1 = FindCollider(sim.scene(), "top1_big_sphere");
  const int big2 = FindCollider(sim.scene(), "top2_big_sphere");
  ASSERT_GE(big1, 0);
  ASSERT_GE(big2, 0);
  const double total_mass = sim.scene().bodies[0].mass + sim.scene().bodies[1].mass;
  const double dt = sim.options().time_step;
  double first_touch = -1.0;
  int touching_steps = 0;
  double top_top_normal = 0.0;  // Σ Λ_N of the top–top contact [N s]
  double worst_balance = 0.0;   // max |ΔP − M g Δt − Σ ground impulses| [N s]
  double max_top_top_penetration = 0.0;
  while (sim.time() < 2.0 && run.finite()) {
    const Eigen::Vector3d before = Momentum(sim);
    const StepStatistics& stats = run.Step();
    (void)stats;
    Eigen::Vector3d ground = Eigen::Vector3d::Zero();
    for (const ContactState& c : sim.contacts()) {
      const bool top_top = (c.collider_a == big1 && c.collider_b == big2) ||
                           (c.collider_a == big2 && c.collider_b == big1);
      if (top_top) {
        if (first_touch < 0.0) first_touch = sim.time();
        ++touching_steps;
        top_top_normal += c.percussion[0];
        max_top_top_penetration = std::max(max_top_top_penetration, -c.gap);
      }
      if (c.body_a == kWorld) ground += ImpulseOnB(c);
    }
    const Eigen::Vector3d balance = Momentum(sim) - before - total_mass * sim.scene().gravity * dt -
                                    ground;
    worst_balance = std::max(worst_balance, balance.norm());
  }
  const BodyState& s1 = sim.state()[0];
  const BodyState& s2 = sim.state()[1];
  std::printf("first touch at %.4f s, %d steps in contact, sum Lambda_N = %.3e N s; momentum "
              "balance <= %.2e N s; v_x after: %+.4f %+.4f m/s; max penetration %.2e m (top-top "
              "%.2e); energy excess <= %.2e J; gap-correction energy %.2e J\n",
              first_touch, touching_steps, top_top_normal, worst_balance,
              s1.linear_velocity.x(), s2.linear_velocity.x(), run.max_penetration(),
              max_top_top_penetration, run.max_energy_excess(), run.gap_correction_energy());
  EXPECT_GT(first_touch, 0.0) << "the big spheres never touched";
  EXPECT_GT(top_top_normal, 0.0);
  // only the ground's impulses (and gravity) change the pair's momentum: round-off of m v ~ 6e-4
  EXPECT_LT(worst_balance, 1e-15);
  // the exchange is visible: each top was pushed back by the other (approach speeds 0.1 m/s)
  EXPECT_LT(s1.linear_velocity.x(), 0.05);
  EXPECT_GT(s2.linear_velocity.x(), -0.05);
  EXPECT_LT(run.max_penetration(), 1e-4);
  EXPECT_LE(run.max_energy_excess(), 0.0) << "at t = " << run.max_energy_excess_time();
  EXPECT_TRUE(run.finite());
}

// Two equal free spheres, frictionless, head-on along x (no ground, no gravity).
Scene TwoSpheres(double restitution, double v1, double v2) {
  Scene scene;
  scene.gravity.setZero();
  ContactLaw law;
  law.mu = 0.0;
  law.restitution = restitution;
  for (int k = 0; k < 2; ++k) {
    RigidBody body;
    body.name = k == 0 ? "left" : "right";
    body.mass = 0.01;
    body.inertia = Eigen::Matrix3d::Identity() * 0.4 * 0.01 * 0.01 * 0.01;  // 2/5 m r², r = 1 cm
    scene.bodies.push_back(body);
    Collider c;
    c.name = body.name + "_sphere";
    c.body = k;
    c.shape = Shape::Sphere(0.01);
    c.law = law;
    scene.colliders.push_back(c);
    BodyState s;
    s.position = Eigen::Vector3d(k == 0 ? -0.0105 : 0.0105, 0.0, 0.0);  // 1 mm apart
    s.linear_velocity = Eigen::Vector3d(k == 0 ? v1 : v2, 0.0, 0.0);
    scene.initial_state.push_back(s);
  }
  return scene;
}

struct HeadOn {
  double v1 = 0.0, v2 = 0.0;
  double momentum_error = 0.0;  // max |P(t) − P0| [N s]
  double max_energy_excess = 0.0;
};

HeadOn RunHeadOn(double restitution, double v1, double v2) {
  SimulatorOptions options;
  options.time_step = 1e-4;
  Simulator sim(TwoSpheres(restitution, v1, v2), options);
  Runner run(&sim);
  const Eigen::Vector3d p0 = Momentum(sim);
  HeadOn r;
  while (sim.time() < 0.05 && run.finite()) {
    run.Step();
    r.momentum_error = std::max(r.momentum_error, (Momentum(sim) - p0).norm());
  }
  r.v1 = sim.state()[0].linear_velocity.x();
  r.v2 = sim.state()[1].linear_velocity.x();
  r.max_energy_excess = run.max_energy_excess();
  return r;
}

// ε = 1: (v1, v2) = (0.1, −0.05) → (−0.05, 0.1) (measured to 1e-17 m/s).
TEST(SphereSphere, ElasticHeadOnExchangesVelocities) {
  const HeadOn r = RunHeadOn(1.0, 0.1, -0.05);
  EXPECT_NEAR(r.v1, -0.05, 1e-15);
  EXPECT_NEAR(r.v2, 0.1, 1e-15);
  EXPECT_LT(r.momentum_error, 1e-18);
  EXPECT_LE(r.max_energy_excess, 0.0);
}

// ε = 0: both move on at the mean velocity 0.025 m/s and stay in contact (no rebound).
TEST(SphereSphere, InelasticHeadOnMovesTogether) {
  const HeadOn r = RunHeadOn(0.0, 0.1, -0.05);
  EXPECT_NEAR(r.v1, 0.025, 1e-15);
  EXPECT_NEAR(r.v2, 0.025, 1e-15);
  EXPECT_LT(r.momentum_error, 1e-18);
  EXPECT_LE(r.max_energy_excess, 0.0);
}

}  // namespace
}  // namespace nonsmooth_sim
