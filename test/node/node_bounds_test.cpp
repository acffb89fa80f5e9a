// ~spawn_urdf_model at its bounds (node_bounds_test.test: the Tippe-Top duel, paused):
// - sizes: model_xml over ~max_urdf_bytes (16 MiB) refused before parsing; names over 256 bytes;
//   more than 4 096 collisions in one URDF; a world of more than 16 384 collisions;
// - names that would share a TF frame or a ~wrench/ topic after sanitising (collisions "x-y" and
//   "x_y" of one model) refused, naming both;
// - robot_namespace confined to the model's own namespace: "/", global parameters (/rosdistro,
//   /use_sim_time, /run_id, the start-up /robot_description) and another model's namespace are
//   refused and keep their values; two models never share a description parameter.
// Every refusal leaves the world as it was (~get_state bit-identical, the same models).
#include <gtest/gtest.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "nonsmooth_sim/DeleteModel.h"
#include "nonsmooth_sim/GetSimulationState.h"
#include "nonsmooth_sim/GetWorldProperties.h"
#include "nonsmooth_sim/SpawnModel.h"
#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

const std::string kTippeTopUrdf = std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/urdf/tippe_top.urdf";
constexpr std::size_t kMaxUrdfBytes = std::size_t{16} << 20;  // ~max_urdf_bytes' default

const std::string kInertial =
    "<inertial><mass value=\"1\"/><inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" "
    "iyz=\"0\" izz=\"0.01\"/></inertial>";

std::string Ball(const std::string& name, double x = 0.0) {
  return "<collision name=\"" + name + "\"><origin xyz=\"" + std::to_string(x) +
         " 0 0\"/><geometry><sphere radius=\"0.01\"/></geometry></collision>";
}

// A free body "b" with the given collisions.
std::string Body(const std::string& collisions, const std::string& link = "b") {
  return "<robot name=\"r\"><link name=\"" + link + "\">" + kInertial + collisions +
         "</link></robot>";
}

// A static root with `statics` collisions and a free body with one.
std::string StaticField(int statics) {
  std::string field;
  for (int k = 0; k < statics; ++k) field += Ball("s" + std::to_string(k), 0.03 * k);
  return "<robot name=\"field\"><link name=\"ground_field\">" + field + "</link>"
         "<link name=\"b\">" + kInertial + Ball("c") + "</link><joint name=\"j\" "
         "type=\"floating\"><parent link=\"ground_field\"/><child link=\"b\"/>"
         "<origin xyz=\"0 0 1\"/></joint></robot>";
}

class Bounds : public testing::Test {
 protected:
  SimulationState State() {
    return Call<GetSimulationState>(nh_, kNode + "get_state").response.state;
  }
  std::vector<std::string> Models() {
    return Call<GetWorldProperties>(nh_, kNode + "get_world_properties").response.model_names;
  }
  SpawnModel::Response Spawn(const std::string& name, const std::string& xml, double x,
                             const std::string& robot_namespace = "") {
    SpawnModel srv;
    srv.request.model_name = name;
    srv.request.model_xml = xml;
    srv.request.robot_namespace = robot_namespace;
    srv.request.initial_pose.position.x = x;
    srv.request.initial_pose.position.z = 0.5;
    srv.request.initial_pose.orientation.w = 1.0;
    return Call<SpawnModel>(nh_, kNode + "spawn_urdf_model", srv).response;
  }
  bool Delete(const std::string& name) {
    DeleteModel srv;
    srv.request.model_name = name;
    return Call<DeleteModel>(nh_, kNode + "delete_model", srv).response.success;
  }
  // The spawn is refused with every part of `expected` in the reply, and nothing changed.
  void ExpectRefused(const SpawnModel::Response& res,
                     const std::vector<std::string>& expected) {
    EXPECT_FALSE(res.success) << expected.front();
    for (const std::string& part : expected) {
      EXPECT_NE(res.status_message.find(part), std::string::npos)
          << "\"" << part << "\" not in: " << res.status_message;
    }
    EXPECT_NE(res.status_message.find("nothing changed"), std::string::npos)
        << res.status_message;
    EXPECT_EQ(res.status_message.find('\n'), std::string::npos) << res.status_message;
    EXPECT_EQ(Models(), models_);
    const SimulationState now = State();
    EXPECT_EQ(now.sim_time, before_.sim_time);
    ExpectSameBodies(before_, now);
  }
  void Remember() {
    before_ = State();
    models_ = Models();
  }
  ros::NodeHandle nh_;
  SimulationState before_;
  std::vector<std::string> models_;
};

