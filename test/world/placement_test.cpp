// Placement and starts: a body is lowered onto the ground until it touches (closed form for a
// sphere off the centre of mass), ~initial/... and ~initial_state/... go through one StartState,
// a model is moved rigidly, and the resets return to the configured start.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "nonsmooth_sim/core/collision/collision.h"
#include "world_fixtures.h"

namespace nonsmooth_sim::world {
namespace {

using testing::BallUrdf;
using testing::Load;
using testing::WorldSnapshot;

// a body whose sphere (radius 0.04 m) sits off its centre of mass at c = (0.1, 0, 0.05) m
scene_io::UrdfScene OffCentre() {
  return Load("<robot name=\"r\"><link name=\"b\"><inertial><mass value=\"1\"/>"
              "<inertia ixx=\"0.02\" ixy=\"0\" ixz=\"0\" iyy=\"0.03\" iyz=\"0\" izz=\"0.04\"/>"
              "</inertial><collision name=\"s\"><origin xyz=\"0.1 0 0.05\"/>"
              "<geometry><sphere radius=\"0.04\"/></geometry></collision></link></robot>",
              9.81, true);
}

TEST(Placement, TouchingHeightIsRadiusMinusTheSpheresDropForAnyTilt) {
  const scene_io::UrdfScene urdf = OffCentre();
  const Eigen::Vector3d c(0.1, 0.0, 0.05);
  for (const double angle : {0.0, 0.3, 1.2, 2.5}) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(angle, Eigen::Vector3d(1, 2, 0).normalized()));
    // S at z = r - (R c)_z puts the sphere's lowest point at z = 0
    const double expected = 0.04 - (q * c).z();
    EXPECT_NEAR(TouchingHeight(urdf.scene, 0, q, -1.0), expected, 1e-15) << angle;
  }
  // no collider of the body: the fallback
  EXPECT_EQ(TouchingHeight(urdf.scene, 7, Eigen::Quaterniond::Identity(), 0.25), 0.25);
}

TEST(Placement, AnOrientationAloneLowersTheBodyOntoTheGround) {
  const scene_io::UrdfScene urdf = OffCentre();
  InitialConditions ic;
  ic.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitY()));
  const std::vector<BodyState> s = StartState(urdf, StartSpec{0, ic, {}});
  const Eigen::Vector3d sphere = s[0].position + s[0].orientation * Eigen::Vector3d(0.1, 0, 0.05);
  EXPECT_NEAR(sphere.z() - 0.04, 0.0, 1e-15);  // touching, not above, not in
  // and the world starts there: its contact with the ground is closed at gap 0
  World w(urdf, WorldConfig{"", "", ic, {}, SimulatorOptions(), "world"});
  EXPECT_NEAR(w.sim().state()[0].position.z(), s[0].position.z(), 0.0);
}

TEST(Placement, InitialStateOfALinkIsAppliedOverTheInitialConditions) {
  const scene_io::UrdfScene urdf = Load(BallUrdf(), 9.81, true);
  WorldConfig config;
  config.initial.spin = 7.0;  // ~initial/spin
  scene_io::BodyInitialState ball;
  ball.position = Eigen::Vector3d(0.3, 0.0, 0.05);  // ~initial_state/bodies/ball/position
  config.initial_state["ball"] = ball;
  World w(urdf, config);
  const BodyState s = w.sim().state()[0];
  EXPECT_EQ(s.position, Eigen::Vector3d(0.3, 0.0, 0.05));
  EXPECT_EQ(s.angular_velocity, Eigen::Vector3d(0.0, 0.0, 7.0));
  // both parameters' routes are StartState's, bit for bit
  const std::vector<BodyState> start =
      StartState(urdf, StartSpec{0, config.initial, config.initial_state});
  EXPECT_EQ(s.position, start[0].position);
  EXPECT_EQ(s.angular_velocity, start[0].angular_velocity);

  // reset_world goes back to it after the body moved
  for (int k = 0; k < 50; ++k) w.sim().Step();
  EXPECT_NE(w.sim().state()[0].position, s.position);
  w.ResetWorld();
  EXPECT_EQ(w.sim().state()[0].position, Eigen::Vector3d(0.3, 0.0, 0.05));

  // ~reset merges over the configured ~initial/...: spin kept unless asked
  InitialConditions reset;
  reset.linear_velocity = Eigen::Vector3d(1.0, 0.0, 0.0);
  w.Reset("", reset);
  EXPECT_EQ(w.sim().state()[0].linear_velocity, Eigen::Vector3d(1.0, 0.0, 0.0));
  EXPECT_EQ(w.sim().state()[0].angular_velocity, Eigen::Vector3d(0.0, 0.0, 7.0));

  // refused: a bad value, an unknown body; nothing changes
  for (const char* body : {"", "nobody"}) {
    InitialConditions bad;
    if (body[0] == '\0') bad.inclination = 4.0;  // outside [0, pi]
    const WorldSnapshot before(w);
    EXPECT_THROW(w.Reset(body, bad), std::invalid_argument) << body;
    before.ExpectSame(WorldSnapshot(w), std::string("reset of \"") + body + "\"");
  }
}

TEST(Placement, SetModelStateMovesTheModelRigidlyOrNotAtAll) {
  World w(Load(BallUrdf(), 9.81, true), WorldConfig());
  Pose pose;
  pose.position = Eigen::Vector3d(0.5, -0.25, 0.1);
  pose.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()));
  Twist twist;
  twist.linear = Eigen::Vector3d(0.1, 0, 0);
  twist.angular = Eigen::Vector3d(0, 0, 2.0);
  w.SetModelState("ball", "", pose, twist);
  const World::ModelFrame f = w.GetModelState("ball", "world");
  EXPECT_LT((f.pose.position - pose.position).norm(), 1e-15);
  EXPECT_LT(f.pose.orientation.angularDistance(pose.orientation), 1e-15);
  EXPECT_LT((f.twist.linear - twist.linear).norm(), 1e-15);
  EXPECT_LT((f.twist.angular - twist.angular).norm(), 1e-15);

  Pose far = pose;
  far.position.x() = 5e3;  // beyond kMaxInitialCoordinate
  const WorldSnapshot before(w);
  EXPECT_THROW(w.SetModelState("ball", "", far, twist), std::invalid_argument);
  EXPECT_THROW(w.SetModelState("nobody", "", pose, twist), std::invalid_argument);
  EXPECT_THROW(w.GetModelState("ball", "nowhere"), std::invalid_argument);
  before.ExpectSame(WorldSnapshot(w), "set_model_state");
}

}  // namespace
}  // namespace nonsmooth_sim::world
