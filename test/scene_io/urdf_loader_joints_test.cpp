// URDF -> Scene, the root and the joints the simulator does not model: a massless root with mass
// fixed below it (`base_footprint` above `base_link`) is one free body whose mass, centre of mass
// and inertia match a hand computation with the reduced mass; a link with mass or collisions on a
// joint that can move is refused with one line naming the joint, its type and the link; a
// revolute or prismatic joint with lower = upper is held where it is and merged with a warning;
// a massless, collision-free link on a moving joint is left out with a warning.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "urdf_fixtures.h"

namespace nonsmooth_sim::scene_io {
namespace {

using namespace urdf_test;  // NOLINT

// A link of mass `mass` with its centre of mass at `com` (link frame), the diagonal inertia
// `moments` ("ixx iyy izz") about it, and a sphere collision there (every pair of spheres, and a
// sphere and the ground, has a collide function: no warning about a missing one).
std::string MassiveLink(const std::string& name, const std::string& com, const std::string& mass,
                        const std::string& moments, const std::string& collision) {
  std::string ixx, iyy, izz;
  std::istringstream(moments) >> ixx >> iyy >> izz;
  return "<link name=\"" + name + "\"><inertial><origin xyz=\"" + com + "\"/><mass value=\"" +
         mass + "\"/><inertia ixx=\"" + ixx + "\" ixy=\"0\" ixz=\"0\" iyy=\"" + iyy +
         "\" iyz=\"0\" izz=\"" + izz + "\"/></inertial><collision name=\"" + collision +
         "\"><origin xyz=\"" + com + "\"/><geometry><sphere radius=\"0.02\"/></geometry>"
         "</collision></link>";
}

// Two rigid parts combined, by hand: the centre of mass c = c1 + (m2/m)(c2 − c1), and about it
// the parts' own inertias plus the reduced mass μ = m1 m2 / m times (|r|² 1 − r rᵀ), r = c2 − c1
// (the two-body form of the parallel-axis theorem; the loader sums over the parts instead).
struct ByHand {
  Eigen::Vector3d com;
  Eigen::Matrix3d inertia;
};
ByHand CombinedByHand(double m1, const Eigen::Vector3d& c1, const Eigen::Matrix3d& theta1,
                      double m2, const Eigen::Vector3d& c2, const Eigen::Matrix3d& theta2) {
  const double m = m1 + m2;
  const Eigen::Vector3d r = c2 - c1;
  const double mu = m1 * m2 / m;
  return {c1 + (m2 / m) * r,
          theta1 + theta2 +
              mu * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose())};
}

std::string Joint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child, const std::string& inside = "") {
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/>" + inside + "</joint>";
}

// --- the massless root of exporters --------------------------------------------------------------

// base_footprint (no inertial) -fixed (0, 0, 0.1)-> base_link: m1 = 5 at (0.01, 0, 0.02) in its
// frame, Θ1 = diag(0.05, 0.06, 0.07) -fixed (0.1, 0.05, 0.08), turned 90° about z-> imu_link:
// m2 = 0.05 at its origin, Θ2 = diag(1, 2, 3)e-5 in imu axes.
const std::string kBaseFootprintRobot =
    "<robot name=\"bot\"><link name=\"base_footprint\"/>" +
    MassiveLink("base_link", "0.01 0 0.02", "5", "0.05 0.06 0.07", "chassis") +
    MassiveLink("imu_link", "0 0 0", "0.05", "1e-5 2e-5 3e-5", "imu_case") +
    Joint("base_joint", "fixed", "base_footprint", "base_link", "<origin xyz=\"0 0 0.1\"/>") +
    Joint("imu_joint", "fixed", "base_link", "imu_link",
          "<origin xyz=\"0.1 0.05 0.08\" rpy=\"0 0 1.5707963267948966\"/>") +
    "</robot>";

