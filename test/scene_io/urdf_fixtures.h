// The URDF fixtures and checks the loader's tests share (urdf_loader_*_test.cpp): small robots
// written inline, the one error line of a URDF that must not load, warnings and shapes compared.
#ifndef NONSMOOTH_SIM_TEST_SCENE_IO_URDF_FIXTURES_H_
#define NONSMOOTH_SIM_TEST_SCENE_IO_URDF_FIXTURES_H_

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <initializer_list>
#include <string>

#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace nonsmooth_sim::scene_io::urdf_test {

inline std::string SourcePath(const std::string& relative) {
  return std::string(NONSMOOTH_SIM_SOURCE_DIR) + "/" + relative;
}

// URDF rpy: fixed axes x, y, z, i.e. R = Rz(yaw) Ry(pitch) Rx(roll)
inline Eigen::Matrix3d Rpy(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// One link "b" with the given body, plus extra top-level XML.
inline std::string Robot(const std::string& link_body, const std::string& extra = "") {
  return "<robot name=\"r\"><link name=\"b\">" + link_body + "</link>" + extra + "</robot>";
}
inline const std::string kUnitInertial =
    "<inertial><mass value=\"2\"/>"
    "<inertia ixx=\"1\" ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>";
inline const std::string kBall =
    "<collision name=\"ball\"><geometry><sphere radius=\"0.1\"/></geometry></collision>";

// A massless root "world" with `world_body` inside its <link>, plus extra XML.
inline std::string World(const std::string& world_body, const std::string& extra) {
  return "<robot name=\"r\"><link name=\"world\">" + world_body + "</link>" + extra + "</robot>";
}
// A free link `name` on a floating joint from world at `xyz`, with a sphere `collision`.
inline std::string FloatingBall(const std::string& name, const std::string& xyz,
                         const std::string& collision) {
  return "<link name=\"" + name + "\">" + kUnitInertial + "<collision name=\"" + collision +
         "\"><geometry><sphere radius=\"0.1\"/></geometry></collision></link>"
         "<joint name=\"world_" + name + "\" type=\"floating\"><parent link=\"world\"/>"
         "<child link=\"" + name + "\"/><origin xyz=\"" + xyz + "\"/></joint>";
}

// The one error line of a URDF that must not load.
inline std::string LoadError(const std::string& xml, const UrdfSceneOptions& options = {}) {
  try {
    SceneFromUrdf(xml, options);
  } catch (const UrdfError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind("urdf: ", 0), 0u) << message;
    return message;
  }
  ADD_FAILURE() << "loaded without an error:\n" << xml;
  return "";
}

inline void ExpectContains(const std::string& message, std::initializer_list<std::string> parts) {
  for (const std::string& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << "\"" << part << "\" not in: " << message;
  }
}

inline bool HasWarning(const UrdfScene& urdf, std::initializer_list<std::string> parts) {
  for (const std::string& warning : urdf.warnings) {
    bool all = true;
    for (const std::string& part : parts) all = all && warning.find(part) != std::string::npos;
    if (all) return true;
  }
  return false;
}

inline void ExpectSameShape(const Shape& a, const Shape& b, const std::string& name) {
  EXPECT_EQ(a.type, b.type) << name;
  EXPECT_EQ(a.radius, b.radius) << name;
  EXPECT_EQ(a.half_length, b.half_length) << name;
  EXPECT_EQ(a.half_extents, b.half_extents) << name;
}

inline const std::string kShellLink =
    kUnitInertial + "<collision name=\"shell\"><geometry><sphere radius=\"0.1\"/></geometry>"
                    "</collision>";
inline std::string Extension(const std::string& content, const std::string& link = "b") {
  return "<nonsmooth_sim reference=\"" + link + "\">" + content + "</nonsmooth_sim>";
}

}  // namespace nonsmooth_sim::scene_io::urdf_test

#endif  // NONSMOOTH_SIM_TEST_SCENE_IO_URDF_FIXTURES_H_
