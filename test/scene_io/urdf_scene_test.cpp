// URDF -> Scene: the shipped Tippe-Top URDF gives exactly the core's Tippe-Top scene; each shape
// tag gives its core shape at the collision's pose relative to the centre of mass; links fixed to
// the massless root are world colliders at their world pose; links fixed to a body merge into it
// (mass, centre of mass and inertia checked against a hand computation with the reduced mass);
// Gazebo's friction tags map onto the contact law; unsupported parts are reported and skipped;
// every malformed input gives one error line naming the element and the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>

#include "nonsmooth_sim/core/collision/collision_table.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace nonsmooth_sim::scene_io {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string SourcePath(const std::string& relative) {
  return std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/" + relative;
}

// URDF rpy: fixed axes x, y, z, i.e. R = Rz(yaw) Ry(pitch) Rx(roll)
Eigen::Matrix3d Rpy(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// One link "b" with the given body, plus extra top-level XML.
std::string Robot(const std::string& link_body, const std::string& extra = "") {
  return "<robot name=\"r\"><link name=\"b\">" + link_body + "</link>" + extra + "</robot>";
}
const std::string kUnitInertial =
    "<inertial><mass value=\"2\"/>"
    "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>";
const std::string kBall =
    "<collision name=\"ball\"><geometry><sphere radius=\"0.1\"/></geometry></collision>";

// A massless root "world" with `world_body` inside its <link>, plus extra XML.
std::string World(const std::string& world_body, const std::string& extra) {
  return "<robot name=\"r\"><link name=\"world\">" + world_body + "</link>" + extra + "</robot>";
}
// A free link `name` on a floating joint from world at `xyz`, with a sphere `collision`.
std::string FloatingBall(const std::string& name, const std::string& xyz,
                         const std::string& collision) {
  return "<link name=\"" + name + "\">" + kUnitInertial + "<collision name=\"" + collision +
         "\"><geometry><sphere radius=\"0.1\"/></geometry></collision></link>"
         "<joint name=\"world_" + name + "\" type=\"floating\"><parent link=\"world\"/>"
         "<child link=\"" + name + "\"/><origin xyz=\"" + xyz + "\"/></joint>";
}

// The one error line of a URDF that must not load.
std::string LoadError(const std::string& xml, const UrdfSceneOptions& options = {}) {
  try {
    SceneFromUrdf(xml, options);
  } catch (const UrdfError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind("urdf: ", 0), 0u) << message;
    return message;
  }
  ADD_FAILURE() << "loaded without an error:\n" << xml;
  return "";
}

void ExpectContains(const std::string& message, std::initializer_list<std::string> parts) {
  for (const std::string& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << "\"" << part << "\" not in: " << message;
  }
}

bool HasWarning(const UrdfScene& urdf, std::initializer_list<std::string> parts) {
  for (const std::string& warning : urdf.warnings) {
    bool all = true;
    for (const std::string& part : parts) all = all && warning.find(part) != std::string::npos;
    if (all) return true;
  }
  return false;
}

void ExpectSameShape(const Shape& a, const Shape& b, const std::string& name) {
  EXPECT_EQ(a.type, b.type) << name;
  EXPECT_EQ(a.radius, b.radius) << name;
  EXPECT_EQ(a.half_length, b.half_length) << name;
  EXPECT_EQ(a.half_extents, b.half_extents) << name;
}

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

TEST(UrdfLoader, OtherJointTypesAreReportedAndSkipped) {
  // b -revolute-> c (skipped) -floating-> d (a body again)
  const std::string xml =
      std::string("<robot name=\"r\">") + "<link name=\"b\">" + kUnitInertial + kBall + "</link>" +
      "<link name=\"c\">" + kUnitInertial + "</link>" +
      "<link name=\"d\">" + kUnitInertial +
      "<collision name=\"ball_d\"><geometry><sphere radius=\"0.1\"/></geometry></collision>"
      "</link>"
      "<joint name=\"bc\" type=\"revolute\"><parent link=\"b\"/><child link=\"c\"/>"
      "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/></joint>"
      "<joint name=\"cd\" type=\"floating\"><parent link=\"c\"/><child link=\"d\"/>"
      "<origin xyz=\"2 0 0\"/></joint></robot>";
  const UrdfScene urdf = SceneFromUrdf(xml);
  ASSERT_EQ(urdf.scene.bodies.size(), 2u);
  EXPECT_EQ(urdf.scene.bodies[1].name, "d");
  EXPECT_EQ(urdf.scene.initial_state[1].position, Eigen::Vector3d(2.0, 0.0, 0.0));
  ASSERT_EQ(urdf.warnings.size(), 1u);
  ExpectContains(urdf.warnings[0], {"link \"c\" hangs on joint \"bc\" (revolute)", "skipped"});
}

// --- shapes --------------------------------------------------------------------------------------

