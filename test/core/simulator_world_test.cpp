// The world changed between two steps (Simulator::AddBodies, RemoveBodies, SetExternalWrench):
// a world that loses a body steps bit for bit like one that never had it (warm starts, tangent
// frames and friction sets re-keyed), a body added steps like a fresh simulator started with its
// state, an external wrench gives the closed-form accelerations (and nothing when zero), and bad
// input throws with the simulator unchanged. Fixed initial conditions, no timing.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "scene_builders.h"

namespace nonsmooth_sim {
namespace {

using test::AddGround;
using test::SphereCollider;

constexpr double kPi = 3.14159265358979323846;

// --- bit-for-bit comparison

// "" if every coefficient of the two states is equal (==), else the first difference.
std::string StateDifference(const BodyState& a, const BodyState& b) {
  std::ostringstream s;
  s.precision(17);
  auto compare = [&s](const char* what, const Eigen::Ref<const Eigen::VectorXd>& x,
                      const Eigen::Ref<const Eigen::VectorXd>& y) {
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      if (x[i] != y[i] && s.tellp() == 0) {
        s << what << "[" << i << "]: " << x[i] << " != " << y[i];
      }
    }
  };
  compare("position", a.position, b.position);
  compare("orientation", a.orientation.coeffs(), b.orientation.coeffs());
  compare("linear_velocity", a.linear_velocity, b.linear_velocity);
  compare("angular_velocity", a.angular_velocity, b.angular_velocity);
  return s.str();
}

// The contact reports of two simulators, where a may have more than b: `collider_map` /
// `body_map` take b's indices to a's, and a's contacts between colliders b has (in their image)
// must be b's, in order, in every field.
std::string ContactsDifference(const Simulator& a, const Simulator& b,
                               const std::vector<int>& collider_map,
                               const std::vector<int>& body_map) {
  std::ostringstream s;
  auto in_b = [&collider_map](int collider) {
    return std::find(collider_map.begin(), collider_map.end(), collider) != collider_map.end();
  };
  std::vector<ContactState> of_b;
  for (const ContactState& x : a.contacts()) {
    if (in_b(x.collider_a) && in_b(x.collider_b)) of_b.push_back(x);
  }
  if (of_b.size() != b.contacts().size()) {
    s << of_b.size() << " contacts != " << b.contacts().size();
    return s.str();
  }
  auto body = [&body_map](int x) { return x == kWorld ? kWorld : body_map.at(x); };
  for (std::size_t i = 0; i < of_b.size(); ++i) {
    const ContactState& x = of_b[i];
    const ContactState& y = b.contacts()[i];
    if (x.collider_a != collider_map.at(y.collider_a) ||
        x.collider_b != collider_map.at(y.collider_b) || x.body_a != body(y.body_a) ||
        x.body_b != body(y.body_b) || x.feature != y.feature || x.gap != y.gap ||
        x.percussion != y.percussion || x.frame.tangent1 != y.frame.tangent1 ||
        x.relative_velocity != y.relative_velocity ||
        ContactName(a.scene(), x) != ContactName(b.scene(), y)) {
      s << "contact " << i << " differs (" << ContactName(a.scene(), x) << " vs "
        << ContactName(b.scene(), y) << ")";
      return s.str();
    }
  }
  return "";
}

// The statistics a step reports (its work: iterations show the warm start).
std::string StatisticsDifference(const StepStatistics& a, const StepStatistics& b) {
  std::ostringstream s;
  if (a.solver.iterations != b.solver.iterations) {
    s << "iterations " << a.solver.iterations << " != " << b.solver.iterations;
  } else if (a.closed_contacts != b.closed_contacts) {
    s << "closed contacts " << a.closed_contacts << " != " << b.closed_contacts;
  } else if (a.gap_correction != b.gap_correction) {
    s << "gap correction " << a.gap_correction << " != " << b.gap_correction;
  }
  return s.str();
}

// --- scenes

// A Tippe-Top as a model: body "top_<tag>", colliders "<tag>_big", "<tag>_peg" (no ground), and
// its start state shifted by `x` along the world x axis.
struct Model {
  Scene scene;
  BodyState state;
};
Model TippeTopModel(const std::string& tag, double inclination, double spin, double x,
                    FrictionSet set = FrictionSet::kSphere) {
  TippeTopParameters parameters;
  parameters.friction_set = set;
  TippeTopInitialConditions initial;
  initial.inclination = inclination;
  initial.spin = spin;
  const Scene top = MakeTippeTopScene(parameters, initial);
  Model model;
  model.scene.bodies = top.bodies;
  model.scene.bodies[0].name = "top_" + tag;
  for (Collider collider : top.colliders) {
    if (collider.body == kWorld) continue;
    collider.name = tag + (collider.name == "big_sphere" ? "_big" : "_peg");
    model.scene.colliders.push_back(collider);
  }
  model.state = top.initial_state[0];
  model.state.position.x() += x;
  model.scene.initial_state = {model.state};
  return model;
}

// The models' bodies and colliders in order, the ground first or last.
Scene World(const std::vector<const Model*>& models, bool ground_first) {
  Scene scene;
  if (ground_first) AddGround(&scene);
  for (const Model* model : models) {
    const int offset = static_cast<int>(scene.bodies.size());
    for (const RigidBody& body : model->scene.bodies) scene.bodies.push_back(body);
    for (Collider collider : model->scene.colliders) {
      if (collider.body != kWorld) collider.body += offset;
      scene.colliders.push_back(collider);
    }
    scene.initial_state.push_back(model->state);
  }
  if (!ground_first) AddGround(&scene);
  return scene;
}

// Two tops 1 m apart, different enough to tell apart: A tilted 0.1 rad spinning at 180 rad/s at
// the origin (it inverts), B tilted 0.3 rad at 150 rad/s.
Model TopA(FrictionSet set = FrictionSet::kSphere) {
  return TippeTopModel("a", 0.1, 180.0, 0.0, set);
}
Model TopB(FrictionSet set = FrictionSet::kSphere) {
  return TippeTopModel("b", 0.3, 150.0, 1.0, set);
}

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
