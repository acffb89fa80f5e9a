// Each malformed URDF fixture and each bad parameter stops the node at start-up with exit code 1
// and exactly one error line on stderr naming the element (or parameter) and the reason. The
// good URDF with the same command line starts (the cases fail for their defect, not the setup).
// Files that are devices, FIFOs or beyond ~max_urdf_bytes, and names that share a frame after
// sanitising, are such defects too.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <functional>
#include <iterator>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "bad_urdf_fixtures.h"
#include "nonsmooth_sim/SpawnModel.h"

extern char** environ;

namespace nonsmooth_sim::node::test {
namespace {

constexpr double kExitTimeout = 20.0;  // [wall s] a failing start-up must end within this

struct NodeRun {
  bool exited = false;  // false: still running at the timeout (then stopped with SIGINT)
  int exit_code = -1;
  std::string out, err;
};

std::string ReadAll(int fd) {
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) > 0;) text.append(buffer, n);
  return text;
}

// Starts the node with `args` (no shell). `started`, if given, is polled while the node runs;
// once it holds the node is stopped with SIGINT. Waits up to kExitTimeout for the node to exit.
NodeRun RunNode(const std::vector<std::string>& args, const std::function<bool()>& started = {}) {
  int out_pipe[2], err_pipe[2];
  EXPECT_EQ(pipe(out_pipe), 0);
  EXPECT_EQ(pipe(err_pipe), 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out_pipe[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, err_pipe[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, out_pipe[0]);
  posix_spawn_file_actions_addclose(&actions, err_pipe[0]);
  std::vector<std::string> argv_strings = {NONSMOOTH_SIM_NODE_EXECUTABLE};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_strings) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(out_pipe[1]);
  close(err_pipe[1]);
  NodeRun run;
  EXPECT_EQ(spawned, 0) << argv[0];
  if (spawned != 0) return run;
  int status = 0;
  bool stopped = false;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(kExitTimeout);
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (!stopped && (ros::WallTime::now() > end || (started && started()))) {
      kill(pid, SIGINT);
      stopped = true;
      waitpid(pid, &status, 0);
      break;
    }
    ros::WallDuration(0.01).sleep();
  }
  run.exited = !stopped;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = ReadAll(out_pipe[0]);
  run.err = ReadAll(err_pipe[0]);
  close(out_pipe[0]);
  close(err_pipe[0]);
  return run;
}

std::vector<std::string> NonEmptyLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  }
  return lines;
}

std::string Fixture(const std::string& file) {
  return std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/test/node/fixtures/" + file;
}

void ExpectOneErrorLine(const NodeRun& run, const std::vector<std::string>& expected,
                        const std::string& label) {
  ASSERT_TRUE(run.exited) << label << ": still running after " << kExitTimeout << " s";
  EXPECT_EQ(run.exit_code, 1) << label;
  const std::vector<std::string> lines = NonEmptyLines(run.err);
  ASSERT_EQ(lines.size(), 1u) << label << ": stderr was:\n" << run.err;
  EXPECT_NE(lines[0].find("[FATAL]"), std::string::npos) << label << ": " << lines[0];
  for (const std::string& part : expected) {
    EXPECT_NE(lines[0].find(part), std::string::npos)
        << label << ": \"" << part << "\" not in: " << lines[0];
  }
  EXPECT_TRUE(NonEmptyLines(run.out).empty()) << label << ": stdout was:\n" << run.out;
}

TEST(NodeBadUrdf, EachMalformedFixtureStopsTheNodeWithOneClearLine) {
  int k = 0;
  for (const BadUrdf& fixture : BadUrdfFixtures()) {
    const NodeRun run = RunNode({"__name:=bad_urdf_" + std::to_string(k++),
                             "_urdf_file:=" + Fixture(fixture.file)});
    ExpectOneErrorLine(run, fixture.expected, fixture.file);
  }
}

