// The scene loader and the world build without ROS: every #include in include/nonsmooth_sim/scene_io
// and src/scene_io names a standard or Eigen header, the core, the mesh library, the loader
// itself, or one of the four plain libraries it uses (urdfdom's parser, console_bridge, TinyXML2,
// yaml-cpp), or POSIX's file calls (fcntl.h, sys/stat.h, unistd.h); every #include in
// include/nonsmooth_sim/mesh and src/mesh a standard or Eigen header, the core, the mesh library,
// assimp or qhull; every #include in include/nonsmooth_sim/world and
// src/world a standard or Eigen header, the core, the loader or the world. roscpp, the ROS urdf
// package (<urdf/model.h>) or the node's headers fail this test.
#include <gtest/gtest.h>

#include <string>

#include "../include_rules.h"

namespace nonsmooth_sim::test {
namespace {

bool IsAllowed(const std::string& header) {
  if (StartsWithOneOf(header, {"Eigen/", "nonsmooth_sim/core/", "nonsmooth_sim/mesh/",
                               "nonsmooth_sim/scene_io/"})) {
    return true;
  }
  // and POSIX for files that must be regular before they are opened (bounded_input.cpp)
  for (const char* library : {"urdf_parser/urdf_parser.h", "console_bridge/console.h",
                              "tinyxml2.h", "yaml-cpp/yaml.h", "yaml-cpp/eventhandler.h",
                              "fcntl.h", "sys/stat.h", "unistd.h"}) {
    if (header == library) return true;
  }
  // and the loader's private headers next to its sources (src/scene_io/link_groups.h)
  if (header.find('/') == std::string::npos &&
      std::filesystem::is_regular_file(std::filesystem::path(NONSMOOTH_SIM_SOURCE_DIR) /
                                       "src/scene_io" / header)) {
    return true;
  }
  return IsStandardHeader(header);
}

// the mesh library: standard, Eigen, the core, itself, assimp and qhull
bool IsAllowedInMesh(const std::string& header) {
  return StartsWithOneOf(header, {"Eigen/", "nonsmooth_sim/core/", "nonsmooth_sim/mesh/",
                                  "assimp/", "libqhull_r/"}) ||
         IsStandardHeader(header);
}

// the world: standard, Eigen, the core, the loader and itself only (no third-party library)
bool IsAllowedInWorld(const std::string& header) {
  return StartsWithOneOf(header, {"Eigen/", "nonsmooth_sim/core/", "nonsmooth_sim/scene_io/",
                                  "nonsmooth_sim/world/"}) ||
         IsStandardHeader(header);
}

TEST(SceneIoIsRosFree, EveryIncludeIsStandardEigenCoreOrAPlainLibrary) {
  const IncludeScan scan =
      ScanIncludes({"include/nonsmooth_sim/scene_io", "src/scene_io"}, IsAllowed);
  ASSERT_GE(scan.files, 6u) << "scene_io sources not found under " << NONSMOOTH_SIM_SOURCE_DIR;
  EXPECT_GT(scan.includes, 0);
  for (const std::string& f : scan.forbidden) ADD_FAILURE() << f;
}

TEST(MeshIsRosFree, EveryIncludeIsStandardEigenCoreAssimpOrQhull) {
  const IncludeScan scan = ScanIncludes({"include/nonsmooth_sim/mesh", "src/mesh"}, IsAllowedInMesh);
  ASSERT_GE(scan.files, 2u) << "mesh sources not found under " << NONSMOOTH_SIM_SOURCE_DIR;
  EXPECT_GT(scan.includes, 0);
  for (const std::string& f : scan.forbidden) ADD_FAILURE() << f;
  EXPECT_FALSE(IsAllowedInMesh("ros/ros.h"));
  EXPECT_FALSE(IsAllowedInMesh("resource_retriever/retriever.h"));
}

TEST(WorldIsRosFree, EveryIncludeIsStandardEigenCoreLoaderOrWorld) {
  const IncludeScan scan =
      ScanIncludes({"include/nonsmooth_sim/world", "src/world"}, IsAllowedInWorld);
  ASSERT_GE(scan.files, 10u) << "world sources not found under " << NONSMOOTH_SIM_SOURCE_DIR;
  EXPECT_GT(scan.includes, 0);
  for (const std::string& f : scan.forbidden) ADD_FAILURE() << f;
  EXPECT_FALSE(IsAllowedInWorld("ros/ros.h"));
  EXPECT_FALSE(IsAllowedInWorld("nonsmooth_sim/node/conversions.h"));
  EXPECT_FALSE(IsAllowedInWorld("geometry_msgs/Pose.h"));
  EXPECT_FALSE(IsAllowedInWorld("yaml-cpp/yaml.h"));
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
}  // namespace nonsmooth_sim::test
