// Every link in TF (node_fixed_links_test.test: test/node/fixtures/fixed_links.urdf, paused): the
// links without a body of their own arrive on /tf_static (latched), as robot_state_publisher sends
// fixed joints, so rviz's RobotModel shows every link with nothing else running:
// - world → base (the massless root) and world → table (fixed to it, 1 m along x);
// - puck → lid (merged into the body by a fixed joint: 2 cm up, turned 90° about z);
// - a spawned copy "m2" adds m2/puck → m2/lid (its static links, placed by the spawn, are not
//   sent), and its delete removes it again, the start-up model's links kept.
// Before, no link but the bodies' own was in TF.
#include <gtest/gtest.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>
#include <map>
#include <mutex>
#include <string>

#include "nonsmooth_sim/DeleteModel.h"
#include "nonsmooth_sim/SpawnModel.h"
#include "ros_test_helpers.h"

namespace nonsmooth_sim::node::test {
namespace {

const std::string kUrdf =
    std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/test/node/fixtures/fixed_links.urdf";

// The last /tf_static message, by child frame.
class StaticFrames {
 public:
  explicit StaticFrames(ros::NodeHandle& nh)
      : sub_(nh.subscribe<tf2_msgs::TFMessage>(
            "/tf_static", 10, [this](const tf2_msgs::TFMessage::ConstPtr& m) {
              const std::lock_guard<std::mutex> lock(mutex_);
              last_.clear();
              for (const auto& t : m->transforms) last_[t.child_frame_id] = t;
              ++count_;
            })) {}
  ~StaticFrames() { sub_.shutdown(); }
  // waits for a message after the first `after` ones that satisfies `predicate`
  bool WaitFor(const std::function<bool(const std::map<std::string,
                                                        geometry_msgs::TransformStamped>&)>&
                   predicate,
               double timeout) {
    return test::WaitFor(
        [&] {
          const std::lock_guard<std::mutex> lock(mutex_);
          return count_ > 0 && predicate(last_);
        },
        timeout);
  }
  std::map<std::string, geometry_msgs::TransformStamped> Last() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return last_;
  }

 private:
  std::mutex mutex_;
  std::map<std::string, geometry_msgs::TransformStamped> last_;
  int count_ = 0;
  ros::Subscriber sub_;
};

void ExpectTransform(const std::map<std::string, geometry_msgs::TransformStamped>& frames,
                     const std::string& child, const std::string& parent, double x, double y,
                     double z, double yaw) {
  const auto found = frames.find(child);
  ASSERT_NE(found, frames.end()) << child << " not on /tf_static";
  const geometry_msgs::TransformStamped& t = found->second;
  EXPECT_EQ(t.header.frame_id, parent) << child;
  EXPECT_NEAR(t.transform.translation.x, x, 1e-12) << child;
  EXPECT_NEAR(t.transform.translation.y, y, 1e-12) << child;
  EXPECT_NEAR(t.transform.translation.z, z, 1e-12) << child;
  EXPECT_NEAR(t.transform.rotation.w, std::cos(yaw / 2), 1e-12) << child;
  EXPECT_NEAR(t.transform.rotation.z, std::sin(yaw / 2), 1e-12) << child;
  EXPECT_NEAR(t.transform.rotation.x, 0.0, 1e-12) << child;
  EXPECT_NEAR(t.transform.rotation.y, 0.0, 1e-12) << child;
}

TEST(FixedLinks, EveryLinkWithoutABodyOfItsOwnIsOnTfStatic) {
  ros::NodeHandle nh;
  StaticFrames frames(nh);
  ASSERT_TRUE(frames.WaitFor([](const auto& f) { return f.count("lid") > 0; }, 20.0));
  const auto start = frames.Last();
  EXPECT_EQ(start.size(), 3u);
  ExpectTransform(start, "base", "world", 0.0, 0.0, 0.0, 0.0);
  ExpectTransform(start, "table", "world", 1.0, 0.0, 0.0, 0.0);
  ExpectTransform(start, "lid", "puck", 0.0, 0.0, 0.02, M_PI / 2);

  SpawnModel spawn;
  spawn.request.model_name = "m2";
  spawn.request.model_xml = ReadFile(kUrdf);
  spawn.request.initial_pose.position.y = 1.0;
  spawn.request.initial_pose.orientation.w = 1.0;
  spawn = Call<SpawnModel>(nh, kNode + "spawn_urdf_model", spawn);
  ASSERT_TRUE(spawn.response.success) << spawn.response.status_message;
  ASSERT_TRUE(frames.WaitFor([](const auto& f) { return f.count("m2/lid") > 0; }, 20.0));
  const auto both = frames.Last();
  EXPECT_EQ(both.size(), 4u);
  ExpectTransform(both, "m2/lid", "m2/puck", 0.0, 0.0, 0.02, M_PI / 2);
  ExpectTransform(both, "lid", "puck", 0.0, 0.0, 0.02, M_PI / 2);

  DeleteModel remove;
  remove.request.model_name = "m2";
  remove = Call<DeleteModel>(nh, kNode + "delete_model", remove);
  ASSERT_TRUE(remove.response.success) << remove.response.status_message;
  ASSERT_TRUE(frames.WaitFor([](const auto& f) { return f.count("m2/lid") == 0; }, 20.0));
  EXPECT_EQ(frames.Last().size(), 3u);
}

}  // namespace
}  // namespace nonsmooth_sim::node::test

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_fixed_links_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
