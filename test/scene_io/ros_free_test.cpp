// The scene loader and the world build without ROS: every #include in include/nonsmooth_sim/scene_io
// and src/scene_io names a standard or Eigen header, the core, the loader itself, or one of the
// four plain libraries it uses (urdfdom's parser, console_bridge, TinyXML2, yaml-cpp), or POSIX's
// file calls (fcntl.h, sys/stat.h, unistd.h); every #include in include/nonsmooth_sim/world and
// src/world a standard or Eigen header, the core, the loader or the world. roscpp, the ROS urdf
// package (<urdf/model.h>) or the node's headers fail this test.
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
    if (ext == ".h" || ext == ".cpp") files.push_back(entry.path());
  }
  return files;
}

bool IsAllowed(const std::string& header) {
  for (const char* prefix : {"Eigen/", "nonsmooth_sim/core/", "nonsmooth_sim/scene_io/"}) {
    if (header.rfind(prefix, 0) == 0) return true;
  }
  // and POSIX for files that must be regular before they are opened (bounded_input.cpp)
  for (const char* library : {"urdf_parser/urdf_parser.h", "console_bridge/console.h",
                              "tinyxml2.h", "yaml-cpp/yaml.h", "yaml-cpp/eventhandler.h",
                              "fcntl.h", "sys/stat.h", "unistd.h"}) {
    if (header == library) return true;
  }
  // standard headers have no directory and no extension (<vector>, <cmath>, ...)
  return header.find('/') == std::string::npos && header.find('.') == std::string::npos;
}

TEST(SceneIoIsRosFree, EveryIncludeIsStandardEigenCoreOrAPlainLibrary) {
  const fs::path root = NONSMOOTH_SIM_SOURCE_DIR;
  std::vector<fs::path> files = SourcesUnder(root / "include/nonsmooth_sim/scene_io");
  const auto src = SourcesUnder(root / "src/scene_io");
  files.insert(files.end(), src.begin(), src.end());
  ASSERT_GE(files.size(), 6u) << "scene_io sources not found under " << root;

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

// the world: standard, Eigen, the core, the loader and itself only (no third-party library)
bool IsAllowedInWorld(const std::string& header) {
  for (const char* prefix :
       {"Eigen/", "nonsmooth_sim/core/", "nonsmooth_sim/scene_io/", "nonsmooth_sim/world/"}) {
    if (header.rfind(prefix, 0) == 0) return true;
  }
  return header.find('/') == std::string::npos && header.find('.') == std::string::npos;
}

TEST(WorldIsRosFree, EveryIncludeIsStandardEigenCoreLoaderOrWorld) {
  const fs::path root = NONSMOOTH_SIM_SOURCE_DIR;
  std::vector<fs::path> files = SourcesUnder(root / "include/nonsmooth_sim/world");
  const auto src = SourcesUnder(root / "src/world");
  files.insert(files.end(), src.begin(), src.end());
  ASSERT_GE(files.size(), 10u) << "world sources not found under " << root;

  const std::regex include_line(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
  int includes = 0;
  for (const auto& file : files) {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
      std::smatch m;
      if (!std::regex_search(line, m, include_line)) continue;
      ++includes;
      EXPECT_TRUE(IsAllowedInWorld(m[1])) << file << " includes <" << m[1] << ">";
    }
  }
  EXPECT_GT(includes, 0);
  EXPECT_FALSE(IsAllowedInWorld("ros/ros.h"));
  EXPECT_FALSE(IsAllowedInWorld("nonsmooth_sim/node/conversions.h"));
  EXPECT_FALSE(IsAllowedInWorld("geometry_msgs/Pose.h"));
  EXPECT_TRUE(IsAllowedInWorld("nonsmooth_sim/world/world.h"));
}

TEST(SceneIoIsRosFree, RecognisesForbiddenIncludes) {
  // the checker itself must reject what it is there to catch
  EXPECT_FALSE(IsAllowed("ros/ros.h"));
  EXPECT_FALSE(IsAllowed("urdf/model.h"));
  EXPECT_FALSE(IsAllowed("nonsmooth_sim/node/urdf_scene.h"));
  EXPECT_FALSE(IsAllowed("tf2_ros/transform_broadcaster.h"));
  EXPECT_TRUE(IsAllowed("urdf_parser/urdf_parser.h"));
  EXPECT_TRUE(IsAllowed("yaml-cpp/yaml.h"));
  EXPECT_TRUE(IsAllowed("vector"));
}

}  // namespace
