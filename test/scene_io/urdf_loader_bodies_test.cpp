// URDF -> Scene, the bodies: the shipped Tippe-Top URDF gives exactly the core's Tippe-Top
// scene; links fixed to a body merge into it (mass, centre of mass and inertia checked against
// a hand computation with the reduced mass); every shipped scene loads as it did before the root
// and joint rules of urdf_loader_joints_test; a Tippe-Top is recognised only with its spheres on
// the axis.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "nonsmooth_sim/core/tippe_top.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "urdf_fixtures.h"

namespace nonsmooth_sim::scene_io {
namespace {

using namespace urdf_test;  // NOLINT

void ExpectSameScene(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_EQ(a.bodies[i].name, b.bodies[i].name);
    EXPECT_EQ(a.bodies[i].mass, b.bodies[i].mass);
    EXPECT_EQ(a.bodies[i].inertia, b.bodies[i].inertia);
    EXPECT_EQ(a.bodies[i].com_in_link, b.bodies[i].com_in_link);
  }
  ASSERT_EQ(a.colliders.size(), b.colliders.size());
  for (std::size_t i = 0; i < a.colliders.size(); ++i) {
    const Collider& s = a.colliders[i];
    const Collider& t = b.colliders[i];
    EXPECT_EQ(s.name, t.name);
    EXPECT_EQ(s.body, t.body) << s.name;
    EXPECT_EQ(s.pose.matrix(), t.pose.matrix()) << s.name;
    ExpectSameShape(s.shape, t.shape, s.name);
    EXPECT_EQ(s.law.mu, t.law.mu) << s.name;
    EXPECT_EQ(s.law.rbar, t.law.rbar) << s.name;
    EXPECT_EQ(s.law.restitution, t.law.restitution) << s.name;
    EXPECT_EQ(s.law.friction_set, t.law.friction_set) << s.name;
  }
  EXPECT_EQ(a.gravity, b.gravity);
  ASSERT_EQ(a.initial_state.size(), b.initial_state.size());
  for (std::size_t i = 0; i < a.initial_state.size(); ++i) {
    EXPECT_EQ(a.initial_state[i].position, b.initial_state[i].position);
    EXPECT_EQ(a.initial_state[i].orientation.coeffs(), b.initial_state[i].orientation.coeffs());
    EXPECT_EQ(a.initial_state[i].linear_velocity, b.initial_state[i].linear_velocity);
    EXPECT_EQ(a.initial_state[i].angular_velocity, b.initial_state[i].angular_velocity);
  }
}

// --- the shipped Tippe-Top ---------------------------------------------------------------------

TEST(UrdfLoader, ShippedTippeTopEqualsTheCoreScene) {
  const UrdfScene urdf = LoadUrdfFile(SourcePath("urdf/tippe_top.urdf"));
  EXPECT_TRUE(urdf.warnings.empty()) << urdf.warnings.front();
  ASSERT_EQ(urdf.scene.bodies.size(), 1u);
  EXPECT_EQ(urdf.scene.bodies[0].name, "tippe_top");
  // bodies = [tippe_top], colliders = [big_sphere, peg_sphere, ground], laws of the paper
  ASSERT_EQ(urdf.scene.colliders.size(), 3u);
  const Collider& big = urdf.scene.colliders[kBigSphere];
  const Collider& peg = urdf.scene.colliders[kPegSphere];
  EXPECT_EQ(big.name, "big_sphere");
  EXPECT_EQ(big.shape.type, ShapeType::kSphere);
  EXPECT_EQ(big.shape.radius, 0.015);
  EXPECT_EQ(big.pose.translation(), Eigen::Vector3d(0.0, 0.0, 0.003));
  EXPECT_EQ(peg.name, "peg_sphere");
  EXPECT_EQ(peg.shape.radius, 0.005);
  EXPECT_EQ(peg.pose.translation(), Eigen::Vector3d(0.0, 0.0, 0.016));
  EXPECT_EQ(urdf.scene.colliders[kTippeTopGround].name, "ground");
  for (const Collider* c : {&big, &peg}) {
    EXPECT_EQ(c->body, 0);
    EXPECT_EQ(c->law.mu, 0.3);
    EXPECT_EQ(c->law.rbar, 3.0 * kPi * 5e-4 / 16.0);
    EXPECT_EQ(c->law.restitution, 0.0);
  }
  // field by field against the core's scene, started as the core starts it
  ASSERT_EQ(urdf.tippe_top.size(), 1u);
  ASSERT_TRUE(urdf.tippe_top[0].has_value());
  Scene scene = urdf.scene;
  scene.initial_state = {TippeTopInitialState(*urdf.tippe_top[0], {})};
  ExpectSameScene(scene, MakeTippeTopScene());
  EXPECT_TRUE(urdf.merged_links[0].empty());
}

// Every shipped scene (urdf/*.urdf) as it loaded before massless roots could become bodies and
// moving joints were refused: its bodies (names and masses, the <mass> of their one link each),
// its colliders (the ground last) and no warning. A root that became a body, or a link refused,
// would change a count or a name here.
TEST(UrdfLoader, ShippedScenesLoadAsBefore) {
  struct Shipped {
    std::string file;
    std::vector<std::pair<std::string, double>> bodies;  // name, mass [kg]
    std::size_t colliders;                               // the ground included
  };
  const std::vector<Shipped> shipped = {
      {"classic_top", {{"classic_top", 0.02}}, 3},
      {"coin", {{"coin", 0.0075}}, 2},
      {"d20", {{"d20", 0.00405073991}}, 2},
      {"die", {{"die", 0.0045}}, 2},
      {"euler_disk", {{"euler_disk", 0.41616285183022284}}, 2},
      {"rattleback", {{"rattleback", 1.0}}, 2},
      {"spinning_egg", {{"spinning_egg", 0.05}}, 2},
      {"tippe_top", {{"tippe_top", 6e-3}}, 3},
      {"tippe_top_duel", {{"top1", 6e-3}, {"top2", 6e-3}}, 5},
  };
  std::size_t checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(SourcePath("urdf"))) {
    if (entry.path().extension() != ".urdf") continue;
    const std::string file = entry.path().stem().string();
    const auto expected = std::find_if(shipped.begin(), shipped.end(),
                                       [&](const Shipped& s) { return s.file == file; });
    ASSERT_NE(expected, shipped.end()) << file << ".urdf: a new shipped scene, add it here";
    ++checked;
    UrdfSceneOptions options;
    options.ros_package_path = SourcePath("");  // package://nonsmooth_sim/meshes/ (d20)
    const UrdfScene urdf = LoadUrdfFile(entry.path().string(), options);
    EXPECT_TRUE(urdf.warnings.empty()) << file << ": " << urdf.warnings.front();
    ASSERT_EQ(urdf.scene.bodies.size(), expected->bodies.size()) << file;
    for (std::size_t b = 0; b < expected->bodies.size(); ++b) {
      EXPECT_EQ(urdf.scene.bodies[b].name, expected->bodies[b].first) << file;
      EXPECT_EQ(urdf.scene.bodies[b].mass, expected->bodies[b].second) << file;
      EXPECT_TRUE(urdf.merged_links[b].empty()) << file;
    }
    ASSERT_EQ(urdf.scene.colliders.size(), expected->colliders) << file;
    for (std::size_t k = 0; k + 1 < urdf.scene.colliders.size(); ++k) {
      EXPECT_NE(urdf.scene.colliders[k].body, kWorld) << file << ": "
                                                      << urdf.scene.colliders[k].name;
    }
    EXPECT_EQ(urdf.scene.colliders.back().name, "ground") << file;
  }
  EXPECT_EQ(checked, shipped.size());
}