TEST(NodeBadUrdf, BadParametersStopTheNodeWithOneClearLine) {
  const std::string urdf = "_urdf_file:=" + std::string(NONSMOOTH_SIM_SOURCE_DIR) +
                           "/urdf/tippe_top.urdf";
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_0", urdf, "_time_step:=-0.001"}),
                     {"time_step"}, "time_step");
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_1", urdf, "_friction_set:=sticky"}),
                     {"~friction_set", "unknown friction set \"sticky\""}, "friction_set");
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_2", urdf, "_real_time_factor:=-1.0"}),
                     {"~real_time_factor", ">= 0"}, "real_time_factor");
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_3", urdf, "_initial/inclination:=4.0"}),
                     {"inclination", "[0, pi]"}, "initial/inclination");
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_4", urdf, "_tf_rate:=abc"}),
                     {"~tf_rate", "expected a number"}, "tf_rate");
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_5", "_urdf_file:=" + Fixture("absent.urdf")}),
                     {"~urdf_file", "absent.urdf", "no such file"}, "urdf_file");
  // finite but beyond the bounds of the core's validation: the node ran 2^31
  // iterations per step, or started with an infinite kinetic energy
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_7", urdf, "_max_iterations:=2147483647"}),
                     {"max_iterations", "<= 100000 in a simulation", "2147483647"},
                     "max_iterations");
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_8", urdf, "_relaxation:=4.9e-324"}),
                     {"relaxation", "[0.001, 2)"}, "relaxation");
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_9", urdf, "_initial/spin:=1.0e+300"}),
                     {"spin", "<= 10000 rad/s"}, "initial/spin");
  ExpectOneErrorLine(
      RunNode({"__name:=bad_parameter_10", urdf, "_max_samples_per_message:=0"}),
      {"~max_samples_per_message", ">= 1 and <= 10000", "got 0"}, "max_samples_per_message");
  // the rolling-resistance length: negative or beyond 1000 m, or not a number
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_11", urdf, "_rolling_resistance:=-1e-4"}),
                     {"rolling_resistance", "[0, 1000] [m]"}, "rolling_resistance");
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_12", urdf, "_rolling_resistance:=abc"}),
                     {"~rolling_resistance", "expected a number"}, "rolling_resistance");
  // ~hold_joints: a name that is no moving joint of the URDF (the loader's line, naming the
  // joints that move), a number, a list with a number
  const std::string gyroscope = "_urdf_file:=" + Fixture("moving_joint.urdf");
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_13", gyroscope, "_hold_joints:=rotor"}),
                     {"urdf: the option hold_joints: no joint named \"rotor\"",
                      "the joints that move here: joint \"rotor_joint\" (continuous)"},
                     "hold_joints rotor");
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_14", gyroscope, "_hold_joints:=1.5"}),
                     {"parameter ~hold_joints: expected a list of strings, or one string"},
                     "hold_joints 1.5");
  XmlRpc::XmlRpcValue mixed;
  mixed[0] = std::string("rotor_joint");
  mixed[1] = 7;
  ros::param::set("/bad_parameter_15/hold_joints", mixed);
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_15", gyroscope}),
                     {"parameter ~hold_joints: expected a list of strings, or one string"},
                     "hold_joints [rotor_joint, 7]");
  // neither ~urdf_file nor robot_description (this test's launch file sets none)
  ExpectOneErrorLine(RunNode({"__name:=bad_parameter_6"}), {"no URDF", "robot_description"},
                     "no URDF");
}