TEST(UrdfLoader, EachShapeTagGivesItsCoreShapeAtTheCollisionPoseRelativeToTheCentreOfMass) {
  const Eigen::Vector3d com(0.01, 0.02, 0.03);
  const std::string xml = Robot(
      "<inertial><origin xyz=\"0.01 0.02 0.03\"/><mass value=\"1\"/>"
      "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>"
      "<collision name=\"s\"><origin xyz=\"0.1 0 0\"/>"
      "<geometry><sphere radius=\"0.1\"/></geometry></collision>"
      "<collision name=\"cyl\"><origin xyz=\"0 0.1 0\" rpy=\"1.5707963267948966 0 0\"/>"
      "<geometry><cylinder radius=\"0.05\" length=\"0.2\"/></geometry></collision>"
      "<collision name=\"slab\"><origin xyz=\"0 0 0.1\" rpy=\"0 0 0.3\"/>"
      "<geometry><box size=\"0.2 0.4 0.6\"/></geometry></collision>"
      "<collision name=\"shell\"><origin xyz=\"0.05 0 0\" rpy=\"0.1 0.2 0.3\"/>"
      "<geometry><sphere radius=\"0.2\"/></geometry></collision>"
      "<collision name=\"pill\"><origin xyz=\"0 0 -0.1\" rpy=\"0 1.5707963267948966 0\"/>"
      "<geometry><cylinder radius=\"0.01\" length=\"0.07\"/></geometry></collision>"
      "<collision name=\"scan\"><geometry><mesh filename=\"package://x/scan.stl\"/></geometry>"
      "</collision>",
      "<nonsmooth_sim reference=\"b\">"
      "<collision name=\"shell\"><ellipsoid semi_axes=\"0.2 0.03 0.02\"/></collision>"
      "<collision name=\"pill\"><capsule radius=\"0.01\" length=\"0.05\"/></collision>"
      "</nonsmooth_sim>");
  const UrdfScene urdf = SceneFromUrdf(xml);
  const Scene& scene = urdf.scene;
  ASSERT_EQ(scene.colliders.size(), 6u);  // five shapes and the ground; the mesh is skipped
  const auto expect = [&](int i, const std::string& name, const Shape& shape,
                          const Eigen::Vector3d& xyz, const Eigen::Matrix3d& rotation) {
    const Collider& c = scene.colliders[i];
    EXPECT_EQ(c.name, name);
    EXPECT_EQ(c.body, 0) << name;
    ExpectSameShape(c.shape, shape, name);
    EXPECT_LT((c.pose.translation() - (xyz - com)).norm(), 1e-17) << name;
    EXPECT_LT((c.pose.linear() - rotation).norm(), 1e-15) << name;
  };
  expect(0, "s", Shape::Sphere(0.1), {0.1, 0.0, 0.0}, Eigen::Matrix3d::Identity());
  expect(1, "cyl", Shape::Cylinder(0.05, 0.1), {0.0, 0.1, 0.0}, Rpy(kPi / 2, 0.0, 0.0));
  expect(2, "slab", Shape::Box({0.1, 0.2, 0.3}), {0.0, 0.0, 0.1}, Rpy(0.0, 0.0, 0.3));
  expect(3, "shell", Shape::Ellipsoid({0.2, 0.03, 0.02}), {0.05, 0.0, 0.0}, Rpy(0.1, 0.2, 0.3));
  expect(4, "pill", Shape::Capsule(0.01, 0.025), {0.0, 0.0, -0.1}, Rpy(0.0, kPi / 2, 0.0));
  // the cylinder's axis (shape z) lies along the link's -y: rpy (π/2, 0, 0) turns z to -y
  EXPECT_LT((scene.colliders[1].pose.linear() * Eigen::Vector3d::UnitZ() +
             Eigen::Vector3d::UnitY())
                .norm(),
            1e-15);
  ASSERT_EQ(urdf.warnings.size(), 1u);
  ExpectContains(urdf.warnings[0], {"link \"b\" > collision \"scan\"", "skipped"});
}

TEST(UrdfLoader, TableAndWallFixedToTheWorldAreWorldCollidersAtTheirWorldPose) {
  // world -fixed (1, 0, 0.4), yaw 90°-> table -fixed (0.5, 0, 0)-> wall; a ball floats above
  const std::string xml = World(
      "",
      "<link name=\"table\"><collision name=\"table_top\"><origin xyz=\"0.1 0 0.375\"/>"
      "<geometry><box size=\"1 0.5 0.05\"/></geometry></collision></link>"
      "<link name=\"wall\"><collision name=\"wall\"><origin xyz=\"0 0 0.2\"/>"
      "<geometry><box size=\"0.02 1 0.4\"/></geometry></collision></link>"
      "<joint name=\"world_table\" type=\"fixed\"><parent link=\"world\"/><child link=\"table\"/>"
      "<origin xyz=\"1 0 0.4\" rpy=\"0 0 1.5707963267948966\"/></joint>"
      "<joint name=\"table_wall\" type=\"fixed\"><parent link=\"table\"/><child link=\"wall\"/>"
      "<origin xyz=\"0.5 0 0\"/></joint>" +
          FloatingBall("ball", "1 0 1", "ball") +
          "<gazebo reference=\"table\"><collision><surface><friction><ode><mu>0.6</mu></ode>"
          "</friction></surface></collision></gazebo>");
  const UrdfScene urdf = SceneFromUrdf(xml);
  EXPECT_TRUE(urdf.warnings.empty()) << urdf.warnings.front();
  ASSERT_EQ(urdf.scene.bodies.size(), 1u);
  ASSERT_EQ(urdf.scene.colliders.size(), 4u);  // table_top, wall, ball, ground
  const Collider& top = urdf.scene.colliders[0];
  const Collider& wall = urdf.scene.colliders[1];
  EXPECT_EQ(top.name, "table_top");
  EXPECT_EQ(top.body, kWorld);
  ExpectSameShape(top.shape, Shape::Box({0.5, 0.25, 0.025}), "table_top");
  // by hand: Rz(90°) (0.1, 0, 0.375) + (1, 0, 0.4) = (1, 0.1, 0.775)
  EXPECT_LT((top.pose.translation() - Eigen::Vector3d(1.0, 0.1, 0.775)).norm(), 1e-15);
  EXPECT_LT((top.pose.linear() - Rpy(0.0, 0.0, kPi / 2)).norm(), 1e-15);
  EXPECT_EQ(top.law.mu, 0.6);
  // wall frame at Rz(90°) (0.5, 0, 0) + (1, 0, 0.4) = (1, 0.5, 0.4), the box 0.2 above it
  EXPECT_EQ(wall.name, "wall");
  EXPECT_EQ(wall.body, kWorld);
  EXPECT_LT((wall.pose.translation() - Eigen::Vector3d(1.0, 0.5, 0.6)).norm(), 1e-15);
  EXPECT_LT((wall.pose.linear() - Rpy(0.0, 0.0, kPi / 2)).norm(), 1e-15);
  EXPECT_EQ(wall.law.mu, 1.0);  // SDF default
  EXPECT_EQ(urdf.scene.colliders[2].body, 0);
  EXPECT_EQ(urdf.scene.colliders[3].name, "ground");
  EXPECT_EQ(urdf.scene.initial_state[0].position, Eigen::Vector3d(1.0, 0.0, 1.0));
}

TEST(UrdfLoader, InclinedPlaneIsAPlaneColliderWhoseNormalIsTheRotatedZ) {
  const std::string xml = World(
      "<collision name=\"slope\"><origin xyz=\"0 0 0.1\" rpy=\"0.2 0 0\"/>"
      "<geometry><box size=\"2 2 0.001\"/></geometry></collision>",
      FloatingBall("ball", "0 0 1", "ball") +
          "<nonsmooth_sim reference=\"world\"><collision name=\"slope\"><plane/></collision>"
          "</nonsmooth_sim>");
  UrdfSceneOptions options;
  options.ground = false;
  const UrdfScene urdf = SceneFromUrdf(xml, options);
  ASSERT_EQ(urdf.scene.colliders.size(), 2u);  // slope, ball: no ground
  const Collider& slope = urdf.scene.colliders[0];
  EXPECT_EQ(slope.name, "slope");
  EXPECT_EQ(slope.body, kWorld);
  EXPECT_EQ(slope.shape.type, ShapeType::kPlane);
  // normal Rx(0.2) ẑ = (0, −sin 0.2, cos 0.2), through (0, 0, 0.1)
  EXPECT_LT((slope.pose.linear() * Eigen::Vector3d::UnitZ() -
             Eigen::Vector3d(0.0, -std::sin(0.2), std::cos(0.2)))
                .norm(),
            1e-16);
  EXPECT_EQ(slope.pose.translation(), Eigen::Vector3d(0.0, 0.0, 0.1));
  EXPECT_EQ(urdf.scene.colliders[1].name, "ball");
}