TEST(UrdfLoader, OptionsReplaceTheUrdfLawAndGravityAsInTheCoreScene) {
  UrdfSceneOptions options;
  options.mu = 0.5;
  options.contact_radius = 1e-3;
  options.friction_set = FrictionSet::kExact;
  options.gravity = 9.80665;
  const UrdfScene urdf = LoadUrdfFile(SourcePath("urdf/tippe_top.urdf"), options);
  ASSERT_TRUE(urdf.tippe_top[0].has_value());
  const TippeTopInitialConditions start{0.4, -60.0};
  Scene scene = urdf.scene;
  scene.initial_state = {TippeTopInitialState(*urdf.tippe_top[0], start)};

  TippeTopParameters parameters;
  parameters.mu = 0.5;
  parameters.contact_radius = 1e-3;
  parameters.friction_set = FrictionSet::kExact;
  parameters.gravity = 9.80665;
  ExpectSameScene(scene, MakeTippeTopScene(parameters, start));
}

TEST(UrdfLoader, DefaultStateIsTheUrdfPoseAtRest) {
  const UrdfScene urdf = SceneFromUrdf(Robot(kUnitInertial + kBall));
  ASSERT_EQ(urdf.scene.initial_state.size(), 1u);
  const BodyState& s = urdf.scene.initial_state[0];
  EXPECT_EQ(s.position, Eigen::Vector3d::Zero());
  EXPECT_EQ(s.orientation.coeffs(), Eigen::Quaterniond::Identity().coeffs());
  EXPECT_EQ(s.linear_velocity, Eigen::Vector3d::Zero());
  EXPECT_EQ(s.angular_velocity, Eigen::Vector3d::Zero());
}

