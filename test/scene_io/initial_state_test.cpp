// Initial state from YAML: absent keys keep the URDF pose at rest; the link frame given in the file
// becomes the centre of mass r_S = position + R c (checked with a non-zero com_in_link and a
// rotation, by hand); every key survives a round trip through InitialStateToYaml; every malformed
// input gives one line naming the key path and what is allowed.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <initializer_list>

#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace nonsmooth_sim::scene_io {
namespace {

const Eigen::Vector3d kCom(0.01, -0.02, 0.03);  // com_in_link of body "b"

// Bodies "b" (centre of mass off the link origin, on a floating joint at (1, 2, 3) turned by
// rpy (0.1, 0.2, 0.3)) and "d" (at (0, 0, 1)), a link "f" fixed to b and a static link "table".
Scene TwoBodies() {
  const std::string inertial =
      "<mass value=\"1\"/><inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/>";
  const auto ball = [](const std::string& name) {
    return "<collision name=\"" + name + "\"><geometry><sphere radius=\"0.1\"/></geometry>"
           "</collision>";
  };
  return SceneFromUrdf(
             "<robot name=\"r\"><link name=\"world\"/>"
             "<link name=\"b\"><inertial><origin xyz=\"0.01 -0.02 0.03\"/>" + inertial +
             "</inertial>" + ball("b_ball") + "</link>"
             "<link name=\"d\"><inertial>" + inertial + "</inertial>" + ball("d_ball") + "</link>"
             "<link name=\"f\"/><link name=\"table\"/>"
             "<joint name=\"wb\" type=\"floating\"><parent link=\"world\"/><child link=\"b\"/>"
             "<origin xyz=\"1 2 3\" rpy=\"0.1 0.2 0.3\"/></joint>"
             "<joint name=\"wd\" type=\"floating\"><parent link=\"world\"/><child link=\"d\"/>"
             "<origin xyz=\"0 0 1\"/></joint>"
             "<joint name=\"bf\" type=\"fixed\"><parent link=\"b\"/><child link=\"f\"/></joint>"
             "<joint name=\"wt\" type=\"fixed\"><parent link=\"world\"/><child link=\"table\"/>"
             "</joint></robot>")
      .scene;
}

Eigen::Quaterniond UrdfRotationOfB() {
  return Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                            Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()) *
                            Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()));
}

void ExpectSameState(const BodyState& a, const BodyState& b, double tolerance,
                     const std::string& what) {
  EXPECT_LE((a.position - b.position).norm(), tolerance) << what;
  // q and −q are one rotation
  EXPECT_LE(std::min((a.orientation.coeffs() - b.orientation.coeffs()).norm(),
                     (a.orientation.coeffs() + b.orientation.coeffs()).norm()),
            tolerance)
      << what;
  EXPECT_LE((a.linear_velocity - b.linear_velocity).norm(), tolerance) << what;
  EXPECT_LE((a.angular_velocity - b.angular_velocity).norm(), tolerance) << what;
}

// The one error line of a YAML text that must not load.
std::string LoadError(const Scene& scene, const std::string& yaml) {
  try {
    InitialStateFromYaml(scene, yaml);
  } catch (const InitialStateError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind("initial state", 0), 0u) << message;
    return message;
  }
  ADD_FAILURE() << "loaded without an error:\n" << yaml;
  return "";
}

void ExpectContains(const std::string& message, std::initializer_list<std::string> parts) {
  for (const std::string& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << "\"" << part << "\" not in: " << message;
  }
}

TEST(InitialStateYaml, EmptyInputsKeepTheUrdfStateAtRest) {
  const Scene scene = TwoBodies();
  for (const std::string yaml : {"", "# nothing\n", "{}", "bodies:", "bodies: {}", "bodies: {b: }",
                                 "bodies:\n  b: {}\n"}) {
    const std::vector<BodyState> state = InitialStateFromYaml(scene, yaml);
    ASSERT_EQ(state.size(), 2u) << yaml;
    for (int b = 0; b < 2; ++b) ExpectSameState(state[b], scene.initial_state[b], 0.0, yaml);
  }
}