TEST(UrdfLoader, GroundIsTheCoresGroundPlaneAndComesLast) {
  const UrdfScene urdf = SceneFromUrdf(Robot(kUnitInertial + kBall));
  ASSERT_EQ(urdf.scene.colliders.size(), 2u);
  const Collider& ground = urdf.scene.colliders.back();
  const Collider core = GroundPlane();
  EXPECT_EQ(ground.name, core.name);
  EXPECT_EQ(ground.body, kWorld);
  EXPECT_EQ(ground.pose.matrix(), core.pose.matrix());
  EXPECT_EQ(ground.shape.type, ShapeType::kPlane);
  EXPECT_EQ(ground.law.mu, core.law.mu);
  EXPECT_EQ(ground.law.rbar, core.law.rbar);
  EXPECT_EQ(ground.law.restitution, core.law.restitution);
}

// --- contact laws --------------------------------------------------------------------------------

TEST(UrdfLoader, GazeboFrictionTagsSetTheContactLaw) {
  const std::string surface =
      "<gazebo reference=\"b\"><collision><surface><friction>"
      "<ode><mu>0.5</mu><mu2>0.5</mu2></ode>"
      "<torsional><coefficient>0.25</coefficient><patch_radius>1e-3</patch_radius></torsional>"
      "</friction></surface></collision></gazebo>"
      "<nonsmooth_sim reference=\"b\"><restitution>0.4</restitution>"
      "<friction_set>exact</friction_set></nonsmooth_sim>";
  const UrdfScene urdf = SceneFromUrdf(Robot(kUnitInertial + kBall, surface));
  const ContactLaw& law = urdf.scene.colliders[0].law;
  EXPECT_EQ(law.mu, 0.5);
  // Gazebo's drilling bound μ_τ (3πR/16) λ_N = R̄ μ λ_N  ⇒  R̄ = 3πR/16 · μ_τ/μ
  EXPECT_NEAR(law.rbar, 3.0 * kPi * 1e-3 / 16.0 * 0.25 / 0.5, 1e-18);
  EXPECT_EQ(law.restitution, 0.4);
  EXPECT_EQ(law.friction_set, FrictionSet::kExact);  // the link's tag beats the option's default
  EXPECT_TRUE(urdf.warnings.empty());

  // μ and R from the options replace both tags: R̄ = 3πR/16 with the one μ
  UrdfSceneOptions options;
  options.mu = 0.2;
  options.contact_radius = 2e-3;
  options.friction_set = FrictionSet::kCoulomb;
  const UrdfScene overridden = SceneFromUrdf(Robot(kUnitInertial + kBall, surface), options);
  EXPECT_EQ(overridden.scene.colliders[0].law.mu, 0.2);
  EXPECT_NEAR(overridden.scene.colliders[0].law.rbar, 3.0 * kPi * 2e-3 / 16.0, 1e-18);
  EXPECT_EQ(overridden.scene.colliders[0].law.friction_set, FrictionSet::kExact);
}

TEST(UrdfLoader, WithoutTagsSdfDefaultsAndTheOptionsFrictionSetApply) {
  UrdfSceneOptions options;
  options.friction_set = FrictionSet::kEllipsoid;
  const UrdfScene urdf = SceneFromUrdf(Robot(kUnitInertial + kBall), options);
  const ContactLaw& law = urdf.scene.colliders[0].law;
  EXPECT_EQ(law.mu, 1.0);    // SDF <mu> default
  EXPECT_EQ(law.rbar, 0.0);  // SDF <patch_radius> default 0: no drilling component
  EXPECT_EQ(law.restitution, 0.0);
  EXPECT_EQ(law.friction_set, FrictionSet::kEllipsoid);
}

TEST(UrdfLoader, EachColliderTakesTheLawOfItsOwnLink) {
  // a body b with a fixed link f: f's collisions keep f's tags
  const std::string xml =
      "<robot name=\"r\"><link name=\"b\">" + kUnitInertial + kBall + "</link>"
      "<link name=\"f\"><collision name=\"tip\"><geometry><sphere radius=\"0.01\"/></geometry>"
      "</collision></link>"
      "<joint name=\"bf\" type=\"fixed\"><parent link=\"b\"/><child link=\"f\"/></joint>"
      "<gazebo reference=\"f\"><collision><surface><friction><ode><mu>0.1</mu></ode></friction>"
      "</surface></collision></gazebo>"
      "<nonsmooth_sim reference=\"f\"><restitution>0.5</restitution></nonsmooth_sim></robot>";
  const UrdfScene urdf = SceneFromUrdf(xml);
  EXPECT_EQ(urdf.scene.colliders[0].law.mu, 1.0);
  EXPECT_EQ(urdf.scene.colliders[1].name, "tip");
  EXPECT_EQ(urdf.scene.colliders[1].law.mu, 0.1);
  EXPECT_EQ(urdf.scene.colliders[1].law.restitution, 0.5);
}

TEST(UrdfLoader, AnisotropicFrictionAndUnknownGazeboReferencesAreReported) {
  const std::string surface =
      "<gazebo reference=\"b\"><collision><surface><friction>"
      "<ode><mu>0.5</mu><mu2>0.7</mu2></ode></friction></surface></collision></gazebo>"
      "<gazebo reference=\"nowhere\"><material>Gazebo/Red</material></gazebo>";
  const UrdfScene urdf = SceneFromUrdf(Robot(kUnitInertial + kBall, surface));
  EXPECT_TRUE(HasWarning(urdf, {"anisotropic"}));
  EXPECT_TRUE(HasWarning(urdf, {"gazebo reference=\"nowhere\"", "ignored"}));
  EXPECT_EQ(urdf.scene.colliders[0].law.mu, 0.5);
}