// --- bodies and inertia --------------------------------------------------------------------------

TEST(UrdfLoader, InertiaInARotatedInertialFrameIsReexpressedInLinkAxes) {
  // principal moments 1, 2, 3 (e-6) about the axes of an <inertial><origin> frame rotated by
  // rpy = (0.3, -0.2, 0.5) and placed at (0.01, 0.02, 0.03) in the link frame
  const std::string xml = Robot(
      "<inertial><origin xyz=\"0.01 0.02 0.03\" rpy=\"0.3 -0.2 0.5\"/><mass value=\"0.1\"/>"
      "<inertia ixx=\"1e-6\" ixy=\"0\" ixz=\"0\" iyy=\"2e-6\" iyz=\"0\" izz=\"3e-6\"/></inertial>"
      "<collision name=\"ball\"><origin xyz=\"0 0 -0.05\"/>"
      "<geometry><sphere radius=\"0.02\"/></geometry></collision>");
  const UrdfScene urdf = SceneFromUrdf(xml);
  ASSERT_EQ(urdf.scene.bodies.size(), 1u);
  const RigidBody& body = urdf.scene.bodies[0];
  const Eigen::Matrix3d r = Rpy(0.3, -0.2, 0.5);
  const Eigen::Matrix3d expected = r * Eigen::Vector3d(1e-6, 2e-6, 3e-6).asDiagonal() * r.transpose();
  EXPECT_LT((body.inertia - expected).norm(), 1e-18);
  // each rotated principal axis is an eigenvector with its moment
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d axis = r.col(k);
    EXPECT_LT((body.inertia * axis - (k + 1) * 1e-6 * axis).norm(), 1e-18) << k;
  }
  EXPECT_EQ(body.com_in_link, Eigen::Vector3d(0.01, 0.02, 0.03));
  ASSERT_EQ(urdf.scene.colliders.size(), 2u);  // ball, ground
  // the collider pose is relative to the centre of mass, in link axes
  EXPECT_LT((urdf.scene.colliders[0].pose.translation() - Eigen::Vector3d(-0.01, -0.02, -0.08))
                .norm(),
            1e-17);
  EXPECT_TRUE(urdf.scene.colliders[0].pose.linear().isIdentity(0.0));
  EXPECT_FALSE(urdf.tippe_top[0].has_value());
  // the default state puts the link frame at the origin: r_S = com_in_link
  EXPECT_EQ(urdf.scene.initial_state[0].position, body.com_in_link);
}

TEST(UrdfLoader, TwoFloatingTippeTopsUnderAMasslessWorldAreTwoBodies) {
  // joint names sort the other way round than the links: bodies follow the document
  const std::string top =
      "<inertial><mass value=\"6e-3\"/>"
      "<inertia ixx=\"8e-7\" ixy=\"0\" ixz=\"0\" iyy=\"8e-7\" iyz=\"0\" izz=\"7e-7\"/></inertial>";
  const auto spheres = [](const std::string& prefix) {
    return "<collision name=\"" + prefix + "big_sphere\"><origin xyz=\"0 0 0.003\"/>"
           "<geometry><sphere radius=\"0.015\"/></geometry></collision>"
           "<collision name=\"" + prefix + "peg_sphere\"><origin xyz=\"0 0 0.016\"/>"
           "<geometry><sphere radius=\"0.005\"/></geometry></collision>";
  };
  const std::string xml =
      "<robot name=\"two\"><link name=\"world\"/>"
      "<link name=\"top_a\">" + top + spheres("a_") + "</link>"
      "<link name=\"top_b\">" + top + spheres("b_") + "</link>"
      "<joint name=\"z_joint\" type=\"floating\"><parent link=\"world\"/><child link=\"top_a\"/>"
      "<origin xyz=\"0 0 0.012\"/></joint>"
      "<joint name=\"a_joint\" type=\"floating\"><parent link=\"world\"/><child link=\"top_b\"/>"
      "<origin xyz=\"0.1 0 0.012\"/></joint></robot>";
  const UrdfScene urdf = SceneFromUrdf(xml);
  EXPECT_TRUE(urdf.warnings.empty()) << urdf.warnings.front();
  ASSERT_EQ(urdf.scene.bodies.size(), 2u);
  EXPECT_EQ(urdf.scene.bodies[0].name, "top_a");
  EXPECT_EQ(urdf.scene.bodies[1].name, "top_b");
  ASSERT_EQ(urdf.scene.colliders.size(), 5u);  // four spheres and the ground, no world collider
  EXPECT_EQ(urdf.scene.colliders[0].name, "a_big_sphere");
  EXPECT_EQ(urdf.scene.colliders[0].body, 0);
  EXPECT_EQ(urdf.scene.colliders[3].name, "b_peg_sphere");
  EXPECT_EQ(urdf.scene.colliders[3].body, 1);
  EXPECT_EQ(urdf.scene.colliders[4].name, "ground");
  EXPECT_EQ(urdf.scene.colliders[4].body, kWorld);
  EXPECT_EQ(urdf.scene.initial_state[0].position, Eigen::Vector3d(0.0, 0.0, 0.012));
  EXPECT_EQ(urdf.scene.initial_state[1].position, Eigen::Vector3d(0.1, 0.0, 0.012));
  // both are Tippe-Tops with the core's geometry (Gazebo's default μ = 1 here)
  for (int b = 0; b < 2; ++b) {
    ASSERT_TRUE(urdf.tippe_top[b].has_value()) << b;
    EXPECT_EQ(urdf.tippe_top[b]->big_offset, 0.003);
    EXPECT_EQ(urdf.tippe_top[b]->peg_radius, 0.005);
    EXPECT_EQ(urdf.tippe_top[b]->mu, 1.0);
  }
}