TEST(InitialStateYaml, TheUrdfStateIsWrittenAsItsLinkPose) {
  // the default state holds r_S; the file holds the link frame: (1, 2, 3) and the URDF rpy
  const Scene scene = TwoBodies();
  const InitialStateSpec spec =
      ParseInitialStateYaml(InitialStateToYaml(scene, scene.initial_state));
  ASSERT_EQ(spec.size(), 2u);
  const BodyInitialState& b = spec.at("b");
  EXPECT_LT((*b.position - Eigen::Vector3d(1.0, 2.0, 3.0)).norm(), 1e-15);
  EXPECT_LT(b.orientation->angularDistance(UrdfRotationOfB()), 1e-15);
  EXPECT_EQ(*b.linear_velocity, Eigen::Vector3d::Zero());
  EXPECT_EQ(*b.angular_velocity, Eigen::Vector3d::Zero());
  EXPECT_EQ(*spec.at("d").position, Eigen::Vector3d(0.0, 0.0, 1.0));
}

TEST(InitialStateYaml, TheLinkFrameIsConvertedToTheCentreOfMass) {
  const Scene scene = TwoBodies();
  ASSERT_EQ(scene.bodies[0].com_in_link, kCom);
  // 90° about x: q = (sin 45°, 0, 0, cos 45°), R (x, y, z) = (x, −z, y)
  const std::vector<BodyState> state = InitialStateFromYaml(scene,
                                                            "bodies:\n"
                                                            "  b:\n"
                                                            "    position: [0.5, -0.25, 2]\n"
                                                            "    orientation: [0.7071067811865476, 0, 0, 0.7071067811865476]\n"
                                                            "    linear_velocity: [1, 2, 3]\n"
                                                            "    angular_velocity: [4, 5, 6]\n");
  const BodyState& s = state[0];
  // by hand: r_S = (0.5, −0.25, 2) + (0.01, −0.03, −0.02)
  EXPECT_LT((s.position - Eigen::Vector3d(0.51, -0.28, 1.98)).norm(), 1e-15);
  EXPECT_LT((s.orientation * Eigen::Vector3d::UnitY() - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  // v_S in the world and ω in the link axes are taken as they are
  EXPECT_EQ(s.linear_velocity, Eigen::Vector3d(1.0, 2.0, 3.0));
  EXPECT_EQ(s.angular_velocity, Eigen::Vector3d(4.0, 5.0, 6.0));
  // the other body is untouched
  ExpectSameState(state[1], scene.initial_state[1], 0.0, "d");
}

TEST(InitialStateYaml, AnOrientationAloneTurnsTheBodyAboutItsLinkOrigin) {
  const Scene scene = TwoBodies();
  const BodyState s =
      InitialStateFromYaml(scene, "bodies: {b: {orientation: [0, 0, 1, 0]}}")[0];  // 180° about z
  // link origin stays at (1, 2, 3); R c = (−0.01, 0.02, 0.03)
  EXPECT_LT((s.position - Eigen::Vector3d(0.99, 2.02, 3.03)).norm(), 1e-15);
  EXPECT_EQ(s.orientation.coeffs(), Eigen::Vector4d(0.0, 0.0, 1.0, 0.0));
  EXPECT_EQ(s.linear_velocity, Eigen::Vector3d::Zero());
}

TEST(InitialStateYaml, APositionAloneKeepsTheOrientation) {
  const Scene scene = TwoBodies();
  const BodyState s = InitialStateFromYaml(scene, "bodies: {b: {position: [0, 0, 0.5]}}")[0];
  EXPECT_LT((s.position - (Eigen::Vector3d(0.0, 0.0, 0.5) + UrdfRotationOfB() * kCom)).norm(),
            1e-15);
  EXPECT_EQ(s.orientation.coeffs(), scene.initial_state[0].orientation.coeffs());
}

TEST(InitialStateYaml, TheQuaternionIsNormalised) {
  const Scene scene = TwoBodies();
  const BodyState s = InitialStateFromYaml(scene, "bodies: {d: {orientation: [0, 0, 2, 2]}}")[1];
  EXPECT_LT((s.orientation.coeffs() - Eigen::Vector4d(0.0, 0.0, std::sqrt(0.5), std::sqrt(0.5)))
                .norm(),
            1e-15);
}

TEST(InitialStateYaml, EveryKeySurvivesARoundTrip) {
  const Scene scene = TwoBodies();
  std::vector<BodyState> state(2);
  state[0].position = Eigen::Vector3d(0.1, -0.2, 0.3);
  state[0].orientation = Eigen::Quaterniond(Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()));
  state[0].linear_velocity = Eigen::Vector3d(-1.5, 2.25, 1e-7);
  state[0].angular_velocity = Eigen::Vector3d(180.0, -3.0, 0.125);
  state[1].position = Eigen::Vector3d(5.0, 6.0, 7.0);
  state[1].orientation = Eigen::Quaterniond(Eigen::AngleAxisd(-2.0, Eigen::Vector3d::UnitY()));
  state[1].linear_velocity = Eigen::Vector3d(0.0, 0.0, -9.81);
  state[1].angular_velocity = Eigen::Vector3d(1.0 / 3.0, 2.0 / 3.0, 1.0);
  const std::string yaml = InitialStateToYaml(scene, state);
  for (const char* key : {"bodies:", "b:", "d:", "position:", "orientation:", "linear_velocity:",
                          "angular_velocity:"}) {
    EXPECT_NE(yaml.find(key), std::string::npos) << key << " not in:\n" << yaml;
  }
  const std::vector<BodyState> back = InitialStateFromYaml(scene, yaml);
  ExpectSameState(back[0], state[0], 1e-15, "b");
  ExpectSameState(back[1], state[1], 1e-15, "d");
  // 17 significant digits: the velocities come back exactly
  EXPECT_EQ(back[1].angular_velocity, state[1].angular_velocity);
}

TEST(InitialStateYaml, ApplyMergesOntoGivenDefaults) {
  const Scene scene = TwoBodies();
  std::vector<BodyState> defaults = scene.initial_state;
  defaults[1].angular_velocity = Eigen::Vector3d(0.0, 0.0, 50.0);
  InitialStateSpec spec;
  spec["d"].linear_velocity = Eigen::Vector3d(1.0, 0.0, 0.0);
  const std::vector<BodyState> state = ApplyInitialState(scene, defaults, spec);
  EXPECT_EQ(state[1].angular_velocity, Eigen::Vector3d(0.0, 0.0, 50.0));
  EXPECT_EQ(state[1].linear_velocity, Eigen::Vector3d(1.0, 0.0, 0.0));
  EXPECT_EQ(state[1].position, defaults[1].position);
  ExpectSameState(state[0], defaults[0], 0.0, "b");
  EXPECT_THROW(ApplyInitialState(scene, {}, spec), std::invalid_argument);  // wrong size
}

TEST(InitialStateYaml, UnknownLinksAndKeysAreErrorsListingWhatIsAllowed) {
  const Scene scene = TwoBodies();
  ExpectContains(LoadError(scene, "bodies:\n  c: {position: [0, 0, 0]}\n"),
                 {"bodies.c (line 2)", "not a free body", "bodies: \"b\", \"d\""});
  // a link merged into b and a static link have no state of their own
  ExpectContains(LoadError(scene, "bodies: {f: {}}"), {"bodies.f", "not a free body"});
  ExpectContains(LoadError(scene, "bodies: {table: {}}"), {"bodies.table", "not a free body"});
  ExpectContains(LoadError(scene, "bodies:\n  b:\n    positon: [0, 0, 0]\n"),
                 {"bodies.b.positon (line 3)", "unknown key",
                  "allowed: position, orientation, linear_velocity, angular_velocity"});
  ExpectContains(LoadError(scene, "simulation: {dt: 1e-3}\n"),
                 {"simulation (line 1)", "unknown key; allowed: bodies"});
  ExpectContains(LoadError(scene, "bodies: [b, d]"), {"bodies", "not a map"});
  ExpectContains(LoadError(scene, "bodies: {b: [0, 0, 0]}"), {"bodies.b", "not a map",
                                                              "allowed keys: position"});
  ExpectContains(LoadError(scene, "- b\n- d\n"), {"not a map", "bodies"});
  ExpectContains(LoadError(scene, "bodies:\n  b: {}\n  b: {}\n"),
                 {"bodies.b (line 3)", "given twice (also on line 2)"});
  ExpectContains(LoadError(scene, "bodies: {b: {position: [0, 0, 0], position: [1, 1, 1]}}"),
                 {"bodies.b.position", "given twice"});
  ExpectContains(LoadError(scene, "bodies: {b: {position: [0, 0, 0]}\n"),
                 {"initial state (line", "not valid YAML"});
}

TEST(InitialStateYaml, WrongLengthsAndNumbersAreErrorsNamingTheKey) {
  const Scene scene = TwoBodies();
  ExpectContains(LoadError(scene, "bodies: {b: {position: [1, 2]}}"),
                 {"bodies.b.position", "has 2 numbers", "expected [x, y, z]"});
  ExpectContains(LoadError(scene, "bodies: {b: {orientation: [0, 0, 1]}}"),
                 {"bodies.b.orientation", "has 3 numbers", "expected [qx, qy, qz, qw]"});
  ExpectContains(LoadError(scene, "bodies: {b: {linear_velocity: 3}}"),
                 {"bodies.b.linear_velocity", "not a list", "[vx, vy, vz]"});
  ExpectContains(LoadError(scene, "bodies: {b: {position: [.nan, 0, 0]}}"),
                 {"bodies.b.position[0]", "\".nan\" is not a finite number"});
  ExpectContains(LoadError(scene, "bodies: {d: {angular_velocity: [0, 0, .inf]}}"),
                 {"bodies.d.angular_velocity[2]", "\".inf\" is not a finite number",
                  "[wx, wy, wz]"});
  ExpectContains(LoadError(scene, "bodies: {d: {angular_velocity: [0, -.Inf, 0]}}"),
                 {"bodies.d.angular_velocity[1]", "not a finite number"});
  ExpectContains(LoadError(scene, "bodies: {b: {position: [0, one, 0]}}"),
                 {"bodies.b.position[1]", "\"one\" is not a finite number"});
  ExpectContains(LoadError(scene, "bodies: {b: {position: [0, [1], 0]}}"),
                 {"bodies.b.position[1]", "not a finite number"});
  ExpectContains(LoadError(scene, "bodies:\n  b:\n    orientation: [0, 0, 0, 0]\n"),
                 {"bodies.b.orientation (line 3)", "zero quaternion"});
}

// Found by scene_yaml_fuzz (test/fuzz, 2026-12-02): yaml-cpp's message about a bad character
// quotes that character, and a name quoted in an error may hold one: control characters are
// escaped, the error stays one line (LoadError checks it).
TEST(InitialStateYaml, ControlCharactersOfTheInputKeepTheErrorOnOneLine) {
  const Scene scene = TwoBodies();
  // the fuzzer's input, as it was found
  const std::string found("boe\0\n:isd bodies:\n\0 die: {n: [0, 0, 0, 0]}\n", 43);
  ExpectContains(LoadError(scene, found), {"initial state (line 2", "not valid YAML"});
  ExpectContains(LoadError(scene, "bodies:\n  \"a\\nb\": {position: [0, 0, 0]}\n"),
                 {"bodies.a\\nb", "not a free body"});
}

// Found by scene_yaml_fuzz (test/fuzz, 2026-12-02): finite components whose |q|² overflows passed
// the zero check and normalised to the zero quaternion, which the Simulator then rejected.
TEST(InitialStateYaml, AQuaternionTooLargeToNormaliseIsAnError) {
  const Scene scene = TwoBodies();
  ExpectContains(LoadError(scene, "bodies: {b: {orientation: [1e300, 0, 0, 1]}}"),
                 {"bodies.b.orientation", "too large to normalise"});
  // large but normalisable: loads as the rotation it is
  const auto state = InitialStateFromYaml(scene, "bodies: {b: {orientation: [0, 0, 1e150, 1e150]}}");
  EXPECT_NEAR(state[0].orientation.z(), std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(state[0].orientation.w(), std::sqrt(0.5), 1e-15);
}

TEST(InitialStateYaml, ValuesBeyondTheBoundsAreErrorsNamingTheKeyAndTheBound) {
  // finite is not enough: a spin of 1e300 rad/s has an infinite kinetic energy
  const Scene scene = TwoBodies();
  ExpectContains(LoadError(scene, "bodies:\n  d:\n    angular_velocity: [0, 0, 1e300]\n"),
                 {"bodies.d.angular_velocity (line 3)", "|w| = 1e+300 rad/s", "<= 10000 rad/s"});
  ExpectContains(LoadError(scene, "bodies: {d: {angular_velocity: [6000, 0, -9000]}}"),
                 {"bodies.d.angular_velocity", "<= 10000 rad/s"});  // |w| = 10817
  ExpectContains(LoadError(scene, "bodies: {d: {linear_velocity: [0, 1e4, 0]}}"),
                 {"bodies.d.linear_velocity", "|v| = 10000 m/s", "<= 1000 m/s"});
  ExpectContains(LoadError(scene, "bodies: {d: {position: [0, 0, 1e300]}}"),
                 {"bodies.d.position", "every coordinate must be in [-1000, 1000] m"});
  ExpectContains(LoadError(scene, "bodies: {d: {position: [-1000.5, 0, 0]}}"),
                 {"bodies.d.position", "[-1000, 1000] m"});
  // the link origin inside, b's centre of mass 0.03 m above it (c = kCom, not turned) outside
  ExpectContains(
      LoadError(scene, "bodies: {b: {position: [0, 0, 1000], orientation: [0, 0, 0, 1]}}"),
      {"bodies.b.position", "the centre of mass", "[-1000, 1000] m"});

  // at the bounds: accepted, and the kinetic energy is finite
  const std::vector<BodyState> state = InitialStateFromYaml(
      scene,
      "bodies: {d: {position: [1000, -1000, 1000], linear_velocity: [0, 0, -1000], "
      "angular_velocity: [0, 10000, 0]}}");
  EXPECT_EQ(state[1].position, Eigen::Vector3d(1000.0, -1000.0, 1000.0));
  EXPECT_EQ(state[1].angular_velocity, Eigen::Vector3d(0.0, 10000.0, 0.0));
  EXPECT_TRUE(std::isfinite(MechanicalEnergy(scene, state)));

  // a spec built in code (the node's ~initial_state parameters) is held to the same bounds
  InitialStateSpec spec;
  spec["d"].angular_velocity = Eigen::Vector3d(0.0, 0.0, 1e300);
  try {
    ApplyInitialState(scene, scene.initial_state, spec);
    ADD_FAILURE() << "a spin of 1e300 rad/s was applied";
  } catch (const InitialStateError& e) {
    ExpectContains(e.what(), {"bodies.d.angular_velocity", "<= 10000 rad/s"});
  }
  spec["d"] = BodyInitialState();
  spec["d"].position = Eigen::Vector3d(0.0, 1e300, 0.0);
  EXPECT_THROW(ApplyInitialState(scene, scene.initial_state, spec), InitialStateError);
  spec["d"] = BodyInitialState();
  spec["d"].linear_velocity = Eigen::Vector3d(-2e3, 0.0, 0.0);
  EXPECT_THROW(ApplyInitialState(scene, scene.initial_state, spec), InitialStateError);
}

TEST(InitialStateYaml, FilesAreReadAndTheirErrorsNameThePath) {
  const Scene scene = TwoBodies();
  const std::string path = ::testing::TempDir() + "/scene_io_initial_state.yaml";
  std::ofstream(path) << "bodies:\n  d:\n    linear_velocity: [0, 0, 1]\n";
  EXPECT_EQ(InitialStateFromYamlFile(scene, path)[1].linear_velocity, Eigen::Vector3d::UnitZ());
  std::ofstream(path) << "bodies:\n  e: {}\n";
  try {
    InitialStateFromYamlFile(scene, path);
    FAIL() << "no exception";
  } catch (const InitialStateError& e) {
    ExpectContains(e.what(), {"initial state: " + path + ": bodies.e (line 2)"});
  }
  try {
    InitialStateFromYamlFile(scene, "/nonexistent/start.yaml");
    FAIL() << "no exception";
  } catch (const InitialStateError& e) {
    ExpectContains(e.what(), {"initial state: /nonexistent/start.yaml: no such file"});
  }
}

TEST(InitialStateYaml, WritingANonFiniteStateIsRejected) {
  const Scene scene = TwoBodies();
  std::vector<BodyState> state = scene.initial_state;
  state[0].position.x() = std::nan("");
  EXPECT_THROW(InitialStateToYaml(scene, state), std::invalid_argument);
  EXPECT_THROW(InitialStateToYaml(scene, {}), std::invalid_argument);
}

}  // namespace
}  // namespace nonsmooth_sim::scene_io