// Found by urdf_loader_fuzz (test/fuzz, 2026-12-02): a newline inside an attribute value was
// quoted verbatim into the error, which then had two lines (the node prints one, and callers split
// on lines). Control characters of the input are escaped in every error and warning now.
TEST(UrdfLoader, ControlCharactersOfTheInputAreEscapedAndTheErrorStaysOneLine) {
  // the fuzzer's input, reduced: xyz="0 0 0.0<newline>3" (LoadError checks: one line)
  ExpectContains(LoadError(Robot(kUnitInertial +
                                 "<collision name=\"ball\"><origin xyz=\"0 0 0.0\n3\"/>"
                                 "<geometry><sphere radius=\"0.1\"/></geometry></collision>")),
                 {"collision \"ball\" > origin", "xyz=\"0 0 0.0\\n3\"", "has 4 numbers"});
  // a tab in a name that an error quotes (TinyXML2 turns a carriage return into a newline)
  ExpectContains(LoadError(Robot(kUnitInertial + kBall,
                                 "<nonsmooth_sim reference=\"no\tlink\r\"/>")),
                 {"reference=\"no\\tlink\\n\"", "no link named \"no\\tlink\\n\""});
  // and in a warning
  const UrdfScene urdf =
      SceneFromUrdf(Robot(kUnitInertial + kBall, "<gazebo reference=\"a\nb\"/>"));
  EXPECT_TRUE(HasWarning(urdf, {"gazebo reference=\"a\\nb\"", "ignored"}));
  for (const std::string& warning : urdf.warnings) {
    EXPECT_EQ(warning.find('\n'), std::string::npos) << warning;
  }
  // the escapes themselves; printable ASCII and UTF-8 pass unchanged
  EXPECT_EQ(OneLine(std::string("a\nb\rc\td\x01" "e\x7f" "f\0g \xc3\xa9", 16)),
            "a\\nb\\rc\\td\\x01e\\x7ff\\x00g \xc3\xa9");
}

// Found by urdf_loader_fuzz (test/fuzz, 2026-12-02): a link named with bytes that are not UTF-8
// ("tip\xe9\x03top") loaded, and its start written as YAML (InitialStateToYaml) did not read back
// (yaml-cpp changes such bytes, the name no longer matched). XML text is UTF-8 without control
// characters other than tab, newline and carriage return; the loader checks that now.
TEST(UrdfLoader, TextThatIsNotXmlCharactersIsRejected) {
  const auto named = [](const std::string& name) {
    return "<robot name=\"r\"><link name=\"" + name + "\">" + kUnitInertial + kBall +
           "</link></robot>";
  };
  ExpectContains(LoadError(named("tip\xe9\x03top")),
                 {"not well-formed XML", "line 1", "byte 0xe9", "not valid"});
  ExpectContains(LoadError(named("a\x03" "b")), {"line 1", "byte 0x03", "control character"});
  ExpectContains(LoadError("<robot name=\"r\">\n<link name=\"b\xff\"/></robot>"),
                 {"line 2", "byte 0xff", "not valid UTF-8"});
  ExpectContains(LoadError(named("\xed\xa0\x80")), {"byte 0xed", "not valid"});  // a surrogate
  ExpectContains(LoadError(named("\xc0\xaf")), {"byte 0xc0", "not valid UTF-8"});  // overlong
  // UTF-8 names load, and their start survives the YAML round trip
  const UrdfScene urdf = SceneFromUrdf(named("M\xc3\xb6ller_\xe2\x82\xac_\xf0\x9f\x8e\xb2"));
  const std::vector<BodyState> back = InitialStateFromYaml(
      urdf.scene, InitialStateToYaml(urdf.scene, urdf.scene.initial_state));
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].position, urdf.scene.initial_state[0].position);
}

// --- names ---------------------------------------------------------------------------------------

TEST(UrdfLoader, UnnamedCollisionsAreNamedAfterTheirLinkAndPosition) {
  const UrdfScene urdf = SceneFromUrdf(Robot(
      kUnitInertial + "<collision><geometry><sphere radius=\"0.1\"/></geometry></collision>" +
      kBall + "<collision><geometry><sphere radius=\"0.2\"/></geometry></collision>"));
  ASSERT_EQ(urdf.scene.colliders.size(), 4u);
  EXPECT_EQ(urdf.scene.colliders[0].name, "b_collision1");
  EXPECT_EQ(urdf.scene.colliders[1].name, "ball");
  EXPECT_EQ(urdf.scene.colliders[2].name, "b_collision3");
}

TEST(UrdfLoader, ANameUsedTwiceIsAnErrorNamingBothLinks) {
  // on one link
  ExpectContains(LoadError(Robot(kUnitInertial + kBall + kBall)),
                 {"link \"b\" > collision \"ball\"", "also used by link \"b\""});
  // on two bodies
  const std::string two = World("", FloatingBall("one", "0 0 1", "ball") +
                                        FloatingBall("two", "1 0 1", "ball"));
  ExpectContains(LoadError(two), {"link \"two\" > collision \"ball\"", "also used by link \"one\"",
                                  "rename one"});
}