TEST(UrdfLoaderJoints, AMasslessRootWithMassFixedBelowIsOneBodyByTheParallelAxisTheorem) {
  const UrdfScene urdf = SceneFromUrdf(kBaseFootprintRobot);
  // Gazebo lumps this root silently: no warning either
  EXPECT_TRUE(urdf.warnings.empty()) << urdf.warnings.front();
  ASSERT_EQ(urdf.scene.bodies.size(), 1u);
  const RigidBody& body = urdf.scene.bodies[0];
  EXPECT_EQ(body.name, "base_footprint");
  EXPECT_EQ(urdf.merged_links[0], (std::vector<std::string>{"base_link", "imu_link"}));

  // by hand, in base_footprint's frame: c1 = (0.01, 0, 0.12), c2 = (0.1, 0.05, 0.18); about the
  // common centre of mass the two point masses add the reduced mass μ = m1 m2 / m times
  // (|r|² 1 − r rᵀ), r = c2 − c1; Θ2 turned by 90° about z swaps its x and y moments
  const Eigen::Vector3d c1(0.01, 0.0, 0.12), c2(0.1, 0.05, 0.18);
  const ByHand expected = CombinedByHand(
      5.0, c1, Eigen::Vector3d(0.05, 0.06, 0.07).asDiagonal(), 0.05, c2,
      Eigen::Vector3d(2e-5, 1e-5, 3e-5).asDiagonal());
  EXPECT_DOUBLE_EQ(body.mass, 5.05);
  const Eigen::Vector3d c = expected.com;
  EXPECT_LT((body.com_in_link - c).norm(), 1e-16) << body.com_in_link.transpose();
  EXPECT_LT((body.inertia - expected.inertia).norm(), 1e-16) << body.inertia;

  // both collisions on the body, relative to its centre of mass; no world collider but the ground
  ASSERT_EQ(urdf.scene.colliders.size(), 3u);  // chassis, imu_case, ground
  EXPECT_EQ(urdf.scene.colliders[0].name, "chassis");
  EXPECT_EQ(urdf.scene.colliders[0].body, 0);
  EXPECT_LT((urdf.scene.colliders[0].pose.translation() - (c1 - c)).norm(), 1e-16);
  EXPECT_EQ(urdf.scene.colliders[1].name, "imu_case");
  EXPECT_EQ(urdf.scene.colliders[1].body, 0);
  EXPECT_LT((urdf.scene.colliders[1].pose.translation() - (c2 - c)).norm(), 1e-16);
  EXPECT_EQ(urdf.scene.colliders[2].name, "ground");
  // it starts at its URDF pose (the root at the origin), the links below it for TF on the body
  EXPECT_LT((urdf.scene.initial_state[0].position - c).norm(), 1e-16);
  ASSERT_EQ(urdf.fixed_links.size(), 2u);
  EXPECT_EQ(urdf.fixed_links[0].name, "base_link");
  EXPECT_EQ(urdf.fixed_links[0].body, 0);
  EXPECT_EQ(urdf.fixed_links[0].pose.translation(), Eigen::Vector3d(0.0, 0.0, 0.1));
}

TEST(UrdfLoaderJoints, AFloatingChildOfALumpedRootIsABodyOfItsOwn) {
  std::string xml = kBaseFootprintRobot;
  xml.insert(xml.find("</robot>"),
             MassiveLink("ball", "0 0 0", "2", "1 1 1", "ball_shell") +
                 Joint("throw", "floating", "base_footprint", "ball", "<origin xyz=\"1 0 0.5\"/>"));
  const UrdfScene urdf = SceneFromUrdf(xml);
  ASSERT_EQ(urdf.scene.bodies.size(), 2u);
  EXPECT_EQ(urdf.scene.bodies[0].name, "base_footprint");
  EXPECT_DOUBLE_EQ(urdf.scene.bodies[0].mass, 5.05);  // the ball is not lumped
  EXPECT_EQ(urdf.scene.bodies[1].name, "ball");
  EXPECT_EQ(urdf.scene.bodies[1].mass, 2.0);
  EXPECT_EQ(urdf.scene.initial_state[1].position, Eigen::Vector3d(1.0, 0.0, 0.5));
}

TEST(UrdfLoaderJoints, AMasslessRootWithMasslessLinksFixedBelowStaysTheStaticWorld) {
  // a table (collision, no mass) fixed to the root "floor": static, the ball the only body
  const std::string xml =
      "<robot name=\"r\"><link name=\"floor\"/><link name=\"table\"><collision name=\"top\">"
      "<origin xyz=\"0 0 0.3\"/><geometry><box size=\"1 1 0.02\"/></geometry></collision></link>" +
      Joint("floor_table", "fixed", "floor", "table") +
      MassiveLink("ball", "0 0 0", "2", "1 1 1", "ball_shell") +
      Joint("throw", "floating", "floor", "ball", "<origin xyz=\"0 0 1\"/>") + "</robot>";
  const UrdfScene urdf = SceneFromUrdf(xml);
  ASSERT_EQ(urdf.scene.bodies.size(), 1u);
  EXPECT_EQ(urdf.scene.bodies[0].name, "ball");
  EXPECT_EQ(urdf.scene.colliders[0].name, "top");
  EXPECT_EQ(urdf.scene.colliders[0].body, kWorld);
}

TEST(UrdfLoaderJoints, TheRootNamedWorldIsNeverABody) {
  // a mass fixed to "world" is a static link with mass (Gazebo and Drake: "world" is the world)
  const std::string xml = World(
      "", MassiveLink("table", "0 0 0", "2", "1 1 1", "top") +
              Joint("world_table", "fixed", "world", "table") +
              FloatingBall("ball", "0 0 1", "ball"));
  ExpectContains(LoadError(xml), {"link \"table\" is fixed to the world link \"world\"",
                                  "static links have no mass"});
}

// --- joints that move: refused when they carry something ----------------------------------------

// The gyroscope toy of issue 32: a frame standing on its tip (0.03 kg) and a rotor (0.10 kg) on
// the joint `rotor_joint` of type `type`.
std::string Gyroscope(const std::string& type, const std::string& limit = "") {
  return "<robot name=\"gyroscope\">" +
         MassiveLink("frame", "0 0 0.03", "0.03", "2e-5 2e-5 1e-5", "tip") +
         MassiveLink("rotor", "0 0 0", "0.10", "2e-5 2e-5 4e-5", "disc") +
         Joint("rotor_joint", type, "frame", "rotor",
               "<origin xyz=\"0 0 0.04\"/><axis xyz=\"0 0 1\"/>" + limit) +
         "</robot>";
}

