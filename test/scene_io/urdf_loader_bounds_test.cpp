// URDF -> Scene, the bounds (urdf_scene.h, "Bounds"): what loads is a simulable rigid body;
// masses, inertias, positions, sizes, friction and options outside their ranges are rejected
// naming the bound; scenes at the bounds step finite; missing and bad files name the path.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "urdf_fixtures.h"

namespace nonsmooth_sim::scene_io {
namespace {

using namespace urdf_test;  // NOLINT

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
  // the rolling-resistance length: negative, beyond 1000 m, NaN or not a number
  for (const std::string bad : {"-1e-4", "2e3", "nan", "inf", "abc"}) {
    ExpectContains(LoadError(with("<nonsmooth_sim reference=\"b\"><rolling_resistance>" + bad +
                                  "</rolling_resistance></nonsmooth_sim>")),
                   {"nonsmooth_sim reference=\"b\" > rolling_resistance"});
    ExpectContains(LoadError(with("<gazebo reference=\"b\"><rolling_friction>" + bad +
                                  "</rolling_friction></gazebo>")),
                   {"rolling_friction"});
  }
  ExpectContains(LoadError(with("<nonsmooth_sim reference=\"b\"><rolling_resistance>-1"
                                "</rolling_resistance></nonsmooth_sim>")),
                 {"-1 is out of range, expected [0, 1000] m"});
  ExpectContains(LoadError(with("<nonsmooth_sim reference=\"b\"><rolling_resistance>nan"
                                "</rolling_resistance></nonsmooth_sim>")),
                 {"\"nan\" is not a finite number"});
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
  for (double bad : {-1e-4, 2e3, std::numeric_limits<double>::quiet_NaN()}) {
    options = {};
    options.rolling_resistance = bad;
    ExpectContains(message(options), {"rolling_resistance", "[0, 1000] [m]"});
  }
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
