// The world's models and names: a spawned model's parts are "<model>/<part>" everywhere (scene,
// services, frames, topics; Gazebo's "<model>::<link>" accepted as input), the start-up model's
// their URDF names; a refused spawn or delete leaves the world bit for bit as it was; a delete
// renumbers the models that stay.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "world_fixtures.h"

namespace nonsmooth_sim::world {
namespace {

using testing::BallUrdf;
using testing::Load;
using testing::WorldSnapshot;

World BallWorld() {
  WorldConfig config;
  config.model_name = "start";
  return World(Load(BallUrdf(), 9.81, /*ground=*/true), config);
}

Pose At(double x, double y, double z) {
  Pose p;
  p.position = Eigen::Vector3d(x, y, z);
  return p;
}

TEST(ModelRegistry, StartUpModelKeepsUrdfNamesAndSpawnedOnesArePrefixed) {
  World w = BallWorld();
  ASSERT_EQ(w.models().models().size(), 1u);
  EXPECT_EQ(w.models().models()[0].name, "start");
  EXPECT_EQ(w.BodyName(0), "ball");

  const Model& m = w.Spawn("box2", Load(BallUrdf(), 9.81, false).scene, "", At(1, 0, 0.05), "d");
  EXPECT_EQ(m.prefix, "box2/");
  ASSERT_EQ(m.bodies.size(), 1u);
  const int b = m.bodies[0];
  EXPECT_EQ(w.sim().scene().bodies[static_cast<std::size_t>(b)].name, "box2/ball");
  EXPECT_EQ(w.sim().scene().colliders[static_cast<std::size_t>(m.colliders[0])].name,
            "box2/shell");
  EXPECT_EQ(w.BodyName(b), "box2/ball");
  EXPECT_EQ(w.BodyIndex("box2/ball"), b);
  EXPECT_EQ(w.BodyIndex("box2::ball"), b);  // Gazebo's spelling addresses it too
  EXPECT_EQ(w.BodyIndex("ball"), 0);
  EXPECT_EQ(w.BodyIndex("start::ball"), 0);
  // its collision's contact frame and wrench topic carry the same name
  const FrameNames frames = MakeFrameNames(w.sim().scene(), "world");
  ASSERT_EQ(frames.contacts.size(), 2u);
  EXPECT_EQ(frames.contacts[1], "box2/shell_contact");
  EXPECT_EQ(frames.topics[1], "box2/shell");  // ~wrench/box2/shell
  EXPECT_EQ(frames.contacts[0], "shell_contact");
  EXPECT_EQ(frames.topics[0], "shell");
  EXPECT_EQ(w.BodyIndex("box2::nothing"), -1);
  // placed where asked: S of the ball at the spawn pose
  EXPECT_NEAR(w.sim().state()[static_cast<std::size_t>(b)].position.x(), 1.0, 1e-15);
  // the configured start (reset_world) holds it too
  EXPECT_EQ(w.configured_scene().bodies.size(), 2u);
}

TEST(ModelRegistry, RefusedSpawnsLeaveTheWorldAsItWas) {
  World w = BallWorld();
  w.Spawn("one", Load(BallUrdf(), 9.81, false).scene, "", At(1, 0, 0.05), "d");
  w.sim().Step();
  const Scene ball = Load(BallUrdf(), 9.81, false).scene;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    const char* what;
    std::string name;
    std::string reference;
    Pose pose;
  };
  Pose zero_q = At(0, 0, 1);
  zero_q.orientation = Eigen::Quaterniond(0, 0, 0, 0);
  const Case cases[] = {
      {"a name taken", "one", "", At(2, 0, 0.05)},
      {"a name starting with a digit", "1x", "", At(2, 0, 0.05)},
      {"a name with a slash", "a/b", "", At(2, 0, 0.05)},
      {"an empty name", "", "", At(2, 0, 0.05)},
      {"an unknown reference frame", "two", "nobody::ball", At(2, 0, 0.05)},
      {"a NaN position", "two", "", At(nan, 0, 0)},
      {"a position beyond the bound", "two", "", At(2e3, 0, 0)},
      {"a zero quaternion", "two", "", zero_q},
  };
  for (const Case& c : cases) {
    const WorldSnapshot before(w);
    EXPECT_THROW(w.Spawn(c.name, ball, c.reference, c.pose, "d"), std::invalid_argument)
        << c.what;
    before.ExpectSame(WorldSnapshot(w), c.what);
  }
  // an empty model: nothing to spawn
  const WorldSnapshot before(w);
  EXPECT_THROW(w.Spawn("empty", Scene(), "", At(0, 0, 0), "d"), std::invalid_argument);
  before.ExpectSame(WorldSnapshot(w), "an empty model");
}

TEST(ModelRegistry, RefusalsSayWhatWasWrongAndWhatIsAllowed) {
  World w = BallWorld();
  const Scene ball = Load(BallUrdf(), 9.81, false).scene;
  try {
    w.Spawn("9lives", ball, "", At(0, 0, 1), "d");
    FAIL() << "a name starting with a digit was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("9lives"), std::string::npos) << what;
    EXPECT_NE(what.find("letters, digits and '_'"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  try {
    w.Delete("ghost");
    FAIL() << "an unknown model was deleted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "no model \"ghost\"; the models are: start");
  }
}

TEST(ModelRegistry, DeleteRenumbersTheModelsThatStayAndDropsTheirWrenches) {
  World w = BallWorld();
  const Scene ball = Load(BallUrdf(), 0.0, false).scene;
  w.Spawn("a", ball, "", At(1, 0, 0.05), "da");
  w.Spawn("b", ball, "", At(2, 0, 0.05), "db");
  WrenchRequest push;
  push.body = "a::ball";
  push.force = Eigen::Vector3d(1, 0, 0);
  push.duration = -1.0;
  ASSERT_TRUE(w.ApplyWrench(push));
  const BodyState b_before = w.sim().state()[2];

  const WorldSnapshot before(w);
  EXPECT_THROW(w.Delete("c"), std::invalid_argument);
  before.ExpectSame(WorldSnapshot(w), "delete of an unknown model");

  const Model removed = w.Delete("a");
  EXPECT_EQ(removed.description, "da");
  ASSERT_EQ(w.models().models().size(), 2u);
  EXPECT_EQ(w.models().Find("a"), -1);
  const Model& b = w.models().at(w.models().Find("b"));
  ASSERT_EQ(b.bodies.size(), 1u);
  EXPECT_EQ(b.bodies[0], 1);  // was 2
  EXPECT_EQ(w.sim().scene().bodies[1].name, "b/ball");
  EXPECT_EQ(w.sim().state()[1].position, b_before.position);
  EXPECT_TRUE(w.wrenches().wrenches().empty());  // the wrench on a's ball went with it
  EXPECT_EQ(w.configured_scene().bodies.size(), 2u);
}

TEST(Names, AContactOfTwoSpawnedCollisionsIsAddressedByItsName) {
  World w = BallWorld();
  const Scene ball = Load(BallUrdf(), 9.81, false).scene;
  w.Spawn("p", ball, "", At(1, 0, 0.05), "dp");
  w.Spawn("q", ball, "", At(2, 0, 0.05), "dq");
  // "<collision>/<collision>" of two names that hold a '/' themselves
  const FrictionSet before = w.sim().FrictionSetOf("p/shell/q/shell");
  const FrictionSet other = before == FrictionSet::kCoulomb ? FrictionSet::kSphere
                                                            : FrictionSet::kCoulomb;
  w.sim().SetFrictionSet(other, "q/shell/p/shell");
  EXPECT_EQ(w.sim().FrictionSetOf("p/shell/q/shell"), other);
  EXPECT_EQ(w.sim().FrictionSetOf("p/shell/shell"), before);  // another pair keeps its set
  EXPECT_THROW(w.sim().FrictionSetOf("p/shell/p/shell"), std::invalid_argument);
  EXPECT_THROW(w.sim().FrictionSetOf("p/shell/nothing"), std::invalid_argument);
}

TEST(Names, FrameNamesKeepTheModelSeparatorAndSanitiseEachSegment) {
  EXPECT_EQ(FrameName("top2/big_sphere"), "top2/big_sphere");
  EXPECT_EQ(FrameName("peg sphere/2"), "peg_sphere/_2");
  EXPECT_EQ(FrameName("a//b"), "a/_/b");
  // names that would share a frame after sanitising are found, both owners named
  Scene scene = Load(BallUrdf(), 9.81, true).scene;
  scene.colliders.push_back(scene.colliders[0]);  // after the ground: a second one on the ball
  scene.colliders[0].name = "x_y";
  scene.colliders.back().name = "x-y";
  EXPECT_EQ(FrameNameClash(scene, "world").rfind(
                "collision \"x-y\" would have the contact frame \"x_y_contact\" and topic "
                "~wrench/x_y of collision \"x_y\"",
                0),
            0u)
      << FrameNameClash(scene, "world");
  scene.colliders.back().name = "x/y";  // a separator, not sanitised: its own frame
  EXPECT_EQ(FrameNameClash(scene, "world"), "");
}

}  // namespace
}  // namespace nonsmooth_sim::world
