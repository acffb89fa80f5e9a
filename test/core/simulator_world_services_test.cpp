// Simulator::AddBodies and RemoveBodies as the world's services use them
// (simulator_world_support.h): a removed top that touched the other leaves it on the ground, an
// emptied world steps and takes bodies again, and bad input throws with the simulator unchanged.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "simulator_world_support.h"

namespace nonsmooth_sim {
namespace {

using test::SphereCollider;
using simulator_world_support::ContactsDifference;
using simulator_world_support::Model;
using simulator_world_support::StateDifference;
using simulator_world_support::StatisticsDifference;
using simulator_world_support::TippeTopModel;
using simulator_world_support::TopA;
using simulator_world_support::TopB;
using simulator_world_support::World;

TEST(WorldServices, RemovingATopThatTouchesTheOtherKeepsTheRestOnTheGround) {
  // B rolls into A (big spheres of 15 mm radius, 40 mm apart, B at 0.2 m/s towards A); A is
  // removed right after a step with a closed A/B contact
  const Model a = TippeTopModel("a", 0.1, 180.0, 0.0);
  Model b = TippeTopModel("b", 0.2, 120.0, 0.04);
  b.state.linear_velocity.x() = -0.2;
  Simulator sim(World({&a, &b}, /*ground_first=*/false), SimulatorOptions{});
  int touching_step = -1;
  for (int k = 0; k < 5000 && touching_step < 0; ++k) {
    sim.Step();
    for (const ContactState& contact : sim.contacts()) {
      if (contact.body_a >= 0) touching_step = k;
    }
  }
  ASSERT_GE(touching_step, 0) << "the tops never touched";
  sim.RemoveBodies({0});
  ASSERT_EQ(sim.scene().bodies.size(), 1u);
  EXPECT_EQ(sim.scene().bodies[0].name, "top_b");
  ASSERT_EQ(sim.scene().colliders.size(), 3u);
  EXPECT_EQ(sim.scene().colliders[0].name, "b_big");
  EXPECT_EQ(sim.scene().colliders[2].name, "ground");
  // the report keeps B's contacts with the ground, re-indexed, and drops the one with A
  for (const ContactState& contact : sim.contacts()) {
    EXPECT_EQ(contact.body_a, kWorld);
    EXPECT_EQ(contact.body_b, 0);
    EXPECT_EQ(contact.collider_a, 2);
    EXPECT_LT(contact.collider_b, 2);
    EXPECT_EQ(ContactName(sim.scene(), contact).substr(0, 2), "b_");
  }
  // it stays on the ground: its lowest point within 10 µm of the floor in every step, its contacts
  // closed in nearly every step (a rolling contact opens for single steps at g(q_M) > 0 by
  // O(Δt²): dev-notes, open end 4)
  int steps_on_ground = 0;
  double highest = -1.0, deepest = 1.0;
  for (int k = 0; k < 3000; ++k) {
    const StepStatistics stats = sim.Step();
    ASSERT_TRUE(stats.state_finite) << k;
    for (const ContactState& contact : sim.contacts()) {
      ASSERT_EQ(contact.body_a, kWorld);
      ASSERT_EQ(contact.collider_a, 2);
    }
    if (sim.InContact(0) || sim.InContact(1)) ++steps_on_ground;
    const double gap = test::MinGroundGap(sim.scene(), sim.state());
    highest = std::max(highest, gap);
    deepest = std::min(deepest, gap);
  }
  EXPECT_GT(steps_on_ground, 2700);
  EXPECT_LT(highest, 1e-5);
  EXPECT_GT(deepest, -1e-5);
}

TEST(WorldServices, AnEmptiedWorldStepsAndTakesBodiesAgain) {
  const Model a = TopA();
  Simulator sim(World({&a}, /*ground_first=*/true), SimulatorOptions{});
  for (int k = 0; k < 100; ++k) sim.Step();
  sim.RemoveBodies({0});
  EXPECT_TRUE(sim.scene().bodies.empty());
  ASSERT_EQ(sim.scene().colliders.size(), 1u);  // the ground stays
  EXPECT_TRUE(sim.contacts().empty());
  const double time = sim.time();
  const StepStatistics stats = sim.Step();
  EXPECT_TRUE(stats.state_finite);
  EXPECT_EQ(stats.closed_contacts, 0);
  EXPECT_EQ(sim.time(), time + sim.options().time_step);
  // a static collider alone can be added to an empty world (a second plane would do as well)
  Scene wall;
  wall.colliders.push_back(
      SphereCollider("boulder", kWorld, Eigen::Vector3d(5.0, 0.0, 0.5), 0.5, GroundLaw()));
  EXPECT_EQ(sim.AddBodies(wall, {}), 0);
  // the top again: it steps like a fresh simulator of the same layout
  EXPECT_EQ(sim.AddBodies(a.scene, {a.state}), 0);
  Scene layout = World({&a}, true);
  layout.colliders.insert(layout.colliders.begin() + 1, wall.colliders[0]);
  Simulator fresh(layout, SimulatorOptions{});
  for (int k = 0; k < 2000; ++k) {
    sim.Step();
    fresh.Step();
    ASSERT_EQ(StateDifference(sim.state()[0], fresh.state()[0]), "") << "step " << k;
  }
}

// --- bad input: throws, nothing changes

TEST(WorldServices, BadInputThrowsAndChangesNothing) {
  const Model a = TopA(), b = TopB();
  const Scene scene = World({&a, &b}, false);
  Simulator sim(scene, SimulatorOptions{});
  Simulator twin(scene, SimulatorOptions{});
  sim.SetExternalWrench(1, Eigen::Vector3d(0.0, 1e-3, 0.0), Eigen::Vector3d::Zero());
  twin.SetExternalWrench(1, Eigen::Vector3d(0.0, 1e-3, 0.0), Eigen::Vector3d::Zero());
  sim.SetFrictionSet(FrictionSet::kExact, "b_big/ground");
  twin.SetFrictionSet(FrictionSet::kExact, "b_big/ground");
  for (int k = 0; k < 300; ++k) {
    sim.Step();
    twin.Step();
  }
  const Model c = TippeTopModel("c", 0.2, 100.0, -1.0);
  auto expect_unchanged = [&](const std::string& what) {
    SCOPED_TRACE(what);
    ASSERT_EQ(sim.scene().bodies.size(), 2u);
    ASSERT_EQ(sim.scene().colliders.size(), 5u);
    ASSERT_EQ(sim.state().size(), 2u);
    for (std::size_t i = 0; i < 5; ++i) {
      EXPECT_EQ(sim.scene().colliders[i].name, twin.scene().colliders[i].name);
    }
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_EQ(StateDifference(sim.state()[i], twin.state()[i]), "");
      EXPECT_EQ(sim.ExternalWrench(static_cast<int>(i)), twin.ExternalWrench(static_cast<int>(i)));
    }
    EXPECT_EQ(sim.time(), twin.time());
    EXPECT_EQ(ContactsDifference(sim, twin, {0, 1, 2, 3, 4}, {0, 1}), "");
    EXPECT_EQ(sim.FrictionSetOf("b_big/ground"), FrictionSet::kExact);
  };
  {
    Model dup = c;
    dup.scene.colliders[0].name = "a_big";  // a collider name already used
    EXPECT_THROW(sim.AddBodies(dup.scene, {dup.state}), std::invalid_argument);
    expect_unchanged("duplicate collider name");
  }
  {
    Model dup = c;
    dup.scene.colliders[1].name = dup.scene.colliders[0].name;  // twice within the model
    EXPECT_THROW(sim.AddBodies(dup.scene, {dup.state}), std::invalid_argument);
    expect_unchanged("duplicate collider name in the model");
  }
  {
    Model dup = c;
    dup.scene.bodies[0].name = "top_b";
    EXPECT_THROW(sim.AddBodies(dup.scene, {dup.state}), std::invalid_argument);
    expect_unchanged("duplicate body name");
  }
  {
    Model bad = c;
    bad.scene.bodies[0].inertia(0, 0) = -1e-7;
    EXPECT_THROW(sim.AddBodies(bad.scene, {bad.state}), std::invalid_argument);
    expect_unchanged("bad inertia");
  }
  {
    Model bad = c;
    bad.scene.bodies[0].mass = 0.0;
    EXPECT_THROW(sim.AddBodies(bad.scene, {bad.state}), std::invalid_argument);
    expect_unchanged("zero mass");
  }
  {
    EXPECT_THROW(sim.AddBodies(c.scene, {}), std::invalid_argument);
    EXPECT_THROW(sim.AddBodies(c.scene, {c.state, c.state}), std::invalid_argument);
    expect_unchanged("state of the wrong size");
  }
  {
    BodyState nan = c.state;
    nan.linear_velocity.x() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(sim.AddBodies(c.scene, {nan}), std::invalid_argument);
    BodyState zero = c.state;
    zero.orientation.coeffs().setZero();
    EXPECT_THROW(sim.AddBodies(c.scene, {zero}), std::invalid_argument);
    expect_unchanged("bad state");
  }
  {
    Model bad = c;
    bad.scene.colliders[1].body = 1;  // the model has one body
    EXPECT_THROW(sim.AddBodies(bad.scene, {bad.state}), std::invalid_argument);
    bad.scene.colliders[1].body = -2;  // shifted by 2 it would name body 0
    EXPECT_THROW(sim.AddBodies(bad.scene, {bad.state}), std::invalid_argument);
    expect_unchanged("collider on a missing model body");
  }
  {
    Model bad = c;
    bad.scene.colliders[0].law.mu = -0.1;
    EXPECT_THROW(sim.AddBodies(bad.scene, {bad.state}), std::invalid_argument);
    bad = c;
    bad.scene.colliders.push_back(GroundPlane());
    bad.scene.colliders.back().name = "floor";
    bad.scene.colliders.back().body = 0;  // a plane on a body
    EXPECT_THROW(sim.AddBodies(bad.scene, {bad.state}), std::invalid_argument);
    expect_unchanged("bad collider");
  }
  {
    EXPECT_THROW(sim.RemoveBodies({2}), std::out_of_range);
    EXPECT_THROW(sim.RemoveBodies({0, -1}), std::out_of_range);
    EXPECT_THROW(sim.RemoveBodies({}, {5}), std::out_of_range);
    EXPECT_THROW(sim.RemoveBodies({0}, {-1}), std::out_of_range);
    EXPECT_THROW(sim.RemoveBodies({1, 1}), std::invalid_argument);
    EXPECT_THROW(sim.RemoveBodies({}, {4, 4}), std::invalid_argument);
    EXPECT_THROW(sim.RemoveBodies({}, {0}), std::invalid_argument);  // on a body
    expect_unchanged("bad removal");
  }
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    EXPECT_THROW(sim.SetExternalWrench(1, Eigen::Vector3d(nan, 0, 0), Eigen::Vector3d::Zero()),
                 std::invalid_argument);
    EXPECT_THROW(sim.SetExternalWrench(1, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, inf, 0)),
                 std::invalid_argument);
    EXPECT_THROW(sim.SetExternalWrench(2, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
                 std::out_of_range);
    EXPECT_THROW(sim.SetExternalWrench(-1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
                 std::out_of_range);
    EXPECT_THROW(sim.ExternalWrench(2), std::out_of_range);
    EXPECT_THROW(sim.ExternalWrench(-1), std::out_of_range);
    expect_unchanged("bad wrench");
  }
  // and the steps that follow are the twin's, bit for bit (warm starts and wrenches intact)
  StepStatistics s, t;
  for (int k = 0; k < 500; ++k) {
    sim.Step(&s);
    twin.Step(&t);
    for (std::size_t i = 0; i < 2; ++i) {
      ASSERT_EQ(StateDifference(sim.state()[i], twin.state()[i]), "") << "step " << k;
    }
    ASSERT_EQ(StatisticsDifference(s, t), "") << "step " << k;
  }
}

}  // namespace
}  // namespace nonsmooth_sim