TEST_F(Bounds, SizesOfTheUrdfAndItsNamesAreBounded) {
  Remember();
  const std::string xml = ReadFile(kTippeTopUrdf);
  ASSERT_FALSE(xml.empty());
  // 16 MiB + 1 byte: a valid URDF with a long comment (500 MB used to be parsed for 27 s)
  std::string big = Body(Ball("c"));
  big.insert(big.size() - std::string("</robot>").size(),
             "<!--" + std::string(kMaxUrdfBytes + 1 - big.size() - 7, ' ') + "-->");
  ASSERT_EQ(big.size(), kMaxUrdfBytes + 1);
  ExpectRefused(Spawn("big", big, 1.0),
                {"model_xml has 16777217 bytes, more than the bound ~max_urdf_bytes = "
                 "16777216 bytes (16 MiB)"});
  ExpectRefused(Spawn(std::string(257, 'm'), xml, 1.0),
                {"model_name \"mmmm", "257 bytes, more than the bound of 256 bytes"});
  ExpectRefused(Spawn("long_link", Body(Ball("c"), std::string(257, 'l')), 1.0),
                {"urdf: line 1: link \"llll", "257 bytes, more than the bound of 256"});
  ExpectRefused(Spawn("long_collision", Body(Ball(std::string(257, 'c'))), 1.0),
                {"collision \"cccc", "257 bytes, more than the bound of 256"});
  std::string many;
  for (int k = 0; k < 4097; ++k) many += Ball("c" + std::to_string(k));
  ExpectRefused(Spawn("many", Body(many), 1.0), {"more than 4096 collisions in one URDF"});

  // per world: 3 x 4 096 + the duel's 5 fit, a fourth field does not
  for (int k = 0; k < 3; ++k) {
    const std::string name = "field" + std::to_string(k);
    const SpawnModel::Response res = Spawn(name, StaticField(4095), 2.0 + k);
    ASSERT_TRUE(res.success) << res.status_message;
  }
  Remember();
  ExpectRefused(Spawn("field3", StaticField(4095), 6.0),
                {"collisions, more than 16384 (the bound on collisions per world)"});
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(Delete("field" + std::to_string(k)));
}

TEST_F(Bounds, NamesThatWouldShareAFrameOrTopicAreRefused) {
  Remember();
  // a spawned model's names keep their "<model>/" (frames "xy/..._contact", topics
  // ~wrench/xy/...): only names of one model that differ in a sanitised character can clash
  ExpectRefused(Spawn("xy", Body(Ball("x_y") + Ball("x-y", 0.02)), 1.0),
                {"model xy: collision \"xy/x-y\" would have the contact frame "
                 "\"xy/x_y_contact\" and topic ~wrench/xy/x_y of collision \"xy/x_y\""});
}

TEST_F(Bounds, RobotNamespaceStaysInTheModelsOwnNamespace) {
  const std::string xml = ReadFile(kTippeTopUrdf);
  std::string rosdistro, description;
  ASSERT_TRUE(nh_.getParam("/rosdistro", rosdistro));
  ASSERT_TRUE(nh_.getParam("/robot_description", description));
  bool use_sim_time = false;
  ASSERT_TRUE(nh_.getParam("/use_sim_time", use_sim_time));
  Remember();
  for (const char* ns : {"/", "/rosdistro", "/use_sim_time", "/run_id", "rosdistro",
                                "/top1", "other"}) {
    ExpectRefused(Spawn("n1", xml, 1.0, ns), {"must be the model's own namespace /n1"});
  }
  ExpectRefused(Spawn("n1", xml, 1.0, "/"), {"robot_namespace \"/\" resolves to /: "});
  ExpectRefused(Spawn("n1", xml, 1.0, "~private"), {"a private name is not allowed"});
  // a model named like a global parameter: its own namespace holds a value
  ExpectRefused(Spawn("rosdistro", xml, 1.0), {"the parameter /rosdistro holds a value"});
  ExpectRefused(Spawn("robot_description", xml, 1.0),
                {"the parameter /robot_description holds a value"});
  // someone else's description under the model's namespace
  nh_.setParam("/n3/robot_description", "someone's");
  ExpectRefused(Spawn("n3", xml, 1.0), {"/n3/robot_description exists already"});
  std::string kept;
  EXPECT_TRUE(nh_.getParam("/n3/robot_description", kept));
  EXPECT_EQ(kept, "someone's");

  // accepted: the own namespace and one under it; another model's is refused
  SpawnModel::Response res = Spawn("n1", xml, 1.0);
  ASSERT_TRUE(res.success) << res.status_message;
  res = Spawn("n2", xml, 1.5, "n2/sub");
  ASSERT_TRUE(res.success) << res.status_message;
  std::string n1, n2;
  EXPECT_TRUE(nh_.getParam("/n1/robot_description", n1));
  EXPECT_TRUE(nh_.getParam("/n2/sub/robot_description", n2));
  EXPECT_EQ(n1, xml);
  EXPECT_EQ(n2, xml);
  Remember();
  ExpectRefused(Spawn("n4", xml, 2.0, "/n1"), {"must be the model's own namespace /n4"});
  // deleting one model removes its description only; the name can be used again
  EXPECT_TRUE(Delete("n1"));
  EXPECT_FALSE(nh_.hasParam("/n1/robot_description"));
  EXPECT_TRUE(nh_.getParam("/n2/sub/robot_description", n2));
  res = Spawn("n1", xml, 1.0);
  EXPECT_TRUE(res.success) << res.status_message;
  EXPECT_TRUE(Delete("n1"));
  EXPECT_TRUE(Delete("n2"));

  std::string after;
  EXPECT_TRUE(nh_.getParam("/rosdistro", after));
  EXPECT_EQ(after, rosdistro);
  EXPECT_TRUE(nh_.getParam("/robot_description", after));
  EXPECT_EQ(after, description);
  bool sim_time_after = false;
  EXPECT_TRUE(nh_.getParam("/use_sim_time", sim_time_after));
  EXPECT_EQ(sim_time_after, use_sim_time);
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_bounds_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
