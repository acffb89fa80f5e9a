// Bounds at the door of the loader (bounded_input.h): devices, FIFOs, directories and oversize
// files refused by type and size before they are read (a FIFO without a writer would block an
// open, /dev/zero would be read until memory runs out); YAML with one document only and a bounded
// nesting depth; names and collision counts bounded. Each refusal is one line naming the file or
// element, the bound and what is allowed.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <string>

#include "nonsmooth_sim/scene_io/bounded_input.h"
#include "nonsmooth_sim/scene_io/initial_state.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace nonsmooth_sim::scene_io {
namespace {

std::string SourcePath(const std::string& relative) {
  return std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/" + relative;
}

// The message of the std::invalid_argument `call` throws; fails the test if it throws none.
template <typename Call>
std::string Refusal(const Call& call) {
  try {
    call();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "no exception";
  return "";
}

void ExpectContains(const std::string& message, std::initializer_list<std::string> parts) {
  for (const std::string& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << "\"" << part << "\" not in: " << message;
  }
  EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
}

// A FIFO in the test's temporary folder (no writer: an ordinary open would block).
std::string MakeFifo(const std::string& name) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::remove(path.c_str());
  EXPECT_EQ(::mkfifo(path.c_str(), 0600), 0) << path;
  return path;
}

std::string WriteFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

const std::string kInertial =
    "<inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" "
    "iyz=\"0\" izz=\"0.01\"/></inertial>";

std::string Ball(const std::string& name) {
  return "<collision name=\"" + name + "\"><geometry><sphere radius=\"0.1\"/></geometry>"
         "</collision>";
}

TEST(BoundedFiles, DevicesAreRefusedByTypeBeforeAnyRead) {
  for (const char* device : {"/dev/zero", "/dev/urandom", "/dev/null"}) {
    ExpectContains(Refusal([&] { LoadUrdfFile(device); }),
                   {std::string("urdf: ") + device + ": is a character device, not a regular "
                                                     "file; allowed: a URDF file, a regular file "
                                                     "of at most 16777216 bytes (16 MiB)"});
    const Scene scene = LoadUrdfFile(SourcePath("urdf/tippe_top.urdf")).scene;
    ExpectContains(Refusal([&] { InitialStateFromYamlFile(scene, device); }),
                   {std::string("initial state: ") + device + ": is a character device",
                    "allowed: a YAML file, a regular file of at most 16777216 bytes"});
  }
}

TEST(BoundedFiles, FifoIsRefusedWithoutWaitingForAWriter) {
  // without the type check the open would block for ever (the test would time out)
  const std::string fifo = MakeFifo("bounded_input_test.fifo");
  ExpectContains(Refusal([&] { LoadUrdfFile(fifo); }),
                 {"urdf: " + fifo + ": is a FIFO, not a regular file; allowed: a URDF file"});
  const Scene scene = LoadUrdfFile(SourcePath("urdf/tippe_top.urdf")).scene;
  ExpectContains(Refusal([&] { InitialStateFromYamlFile(scene, fifo); }),
                 {"initial state: " + fifo + ": is a FIFO"});
  std::remove(fifo.c_str());
}

TEST(BoundedFiles, DirectoryAndMissingFileNameThePath) {
  ExpectContains(Refusal([] { LoadUrdfFile("/tmp"); }),
                 {"urdf: /tmp: is a directory, expected a URDF file"});
  ExpectContains(Refusal([] { ReadBoundedFile("/nonexistent/x.yaml", 10, "a YAML file"); }),
                 {"no such file"});
}

TEST(BoundedFiles, SizeBoundIsExactAndNamed) {
  const std::string path = WriteFile("bounded_input_test.txt", std::string(100, 'x'));
  EXPECT_EQ(ReadBoundedFile(path, 100, "a text").size(), 100u);  // at the bound: read whole
  ExpectContains(Refusal([&] { ReadBoundedFile(path, 99, "a text"); }),
                 {"has 100 bytes, more than the bound of 99 bytes; allowed: a text, a regular "
                  "file of at most 99 bytes"});
  // the default bound of the loader: 16 MiB + 1 byte of comment in an otherwise valid URDF
  const std::string big = WriteFile(
      "bounded_input_test_big.urdf",
      "<robot name=\"r\"><link name=\"b\">" + kInertial + Ball("c") + "</link><!--" +
          std::string(kMaxInputBytes, ' ') + "--></robot>");
  ExpectContains(Refusal([&] { LoadUrdfFile(big); }),
                 {"urdf: " + big + ": has ", "more than the bound of 16777216 bytes (16 MiB)"});
  UrdfSceneOptions options;
  options.max_bytes = kMaxInputBytes + 1024;  // a larger configured bound reads it
  EXPECT_EQ(LoadUrdfFile(big, options).scene.bodies.size(), 1u);
  std::remove(big.c_str());
}

TEST(BoundedFiles, UrdfTextOverTheOptionBoundIsRefusedBeforeParsing) {
  UrdfSceneOptions options;
  options.max_bytes = 64;
  // not even XML: refused by size, not by the parser
  ExpectContains(Refusal([&] { SceneFromUrdf(std::string(65, '<'), options); }),
                 {"urdf: the text has 65 bytes, more than the bound of 64 bytes"});
  options.max_bytes = 0;
  ExpectContains(Refusal([&] { ValidateUrdfSceneOptions(options); }), {"max_bytes = 0"});
}

TEST(BoundedYaml, OneDocumentOnly) {
  const Scene scene = LoadUrdfFile(SourcePath("urdf/tippe_top.urdf")).scene;
  const std::string body = "bodies:\n  tippe_top:\n    position: [0, 0, 0.5]\n";
  EXPECT_NO_THROW(InitialStateFromYaml(scene, body));
  EXPECT_NO_THROW(InitialStateFromYaml(scene, "---\n" + body + "...\n# a comment\n"));
  ExpectContains(Refusal([&] { InitialStateFromYaml(scene, body + "---\nbodies: {}\n"); }),
                 {"initial state (line 4, column 1): a second YAML document", "allowed: one"});
  ExpectContains(Refusal([&] { InitialStateFromYaml(scene, body + "...\ntrailing text\n"); }),
                 {"(line 5, column 1): a second YAML document", "after --- or ..."});
  const std::string path = WriteFile("bounded_input_test_two.yaml", body + "---\n" + body);
  ExpectContains(Refusal([&] { InitialStateFromYamlFile(scene, path); }),
                 {"initial state: " + path + " (line 4, column 1): a second YAML document"});
}

// Found by scene_yaml_fuzz (test/fuzz, 2026-12-06): a "," outside brackets is a token that no
// document consumes, and yaml-cpp's LoadAll never returned on it (it appended empty documents
// until the memory was gone). The documents are counted up to the second, which begins there.
TEST(BoundedYaml, ATokenOutsideTheDocumentIsRefusedWhereItIs) {
  ExpectContains(Refusal([&] { ParseInitialStateYaml(","); }),
                 {"initial state (line 1, column 1): a second YAML document", "\",\""});
  ExpectContains(Refusal([&] { ParseInitialStateYaml("{bodies: {}},\n"); }),
                 {"(line 1, column 13): a second YAML document"});
  ExpectContains(Refusal([&] { ParseInitialStateYaml("[1, 2]\n, x\n"); }),
                 {"(line 2, column 1): a second YAML document"});
  // in a block map it is the map that is not closed
  ExpectContains(Refusal([&] { ParseInitialStateYaml("bodies:\n  b: {}\n, x\n"); }),
                 {"(line 3, column 1): not valid YAML"});
  // a "," inside a plain scalar or inside brackets is YAML, and reaches the format's own checks
  ExpectContains(Refusal([&] { ParseInitialStateYaml("bodies: 1,2\n"); }), {"bodies", "not a map"});
  EXPECT_NO_THROW(ParseInitialStateYaml("bodies: {b: {position: [0, 0, 1]}, d: {}}\n"));
}

TEST(BoundedYaml, DeepNestingIsRefusedBeforeParsing) {
  const auto flow = [](int depth) {
    return "bodies: " + std::string(depth, '[') + std::string(depth, ']') + "\n";
  };
  // 63 brackets under the block level of "bodies": 64 levels, parsed (and refused as a list)
  const std::string ok = Refusal([&] { ParseInitialStateYaml(flow(63)); });
  EXPECT_EQ(ok.find("nested"), std::string::npos) << ok;
  ExpectContains(Refusal([&] { ParseInitialStateYaml(flow(64)); }),
                 {"initial state: nested deeper than 64 levels (line 1"});
  // the 20 MB of '[': refused by the size bound, before any scan
  ExpectContains(Refusal([&] { ParseInitialStateYaml(std::string(20u << 20, '[')); }),
                 {"has 20971520 bytes, more than the bound of 16777216 bytes (16 MiB)"});
  // block nesting: compact sequences and indentation
  std::string dashes;
  for (int k = 0; k < 70; ++k) dashes += "- ";
  ExpectContains(Refusal([&] { ParseInitialStateYaml(dashes + "x\n"); }),
                 {"nested deeper than 64 levels"});
  std::string indented;
  for (int k = 0; k < 70; ++k) indented += std::string(k, ' ') + "k" + std::to_string(k) + ":\n";
  ExpectContains(Refusal([&] { ParseInitialStateYaml(indented); }),
                 {"nested deeper than 64 levels (line 65"});
  // brackets in quotes and comments are not nesting
  EXPECT_NO_THROW(CheckYamlText("a: \"" + std::string(100, '[') + "\" # " +
                                std::string(100, '{') + "\n"));
}

TEST(BoundedNames, LengthOfRobotLinkJointAndCollisionNames) {
  const std::string ok(kMaxNameLength, 'n');
  const std::string long_name(kMaxNameLength + 1, 'n');
  const auto robot = [&](const std::string& robot_name, const std::string& link,
                         const std::string& collision) {
    return "<robot name=\"" + robot_name + "\"><link name=\"world\"/><link name=\"" + link +
           "\">" + kInertial + Ball(collision) + "</link><joint name=\"j\" type=\"floating\">"
           "<parent link=\"world\"/><child link=\"" + link + "\"/></joint></robot>";
  };
  EXPECT_NO_THROW(SceneFromUrdf(robot(ok, ok, ok)));
  ExpectContains(Refusal([&] { SceneFromUrdf(robot(long_name, "b", "c")); }),
                 {"urdf: line 1: robot \"nnnn", "257 bytes, more than the bound of 256 bytes"});
  ExpectContains(Refusal([&] { SceneFromUrdf(robot("r", long_name, "c")); }),
                 {"link \"nnnn", "257 bytes, more than the bound of 256"});
  ExpectContains(Refusal([&] { SceneFromUrdf(robot("r", "b", long_name)); }),
                 {"collision \"nnnn", "257 bytes, more than the bound of 256"});
}

TEST(BoundedNames, CollisionsPerUrdf) {
  const auto link = [&](std::size_t collisions) {
    std::string body = kInertial;
    for (std::size_t k = 0; k < collisions; ++k) body += Ball("c" + std::to_string(k));
    return "<robot name=\"r\"><link name=\"b\">" + body + "</link></robot>";
  };
  EXPECT_EQ(SceneFromUrdf(link(kMaxCollisionsPerModel)).scene.colliders.size(),
            kMaxCollisionsPerModel + 1);  // and the ground
  ExpectContains(Refusal([&] { SceneFromUrdf(link(kMaxCollisionsPerModel + 1)); }),
                 {"collision \"c4096\"", "more than 4096 collisions in one URDF"});
}

}  // namespace
}  // namespace nonsmooth_sim::scene_io