// ~initial_state (rosparam load FILE ~initial_state) arrives from the master whole, with no byte
// bound of its own: more entries than a world holds bodies, or a link name beyond the name bound,
// stop the start-up before the entries are read.
TEST(NodeBadUrdf, AnInitialStateBeyondTheBoundsStopsTheNode) {
  const std::string urdf = "_urdf_file:=" + std::string(NONSMOOTH_SIM_SOURCE_DIR) +
                           "/urdf/tippe_top.urdf";
  XmlRpc::XmlRpcValue state;
  state["position"][0] = 0.0;
  state["position"][1] = 0.0;
  state["position"][2] = 0.1;
  XmlRpc::XmlRpcValue many;
  for (int k = 0; k <= 4096; ++k) many["bodies"]["b" + std::to_string(k)] = state;
  ros::param::set("/too_many_bodies/initial_state", many);
  ExpectOneErrorLine(RunNode({"__name:=too_many_bodies", urdf}),
                     {"~initial_state/bodies", "4097 entries, more than the bound of 4096"},
                     "4097 bodies");
  XmlRpc::XmlRpcValue long_name;
  long_name["bodies"][std::string(300, 'x')] = state;
  ros::param::set("/long_link_name/initial_state", long_name);
  ExpectOneErrorLine(RunNode({"__name:=long_link_name", urdf}),
                     {"~initial_state/bodies", "300 bytes, more than the bound of 256"},
                     "a 300-byte link name");
}

// Files that are not regular files or exceed ~max_urdf_bytes are refused by type and size before
// they are read: /dev/zero was read for about 1 GB, a FIFO without a writer hung the start-up.
TEST(NodeBadUrdf, DevicesFifosAndOversizeFilesAreRefusedBeforeReading) {
  ExpectOneErrorLine(RunNode({"__name:=bad_file_0", "_urdf_file:=/dev/zero"}),
                     {"~urdf_file", "/dev/zero", "is a character device, not a regular file",
                      "a regular file of at most 16777216 bytes (16 MiB)"},
                     "/dev/zero");
  const std::string fifo = ::testing::TempDir() + "/node_bad_urdf_test.fifo";
  unlink(fifo.c_str());
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0) << fifo;
  ExpectOneErrorLine(RunNode({"__name:=bad_file_1", "_urdf_file:=" + fifo}),
                     {"~urdf_file", fifo, "is a FIFO, not a regular file"}, "FIFO");
  unlink(fifo.c_str());
  const std::string urdf = std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/urdf/tippe_top.urdf";
  ExpectOneErrorLine(RunNode({"__name:=bad_file_2", "_urdf_file:=" + urdf,
                              "_max_urdf_bytes:=1000"}),
                     {"~urdf_file", "more than the bound of 1000 bytes"}, "max_urdf_bytes");
  ExpectOneErrorLine(RunNode({"__name:=bad_file_3", "_urdf_file:=" + urdf,
                              "_max_urdf_bytes:=0"}),
                     {"~max_urdf_bytes", "must be in [1, 268435456]"}, "max_urdf_bytes 0");
}

// Names that would share a TF frame or a ~wrench/ topic after sanitising stop the start-up, naming
// both (collisions "x-y" and "x_y" would publish one frame with two transforms per stamp).
TEST(NodeBadUrdf, NamesThatShareAFrameAfterSanitisingStopTheNode) {
  const std::string path = ::testing::TempDir() + "/node_bad_urdf_test_clash.urdf";
  const std::string inertial =
      "<inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" "
      "iyz=\"0\" izz=\"0.01\"/></inertial>";
  const auto ball = [](const char* name, double z) {
    return "<collision name=\"" + std::string(name) + "\"><origin xyz=\"0 0 " +
           std::to_string(z) + "\"/><geometry><sphere radius=\"0.05\"/></geometry></collision>";
  };
  std::ofstream(path) << "<robot name=\"r\"><link name=\"b\">" << inertial << ball("x_y", 0.0)
                      << ball("x-y", 0.01) << "</link></robot>";
  ExpectOneErrorLine(RunNode({"__name:=name_clash", "_urdf_file:=" + path}),
                     {"collision \"x-y\" would have the contact frame \"x_y_contact\" and "
                      "topic ~wrench/x_y of collision \"x_y\""},
                     "x-y and x_y");
}