TEST(UrdfLoaderJoints, ARotorOnAContinuousJointIsRefusedNamingTheJointAndWhatToDo) {
  ExpectContains(LoadError(Gyroscope("continuous")),
                 {"urdf: joint \"rotor_joint\" (continuous) moves link \"rotor\"",
                  "carries 0.1 kg and 1 collision", "the simulator has no joints",
                  "make it fixed to merge the link into its parent, or floating to make it a "
                  "body of its own",
                  // and the opt-in that needs no edit of the joint
                  "or hold it rigid without editing it: <nonsmooth_sim joint=\"rotor_joint\">"
                  "<hold/></nonsmooth_sim>, or the loader option hold_joints"});
}

TEST(UrdfLoaderJoints, TheRotorOnAFixedJointMergesWithTheTotalMass) {
  const UrdfScene urdf = SceneFromUrdf(Gyroscope("fixed"));
  EXPECT_TRUE(urdf.warnings.empty()) << urdf.warnings.front();
  ASSERT_EQ(urdf.scene.bodies.size(), 1u);
  EXPECT_EQ(urdf.scene.bodies[0].name, "frame");
  EXPECT_DOUBLE_EQ(urdf.scene.bodies[0].mass, 0.13);  // frame 0.03 + rotor 0.10
  EXPECT_EQ(urdf.merged_links[0], std::vector<std::string>{"rotor"});
  // c = (0.03·0.03 + 0.10·0.04)/0.13 on z
  EXPECT_NEAR(urdf.scene.bodies[0].com_in_link.z(), (0.03 * 0.03 + 0.10 * 0.04) / 0.13, 1e-17);
}

TEST(UrdfLoaderJoints, EveryMovingJointTypeWithMassOrCollisionsIsRefused) {
  const std::string limit = "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>";
  for (const std::string type : {"revolute", "prismatic"}) {
    // a joint that can move within its limits: the hint names the rule that merges
    ExpectContains(LoadError(Gyroscope(type, limit)),
                   {"joint \"rotor_joint\" (" + type + ") moves link \"rotor\"",
                    "(a joint with lower = upper cannot move and is merged as fixed)"});
  }
  const std::string planar = LoadError(Gyroscope("planar"));
  ExpectContains(planar, {"joint \"rotor_joint\" (planar) moves link \"rotor\""});
  EXPECT_EQ(planar.find("lower = upper"), std::string::npos) << planar;

  // a collision alone (no mass), and mass on a link fixed to the moving one, count too
  const std::string ghost =
      "<robot name=\"r\">" + MassiveLink("b", "0 0 0", "2", "1 1 1", "core") +
      "<link name=\"wheel\"><collision name=\"rim\"><geometry><sphere radius=\"0.1\"/>"
      "</geometry></collision></link>" + Joint("spin", "continuous", "b", "wheel") + "</robot>";
  ExpectContains(LoadError(ghost), {"joint \"spin\" (continuous) moves link \"wheel\"",
                                    "carries 1 collision,"});
  const std::string hub =
      "<robot name=\"r\">" + MassiveLink("b", "0 0 0", "2", "1 1 1", "core") +
      "<link name=\"hub\"/>" + MassiveLink("weight", "0 0 0", "0.5", "1e-3 1e-3 1e-3", "w") +
      Joint("spin", "continuous", "b", "hub") + Joint("hub_weight", "fixed", "hub", "weight") +
      "</robot>";
  ExpectContains(LoadError(hub), {"joint \"spin\" (continuous) moves link \"hub\"",
                                  "carries 0.5 kg and 1 collision with the links fixed to it"});
}

TEST(UrdfLoaderJoints, AMovingJointBelowTheStaticWorldIsRefused) {
  const std::string xml = World(
      "", MassiveLink("door", "0 0 0", "2", "1 1 1", "panel") +
              Joint("hinge", "continuous", "world", "door") +
              FloatingBall("ball", "0 0 1", "ball"));
  ExpectContains(LoadError(xml), {"joint \"hinge\" (continuous) moves link \"door\""});
}

// --- joints that cannot move: held where they are, with a warning -------------------------------