TEST(UrdfLoader, FixedLinksMergeIntoTheirBodyByTheParallelAxisTheorem) {
  // base: m1 = 2 at its origin, Θ1 = diag(1.2, 2.1, 3.3)e-2. arm, fixed at (0.3, 0, 0) and turned
  // by 90° about z: m2 = 1 at (0.1, 0, 0) in the arm frame, Θ2 = diag(0.1, 0.2, 0.3)e-2 in arm
  // axes. sensor: fixed to the arm, massless, one collision.
  const std::string xml =
      "<robot name=\"r\"><link name=\"base\"><inertial><mass value=\"2\"/>"
      "<inertia ixx=\"1.2e-2\" ixy=\"0\" ixz=\"0\" iyy=\"2.1e-2\" iyz=\"0\" izz=\"3.3e-2\"/>"
      "</inertial>" + kBall + "</link>"
      "<link name=\"arm\"><inertial><origin xyz=\"0.1 0 0\"/><mass value=\"1\"/>"
      "<inertia ixx=\"0.1e-2\" ixy=\"0\" ixz=\"0\" iyy=\"0.2e-2\" iyz=\"0\" izz=\"0.3e-2\"/>"
      "</inertial><collision name=\"hand\"><origin xyz=\"0.1 0 0\"/>"
      "<geometry><sphere radius=\"0.05\"/></geometry></collision></link>"
      "<link name=\"sensor\"><collision name=\"lens\"><origin xyz=\"0 0 0.1\"/>"
      "<geometry><box size=\"0.02 0.02 0.02\"/></geometry></collision></link>"
      "<joint name=\"base_arm\" type=\"fixed\"><parent link=\"base\"/><child link=\"arm\"/>"
      "<origin xyz=\"0.3 0 0\" rpy=\"0 0 1.5707963267948966\"/></joint>"
      "<joint name=\"arm_sensor\" type=\"fixed\"><parent link=\"arm\"/><child link=\"sensor\"/>"
      "</joint></robot>";
  const UrdfScene urdf = SceneFromUrdf(xml);
  EXPECT_TRUE(urdf.warnings.empty()) << urdf.warnings.front();
  ASSERT_EQ(urdf.scene.bodies.size(), 1u);
  const RigidBody& body = urdf.scene.bodies[0];
  EXPECT_EQ(body.name, "base");
  EXPECT_EQ(urdf.merged_links[0], (std::vector<std::string>{"arm", "sensor"}));

  // by hand: the arm's centre of mass in base coordinates is r = (0.3, 0.1, 0); m = 3;
  // c = m2 r / m; about c the two point masses add the reduced mass μ = m1 m2 / m = 2/3 times
  // (|r|² 1 − r rᵀ); the arm's Θ2 turned by 90° about z swaps its x and y moments
  EXPECT_EQ(body.mass, 3.0);
  const Eigen::Vector3d r(0.3, 0.1, 0.0);
  EXPECT_LT((body.com_in_link - r / 3.0).norm(), 1e-16);
  Eigen::Matrix3d expected;
  expected << 1.2e-2 + 0.2e-2 + 2.0 / 3.0 * 0.01, -2.0 / 3.0 * 0.03, 0.0,  //
      -2.0 / 3.0 * 0.03, 2.1e-2 + 0.1e-2 + 2.0 / 3.0 * 0.09, 0.0,          //
      0.0, 0.0, 3.3e-2 + 0.3e-2 + 2.0 / 3.0 * 0.1;
  EXPECT_LT((body.inertia - expected).norm(), 1e-16) << body.inertia;

  // colliders of all three links on the body, relative to the new centre of mass
  ASSERT_EQ(urdf.scene.colliders.size(), 4u);  // ball, hand, lens, ground
  const Eigen::Vector3d c = r / 3.0;
  EXPECT_EQ(urdf.scene.colliders[0].name, "ball");
  EXPECT_LT((urdf.scene.colliders[0].pose.translation() - (-c)).norm(), 1e-16);
  EXPECT_EQ(urdf.scene.colliders[1].name, "hand");
  EXPECT_EQ(urdf.scene.colliders[1].body, 0);
  EXPECT_LT((urdf.scene.colliders[1].pose.translation() - (Eigen::Vector3d(0.3, 0.1, 0.0) - c))
                .norm(),
            1e-16);
  EXPECT_LT((urdf.scene.colliders[1].pose.linear() - Rpy(0.0, 0.0, kPi / 2)).norm(), 1e-16);
  EXPECT_EQ(urdf.scene.colliders[2].name, "lens");
  EXPECT_LT((urdf.scene.colliders[2].pose.translation() - (Eigen::Vector3d(0.3, 0.0, 0.1) - c))
                .norm(),
            1e-16);
  // the body starts at its URDF pose: r_S = c
  EXPECT_LT((urdf.scene.initial_state[0].position - c).norm(), 1e-16);
}