TEST(NodeBadUrdf, OverlapsAtTheStartAreAWarningWithTheDepth) {
  // a box of 0.1 m centred on the ground: 5 cm deep; the node starts and says so once
  const std::string path = ::testing::TempDir() + "/node_bad_urdf_test_overlap.urdf";
  std::ofstream(path) << "<robot name=\"r\"><link name=\"b\"><inertial><mass value=\"1\"/>"
                         "<inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" "
                         "izz=\"0.01\"/></inertial><collision name=\"shell\"><geometry>"
                         "<box size=\"0.1 0.1 0.1\"/></geometry></collision></link></robot>";
  bool services_up = false;
  const NodeRun run = RunNode({"__name:=overlap", "_urdf_file:=" + path, "_paused:=true"}, [&] {
    services_up = ros::service::exists("/overlap/get_state", false);
    return services_up;
  });
  EXPECT_TRUE(services_up) << "stderr:\n" << run.err;
  EXPECT_FALSE(run.exited) << "exit code " << run.exit_code << ", stderr:\n" << run.err;
  const std::string all = run.out + run.err;
  EXPECT_NE(all.find("collisions \"shell\" and \"ground\" overlap by 0.05 m"), std::string::npos)
      << all;
}

// A body without any collision starts and falls for ever: the node warns once
// that it never touches anything, and /diagnostics says so (WARN) while it runs.
TEST(NodeBadUrdf, ABodyThatCanTouchNothingIsAWarningInTheLogAndInDiagnostics) {
  const std::string path = ::testing::TempDir() + "/node_bad_urdf_test_mesh_top.urdf";
  std::ofstream(path) << "<robot name=\"r\"><link name=\"top\"><inertial><mass value=\"0.1\"/>"
                         "<inertia ixx=\"1e-4\" ixy=\"0\" ixz=\"0\" iyy=\"1e-4\" iyz=\"0\" "
                         "izz=\"1e-4\"/></inertial></link></robot>";
  ros::NodeHandle nh;
  std::mutex mutex;
  std::string summary;  // the WARN's message, once one came (under mutex)
  ros::Subscriber diagnostics = nh.subscribe<diagnostic_msgs::DiagnosticArray>(
      "/diagnostics", 10, [&](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        for (const auto& status : m->status) {
          if (status.level == diagnostic_msgs::DiagnosticStatus::WARN &&
              status.message.find("can no longer touch anything") != std::string::npos) {
            const std::lock_guard<std::mutex> lock(mutex);
            summary = status.message;
          }
        }
      });
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const NodeRun run =
      RunNode({"__name:=mesh_top", "_urdf_file:=" + path, "_paused:=true"}, [&] {
        const std::lock_guard<std::mutex> lock(mutex);
        return !summary.empty();
      });
  spinner.stop();
  diagnostics.shutdown();
  EXPECT_FALSE(run.exited) << "exit code " << run.exit_code << ", stderr:\n" << run.err;
  EXPECT_EQ(summary,
            "1 bodies can no longer touch anything: body top has no collision: it never touches "
            "anything");
  const std::string all = run.out + run.err;
  const std::string warning = "body top has no collision: it never touches anything";
  const std::size_t first = all.find(warning);
  EXPECT_NE(first, std::string::npos) << all;
  EXPECT_EQ(all.find(warning, first + 1), std::string::npos) << "warned twice:\n" << all;
}

