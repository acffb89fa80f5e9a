// Validation of scenes, options and setters: errors name the element, bad input leaves the
// state as it was, and SetFrictionSet changes the law of one contact, one collider or all.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "dynamics_scenes.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"

namespace nonsmooth_sim {
namespace {

using test::Options;

void ExpectRejected(const Scene& scene, const std::string& fragment) {
  try {
    ValidateScene(scene);
    ADD_FAILURE() << "accepted, expected an error naming " << fragment;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
  EXPECT_THROW(Simulator(scene, SimulatorOptions{}), std::invalid_argument);
}

TEST(Validation, SceneErrorsNameTheElement) {
  const Scene good = MakeTippeTopScene();
  EXPECT_NO_THROW(ValidateScene(good));
  Scene s = good;
  s.bodies[0].mass = -1.0;
  ExpectRejected(s, "mass");
  s = good;
  s.bodies[0].mass = std::nan("");
  ExpectRejected(s, "mass");
  s = good;
  s.bodies[0].inertia(2, 2) = -7e-7;
  ExpectRejected(s, "inertia");
  s = good;
  s.bodies[0].inertia(0, 1) = 1e-7;
  ExpectRejected(s, "symmetric");
  s = good;
  s.colliders[kPegSphere].shape.radius = 0.0;
  ExpectRejected(s, "colliders[1] (peg_sphere).shape: radius");
  s = good;
  s.colliders[kBigSphere].law.mu = -0.1;
  ExpectRejected(s, "colliders[0] (big_sphere).law.mu");
  s = good;
  s.colliders[kBigSphere].law.rbar = -1e-4;
  ExpectRejected(s, "colliders[0] (big_sphere).law.rbar");
  s = good;
  s.colliders[kBigSphere].law.restitution = 1.5;
  ExpectRejected(s, "colliders[0] (big_sphere).law.restitution");
  s = good;
  s.colliders[kTippeTopGround].law.restitution = -0.5;  // the ground's law is validated too
  ExpectRejected(s, "colliders[2] (ground).law.restitution");
  s = good;
  s.colliders[kBigSphere].pose.translation().x() = std::nan("");  // was Sphere::center
  ExpectRejected(s, "colliders[0] (big_sphere).pose");
  s = good;
  s.colliders[kBigSphere].body = 3;
  ExpectRejected(s, "colliders[0] (big_sphere).body");
  s = good;
  s.colliders[kPegSphere].name = "big_sphere";
  ExpectRejected(s, "colliders[1] (big_sphere).name");
  s = good;
  s.colliders[kTippeTopGround].body = 0;
  ExpectRejected(s, "colliders[2] (ground).shape");
  s = good;
  s.initial_state.clear();
  ExpectRejected(s, "one per scene body");
  s = good;
  s.initial_state[0].angular_velocity.x() = INFINITY;
  ExpectRejected(s, "angular_velocity");
  s = good;
  s.initial_state[0].orientation.coeffs().setZero();
  ExpectRejected(s, "orientation");
  s = good;
  s.gravity.z() = std::nan("");
  ExpectRejected(s, "gravity");
  s = good;
  s.bodies.clear();
  ExpectRejected(s, "bodies");
}

TEST(Validation, OptionsAndSettersRejectBadInputAndKeepTheState) {
  SimulatorOptions bad;
  bad.time_step = 0.0;
  EXPECT_THROW(ValidateSimulatorOptions(bad), std::invalid_argument);
  bad.time_step = 0.1;
  EXPECT_THROW(ValidateSimulatorOptions(bad), std::invalid_argument);
  bad = SimulatorOptions{};
  bad.solver.relaxation = 2.0;
  EXPECT_THROW(ValidateSimulatorOptions(bad), std::invalid_argument);

  Simulator sim(MakeTippeTopScene(), SimulatorOptions{});
  for (int k = 0; k < 10; ++k) sim.Step();
  const std::vector<BodyState> before = sim.state();
  std::vector<BodyState> nan_state = before;
  nan_state[0].position.z() = std::nan("");
  EXPECT_THROW(sim.SetState(nan_state), std::invalid_argument);
  EXPECT_EQ(sim.state()[0].position, before[0].position);
  SimulatorOptions options = sim.options();
  options.time_step = -1e-4;
  EXPECT_THROW(sim.SetOptions(options), std::invalid_argument);
  EXPECT_EQ(sim.options().time_step, 1e-4);
  // friction sets are addressed by collider or contact name: an unknown one changes nothing
  for (const std::string name : {"no_such_collider", "big_sphere/no_such_collider",
                                 "big_sphere/big_sphere", "big_sphere/", "/ground"}) {
    EXPECT_THROW(sim.SetFrictionSet(FrictionSet::kExact, name), std::invalid_argument) << name;
  }
  EXPECT_THROW(sim.FrictionSetOf("no_such_collider"), std::invalid_argument);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(sim.scene().colliders[static_cast<std::size_t>(i)].law.friction_set,
              MakeTippeTopScene().colliders[static_cast<std::size_t>(i)].law.friction_set);
  }
  EXPECT_EQ(sim.FrictionSetOf("big_sphere/ground"), FrictionSet::kSphere);
  EXPECT_EQ(sim.FrictionSetOf("peg_sphere/ground"), FrictionSet::kSphere);
  ContactLaw law;
  law.mu = -1.0;
  EXPECT_THROW(sim.SetContactLaw(0, law), std::invalid_argument);
  EXPECT_THROW(sim.SetContactLaw(5, ContactLaw{}), std::out_of_range);
  EXPECT_THROW(sim.SetContactLaw(-1, ContactLaw{}), std::out_of_range);
  EXPECT_EQ(sim.scene().colliders[kBigSphere].law.mu, 0.3);
  EXPECT_THROW(sim.SetTime(INFINITY), std::invalid_argument);
}

TEST(Validation, SetFrictionSetChangesTheLawOfOneOrAllContacts) {
  Simulator sim(MakeTippeTopScene(), SimulatorOptions{});
  // one collider by name: its contacts only
  sim.SetFrictionSet(FrictionSet::kCoulomb, "peg_sphere");
  EXPECT_EQ(sim.scene().colliders[kBigSphere].law.friction_set, FrictionSet::kSphere);
  EXPECT_EQ(sim.scene().colliders[kPegSphere].law.friction_set, FrictionSet::kCoulomb);
  EXPECT_EQ(sim.FrictionSetOf("big_sphere/ground"), FrictionSet::kSphere);
  EXPECT_EQ(sim.FrictionSetOf("peg_sphere/ground"), FrictionSet::kCoulomb);
  // one contact by name, in either order: only that contact, the colliders' laws stay
  sim.SetFrictionSet(FrictionSet::kEllipsoid, "ground/big_sphere");
  EXPECT_EQ(sim.FrictionSetOf("big_sphere/ground"), FrictionSet::kEllipsoid);
  EXPECT_EQ(sim.FrictionSetOf("peg_sphere/ground"), FrictionSet::kCoulomb);
  EXPECT_EQ(sim.scene().colliders[kBigSphere].law.friction_set, FrictionSet::kSphere);
  // and the contact uses it once closed (the first step may see the exact-zero gap as open)
  for (int k = 0; k < 10 && !sim.InContact(kBigSphere); ++k) sim.Step();
  const ContactState* big = sim.FindContact(kBigSphere);
  ASSERT_NE(big, nullptr);
  EXPECT_EQ(ContactName(sim.scene(), *big), "big_sphere/ground");
  EXPECT_EQ(big->law.friction_set, FrictionSet::kEllipsoid);
  EXPECT_EQ(big->dimension, 4);
  // all contacts
  sim.SetFrictionSet(FrictionSet::kExact);
  EXPECT_EQ(sim.scene().colliders[kBigSphere].law.friction_set, FrictionSet::kExact);
  EXPECT_EQ(sim.scene().colliders[kPegSphere].law.friction_set, FrictionSet::kExact);
  EXPECT_EQ(sim.FrictionSetOf("big_sphere/ground"), FrictionSet::kExact);
  EXPECT_EQ(sim.FrictionSetOf("peg_sphere/ground"), FrictionSet::kExact);
  // coulomb has no drilling component: the contact's dimension follows the set
  sim.SetFrictionSet(FrictionSet::kCoulomb, "big_sphere");
  sim.Step();
  for (int k = 0; k < 10 && !sim.InContact(kBigSphere); ++k) sim.Step();
  big = sim.FindContact(kBigSphere);
  ASSERT_NE(big, nullptr);
  EXPECT_EQ(big->law.friction_set, FrictionSet::kCoulomb);
  EXPECT_EQ(big->dimension, 3);
}

}  // namespace
}  // namespace nonsmooth_sim