TEST(UrdfLoader, AMasslessFloatingLinkTakesTheMassOfTheLinksFixedToIt) {
  // carrier (no inertial) -fixed (0, 0.2, 0)-> load (m = 2): the body is "carrier", S at the load
  const std::string xml = World(
      "", "<link name=\"carrier\"/><link name=\"load\">" + kUnitInertial + kBall + "</link>"
          "<joint name=\"wc\" type=\"floating\"><parent link=\"world\"/>"
          "<child link=\"carrier\"/><origin xyz=\"0 0 1\"/></joint>"
          "<joint name=\"cl\" type=\"fixed\"><parent link=\"carrier\"/><child link=\"load\"/>"
          "<origin xyz=\"0 0.2 0\"/></joint>");
  const UrdfScene urdf = SceneFromUrdf(xml);
  ASSERT_EQ(urdf.scene.bodies.size(), 1u);
  EXPECT_EQ(urdf.scene.bodies[0].name, "carrier");
  EXPECT_EQ(urdf.scene.bodies[0].mass, 2.0);
  EXPECT_EQ(urdf.scene.bodies[0].inertia, Eigen::Matrix3d::Identity());
  EXPECT_EQ(urdf.scene.bodies[0].com_in_link, Eigen::Vector3d(0.0, 0.2, 0.0));
  EXPECT_EQ(urdf.scene.colliders[0].pose.translation(), Eigen::Vector3d::Zero());
  EXPECT_EQ(urdf.scene.initial_state[0].position, Eigen::Vector3d(0.0, 0.2, 1.0));
  EXPECT_EQ(urdf.merged_links[0], std::vector<std::string>{"load"});
}

// --- Tippe-Top detection -------------------------------------------------------------------------

TEST(UrdfLoader, SpheresOffTheAxisAreNotATippeTop) {
  const std::string xml = Robot(
      "<inertial><mass value=\"6e-3\"/>"
      "<inertia ixx=\"8e-7\" ixy=\"0\" ixz=\"0\" iyy=\"8e-7\" iyz=\"0\" izz=\"7e-7\"/></inertial>"
      "<collision name=\"big_sphere\"><origin xyz=\"0.001 0 0.003\"/>"
      "<geometry><sphere radius=\"0.015\"/></geometry></collision>"
      "<collision name=\"peg_sphere\"><origin xyz=\"0 0 0.016\"/>"
      "<geometry><sphere radius=\"0.005\"/></geometry></collision>");
  EXPECT_FALSE(SceneFromUrdf(xml).tippe_top[0].has_value());
  std::string on_axis = xml;
  on_axis.replace(on_axis.find("0.001 0 0.003"), 13, "0 0 0.003");
  EXPECT_TRUE(SceneFromUrdf(on_axis).tippe_top[0].has_value());
}

}  // namespace
}  // namespace nonsmooth_sim::scene_io