// The gyroscope refused above (a rotor with mass on a continuous joint) starts with ~hold_joints
// naming its joint, as a list (rosparam, a launch file) or as one string (the command line), and
// says once that the rotor is held. A gyroscope spawned into it is not held by ~hold_joints (it
// names the start-up URDF's joints), only by its own <nonsmooth_sim joint> block.
TEST(NodeBadUrdf, TheGyroscopeStartsWithItsRotorJointHeld) {
  const std::string gyroscope = "_urdf_file:=" + Fixture("moving_joint.urdf");
  XmlRpc::XmlRpcValue list;
  list[0] = std::string("rotor_joint");
  ros::param::set("/held_list/hold_joints", list);
  const std::vector<std::vector<std::string>> runs = {
      {"__name:=held_list", gyroscope, "_paused:=true"},
      {"__name:=held_string", gyroscope, "_paused:=true", "_hold_joints:=rotor_joint"}};
  // ~hold_joints is the start-up URDF's: a spawned gyroscope holds only by its own block
  std::ifstream file(Fixture("moving_joint.urdf"));
  const std::string gyroscope_xml((std::istreambuf_iterator<char>(file)),
                                  std::istreambuf_iterator<char>());
  std::string held_by_block = gyroscope_xml;
  held_by_block.insert(held_by_block.find("</robot>"),
                       "<nonsmooth_sim joint=\"rotor_joint\"><hold/></nonsmooth_sim>");
  std::vector<SpawnModel> spawns(2);
  spawns[0].request.model_name = "unheld";
  spawns[0].request.model_xml = gyroscope_xml;
  spawns[1].request.model_name = "held";
  spawns[1].request.model_xml = held_by_block;
  for (std::size_t k = 0; k < spawns.size(); ++k) {
    spawns[k].request.initial_pose.position.x = 1.0 + static_cast<double>(k);
    spawns[k].request.initial_pose.orientation.w = 1.0;
  }
  std::vector<bool> called(spawns.size(), false);
  for (const std::vector<std::string>& args : runs) {
    const std::string node = "/" + args[0].substr(8) + "/";
    bool services_up = false;
    const NodeRun run = RunNode(args, [&] {
      services_up = ros::service::exists(node + "get_state", false);
      if (services_up && args[0] == "__name:=held_list") {
        for (std::size_t k = 0; k < spawns.size(); ++k) {
          called[k] = ros::service::call(node + "spawn_urdf_model", spawns[k]);
        }
      }
      return services_up;
    });
    EXPECT_TRUE(services_up) << args[0] << ": stderr:\n" << run.err;
    EXPECT_FALSE(run.exited) << args[0] << ": exit code " << run.exit_code << ", stderr:\n"
                             << run.err;
    const std::string all = run.out + run.err;
    const std::string warning = "urdf: joint \"rotor_joint\" (continuous) is held rigid at 0 rad "
                                "by the option hold_joints: its link \"rotor\" (0.1 kg and 1 "
                                "collision) is merged into its parent link \"frame\"";
    const std::size_t first = all.find(warning);
    EXPECT_NE(first, std::string::npos) << args[0] << ":\n" << all;
    EXPECT_EQ(all.find(warning, first + 1), std::string::npos) << "warned twice:\n" << all;
  }
  ASSERT_TRUE(called[0] && called[1]) << "a ~spawn_urdf_model call failed";
  EXPECT_FALSE(spawns[0].response.success);
  EXPECT_NE(spawns[0].response.status_message.find(
                "joint \"rotor_joint\" (continuous) moves link \"rotor\""),
            std::string::npos)
      << spawns[0].response.status_message;
  EXPECT_TRUE(spawns[1].response.success) << spawns[1].response.status_message;
}

TEST(NodeBadUrdf, TheGoodUrdfStartsWithTheSameCommandLine) {
  // the node comes up (its services appear) and stops cleanly on SIGINT: the failures above are
  // the fixtures' own
  bool services_up = false;
  const NodeRun run = RunNode({"__name:=good_urdf",
                           "_urdf_file:=" + std::string(NONSMOOTH_SIM_SOURCE_DIR) +
                               "/urdf/tippe_top.urdf",
                           "_paused:=true"},
                          [&] {
                            services_up = ros::service::exists("/good_urdf/get_state", false);
                            return services_up;
                          });
  EXPECT_TRUE(services_up) << "stderr:\n" << run.err;
  EXPECT_FALSE(run.exited) << "exit code " << run.exit_code << ", stderr:\n" << run.err;
  EXPECT_EQ(run.exit_code, 0) << "stderr:\n" << run.err;
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_bad_urdf_test");
  ros::Time::init();
  return RUN_ALL_TESTS();
}
