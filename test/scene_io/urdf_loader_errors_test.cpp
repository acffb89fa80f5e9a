// URDF -> Scene, the errors: every malformed input gives one error line naming the element and
// the reason (control characters escaped, text that is not XML characters, degenerate shapes,
// typos in the extension, planes on free links, static links with mass, no free body, ...).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "urdf_fixtures.h"

namespace nonsmooth_sim::scene_io {
namespace {

using namespace urdf_test;  // NOLINT

// --- errors --------------------------------------------------------------------------------------

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
                  "allowed in <nonsmooth_sim>: <restitution>, <friction_set>, "
                  "<rolling_resistance>, <collision"});
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

}  // namespace
}  // namespace nonsmooth_sim::scene_io