TEST(UrdfLoader, GroundIsAReservedNameUnlessTheGroundIsOff) {
  const std::string xml = Robot(
      kUnitInertial + "<collision name=\"ground\"><geometry><sphere radius=\"0.1\"/></geometry>"
                      "</collision>");
  ExpectContains(LoadError(xml), {"collision \"ground\"", "reserved for the ground plane"});
  UrdfSceneOptions options;
  options.ground = false;
  const UrdfScene urdf = SceneFromUrdf(xml, options);
  ASSERT_EQ(urdf.scene.colliders.size(), 1u);
  EXPECT_EQ(urdf.scene.colliders[0].shape.type, ShapeType::kSphere);
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

// --- collide functions ---------------------------------------------------------------------------

TEST(UrdfLoader, PairsWithoutACollideFunctionAreReported) {
  // a ball on a world box: reported with a table without the sphere-box pair, not with the
  // defaults; the scene carries the options' table
  const std::string xml = World(
      "<collision name=\"block\"><geometry><box size=\"1 1 1\"/></geometry></collision>",
      FloatingBall("ball", "0 0 2", "ball"));
  UrdfSceneOptions without_pair;
  without_pair.collision_table.Register(ShapeType::kSphere, ShapeType::kBox, nullptr);
  const UrdfScene missing = SceneFromUrdf(xml, without_pair);
  EXPECT_TRUE(HasWarning(missing, {"no collide function for sphere-box pairs", "\"ball\"",
                                   "\"block\""}));
  EXPECT_EQ(missing.scene.collision_table.Find(ShapeType::kSphere, ShapeType::kBox), nullptr);
  const UrdfScene with_pair = SceneFromUrdf(xml);
  EXPECT_FALSE(HasWarning(with_pair, {"no collide function"}));
  EXPECT_NE(with_pair.scene.collision_table.Find(ShapeType::kSphere, ShapeType::kBox), nullptr);
}

// --- errors --------------------------------------------------------------------------------------

const std::string kShellLink =
    kUnitInertial + "<collision name=\"shell\"><geometry><sphere radius=\"0.1\"/></geometry>"
                    "</collision>";
std::string Extension(const std::string& content, const std::string& link = "b") {
  return "<nonsmooth_sim reference=\"" + link + "\">" + content + "</nonsmooth_sim>";
}

TEST(UrdfLoader, DegenerateExtensionShapesAreErrors) {
  ExpectContains(
      LoadError(Robot(kShellLink, Extension("<collision name=\"shell\">"
                                            "<ellipsoid semi_axes=\"0.2 0 0.02\"/></collision>"))),
      {"nonsmooth_sim reference=\"b\" > collision \"shell\" > ellipsoid", "semi_axes",
       "must be > 0"});
  ExpectContains(
      LoadError(Robot(kShellLink, Extension("<collision name=\"shell\">"
                                            "<capsule radius=\"0.01\" length=\"-0.05\"/>"
                                            "</collision>"))),
      {"collision \"shell\" > capsule", "length=\"-0.05\" must be >= 0"});
  ExpectContains(
      LoadError(Robot(kShellLink, Extension("<collision name=\"shell\">"
                                            "<capsule radius=\"0\" length=\"0.05\"/>"
                                            "</collision>"))),
      {"collision \"shell\" > capsule", "radius=\"0\" must be > 0"});
  ExpectContains(
      LoadError(Robot(kShellLink, Extension("<collision name=\"shell\">"
                                            "<ellipsoid semi_axes=\"nan 1 1\"/></collision>"))),
      {"ellipsoid", "\"nan\" is not a finite number"});
  ExpectContains(LoadError(Robot(kShellLink, Extension("<collision name=\"shell\">"
                                                       "<capsule radius=\"0.01\"/></collision>"))),
                 {"capsule", "attribute length is missing"});
  // a zero-length capsule is a sphere: allowed
  EXPECT_NO_THROW(SceneFromUrdf(Robot(kShellLink, Extension("<collision name=\"shell\">"
                                                            "<capsule radius=\"0.01\" "
                                                            "length=\"0\"/></collision>"))));
}

TEST(UrdfLoader, DegenerateUrdfShapesAreErrors) {
  ExpectContains(
      LoadError(Robot(kUnitInertial + "<collision name=\"c\"><geometry>"
                                      "<cylinder radius=\"0.1\" length=\"-1\"/></geometry>"
                                      "</collision>")),
      {"link \"b\" > collision \"c\" > geometry > cylinder", "length=\"-1\" must be > 0"});
  ExpectContains(
      LoadError(Robot(kUnitInertial + "<collision name=\"c\"><geometry>"
                                      "<box size=\"0.1 0 0.1\"/></geometry></collision>")),
      {"collision \"c\" > geometry > box", "must be > 0"});
}

TEST(UrdfLoader, ExtensionTyposAreErrorsListingWhatIsAllowed) {
  ExpectContains(LoadError(Robot(kShellLink, Extension("<restitutoin>0.1</restitutoin>"))),
                 {"nonsmooth_sim reference=\"b\" > restitutoin", "unknown element <restitutoin>",
                  "allowed in <nonsmooth_sim>: <restitution>, <friction_set>, <collision"});
  ExpectContains(LoadError(Robot(kShellLink, Extension("<collision name=\"shell\">"
                                                       "<ellipsoid semiaxes=\"1 1 1\"/>"
                                                       "</collision>"))),
                 {"collision \"shell\" > ellipsoid", "unknown attribute \"semiaxes\"",
                  "allowed: semi_axes"});
  ExpectContains(LoadError(Robot(kShellLink, Extension("<collision name=\"shell\">"
                                                       "<cone radius=\"1\"/></collision>"))),
                 {"collision \"shell\" > cone", "unknown shape <cone>", "<ellipsoid",
                  "<capsule", "<plane/>"});
  ExpectContains(
      LoadError(Robot(kShellLink, Extension("<collision name=\"shel\">"
                                            "<ellipsoid semi_axes=\"1 1 1\"/></collision>"))),
      {"collision \"shel\"", "link \"b\" has no collision named \"shel\"",
       "its named collisions: \"shell\""});
  ExpectContains(LoadError(Robot(kShellLink, Extension("<restitution>0.1</restitution>", "bb"))),
                 {"nonsmooth_sim reference=\"bb\"", "no link named \"bb\"", "links: \"b\""});
  ExpectContains(LoadError(Robot(kShellLink, "<nonsmooth_sim reference=\"b\" link=\"b\"/>")),
                 {"unknown attribute \"link\"", "allowed: reference"});
  ExpectContains(LoadError(Robot(kShellLink, Extension("<friction_set>exakt</friction_set>"))),
                 {"friction_set", "\"exakt\" is not a friction set",
                  "allowed: coulomb, cylinder, ellipsoid, sphere, exact"});
  ExpectContains(LoadError(Robot(kShellLink, Extension("<collision name=\"shell\"/>"))),
                 {"collision \"shell\"", "no shape; expected one of"});
  ExpectContains(LoadError(Robot(kShellLink, Extension("<collision name=\"shell\"><plane/>"
                                                       "<plane/></collision>"))),
                 {"a second shape"});
  ExpectContains(
      LoadError(Robot(kShellLink, Extension("<collision name=\"shell\"><plane/></collision>") +
                                      Extension("<collision name=\"shell\"><ellipsoid "
                                                "semi_axes=\"1 1 1\"/></collision>"))),
      {"collision \"shell\"", "already given at"});
  ExpectContains(LoadError(Robot(kShellLink, Extension("<restitution>1.5</restitution>"))),
                 {"restitution", "out of range, expected [0, 1]"});
}

TEST(UrdfLoader, APlaneOnAFreeLinkIsAnError) {
  ExpectContains(
      LoadError(Robot(kShellLink, Extension("<collision name=\"shell\"><plane/></collision>"))),
      {"collision \"shell\" > plane", "a plane is a half-space fixed in the world",
       "link \"b\" is part of a free body", "allowed on free bodies: <ellipsoid>, <capsule>"});
}

TEST(UrdfLoader, AStaticLinkWithMassIsAnError) {
  const std::string xml = World(
      "", "<link name=\"table\">" + kUnitInertial + "</link>"
          "<joint name=\"world_table\" type=\"fixed\"><parent link=\"world\"/>"
          "<child link=\"table\"/></joint>" + FloatingBall("ball", "0 0 1", "ball"));
  ExpectContains(LoadError(xml), {"link \"table\" is fixed to the world link \"world\"",
                                  "static links have no mass; make it a floating joint or "
                                  "remove the inertial"});
}

TEST(UrdfLoader, AFreeLinkWithCollisionsButNoMassIsAnError) {
  const std::string xml =
      World("", "<link name=\"ghost\">" + kBall + "</link>"
                "<joint name=\"j\" type=\"floating\"><parent link=\"world\"/>"
                "<child link=\"ghost\"/></joint>");
  ExpectContains(LoadError(xml), {"link \"ghost\"", "no <inertial>"});
}

TEST(UrdfLoader, NoFreeBodyIsAnError) {
  ExpectContains(LoadError("<robot name=\"r\"><link name=\"world\"/></robot>"),
                 {"no free body", "root link \"world\" has no <inertial>"});
  // a root without mass is the static world, even with collisions (the old "no_inertial" case)
  ExpectContains(LoadError("<robot name=\"r\"><link name=\"tippe_top\">" + kBall +
                           "</link></robot>"),
                 {"link \"tippe_top\"", "no <inertial>"});
}

TEST(UrdfLoader, MalformedUrdfsGiveOneLineNamingElementAndReason) {
  const std::string inertial_head =
      "<inertial><mass value=\"6e-3\"/><inertia ixx=\"8e-7\" ixy=\"0\" ixz=\"0\" ";
  const std::string good_inertial = inertial_head + "iyy=\"8e-7\" iyz=\"0\" izz=\"7e-7\"/></inertial>";
  const std::string big =
      "<collision name=\"big_sphere\"><origin xyz=\"0 0 0.003\"/>"
      "<geometry><sphere radius=\"0.015\"/></geometry></collision>";
  const auto top = [](const std::string& body, const std::string& extra = "") {
    return "<robot name=\"t\"><link name=\"tippe_top\">" + body + "</link>" + extra + "</robot>";
  };
  struct Case {
    std::string xml;
    std::vector<std::string> expected;
  };
  const std::vector<Case> cases = {
      {"<robot name=\"broken\">\n<link name=\"tippe_top\">\n<inertial><mass value=\"6e-3\"/>\n"
       "</link>\n</robot>",
       {"not well-formed XML", "inertial"}},
      {"<model name=\"m\"/>", {"root element is <model>", "expected <robot>"}},
      {top("<inertial><mass value=\"-6e-3\"/><inertia ixx=\"8e-7\" ixy=\"0\" ixz=\"0\" "
           "iyy=\"8e-7\" iyz=\"0\" izz=\"7e-7\"/></inertial>" + big),
       {"link \"tippe_top\" > inertial > mass", "must be > 0"}},
      {top("<inertial><mass value=\"6e-3\"/><inertia ixx=\"1e-6\" ixy=\"2e-6\" ixz=\"0\" "
           "iyy=\"1e-6\" iyz=\"0\" izz=\"7e-7\"/></inertial>" + big),
       {"link \"tippe_top\" > inertial > inertia", "not positive definite"}},
      {top(good_inertial + "<collision name=\"big_sphere\"><geometry><sphere radius=\"0\"/>"
                           "</geometry></collision>"),
       {"collision \"big_sphere\" > geometry > sphere", "radius=\"0\"", "must be > 0"}},
      {top(good_inertial + "<collision name=\"peg_sphere\"><origin xyz=\"0 nan 0.016\"/>"
                           "<geometry><sphere radius=\"0.005\"/></geometry></collision>"),
       {"collision \"peg_sphere\" > origin", "\"nan\" is not a finite number"}},
      {top(inertial_head + "iyy=\"NaN\" iyz=\"0\" izz=\"7e-7\"/></inertial>" + big),
       {"inertial > inertia", "iyy", "\"NaN\" is not a finite number"}},
      {top(good_inertial + big,
           "<gazebo reference=\"tippe_top\"><collision><surface><friction><ode><mu>nan</mu>"
           "</ode></friction></surface></collision></gazebo>"),
       {"gazebo reference=\"tippe_top\"", "mu", "not a finite number"}},
      {top(good_inertial + "<visual><origin xyz=\"0 0 inf\"/><geometry><sphere radius=\"1\"/>"
                           "</geometry></visual>" + big),
       {"visual > origin", "\"inf\" is not a finite number"}},
  };
  // the pieces the cases are made of load when put together correctly
  EXPECT_NO_THROW(SceneFromUrdf(top(good_inertial + big)));
  for (const Case& c : cases) {
    const std::string message = LoadError(c.xml);
    for (const std::string& part : c.expected) {
      EXPECT_NE(message.find(part), std::string::npos) << "\"" << part << "\" not in: " << message;
    }
  }
}

// --- bounds: what loads is a simulable rigid body -------------------------------------

// An inertial of mass `mass` and principal moments `ixx iyy izz` (plus `extra` attributes, e.g.
// products of inertia, and an origin `xyz`).
std::string Inertial(const std::string& mass, const std::string& ixx, const std::string& iyy,
                     const std::string& izz,
                     const std::string& extra = "ixy=\"0\" ixz=\"0\" iyz=\"0\"",
                     const std::string& xyz = "0 0 0") {
  return "<inertial><origin xyz=\"" + xyz + "\"/><mass value=\"" + mass + "\"/><inertia ixx=\"" +
         ixx + "\" iyy=\"" + iyy + "\" izz=\"" + izz + "\" " + extra + "/></inertial>";
}
std::string Ball(const std::string& radius) {
  return "<collision name=\"ball\"><geometry><sphere radius=\"" + radius +
         "\"/></geometry></collision>";
}
// Gazebo friction tags of link "b".
std::string Friction(const std::string& mu, const std::string& coefficient = "1",
                     const std::string& patch_radius = "0") {
  return "<gazebo reference=\"b\"><collision><surface><friction><ode><mu>" + mu +
         "</mu></ode><torsional><coefficient>" + coefficient + "</coefficient><patch_radius>" +
         patch_radius + "</patch_radius></torsional></friction></surface></collision></gazebo>";
}

TEST(UrdfLoader, TheHostileMassAndInertialOriginAreRejectedAtTheDoor) {
  // both loaded before, and the first step threw "ContactProblem.G: must be finite"
  ExpectContains(LoadError(Robot(Inertial("4.9e-324", "1e-3", "1e-3", "1e-3") + kBall)),
                 {"link \"b\" > inertial > mass (line 1)", "value=\"4.9e-324\"",
                  "expected [1e-06, 1e+06] kg"});
  ExpectContains(LoadError(Robot(Inertial("1", "1e-3", "1e-3", "1e-3", "ixy=\"0\" ixz=\"0\" "
                                          "iyz=\"0\"", "0 0 1e300") + kBall)),
                 {"link \"b\" > inertial > origin", "xyz=\"0 0 1e300\"",
                  "expected [-1000, 1000] m"});
  // absurd: a million tonnes; the bounds themselves load
  ExpectContains(LoadError(Robot(Inertial("1e12", "1e9", "1e9", "1e9") + kBall)),
                 {"inertial > mass", "[1e-06, 1e+06] kg"});
  EXPECT_NO_THROW(SceneFromUrdf(Robot(Inertial("1e-6", "4e-12", "4e-12", "4e-12") + kBall)));
  EXPECT_NO_THROW(SceneFromUrdf(Robot(Inertial("1e6", "4e3", "4e3", "4e3") + kBall)));
  EXPECT_NO_THROW(SceneFromUrdf(Robot(Inertial("1", "1e-3", "1e-3", "1e-3", "ixy=\"0\" "
                                               "ixz=\"0\" iyz=\"0\"", "-1000 0 1000") + kBall)));
  // links merged into one body: the total counts
  const std::string heavy = Inertial("9e5", "1e5", "1e5", "1e5");
  ExpectContains(LoadError("<robot name=\"r\"><link name=\"b\">" + heavy + kBall + "</link>"
                           "<link name=\"c\">" + heavy + "</link><joint name=\"bc\" type=\"fixed\">"
                           "<parent link=\"b\"/><child link=\"c\"/></joint></robot>"),
                 {"link \"b\" (the body, with the links fixed to it)", "mass 1.8e+06 kg",
                  "[1e-06, 1e+06] kg"});
}

TEST(UrdfLoader, InertiaNoRigidBodyHasIsRejected) {
  // izz > ixx + iyy: the triangle inequality of the principal moments
  ExpectContains(LoadError(Robot(Inertial("1", "1e-3", "1e-3", "3e-3") + kBall)),
                 {"link \"b\" > inertial > inertia", "principal moments", "triangle inequality"});
  // the diagonal satisfies it, the principal moments (0.1, 1, 1.9) do not: eigenvalues count
  ExpectContains(LoadError(Robot(Inertial("1", "1e-3", "1e-3", "1e-3",
                                          "ixy=\"0.9e-3\" ixz=\"0\" iyz=\"0\"") + kBall)),
                 {"inertial > inertia", "triangle inequality"});
  // a flat body sits on the equality; rounded entries up to the tolerance (1e-3) load
  EXPECT_NO_THROW(SceneFromUrdf(Robot(Inertial("1", "1e-3", "2e-3", "3e-3") + kBall)));
  EXPECT_NO_THROW(SceneFromUrdf(Robot(Inertial("1", "1e-3", "2e-3", "3.002e-3") + kBall)));
  EXPECT_THROW(SceneFromUrdf(Robot(Inertial("1", "1e-3", "2e-3", "3.01e-3") + kBall)), UrdfError);
  // radii of gyration sqrt(I/m) outside [1e-6, 1e3] m
  ExpectContains(LoadError(Robot(Inertial("1", "1e-14", "1e-14", "1e-14") + kBall)),
                 {"inertial > inertia", "radii of gyration", "[1e-06, 1000] m"});
  ExpectContains(LoadError(Robot(Inertial("1", "1e7", "1e7", "1e7") + kBall)),
                 {"inertial > inertia", "radii of gyration", "[1e-06, 1000] m"});
  // and against the body's size: a 1 kg ball of radius 0.1 m cannot have sqrt(I/m) = 11 m
  ExpectContains(LoadError(Robot(Inertial("1", "121", "121", "121") + kBall)),
                 {"link \"b\" (the body)", "radius of gyration sqrt(I/m) = 11 m",
                  "100 x the body's extent 0.1 m"});
  EXPECT_NO_THROW(SceneFromUrdf(Robot(Inertial("1", "99", "99", "99") + kBall)));  // 9.95 m
}

TEST(UrdfLoader, PositionsAndSizesOutsideTheirRangesAreRejected) {
  ExpectContains(LoadError(World("", FloatingBall("b", "0 2000 0", "ball"))),
                 {"joint \"world_b\" > origin", "xyz=\"0 2000 0\"", "[-1000, 1000] m"});
  // each origin inside, their composition outside
  ExpectContains(
      LoadError(World("", "<link name=\"shelf\"/><joint name=\"ws\" type=\"fixed\">"
                          "<parent link=\"world\"/><child link=\"shelf\"/>"
                          "<origin xyz=\"900 0 0\"/></joint>" +
                              std::string("<link name=\"b\">") + kUnitInertial + kBall +
                              "</link><joint name=\"sb\" type=\"floating\"><parent link=\"shelf\"/>"
                              "<child link=\"b\"/><origin xyz=\"900 0 0\"/></joint>")),
      {"link \"b\": its start", "(1800, 0, 0) m", "[-1000, 1000] m"});
  // collision sizes in [1e-5, 1e3] m, in every shape
  ExpectContains(LoadError(Robot(kUnitInertial + Ball("1e-9"))),
                 {"collision \"ball\" > geometry > sphere", "radius=\"1e-9\"",
                  "expected [1e-05, 1000] m"});
  ExpectContains(LoadError(Robot(kUnitInertial + Ball("1e300"))), {"sphere", "[1e-05, 1000] m"});
  ExpectContains(LoadError(Robot(kUnitInertial + "<collision name=\"c\"><geometry><cylinder "
                                                 "radius=\"0.1\" length=\"2000\"/></geometry>"
                                                 "</collision>")),
                 {"cylinder", "length=\"2000\"", "[1e-05, 1000] m"});
  ExpectContains(LoadError(Robot(kUnitInertial + "<collision name=\"c\"><geometry><box "
                                                 "size=\"0.1 1e-6 0.1\"/></geometry></collision>")),
                 {"box", "size=\"0.1 1e-6 0.1\"", "[1e-05, 1000] m"});
  ExpectContains(
      LoadError(Robot(kShellLink, Extension("<collision name=\"shell\"><ellipsoid "
                                            "semi_axes=\"0.1 0.1 1e-6\"/></collision>"))),
      {"collision \"shell\" > ellipsoid", "[1e-05, 1000] m"});
  ExpectContains(LoadError(Robot(kShellLink, Extension("<collision name=\"shell\"><capsule "
                                                       "radius=\"0.1\" length=\"5e3\"/>"
                                                       "</collision>"))),
                 {"collision \"shell\" > capsule", "length=\"5e3\"", "[0, 1000] m"});
  // what is not simulated (a visual) is only required finite and positive
  EXPECT_NO_THROW(SceneFromUrdf(Robot(
      kUnitInertial + kBall + "<visual><geometry><sphere radius=\"1e-9\"/></geometry></visual>")));
}

TEST(UrdfLoader, FrictionAndContactRadiiOutsideTheirRangesAreRejected) {
  const std::string body = Robot(kUnitInertial + kBall, "%");
  const auto with = [&](const std::string& tags) {
    std::string xml = body;
    return xml.replace(xml.find('%'), 1, tags);
  };
  ExpectContains(LoadError(with(Friction("1e300"))),
                 {"gazebo reference=\"b\" > collision > surface > friction > ode > mu",
                  "1e300 is out of range, expected [0, 1000]"});
  ExpectContains(LoadError(with("<gazebo reference=\"b\"><mu1>5e3</mu1></gazebo>")),
                 {"mu1", "[0, 1000]"});
  ExpectContains(LoadError(with(Friction("0.5", "1e4"))), {"coefficient", "[0, 1000]"});
  ExpectContains(LoadError(with(Friction("0.5", "0.5", "1e4"))), {"patch_radius", "[0, 1000] m"});
  // the patch lies on the shape: R at most its bounding radius (the ball's 0.1 m)
  ExpectContains(LoadError(with(Friction("0.5", "0.5", "0.2"))),
                 {"link \"b\" > collision \"ball\"", "contact patch radius R = 0.2 m",
                  "<torsional><patch_radius>", "bounding radius 0.1 m"});
  UrdfSceneOptions options;
  options.contact_radius = 0.2;
  ExpectContains(LoadError(Robot(kUnitInertial + kBall), options),
                 {"collision \"ball\"", "the option contact_radius", "bounding radius 0.1 m"});
  options.contact_radius = 0.1;
  EXPECT_NO_THROW(SceneFromUrdf(Robot(kUnitInertial + kBall), options));
  // R̄ = 3πR/16·μ_τ/μ with a vanishing μ
  ExpectContains(LoadError(with(Friction("1e-12", "1000", "0.05"))),
                 {"collision \"ball\"", "drilling radius Rbar", "at most 1000 m"});
  EXPECT_NO_THROW(SceneFromUrdf(with(Friction("1000", "1000", "0.1"))));
}

TEST(UrdfLoader, OptionsBeyondTheirBoundsAreRejectedNamingTheBound) {
  const auto message = [](const UrdfSceneOptions& options) {
    try {
      ValidateUrdfSceneOptions(options);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    ADD_FAILURE() << "accepted";
    return std::string();
  };
  UrdfSceneOptions options;
  options.mu = 1e300;
  ExpectContains(message(options), {"mu", "[0, 1000]"});
  options = {};
  options.gravity = 1e300;
  ExpectContains(message(options), {"gravity", "[0, 1000]"});
  options = {};
  options.contact_radius = 1e300;
  ExpectContains(message(options), {"contact_radius", "[0, 1000]"});
  options = {};
  options.mu = 1000.0;
  options.gravity = 1000.0;
  options.contact_radius = 1000.0;
  EXPECT_NO_THROW(ValidateUrdfSceneOptions(options));
}

TEST(UrdfLoader, ScenesAtTheBoundsStepFinite) {
  // what loads can be simulated: bodies at the corners of the accepted ranges fall onto the
  // ground, bounce and roll for 2000 steps without an exception or a non-finite state
  struct Case {
    std::string name;
    std::string xml;
  };
  const auto ball = [](const std::string& mass, const std::string& moment,
                       const std::string& radius, const std::string& z,
                       const std::string& tags = "") {
    return "<robot name=\"r\"><link name=\"world\"/><link name=\"b\">" +
           Inertial(mass, moment, moment, moment) + Ball(radius) +
           "</link><joint name=\"wb\" type=\"floating\"><parent link=\"world\"/>"
           "<child link=\"b\"/><origin xyz=\"0 0 " + z + "\" rpy=\"0.3 0.2 0.1\"/></joint>" +
           tags + "</robot>";
  };
  const std::vector<Case> cases = {
      {"lightest, smallest", ball("1e-6", "4e-17", "1e-5", "2e-5")},
      {"heaviest, largest", ball("1e6", "4e11", "1000", "1000")},
      {"largest radius of gyration (100 x the ball)", ball("1", "0.99e4", "1", "1.5")},
      {"largest mu and patch, bouncing",
       ball("1", "4e-3", "0.1", "0.3",
            Friction("1000", "1000", "0.1") +
                "<nonsmooth_sim reference=\"b\"><restitution>1</restitution></nonsmooth_sim>")},
      {"largest drilling radius",
       ball("1", "4e-3", "0.1", "0.1",
            "<gazebo reference=\"b\"><collision><surface><friction><ode><mu>0.06</mu></ode>"
            "<torsional><coefficient>1000</coefficient><patch_radius>0.1</patch_radius>"
            "</torsional></friction></surface></collision></gazebo>")},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    UrdfSceneOptions options;
    options.gravity = 1000.0;
    UrdfScene urdf;
    ASSERT_NO_THROW(urdf = SceneFromUrdf(c.xml, options));
    urdf.scene.initial_state[0].linear_velocity = Eigen::Vector3d(1000.0, 0.0, -1000.0);
    urdf.scene.initial_state[0].angular_velocity = Eigen::Vector3d(0.0, 1e4, 0.0);
    SimulatorOptions settings;
    settings.gyroscopic = GyroscopicScheme::kImplicitMidpoint;
    Simulator sim(urdf.scene, settings);
    int contact_steps = 0;
    for (int k = 0; k < 2000; ++k) {
      StepStatistics stats;
      ASSERT_NO_THROW(stats = sim.Step()) << "step " << k;
      ASSERT_TRUE(stats.state_finite) << "step " << k;
      contact_steps += stats.closed_contacts > 0 ? 1 : 0;
    }
    EXPECT_GT(contact_steps, 0);
    EXPECT_TRUE(std::isfinite(MechanicalEnergy(urdf.scene, sim.state())));
  }
}

TEST(UrdfLoader, MissingAndBadFilesNameThePath) {
  try {
    LoadUrdfFile("/nonexistent/robot.urdf");
    FAIL() << "no exception";
  } catch (const UrdfError& e) {
    ExpectContains(e.what(), {"urdf: /nonexistent/robot.urdf: no such file"});
  }
  const std::string path = ::testing::TempDir() + "/scene_io_bad.urdf";
  std::ofstream(path) << "<robot name=\"r\"><link name=\"world\"/></robot>";
  try {
    LoadUrdfFile(path);
    FAIL() << "no exception";
  } catch (const UrdfError& e) {
    ExpectContains(e.what(), {"urdf: " + path + ": no free body"});
  }
}

TEST(UrdfLoader, OptionsOutOfRangeAreRejected) {
  UrdfSceneOptions options;
  options.mu = -0.1;
  EXPECT_THROW(SceneFromUrdf(Robot(kUnitInertial + kBall), options), std::invalid_argument);
  options = {};
  options.gravity = std::nan("");
  EXPECT_THROW(ValidateUrdfSceneOptions(options), std::invalid_argument);
  options = {};
  options.contact_radius = -1.0;
  EXPECT_THROW(ValidateUrdfSceneOptions(options), std::invalid_argument);
}

}  // namespace
}  // namespace nonsmooth_sim::scene_io