TEST(UrdfLoaderJoints, ARevoluteJointWithEqualLimitsMergesAtThatAngleWithAWarning) {
  // frame -revolute held at π/2 about z, origin (0, 0, 0.04)-> rotor, whose centre of mass is at
  // (0.01, 0, 0) in its own frame: turned to (0, 0.01, 0.04) in the frame's
  const std::string held = "<limit lower=\"1.5707963267948966\" upper=\"1.5707963267948966\" "
                           "effort=\"1\" velocity=\"1\"/>";
  std::string xml = Gyroscope("revolute", held);
  xml.replace(xml.find("<origin xyz=\"0 0 0\"/>"), 21, "<origin xyz=\"0.01 0 0\"/>");
  const UrdfScene urdf = SceneFromUrdf(xml);
  ASSERT_EQ(urdf.warnings.size(), 1u);
  ExpectContains(urdf.warnings[0],
                 {"urdf: joint \"rotor_joint\" (revolute) has lower = upper = 1.5708 rad",
                  "cannot move", "link \"rotor\" is merged into its parent link \"frame\"",
                  "as if the joint were fixed there"});
  ASSERT_EQ(urdf.scene.bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(urdf.scene.bodies[0].mass, 0.13);  // the rotor's mass is kept
  const Eigen::Vector3d expected =
      (0.03 * Eigen::Vector3d(0.0, 0.0, 0.03) + 0.10 * Eigen::Vector3d(0.0, 0.01, 0.04)) / 0.13;
  EXPECT_LT((urdf.scene.bodies[0].com_in_link - expected).norm(), 1e-17);
  // the rotor's frame for TF, turned by the held angle
  ASSERT_EQ(urdf.fixed_links.size(), 1u);
  EXPECT_LT((urdf.fixed_links[0].pose.linear() - Rpy(0.0, 0.0, kPi / 2)).norm(), 1e-15);
}

TEST(UrdfLoaderJoints, APrismaticJointWithEqualLimitsIsHeldAtItsShift) {
  // a shelf on a prismatic joint held at 0.2 m along y below the static world: a static collider
  const std::string xml = World(
      "", "<link name=\"shelf\"><collision name=\"board\"><geometry><box size=\"1 1 0.02\"/>"
          "</geometry></collision></link>" +
              Joint("slide", "prismatic", "world", "shelf",
                    "<origin xyz=\"0 0 0.5\"/><axis xyz=\"0 2 0\"/>"
                    "<limit lower=\"0.2\" upper=\"0.2\" effort=\"1\" velocity=\"1\"/>") +
              FloatingBall("ball", "0 0 1", "ball"));
  const UrdfScene urdf = SceneFromUrdf(xml);
  ASSERT_EQ(urdf.warnings.size(), 1u);
  ExpectContains(urdf.warnings[0], {"joint \"slide\" (prismatic) has lower = upper = 0.2 m"});
  EXPECT_EQ(urdf.scene.colliders[0].name, "board");
  EXPECT_EQ(urdf.scene.colliders[0].body, kWorld);
  // the axis is normalised: 0.2 m along y, not 0.4
  EXPECT_LT((urdf.scene.colliders[0].pose.translation() - Eigen::Vector3d(0.0, 0.2, 0.5)).norm(),
            1e-16);
}

TEST(UrdfLoaderJoints, ALimitWithoutLowerAndUpperHoldsTheJointAtZero) {
  // URDF's lower and upper default to 0: the rotor cannot turn, so it is merged, mass kept
  const UrdfScene urdf =
      SceneFromUrdf(Gyroscope("revolute", "<limit effort=\"1\" velocity=\"1\"/>"));
  ASSERT_EQ(urdf.warnings.size(), 1u);
  ExpectContains(urdf.warnings[0], {"joint \"rotor_joint\" (revolute) has lower = upper = 0 rad"});
  EXPECT_DOUBLE_EQ(urdf.scene.bodies[0].mass, 0.13);
}

TEST(UrdfLoaderJoints, AJointHeldAwayFromZeroNeedsAnAxis) {
  std::string xml = Gyroscope(
      "revolute", "<limit lower=\"0.3\" upper=\"0.3\" effort=\"1\" velocity=\"1\"/>");
  xml.replace(xml.find("<axis xyz=\"0 0 1\"/>"), 19, "<axis xyz=\"0 0 0\"/>");
  ExpectContains(LoadError(xml), {"joint \"rotor_joint\" (revolute) > axis: xyz=\"0 0 0\"",
                                  "gives no direction to hold the joint at 0.3"});
}

// --- joints that move but carry nothing ---------------------------------------------------------

TEST(UrdfLoaderJoints, AMasslessLinkWithoutCollisionsOnAMovingJointIsLeftOutWithAWarning) {
  // b -revolute-> c (no mass, no collision: left out) -floating-> d (a body again)
  const std::string xml =
      "<robot name=\"r\">" + MassiveLink("b", "0 0 0", "2", "1 1 1", "core") +
      "<link name=\"c\"/>" + MassiveLink("d", "0 0 0", "2", "1 1 1", "ball_d") +
      Joint("bc", "revolute", "b", "c",
            "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>") +
      Joint("cd", "floating", "c", "d", "<origin xyz=\"2 0 0\"/>") + "</robot>";
  const UrdfScene urdf = SceneFromUrdf(xml);
  ASSERT_EQ(urdf.scene.bodies.size(), 2u);
  EXPECT_EQ(urdf.scene.bodies[1].name, "d");
  EXPECT_EQ(urdf.scene.initial_state[1].position, Eigen::Vector3d(2.0, 0.0, 0.0));
  ASSERT_EQ(urdf.warnings.size(), 1u);
  ExpectContains(urdf.warnings[0], {"link \"c\" hangs on joint \"bc\" (revolute)",
                                    "no mass and no collision", "left out"});
  for (const FixedLink& link : urdf.fixed_links) EXPECT_NE(link.name, "c");
}

// --- moving joints the user holds rigid (<nonsmooth_sim joint><hold>, the option hold_joints) ----

// `xml` with `extra` added before </robot>.
std::string With(std::string xml, const std::string& extra) {
  xml.insert(xml.find("</robot>"), extra);
  return xml;
}

std::string HoldBlock(const std::string& joint, const std::string& hold = "<hold/>") {
  return "<nonsmooth_sim joint=\"" + joint + "\">" + hold + "</nonsmooth_sim>";
}

UrdfSceneOptions Holding(std::vector<std::string> joints) {
  UrdfSceneOptions options;
  options.hold_joints = std::move(joints);
  return options;
}

TEST(UrdfLoaderHold, TheGyroscopesRotorHeldOnItsContinuousJointIsOneBodyByTheParallelAxisTheorem) {
  const UrdfScene urdf = SceneFromUrdf(With(Gyroscope("continuous"), HoldBlock("rotor_joint")));
  ASSERT_EQ(urdf.warnings.size(), 1u);
  ExpectContains(urdf.warnings[0],
                 {"urdf: joint \"rotor_joint\" (continuous) is held rigid at 0 rad by "
                  "<nonsmooth_sim joint=\"rotor_joint\"> (line 1): its link \"rotor\" (0.1 kg and "
                  "1 collision) is merged into its parent link \"frame\"; the simulator has no "
                  "joints"});
  ASSERT_EQ(urdf.scene.bodies.size(), 1u);
  const RigidBody& body = urdf.scene.bodies[0];
  EXPECT_EQ(body.name, "frame");
  EXPECT_DOUBLE_EQ(body.mass, 0.13);  // frame 0.03 + rotor 0.10
  EXPECT_EQ(urdf.merged_links[0], std::vector<std::string>{"rotor"});
  // by hand: the frame's centre of mass at (0, 0, 0.03), the rotor's at the joint (0, 0, 0.04)
  const ByHand expected = CombinedByHand(
      0.03, Eigen::Vector3d(0.0, 0.0, 0.03), Eigen::Vector3d(2e-5, 2e-5, 1e-5).asDiagonal(), 0.10,
      Eigen::Vector3d(0.0, 0.0, 0.04), Eigen::Vector3d(2e-5, 2e-5, 4e-5).asDiagonal());
  EXPECT_LT((body.com_in_link - expected.com).norm(), 1e-17) << body.com_in_link.transpose();
  EXPECT_LT((body.inertia - expected.inertia).norm(), 1e-19) << body.inertia;
  // μ = 0.03·0.1/0.13, r = 0.01 m: the equatorial moments gain μ r² = 2.3e-6 kg m² over the sum
  EXPECT_NEAR(body.inertia(0, 0), 4e-5 + 0.003 / 0.13 * 1e-4, 1e-19);
  EXPECT_NEAR(body.inertia(2, 2), 5e-5, 1e-19);
  // both collisions on the body, the rotor in TF as a fixed link at the joint
  EXPECT_EQ(urdf.scene.colliders[1].name, "disc");
  EXPECT_EQ(urdf.scene.colliders[1].body, 0);
  ASSERT_EQ(urdf.fixed_links.size(), 1u);
  EXPECT_EQ(urdf.fixed_links[0].name, "rotor");
  EXPECT_EQ(urdf.fixed_links[0].body, 0);
  EXPECT_EQ(urdf.fixed_links[0].pose.translation(), Eigen::Vector3d(0.0, 0.0, 0.04));
}

// Everything a scene is made of, compared exactly.
void ExpectSameScene(const UrdfScene& a, const UrdfScene& b) {
  ASSERT_EQ(a.scene.bodies.size(), b.scene.bodies.size());
  for (std::size_t i = 0; i < a.scene.bodies.size(); ++i) {
    EXPECT_EQ(a.scene.bodies[i].name, b.scene.bodies[i].name);
    EXPECT_EQ(a.scene.bodies[i].mass, b.scene.bodies[i].mass);
    EXPECT_EQ(a.scene.bodies[i].inertia, b.scene.bodies[i].inertia);
    EXPECT_EQ(a.scene.bodies[i].com_in_link, b.scene.bodies[i].com_in_link);
    EXPECT_EQ(a.scene.initial_state[i].position, b.scene.initial_state[i].position);
    EXPECT_EQ(a.scene.initial_state[i].orientation.coeffs(),
              b.scene.initial_state[i].orientation.coeffs());
  }
  ASSERT_EQ(a.scene.colliders.size(), b.scene.colliders.size());
  for (std::size_t i = 0; i < a.scene.colliders.size(); ++i) {
    EXPECT_EQ(a.scene.colliders[i].name, b.scene.colliders[i].name);
    EXPECT_EQ(a.scene.colliders[i].body, b.scene.colliders[i].body);
    EXPECT_EQ(a.scene.colliders[i].pose.matrix(), b.scene.colliders[i].pose.matrix());
  }
  EXPECT_EQ(a.merged_links, b.merged_links);
  ASSERT_EQ(a.fixed_links.size(), b.fixed_links.size());
  for (std::size_t i = 0; i < a.fixed_links.size(); ++i) {
    EXPECT_EQ(a.fixed_links[i].name, b.fixed_links[i].name);
    EXPECT_EQ(a.fixed_links[i].pose.matrix(), b.fixed_links[i].pose.matrix());
  }
}

TEST(UrdfLoaderHold, TheOptionAndTheBlockGiveTheSameScene) {
  const UrdfScene by_block =
      SceneFromUrdf(With(Gyroscope("continuous"), HoldBlock("rotor_joint")));
  const UrdfScene by_option = SceneFromUrdf(Gyroscope("continuous"), Holding({"rotor_joint"}));
  ExpectSameScene(by_block, by_option);
  ASSERT_EQ(by_option.warnings.size(), 1u);
  ExpectContains(by_option.warnings[0],
                 {"joint \"rotor_joint\" (continuous) is held rigid at 0 rad by the option "
                  "hold_joints: its link \"rotor\""});
  // the same as a fixed joint: the held joint is exactly the merge the user could have written
  ExpectSameScene(by_option, SceneFromUrdf(Gyroscope("fixed")));
}

TEST(UrdfLoaderHold, TheOptionOnAJointTheBlockPositionsHoldsItAtTheBlocksPosition) {
  const std::string xml = With(Gyroscope("continuous"),
                               HoldBlock("rotor_joint", "<hold position=\"0.3\"/>"));
  const UrdfScene both = SceneFromUrdf(xml, Holding({"rotor_joint", "rotor_joint"}));
  ExpectSameScene(both, SceneFromUrdf(xml));
  ASSERT_EQ(both.warnings.size(), 1u);
  ExpectContains(both.warnings[0],
                 {"held rigid at 0.3 rad by <nonsmooth_sim joint=\"rotor_joint\"> (line 1) and "
                  "the option hold_joints:"});
  ASSERT_EQ(both.fixed_links.size(), 1u);
  EXPECT_LT((both.fixed_links[0].pose.linear() - Rpy(0.0, 0.0, 0.3)).norm(), 1e-15);
}

TEST(UrdfLoaderHold, ARevoluteJointHeldAtAnAngleMovesTheCentreOfMassAsComputedByHand) {
  // the rotor's centre of mass 0.02 m off its axis, its inertia not round about it: held at
  // 0.5 rad about z (the axis given unnormalised) both turn
  const std::string xml =
      "<robot name=\"gyroscope\">" +
      MassiveLink("frame", "0 0 0.03", "0.03", "2e-5 2e-5 1e-5", "tip") +
      MassiveLink("rotor", "0.02 0 0", "0.10", "1e-5 3e-5 3.5e-5", "disc") +
      Joint("rotor_joint", "revolute", "frame", "rotor",
            "<origin xyz=\"0 0 0.04\"/><axis xyz=\"0 0 3\"/>"
            "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>") +
      HoldBlock("rotor_joint", "<hold position=\"0.5\"/>") + "</robot>";
  const UrdfScene urdf = SceneFromUrdf(xml);
  ASSERT_EQ(urdf.warnings.size(), 1u);
  ExpectContains(urdf.warnings[0], {"joint \"rotor_joint\" (revolute) is held rigid at 0.5 rad"});
  ASSERT_EQ(urdf.scene.bodies.size(), 1u);
  const Eigen::Matrix3d turn = Rpy(0.0, 0.0, 0.5);
  const ByHand expected = CombinedByHand(
      0.03, Eigen::Vector3d(0.0, 0.0, 0.03), Eigen::Vector3d(2e-5, 2e-5, 1e-5).asDiagonal(), 0.10,
      Eigen::Vector3d(0.02 * std::cos(0.5), 0.02 * std::sin(0.5), 0.04),
      turn * Eigen::Vector3d(1e-5, 3e-5, 3.5e-5).asDiagonal() * turn.transpose());
  const RigidBody& body = urdf.scene.bodies[0];
  EXPECT_DOUBLE_EQ(body.mass, 0.13);
  EXPECT_LT((body.com_in_link - expected.com).norm(), 1e-17) << body.com_in_link.transpose();
  EXPECT_GT(body.com_in_link.y(), 1e-3);  // the turn moved it off the xz plane
  EXPECT_LT((body.inertia - expected.inertia).norm(), 1e-19) << body.inertia;
  EXPECT_GT(std::abs(body.inertia(0, 1)), 1e-7);  // and turned the rotor's inertia
}

TEST(UrdfLoaderHold, APrismaticJointHeldAtAShiftMovesTheLinkAlongItsAxis) {
  const std::string xml = With(
      Gyroscope("prismatic", "<limit lower=\"-0.1\" upper=\"0.1\" effort=\"1\" velocity=\"1\"/>"),
      HoldBlock("rotor_joint", "<hold position=\"0.05\"/>"));
  const UrdfScene urdf = SceneFromUrdf(xml);
  ASSERT_EQ(urdf.warnings.size(), 1u);
  ExpectContains(urdf.warnings[0], {"joint \"rotor_joint\" (prismatic) is held rigid at 0.05 m"});
  // the rotor 0.05 m up its z axis: at (0, 0, 0.09)
  EXPECT_NEAR(urdf.scene.bodies[0].com_in_link.z(), (0.03 * 0.03 + 0.10 * 0.09) / 0.13, 1e-16);
  EXPECT_LT((urdf.fixed_links[0].pose.translation() - Eigen::Vector3d(0.0, 0.0, 0.09)).norm(),
            1e-16);
}

TEST(UrdfLoaderHold, APlanarJointIsHeldOnlyAtItsZeroPosition) {
  for (const std::string hold : {"<hold/>", "<hold position=\"0\"/>"}) {
    const UrdfScene urdf =
        SceneFromUrdf(With(Gyroscope("planar"), HoldBlock("rotor_joint", hold)));
    EXPECT_DOUBLE_EQ(urdf.scene.bodies[0].mass, 0.13) << hold;
    ASSERT_EQ(urdf.warnings.size(), 1u);
    ExpectContains(urdf.warnings[0],
                   {"joint \"rotor_joint\" (planar) is held rigid at its zero position"});
  }
  const UrdfScene by_option = SceneFromUrdf(Gyroscope("planar"), Holding({"rotor_joint"}));
  EXPECT_DOUBLE_EQ(by_option.scene.bodies[0].mass, 0.13);
  ExpectContains(
      LoadError(With(Gyroscope("planar"), HoldBlock("rotor_joint", "<hold position=\"0.1\"/>"))),
      {"urdf: nonsmooth_sim joint=\"rotor_joint\" > hold (line 1): joint \"rotor_joint\" (planar) "
       "can be held only at its zero position, not at 0.1",
       "allowed: no position, or position=\"0\""});
}

TEST(UrdfLoaderHold, AJointThatDoesNotExistIsRefusedNamingTheJointsThatMove) {
  // two moving joints (listed by name), a fixed and a floating one (not listed)
  const std::string xml = With(
      Gyroscope("continuous"),
      MassiveLink("ball", "0 0 0", "2", "1 1 1", "ball") +
          Joint("throw", "floating", "frame", "ball", "<origin xyz=\"1 0 0\"/>") +
          "<link name=\"cam\"/>" + Joint("cam_joint", "fixed", "frame", "cam") +
          "<link name=\"pan\"/>" +
          Joint("a_pan", "revolute", "frame", "pan",
                "<limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>"));
  const std::string moving = "allowed: a revolute, continuous, prismatic or planar joint; the "
                             "joints that move here: joint \"a_pan\" (revolute), joint "
                             "\"rotor_joint\" (continuous)";
  ExpectContains(LoadError(With(xml, HoldBlock("rotor"))),
                 {"urdf: nonsmooth_sim joint=\"rotor\" > hold (line 1): no joint named "
                  "\"rotor\"; " + moving});
  ExpectContains(LoadError(xml, Holding({"rotor_joint", "rotorjoint"})),
                 {"urdf: the option hold_joints: no joint named \"rotorjoint\"; " + moving});
  // a fixed or floating joint is no joint to hold
  ExpectContains(LoadError(With(xml, HoldBlock("cam_joint"))),
                 {"nonsmooth_sim joint=\"cam_joint\" > hold (line 1): joint \"cam_joint\" (fixed) "
                  "does not move, there is nothing to hold",
                  moving});
  ExpectContains(LoadError(xml, Holding({"throw"})),
                 {"the option hold_joints: joint \"throw\" (floating) makes its link a free body "
                  "of its own, not a joint to hold",
                  moving});
}

TEST(UrdfLoaderHold, APositionOutsideTheJointsLimitsIsRefusedWithTheRange) {
  const std::string limit = "<limit lower=\"-0.5\" upper=\"0.25\" effort=\"1\" velocity=\"1\"/>";
  ExpectContains(LoadError(With(Gyroscope("revolute", limit),
                                HoldBlock("rotor_joint", "<hold position=\"0.3\"/>"))),
                 {"nonsmooth_sim joint=\"rotor_joint\" > hold (line 1): joint \"rotor_joint\" "
                  "(revolute): position 0.3 rad is outside its limits; allowed: [-0.5, 0.25] rad"});
  ExpectContains(LoadError(With(Gyroscope("prismatic", limit),
                                HoldBlock("rotor_joint", "<hold position=\"-0.6\"/>"))),
                 {"joint \"rotor_joint\" (prismatic): position -0.6 m is outside its limits; "
                  "allowed: [-0.5, 0.25] m"});
  // the option holds at 0: a range without 0 needs the block's position
  const std::string away = "<limit lower=\"0.1\" upper=\"0.2\" effort=\"1\" velocity=\"1\"/>";
  ExpectContains(LoadError(Gyroscope("revolute", away), Holding({"rotor_joint"})),
                 {"urdf: the option hold_joints: joint \"rotor_joint\" (revolute) would be held "
                  "at 0 rad, outside its limits [0.1, 0.2] rad; give a position within them in "
                  "<nonsmooth_sim joint=\"rotor_joint\"><hold position=\"...\"/></nonsmooth_sim>"});
  // the limits' ends themselves are positions of the joint
  EXPECT_DOUBLE_EQ(SceneFromUrdf(With(Gyroscope("revolute", away),
                                      HoldBlock("rotor_joint", "<hold position=\"0.2\"/>")))
                       .scene.bodies[0]
                       .mass,
                   0.13);
}

TEST(UrdfLoaderHold, TyposInTheJointBlockAreRefusedWithWhatIsAllowed) {
  const std::string gyroscope = Gyroscope("continuous");
  const auto error = [&](const std::string& block) { return LoadError(With(gyroscope, block)); };
  ExpectContains(error(HoldBlock("rotor_joint", "<hold angle=\"0.3\"/>")),
                 {"nonsmooth_sim joint=\"rotor_joint\" > hold (line 1): unknown attribute "
                  "\"angle\"; allowed: position"});
  ExpectContains(error(HoldBlock("rotor_joint", "<lock/>")),
                 {"nonsmooth_sim joint=\"rotor_joint\" > lock (line 1): unknown element <lock>; "
                  "allowed in <nonsmooth_sim joint=\"...\">: <hold/> or <hold position=\"q\"/>"});
  ExpectContains(error(HoldBlock("rotor_joint", "<hold/><restitution>0.5</restitution>")),
                 {"unknown element <restitution>"});
  ExpectContains(error(HoldBlock("rotor_joint", "<hold><position>1</position></hold>")),
                 {"unknown element <position>; <hold> has no child elements"});
  ExpectContains(error("<nonsmooth_sim joint=\"rotor_joint\" lock=\"1\"><hold/></nonsmooth_sim>"),
                 {"nonsmooth_sim joint=\"rotor_joint\" (line 1): unknown attribute \"lock\"; "
                  "allowed: reference, joint"});
  ExpectContains(error("<nonsmooth_sim joint=\"rotor_joint\" reference=\"rotor\"><hold/>"
                       "</nonsmooth_sim>"),
                 {"attributes reference and joint in one block"});
  ExpectContains(error("<nonsmooth_sim joint=\"rotor_joint\"></nonsmooth_sim>"),
                 {"nonsmooth_sim joint=\"rotor_joint\" (line 1): no <hold>; expected <hold/> or "
                  "<hold position=\"q\"/>"});
  ExpectContains(error(HoldBlock("rotor_joint", "<hold/><hold/>")),
                 {"<hold> given twice in one block"});
  ExpectContains(error(HoldBlock("rotor_joint") + HoldBlock("rotor_joint")),
                 {"joint \"rotor_joint\" is already held by nonsmooth_sim joint=\"rotor_joint\" > "
                  "hold (line 1) (one <hold> per joint)"});
  for (const std::string position : {"nan", "inf", "0.3rad", "", "0.1 0.2"}) {
    ExpectContains(error(HoldBlock("rotor_joint", "<hold position=\"" + position + "\"/>")),
                   {"nonsmooth_sim joint=\"rotor_joint\" > hold (line 1): position=\"" + position +
                    "\""});
  }
}

TEST(UrdfLoaderHold, AnOptionNameBeyondTheNameBoundIsRefusedBeforeTheFileIsRead) {
  try {
    SceneFromUrdf(Gyroscope("continuous"), Holding({std::string(300, 'j')}));
    ADD_FAILURE() << "loaded";
  } catch (const UrdfError& e) {
    ADD_FAILURE() << "a URDF error for an option: " << e.what();
  } catch (const std::invalid_argument& e) {
    ExpectContains(e.what(), {"hold_joints: joint", "300 bytes, more than the bound of 256"});
  }
}

TEST(UrdfLoaderHold, AHeldJointsSubtreeJoinsTheParentAndMovingJointsBelowItAreStillChecked) {
  // b -continuous "spin" (held)-> hub (no mass) -fixed-> weight (0.5 kg); and hub -continuous
  // "flap" (not held)-> flap (0.2 kg): refused, then held too
  const std::string xml =
      "<robot name=\"r\">" + MassiveLink("b", "0 0 0", "2", "1 1 1", "core") +
      "<link name=\"hub\"/>" + MassiveLink("weight", "0 0 0", "0.5", "1e-3 1e-3 1e-3", "w") +
      MassiveLink("flap", "0 0 0", "0.2", "1e-3 1e-3 1e-3", "f") +
      Joint("spin", "continuous", "b", "hub", "<origin xyz=\"0 0 1\"/>") +
      Joint("hub_weight", "fixed", "hub", "weight") +
      Joint("flap_joint", "continuous", "hub", "flap") + "</robot>";
  ExpectContains(LoadError(xml, Holding({"spin"})),
                 {"joint \"flap_joint\" (continuous) moves link \"flap\""});
  const UrdfScene urdf = SceneFromUrdf(xml, Holding({"spin", "flap_joint"}));
  ASSERT_EQ(urdf.scene.bodies.size(), 1u);
  EXPECT_DOUBLE_EQ(urdf.scene.bodies[0].mass, 2.7);
  EXPECT_EQ(urdf.merged_links[0], (std::vector<std::string>{"hub", "weight", "flap"}));
  ASSERT_EQ(urdf.warnings.size(), 2u);
  ExpectContains(urdf.warnings[0],
                 {"joint \"spin\" (continuous) is held rigid at 0 rad by the option hold_joints: "
                  "its link \"hub\" (no mass, no collision)"});
}

}  // namespace
}  // namespace nonsmooth_sim::scene_io
