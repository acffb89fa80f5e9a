// URDF -> Scene: the shipped Tippe-Top URDF gives exactly the core's Tippe-Top scene; inertia in a
// rotated <inertial><origin> frame is re-expressed at the centre of mass in link axes; Gazebo's
// friction tags map onto the contact law; unsupported parts are reported and skipped; every
// malformed fixture gives one error line naming the element and the reason.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <fstream>
#include <sstream>

#include "bad_urdf_fixtures.h"
#include "nonsmooth_sim/core/tippe_top.h"
#include "nonsmooth_sim/node/initial_conditions.h"
#include "nonsmooth_sim/node/urdf_scene.h"

namespace nonsmooth_sim::node {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string ReadSourceFile(const std::string& relative) {
  std::ifstream in(std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/" + relative);
  EXPECT_TRUE(in.good()) << relative;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// One link "b" with the given <inertial> body and collisions, plus extra top-level XML.
std::string Robot(const std::string& link_body, const std::string& extra = "") {
  return "<robot name=\"r\"><link name=\"b\">" + link_body + "</link>" + extra + "</robot>";
}
const char* kUnitInertial =
    "<inertial><mass value=\"2\"/>"
    "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>";
const char* kBall =
    "<collision name=\"ball\"><geometry><sphere radius=\"0.1\"/></geometry></collision>";

void ExpectSameScene(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_EQ(a.bodies[i].name, b.bodies[i].name);
    EXPECT_EQ(a.bodies[i].mass, b.bodies[i].mass);
    EXPECT_EQ(a.bodies[i].inertia, b.bodies[i].inertia);
    EXPECT_EQ(a.bodies[i].com_in_link, b.bodies[i].com_in_link);
  }
  ASSERT_EQ(a.spheres.size(), b.spheres.size());
  for (std::size_t i = 0; i < a.spheres.size(); ++i) {
    const Sphere& s = a.spheres[i];
    const Sphere& t = b.spheres[i];
    EXPECT_EQ(s.name, t.name);
    EXPECT_EQ(s.body, t.body);
    EXPECT_EQ(s.center, t.center) << s.name;
    EXPECT_EQ(s.radius, t.radius) << s.name;
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

TEST(UrdfScene, ShippedTippeTopEqualsTheCoreScene) {
  const UrdfScene urdf = SceneFromUrdf(ReadSourceFile("urdf/tippe_top.urdf"));
  EXPECT_TRUE(urdf.warnings.empty()) << urdf.warnings.front();
  ASSERT_EQ(urdf.tippe_top.size(), 1u);
  EXPECT_TRUE(urdf.tippe_top[0].has_value());
  Scene scene = urdf.scene;
  scene.initial_state = InitialState(urdf, 0, {});
  ExpectSameScene(scene, MakeTippeTopScene());
}

TEST(UrdfScene, OverridesAndInitialConditionsMatchTheCoreScene) {
  UrdfSceneOptions options;
  options.mu = 0.5;
  options.contact_radius = 1e-3;
  options.friction_set = FrictionSet::kExact;
  options.gravity = 9.80665;
  const UrdfScene urdf = SceneFromUrdf(ReadSourceFile("urdf/tippe_top.urdf"), options);
  InitialConditions initial;
  initial.inclination = 0.4;
  initial.spin = -60.0;
  Scene scene = urdf.scene;
  scene.initial_state = InitialState(urdf, 0, initial);

  TippeTopParameters parameters;
  parameters.mu = 0.5;
  parameters.contact_radius = 1e-3;
  parameters.friction_set = FrictionSet::kExact;
  parameters.gravity = 9.80665;
  ExpectSameScene(scene, MakeTippeTopScene(parameters, {0.4, -60.0}));
}

TEST(UrdfScene, InertiaInARotatedInertialFrameIsReexpressedInLinkAxes) {
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

  // URDF rpy: fixed axes x, y, z, i.e. R = Rz(yaw) Ry(pitch) Rx(roll)
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  const Eigen::Matrix3d expected = r * Eigen::Vector3d(1e-6, 2e-6, 3e-6).asDiagonal() * r.transpose();
  EXPECT_LT((body.inertia - expected).norm(), 1e-18);
  // each rotated principal axis is an eigenvector with its moment
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d axis = r.col(k);
    EXPECT_LT((body.inertia * axis - (k + 1) * 1e-6 * axis).norm(), 1e-18) << k;
  }
  EXPECT_EQ(body.com_in_link, Eigen::Vector3d(0.01, 0.02, 0.03));
  ASSERT_EQ(urdf.scene.spheres.size(), 1u);
  // the sphere centre is given relative to the centre of mass, in link axes
  EXPECT_LT((urdf.scene.spheres[0].center - Eigen::Vector3d(-0.01, -0.02, -0.08)).norm(), 1e-17);
  EXPECT_FALSE(urdf.tippe_top[0].has_value());
}

TEST(UrdfScene, GazeboFrictionTagsSetTheContactLaw) {
  const std::string surface =
      "<gazebo reference=\"b\"><collision><surface><friction>"
      "<ode><mu>0.5</mu><mu2>0.5</mu2></ode>"
      "<torsional><coefficient>0.25</coefficient><patch_radius>1e-3</patch_radius></torsional>"
      "</friction></surface></collision></gazebo>"
      "<nonsmooth_sim reference=\"b\"><restitution>0.4</restitution></nonsmooth_sim>";
  const UrdfScene urdf = SceneFromUrdf(Robot(std::string(kUnitInertial) + kBall, surface));
  ASSERT_EQ(urdf.scene.spheres.size(), 1u);
  const ContactLaw& law = urdf.scene.spheres[0].law;
  EXPECT_EQ(law.mu, 0.5);
  // Gazebo's drilling bound μ_τ (3πR/16) λ_N = R̄ μ λ_N  ⇒  R̄ = 3πR/16 · μ_τ/μ
  EXPECT_NEAR(law.rbar, 3.0 * kPi * 1e-3 / 16.0 * 0.25 / 0.5, 1e-18);
  EXPECT_EQ(law.restitution, 0.4);
  EXPECT_TRUE(urdf.warnings.empty());

  // μ and R from parameters replace both tags: R̄ = 3πR/16 with the one μ
  UrdfSceneOptions options;
  options.mu = 0.2;
  options.contact_radius = 2e-3;
  const UrdfScene overridden =
      SceneFromUrdf(Robot(std::string(kUnitInertial) + kBall, surface), options);
  EXPECT_EQ(overridden.scene.spheres[0].law.mu, 0.2);
  EXPECT_NEAR(overridden.scene.spheres[0].law.rbar, 3.0 * kPi * 2e-3 / 16.0, 1e-18);
}

TEST(UrdfScene, WithoutGazeboTagsSdfDefaultsApply) {
  const UrdfScene urdf = SceneFromUrdf(Robot(std::string(kUnitInertial) + kBall));
  const ContactLaw& law = urdf.scene.spheres[0].law;
  EXPECT_EQ(law.mu, 1.0);    // SDF <mu> default
  EXPECT_EQ(law.rbar, 0.0);  // SDF <patch_radius> default 0: no drilling component
  EXPECT_EQ(law.restitution, 0.0);
}

TEST(UrdfScene, AnisotropicFrictionIsReported) {
  const std::string surface =
      "<gazebo reference=\"b\"><collision><surface><friction>"
      "<ode><mu>0.5</mu><mu2>0.7</mu2></ode></friction></surface></collision></gazebo>";
  const UrdfScene urdf = SceneFromUrdf(Robot(std::string(kUnitInertial) + kBall, surface));
  ASSERT_EQ(urdf.warnings.size(), 1u);
  EXPECT_NE(urdf.warnings[0].find("anisotropic"), std::string::npos) << urdf.warnings[0];
  EXPECT_EQ(urdf.scene.spheres[0].law.mu, 0.5);
}

TEST(UrdfScene, UnsupportedGeometryIsReportedAndSkipped) {
  const UrdfScene urdf = SceneFromUrdf(Robot(
      std::string(kUnitInertial) + kBall +
      "<collision name=\"slab\"><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision>"));
  EXPECT_EQ(urdf.scene.spheres.size(), 1u);
  ASSERT_EQ(urdf.warnings.size(), 1u);
  EXPECT_NE(urdf.warnings[0].find("collision \"slab\""), std::string::npos) << urdf.warnings[0];
  EXPECT_NE(urdf.warnings[0].find("skipped"), std::string::npos) << urdf.warnings[0];
}

TEST(UrdfScene, RootAndFloatingJointChildrenAreFreeBodies) {
  // world (a frame) -floating-> a at (1, 0, 0.5) -fixed-> c (skipped) ; a -floating-> d
  const std::string xml =
      std::string("<robot name=\"r\"><link name=\"world\"/>") +
      "<link name=\"a\">" + kUnitInertial + kBall + "</link>" +
      "<link name=\"c\">" + kUnitInertial + "</link>" +
      "<link name=\"d\">" + kUnitInertial +
      "<collision name=\"ball_d\"><geometry><sphere radius=\"0.1\"/></geometry></collision>"
      "</link>"
      "<joint name=\"wa\" type=\"floating\"><parent link=\"world\"/><child link=\"a\"/>"
      "<origin xyz=\"1 0 0.5\" rpy=\"0 0 1.5707963267948966\"/></joint>"
      "<joint name=\"ac\" type=\"fixed\"><parent link=\"a\"/><child link=\"c\"/></joint>"
      "<joint name=\"ad\" type=\"floating\"><parent link=\"a\"/><child link=\"d\"/>"
      "<origin xyz=\"2 0 0\"/></joint></robot>";
  const UrdfScene urdf = SceneFromUrdf(xml);
  ASSERT_EQ(urdf.scene.bodies.size(), 2u);
  EXPECT_EQ(urdf.scene.bodies[0].name, "a");
  EXPECT_EQ(urdf.scene.bodies[1].name, "d");
  ASSERT_EQ(urdf.scene.spheres.size(), 2u);
  EXPECT_EQ(urdf.scene.spheres[1].body, 1);
  // d starts at its URDF pose: a's origin composed with the joint origin (a is turned by 90°)
  EXPECT_LT((urdf.scene.initial_state[1].position - Eigen::Vector3d(1.0, 2.0, 0.5)).norm(), 1e-12);
  ASSERT_EQ(urdf.warnings.size(), 1u);
  EXPECT_NE(urdf.warnings[0].find("link \"c\" hangs on joint \"ac\""), std::string::npos)
      << urdf.warnings[0];
}

TEST(UrdfScene, DuplicateCollisionNamesAreAnError) {
  // contacts are addressed by name (services, topics, TF frames)
  try {
    SceneFromUrdf(Robot(std::string(kUnitInertial) + kBall + kBall));
    FAIL() << "no exception";
  } catch (const UrdfError& e) {
    EXPECT_NE(std::string(e.what()).find("\"ball\" is used twice"), std::string::npos) << e.what();
  }
}

TEST(UrdfScene, NoFreeBodyIsAnError) {
  try {
    SceneFromUrdf("<robot name=\"r\"><link name=\"world\"/></robot>");
    FAIL() << "no exception";
  } catch (const UrdfError& e) {
    EXPECT_NE(std::string(e.what()).find("no free body"), std::string::npos) << e.what();
  }
}

TEST(UrdfScene, OptionsOutOfRangeAreRejected) {
  UrdfSceneOptions options;
  options.mu = -0.1;
  EXPECT_THROW(SceneFromUrdf(Robot(std::string(kUnitInertial) + kBall), options),
               std::invalid_argument);
  options = {};
  options.gravity = std::nan("");
  EXPECT_THROW(ValidateUrdfSceneOptions(options), std::invalid_argument);
}

TEST(UrdfScene, RestitutionOutOfRangeIsAnError) {
  try {
    SceneFromUrdf(Robot(std::string(kUnitInertial) + kBall,
                        "<nonsmooth_sim reference=\"b\"><restitution>1.5</restitution>"
                        "</nonsmooth_sim>"));
    FAIL() << "no exception";
  } catch (const UrdfError& e) {
    EXPECT_NE(std::string(e.what()).find("restitution"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("[0, 1]"), std::string::npos) << e.what();
  }
}

TEST(UrdfScene, EveryMalformedFixtureGivesOneLineNamingElementAndReason) {
  for (const test::BadUrdf& fixture : test::BadUrdfFixtures()) {
    const std::string xml = ReadSourceFile("test/node/fixtures/" + fixture.file);
    try {
      SceneFromUrdf(xml);
      ADD_FAILURE() << fixture.file << ": no exception";
    } catch (const UrdfError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << fixture.file << ": " << message;
      EXPECT_EQ(message.rfind("urdf: ", 0), 0u) << fixture.file << ": " << message;
      for (const std::string& part : fixture.expected) {
        EXPECT_NE(message.find(part), std::string::npos)
            << fixture.file << ": \"" << part << "\" not in: " << message;
      }
    }
  }
}

TEST(UrdfScene, EachFixtureDiffersFromAValidUrdfOnlyInItsDefect) {
  // the fixtures must fail for their own reason: repaired, the same text converts
  const std::string repaired_mass = [] {
    std::string xml = ReadSourceFile("test/node/fixtures/negative_mass.urdf");
    xml.replace(xml.find("-6e-3"), 5, "6e-3");
    return xml;
  }();
  EXPECT_NO_THROW(SceneFromUrdf(repaired_mass));
  std::string radius = ReadSourceFile("test/node/fixtures/zero_radius.urdf");
  radius.replace(radius.find("radius=\"0\""), 10, "radius=\"0.015\"");
  EXPECT_NO_THROW(SceneFromUrdf(radius));
  std::string origin = ReadSourceFile("test/node/fixtures/nan_origin.urdf");
  origin.replace(origin.find("0 nan 0.016"), 11, "0 0 0.016");
  EXPECT_NO_THROW(SceneFromUrdf(origin));
}

}  // namespace
}  // namespace nonsmooth_sim::node
