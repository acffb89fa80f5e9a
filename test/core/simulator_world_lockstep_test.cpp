// The world changed between two steps, in lockstep with a world built that way
// (simulator_world_support.h): a world that loses a body steps bit for bit like one that never had
// it (warm starts, tangent frames and friction sets re-keyed), a body added steps like a fresh
// simulator started with its state, and setting one top's state leaves the other as if alone.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "simulator_world_support.h"

namespace nonsmooth_sim {
namespace {

using test::SphereCollider;
using simulator_world_support::ContactsDifference;
using simulator_world_support::Model;
using simulator_world_support::StateDifference;
using simulator_world_support::StatisticsDifference;
using simulator_world_support::TopA;
using simulator_world_support::TopB;
using simulator_world_support::World;

struct WorldCase {
  const char* name;
  FrictionSet set;
  GyroscopicScheme gyroscopic;
};
const WorldCase kWorldCases[] = {
    {"sphere_explicit", FrictionSet::kSphere, GyroscopicScheme::kExplicit},
    {"exact_implicit", FrictionSet::kExact, GyroscopicScheme::kImplicitMidpoint},
    {"coulomb_explicit", FrictionSet::kCoulomb, GyroscopicScheme::kExplicit},
};

SimulatorOptions OptionsOf(const WorldCase& c) {
  SimulatorOptions options;  // the default solver tolerance: the warm start changes the bits
  options.gyroscopic = c.gyroscopic;
  return options;
}

class WorldLockstep : public ::testing::TestWithParam<WorldCase> {};

// Before the removal W1 (both tops) and W0 (the one that stays) are bit-identical: their contacts
// form separate islands, each solved alone in the same order. After it W1 is W0 in every bit,
// its contact report and its solver's iterations included (the warm start was carried over); a
// world started at that moment from W0's state (no warm start, no memory of closed contacts)
// is not.
void ExpectRemovalEqualsNeverHadIt(const WorldCase& c, int removed, bool ground_first) {
  const Model a = TopA(c.set), b = TopB(c.set);
  const Model& stays = removed == 0 ? b : a;
  const SimulatorOptions options = OptionsOf(c);
  Simulator w1(World({&a, &b}, ground_first), options);
  Simulator w0(World({&stays}, ground_first), options);
  // a friction set set per contact, on the big sphere's contact (closed all along): another set
  // than the law's, so that losing the entry would change the trajectory
  const FrictionSet pair_set =
      c.set == FrictionSet::kCoulomb ? FrictionSet::kCylinder : FrictionSet::kCoulomb;
  const std::string kept_pair = ground_first ? "ground/" + stays.scene.colliders[0].name
                                             : stays.scene.colliders[0].name + "/ground";
  w1.SetFrictionSet(pair_set, kept_pair);
  w0.SetFrictionSet(pair_set, kept_pair);
  // indices of w0's colliders and body in w1
  const int stays_body = removed == 0 ? 1 : 0;
  std::vector<int> collider_map;
  if (ground_first) collider_map.push_back(0);
  for (int k = 0; k < 2; ++k) collider_map.push_back((ground_first ? 1 : 0) + 2 * stays_body + k);
  if (!ground_first) collider_map.push_back(4);
  const std::vector<int> body_map = {stays_body};

  const int before = 1500;  // both tops spin on the ground, A rising
  const int after = 4000;
  StepStatistics s1, s0;
  for (int k = 0; k < before; ++k) {
    w1.Step(&s1);
    w0.Step(&s0);
    const std::string diff =
        StateDifference(w1.state()[static_cast<std::size_t>(stays_body)], w0.state()[0]);
    ASSERT_EQ(diff, "") << "before the removal, step " << k;
    ASSERT_EQ(ContactsDifference(w1, w0, collider_map, body_map), "") << "step " << k;
  }
  ASSERT_GE(s0.closed_contacts, 1);

  w1.RemoveBodies({removed});
  ASSERT_EQ(w1.scene().bodies.size(), 1u);
  ASSERT_EQ(w1.state().size(), 1u);
  ASSERT_EQ(w1.scene().colliders.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(w1.scene().colliders[i].name, w0.scene().colliders[i].name);
    EXPECT_EQ(w1.scene().colliders[i].body, w0.scene().colliders[i].body);
  }
  EXPECT_EQ(w1.scene().bodies[0].name, stays.scene.bodies[0].name);
  EXPECT_EQ(w1.time(), w0.time());
  EXPECT_EQ(StateDifference(w1.state()[0], w0.state()[0]), "");
  // the report of the last step, re-indexed
  const std::vector<int> identity = {0, 1, 2};
  EXPECT_EQ(ContactsDifference(w1, w0, identity, {0}), "");
  EXPECT_EQ(w1.FrictionSetOf(kept_pair), pair_set);
  for (int collider = 0; collider < 3; ++collider) {
    EXPECT_EQ(w1.InContact(collider), w0.InContact(collider)) << collider;
  }

  // a world started now from the same state, without the warm start: the control
  Scene fresh_scene = w0.scene();
  fresh_scene.initial_state = w0.state();
  Simulator fresh(fresh_scene, options);
  fresh.SetFrictionSet(pair_set, kept_pair);
  bool fresh_differs = false;
  for (int k = 0; k < after; ++k) {
    w1.Step(&s1);
    w0.Step(&s0);
    fresh.Step();
    ASSERT_EQ(StateDifference(w1.state()[0], w0.state()[0]), "") << "after the removal, step " << k;
    ASSERT_EQ(StatisticsDifference(s1, s0), "") << "after the removal, step " << k;
    ASSERT_EQ(ContactsDifference(w1, w0, identity, {0}), "") << "step " << k;
    fresh_differs = fresh_differs || StateDifference(fresh.state()[0], w0.state()[0]) != "";
  }
  EXPECT_GE(s0.closed_contacts, 1);
  // the comparison can tell: without the carried-over memory the bits differ
  EXPECT_TRUE(fresh_differs);
}

TEST_P(WorldLockstep, RemovingTheSecondTopEqualsNeverHavingIt) {
  ExpectRemovalEqualsNeverHadIt(GetParam(), /*removed=*/1, /*ground_first=*/false);
}

TEST_P(WorldLockstep, RemovingTheFirstTopEqualsNeverHavingIt) {
  // the remaining top's colliders move from 2, 3 to 0, 1 and the ground from 4 to 2: every key
  // of the memory is re-keyed
  ExpectRemovalEqualsNeverHadIt(GetParam(), /*removed=*/0, /*ground_first=*/false);
}

TEST_P(WorldLockstep, RemovingTheFirstTopWithTheGroundFirstEqualsNeverHavingIt) {
  ExpectRemovalEqualsNeverHadIt(GetParam(), /*removed=*/0, /*ground_first=*/true);
}

TEST_P(WorldLockstep, RemovingAStaticColliderEqualsNeverHavingIt) {
  // a static sphere "rock" 2 m away, first in the scene (every index shifts by one), removed
  const WorldCase& c = GetParam();
  const Model a = TopA(c.set);
  Scene with_rock = World({&a}, /*ground_first=*/false);
  Collider rock = SphereCollider("rock", kWorld, Eigen::Vector3d(2.0, 0.0, 0.1), 0.1, GroundLaw());
  with_rock.colliders.insert(with_rock.colliders.begin(), rock);
  Simulator w1(with_rock, OptionsOf(c));
  Simulator w0(World({&a}, false), OptionsOf(c));
  for (int k = 0; k < 1000; ++k) {
    w1.Step();
    w0.Step();
    ASSERT_EQ(StateDifference(w1.state()[0], w0.state()[0]), "") << "step " << k;
  }
  EXPECT_THROW(w1.RemoveBodies({}, {1}), std::invalid_argument);  // a collider on the top
  w1.RemoveBodies({}, {0});
  ASSERT_EQ(w1.scene().colliders.size(), 3u);
  EXPECT_EQ(FindCollider(w1.scene(), "rock"), -1);
  EXPECT_EQ(ContactsDifference(w1, w0, {0, 1, 2}, {0}), "");
  StepStatistics s1, s0;
  for (int k = 0; k < 2000; ++k) {
    w1.Step(&s1);
    w0.Step(&s0);
    ASSERT_EQ(StateDifference(w1.state()[0], w0.state()[0]), "") << "step " << k;
    ASSERT_EQ(StatisticsDifference(s1, s0), "") << "step " << k;
  }
}

TEST_P(WorldLockstep, AddedTopStepsLikeAFreshSimulatorAndTheOtherAsIfAlone) {
  const WorldCase& c = GetParam();
  const SimulatorOptions options = OptionsOf(c);
  const Model a = TopA(c.set);
  Model b = TopB(c.set);
  Simulator w1(World({&a}, /*ground_first=*/false), options);
  Simulator w0(World({&a}, false), options);
  const int before = 700;
  for (int k = 0; k < before; ++k) {
    w1.Step();
    w0.Step();
  }
  // B enters with its own state; its model carries another initial_state, which is not used
  b.scene.initial_state[0].position.z() += 1.0;
  const int first = w1.AddBodies(b.scene, {b.state});
  EXPECT_EQ(first, 1);
  ASSERT_EQ(w1.scene().bodies.size(), 2u);
  ASSERT_EQ(w1.scene().colliders.size(), 5u);
  EXPECT_EQ(w1.scene().colliders[3].name, "b_big");  // appended after the ground, in order
  EXPECT_EQ(w1.scene().colliders[3].body, 1);
  EXPECT_EQ(w1.scene().colliders[4].body, 1);
  BodyState normalized = b.state;
  normalized.orientation.normalize();  // as the constructor and SetState do
  EXPECT_EQ(StateDifference(w1.state()[1], normalized), "");
  EXPECT_EQ(w1.time(), w0.time());
  // the last step's report is kept
  EXPECT_EQ(ContactsDifference(w1, w0, {0, 1, 2}, {0}), "");
  // B alone from its state at this moment, its ground last (another collider order than in W1)
  Simulator fresh(World({&b}, false), options);
  StepStatistics s1, s0;
  for (int k = 0; k < 4000; ++k) {
    w1.Step(&s1);
    w0.Step(&s0);
    fresh.Step();
    ASSERT_EQ(StateDifference(w1.state()[0], w0.state()[0]), "") << "A, step " << k;
    ASSERT_EQ(StateDifference(w1.state()[1], fresh.state()[0]), "") << "B, step " << k;
  }
  EXPECT_GE(s1.closed_contacts, 2);
  EXPECT_TRUE(w1.InContact(3) || w1.InContact(4));  // B on the ground
}

TEST_P(WorldLockstep, SettingOneTopsStateLeavesTheOtherAsIfAlone) {
  // SetBodyStates forgets the moved body's contacts only: the other top keeps its warm starts
  // and steps bit for bit as in a world without the first; SetState (every contact forgotten)
  // is the control that the comparison can tell
  const WorldCase& c = GetParam();
  const SimulatorOptions options = OptionsOf(c);
  const Model a = TopA(c.set), b = TopB(c.set);
  Simulator w1(World({&a, &b}, /*ground_first=*/false), options);
  Simulator w0(World({&b}, false), options);
  Simulator control(World({&a, &b}, false), options);
  for (int k = 0; k < 1500; ++k) {
    w1.Step();
    w0.Step();
    control.Step();
  }
  BodyState moved = a.state;
  moved.position.x() -= 0.25;
  moved.orientation.coeffs() *= 2.0;  // normalised by the simulator
  const std::vector<BodyState> before = w1.state();
  EXPECT_THROW(w1.SetBodyStates({0, 0}, {moved, moved}), std::invalid_argument);
  EXPECT_THROW(w1.SetBodyStates({2}, {moved}), std::out_of_range);
  EXPECT_THROW(w1.SetBodyStates({0}, {}), std::invalid_argument);
  BodyState bad = moved;
  bad.linear_velocity.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(w1.SetBodyStates({0}, {bad}), std::invalid_argument);
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(StateDifference(w1.state()[i], before[i]), "");

  w1.SetBodyStates({0}, {moved});
  std::vector<BodyState> all = control.state();
  all[0] = moved;
  control.SetState(all);
  BodyState normalized = moved;
  normalized.orientation.normalize();
  EXPECT_EQ(StateDifference(w1.state()[0], normalized), "");
  EXPECT_EQ(StateDifference(w1.state()[1], w0.state()[0]), "");
  ASSERT_FALSE(w1.contacts().empty());  // B's
  for (const ContactState& contact : w1.contacts()) {  // A's are gone
    EXPECT_NE(contact.body_a, 0);
    EXPECT_NE(contact.body_b, 0);
  }
  bool control_differs = false;
  for (int k = 0; k < 3000; ++k) {
    w1.Step();
    w0.Step();
    control.Step();
    ASSERT_EQ(StateDifference(w1.state()[1], w0.state()[0]), "") << "B, step " << k;
    control_differs = control_differs || StateDifference(control.state()[1], w0.state()[0]) != "";
  }
  EXPECT_TRUE(control_differs);
}

INSTANTIATE_TEST_SUITE_P(Cases, WorldLockstep, ::testing::ValuesIn(kWorldCases),
                         [](const ::testing::TestParamInfo<WorldCase>& info) {
                           return std::string(info.param.name);
                         });

}  // namespace
}  // namespace nonsmooth_sim
