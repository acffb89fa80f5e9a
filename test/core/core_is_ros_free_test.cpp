// The core library depends on Eigen and the C++ standard library only: every #include in
// include/nonsmooth_sim/core and src/core names an Eigen header, a standard header or another
// core header. A ROS, tf2, urdf or rosbag include (or any other library) fails this test.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::vector<fs::path> SourcesUnder(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const auto ext = entry.path().extension();
    if (ext == ".h" || ext == ".hpp" || ext == ".cpp" || ext == ".cc") files.push_back(entry.path());
  }
  return files;
}

bool IsAllowed(const std::string& header) {
  if (header.rfind("Eigen/", 0) == 0 || header.rfind("unsupported/Eigen/", 0) == 0) return true;
  if (header.rfind("nonsmooth_sim/core/", 0) == 0) return true;
  // standard headers have no directory and no extension (<vector>, <cmath>, ...)
  return header.find('/') == std::string::npos && header.find('.') == std::string::npos;
}

TEST(CoreIsRosFree, EveryIncludeIsEigenStandardOrCore) {
  const fs::path root = NONSMOOTH_SIM_SOURCE_DIR;
  std::vector<fs::path> files = SourcesUnder(root / "include/nonsmooth_sim/core");
  const auto src = SourcesUnder(root / "src/core");
  files.insert(files.end(), src.begin(), src.end());
  ASSERT_GE(files.size(), 4u) << "core sources not found under " << root;

  const std::regex include_line(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
  int includes = 0;
  for (const auto& file : files) {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
      std::smatch m;
      if (!std::regex_search(line, m, include_line)) continue;
      ++includes;
      EXPECT_TRUE(IsAllowed(m[1])) << file << " includes <" << m[1] << ">";
    }
  }
  EXPECT_GT(includes, 0);
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
