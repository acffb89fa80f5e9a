// The core library depends on Eigen and the C++ standard library only: every #include in
// include/nonsmooth_sim/core and src/core names an Eigen header, a standard header or another
// core header. A ROS, tf2, urdf or rosbag include (or any other library) fails this test.
#include <gtest/gtest.h>

#include <string>

#include "../include_rules.h"

namespace nonsmooth_sim::test {
namespace {

bool IsAllowed(const std::string& header) {
  return StartsWithOneOf(header, {"Eigen/", "unsupported/Eigen/", "nonsmooth_sim/core/"}) ||
         IsStandardHeader(header);
}

TEST(CoreIsRosFree, EveryIncludeIsEigenStandardOrCore) {
  const IncludeScan scan = ScanIncludes({"include/nonsmooth_sim/core", "src/core"}, IsAllowed);
  ASSERT_GE(scan.files, 4u) << "core sources not found under " << NONSMOOTH_SIM_SOURCE_DIR;
  EXPECT_GT(scan.includes, 0);
  for (const std::string& f : scan.forbidden) ADD_FAILURE() << f;
}

TEST(CoreIsRosFree, RecognisesForbiddenIncludes) {
  // the checker itself must reject what it is there to catch
  EXPECT_FALSE(IsAllowed("ros/ros.h"));
  EXPECT_FALSE(IsAllowed("tf2_ros/transform_broadcaster.h"));
  EXPECT_FALSE(IsAllowed("urdf_parser/urdf_parser.h"));
  EXPECT_FALSE(IsAllowed("rosbag/bag.h"));
  EXPECT_TRUE(IsAllowed("Eigen/Core"));
  EXPECT_TRUE(IsAllowed("vector"));
}

}  // namespace
}  // namespace nonsmooth_sim::test
