// URDF <mesh> collisions (urdf_scene.h, mesh_source.h; docs/urdf.md, "Meshes"): package:// found
// on ROS_PACKAGE_PATH as rospack finds it, file:// and relative paths; a top whose collision is an
// STL stands on the ground instead of falling through it; a box from an STL rests and slides as
// the box shape does; every bad mesh refused with one line naming the link, the collision and the
// file, and what is allowed, and nothing loaded.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "mesh_fixtures.h"
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/scene_io/mesh_source.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "urdf_fixtures.h"
#include "../measured_value.h"

namespace nonsmooth_sim::scene_io {
namespace {

using test::Scientific;

using namespace urdf_test;  // NOLINT
using namespace mesh_test;  // NOLINT

// Half extents exact in float (STL stores float): the mesh box is exactly the box shape.
const Eigen::Vector3d kHalf(0.125, 0.0625, 0.03125);

// Link "b" with a unit-ish inertial of a 0.5 kg box of kHalf and one collision `geometry`.
std::string BoxRobot(const std::string& geometry) {
  const double m = 0.5;
  const Eigen::Vector3d h2 = kHalf.cwiseAbs2();
  const auto moment = [&](double a, double b) { return Number(m * (a + b) / 3.0); };
  return Robot("<inertial><mass value=\"0.5\"/><inertia ixx=\"" + moment(h2.y(), h2.z()) +
               "\" ixy=\"0\" ixz=\"0\" iyy=\"" + moment(h2.x(), h2.z()) + "\" iyz=\"0\" izz=\"" +
               moment(h2.x(), h2.y()) + "\"/></inertial><collision name=\"c\"><geometry>" +
               geometry + "</geometry></collision>");
}

std::string MeshTag(const std::string& filename, const std::string& scale = "") {
  return "<mesh filename=\"" + filename + "\"" +
         (scale.empty() ? "" : " scale=\"" + scale + "\"") + "/>";
}

UrdfSceneOptions WithPackagePath(const std::string& path) {
  UrdfSceneOptions options;
  options.ros_package_path = path;
  return options;
}

TEST(UrdfMesh, PackageUrlsAreFoundOnTheRosPackagePathAsRospackFindsThem) {
  const TempFolder folder;
  // ws/src/shapes_pkg is the package "my_meshes" (the folder's name does not matter); a copy
  // under a CATKIN_IGNORE folder and one inside another package are not searched
  const std::string xml = "<package format=\"2\"><name>my_meshes</name></package>";
  folder.Write("ws/src/shapes_pkg/package.xml", xml);
  folder.Write("ws/src/shapes_pkg/meshes/box.stl", BinaryStl(BoxMesh(kHalf)));
  folder.Write("ws/build/CATKIN_IGNORE", "");
  folder.Write("ws/build/a/package.xml", xml);
  folder.Write("ws/build/a/meshes/box.stl", BinaryStl(BoxMesh(2.0 * kHalf)));
  const std::string robot = BoxRobot(MeshTag("package://my_meshes/meshes/box.stl"));
  const UrdfScene urdf =
      SceneFromUrdf(robot, WithPackagePath("/nonexistent:" + folder.path() + "/ws"));
  ASSERT_EQ(urdf.scene.colliders.size(), 2u);  // the hull and the ground
  const Collider& c = urdf.scene.colliders[0];
  ASSERT_EQ(c.shape.type, ShapeType::kConvexHull);
  EXPECT_NEAR(ShapeVolume(c.shape), 8.0 * kHalf.prod(), 1e-18);
  EXPECT_TRUE(urdf.warnings.empty());
  // the mass and inertia are the <inertial>'s, not the mesh's
  EXPECT_EQ(urdf.scene.bodies[0].mass, 0.5);
  // through the environment's ROS_PACKAGE_PATH when the option is unset
  ::setenv("ROS_PACKAGE_PATH", (folder.path() + "/ws").c_str(), 1);
  EXPECT_EQ(SceneFromUrdf(robot).scene.colliders[0].shape.hull, c.shape.hull);  // cached
  ::unsetenv("ROS_PACKAGE_PATH");
}

TEST(UrdfMesh, FileUrlsAndPathsRelativeToTheUrdfFileAreFound) {
  const TempFolder folder;
  folder.Write("meshes/box.obj", Obj(BoxMesh(kHalf)));
  const std::string dae = folder.Write("elsewhere/box.dae", Dae(BoxMesh(kHalf)));
  for (const std::string& filename : {std::string("meshes/box.obj"), "file://" + dae}) {
    const std::string path = folder.Write("robot.urdf", BoxRobot(MeshTag(filename)));
    const UrdfScene urdf = LoadUrdfFile(path);
    ASSERT_EQ(urdf.scene.colliders[0].shape.type, ShapeType::kConvexHull) << filename;
    EXPECT_NEAR(ShapeVolume(urdf.scene.colliders[0].shape), 8.0 * kHalf.prod(), 1e-18);
  }
  // a URDF text: relative to options.mesh_directory
  UrdfSceneOptions options;
  options.mesh_directory = folder.path();
  EXPECT_EQ(SceneFromUrdf(BoxRobot(MeshTag("meshes/box.obj")), options)
                .scene.colliders[0].shape.type,
            ShapeType::kConvexHull);
}

// A top of revolution (apex down, a cone to a disc) as a triangle mesh: `n` points on each rim.
TriangleMesh TopMesh(int n) {
  TriangleMesh m;
  m.vertices.push_back({0, 0, 0});       // apex
  m.vertices.push_back({0, 0, 0.05});    // top centre
  for (int ring = 0; ring < 2; ++ring) {
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * kPi * i / n;
      m.vertices.push_back({0.03 * std::cos(a), 0.03 * std::sin(a), ring == 0 ? 0.04 : 0.05});
    }
  }
  for (int i = 0; i < n; ++i) {
    const int a = 2 + i, b = 2 + (i + 1) % n, c = 2 + n + i, d = 2 + n + (i + 1) % n;
    m.triangles.push_back({0, b, a});
    m.triangles.push_back({a, b, d});
    m.triangles.push_back({a, d, c});
    m.triangles.push_back({1, c, d});
  }
  return m;
}

TEST(UrdfMesh, ATopWhoseCollisionIsAnStlStandsOnTheGround) {
  // as a user writes it: package://, the mesh in its own frame, the top's tip at the link origin
  const TempFolder folder;
  folder.Write("pkg/package.xml", "<package><name>tops</name></package>");
  folder.Write("pkg/meshes/top.stl", BinaryStl(TopMesh(32)));
  const std::string robot =
      "<robot name=\"r\"><link name=\"top\"><inertial><origin xyz=\"0 0 0.035\"/>"
      "<mass value=\"0.05\"/><inertia ixx=\"1.2e-5\" ixy=\"0\" ixz=\"0\" iyy=\"1.2e-5\" iyz=\"0\" "
      "izz=\"1.6e-5\"/></inertial><collision name=\"hull\"><geometry>"
      "<mesh filename=\"package://tops/meshes/top.stl\"/></geometry></collision></link></robot>";
  const UrdfScene urdf = SceneFromUrdf(robot, WithPackagePath(folder.path()));
  Scene scene = urdf.scene;
  // spinning upright on its tip, a little tilted, 1 mm above the ground
  scene.initial_state[0].position.z() += 1e-3;
  scene.initial_state[0].orientation =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()));
  scene.initial_state[0].angular_velocity = Eigen::Vector3d(0.0, 0.0, 60.0);
  Simulator sim(scene, SimulatorOptions{});
  double lowest = 1.0;
  for (int k = 0; k < 2000; ++k) {  // 2 s
    sim.Step();
    const BodyState& s = sim.state()[0];
    // the hull's frame in the world: the body's pose, then the collider's
    Eigen::Isometry3d body = Eigen::Isometry3d::Identity();
    body.linear() = s.orientation.normalized().toRotationMatrix();
    body.translation() = s.position;
    const Eigen::Isometry3d pose = body * scene.colliders[0].pose;
    for (const Eigen::Vector3d& v : scene.colliders[0].shape.hull->vertices) {
      lowest = std::min(lowest, (pose * v).z());
    }
    ASSERT_GT(s.position.z(), 0.0) << "fell through at step " << k;
  }
  // the lowest vertex never sinks more than the contact's penetration (measured: ~1e-5 m)
  EXPECT_GT(lowest, -1e-3);
  EXPECT_LT(sim.state()[0].position.z(), 0.06);
}

// The scene of BoxRobot(geometry) resting on its largest face, pushed along x at 0.5 m/s.
Simulator PushedBox(const std::string& geometry, const UrdfSceneOptions& options) {
  Scene scene = SceneFromUrdf(BoxRobot(geometry), options).scene;
  scene.initial_state[0].position = Eigen::Vector3d(0.0, 0.0, kHalf.z());
  scene.initial_state[0].linear_velocity = Eigen::Vector3d(0.5, 0.0, 0.0);
  // the solver converged to round-off: the box's and the hull's face points are the same but
  // listed in another order, which at the default tolerance leaves differences of ~1e-10
  SimulatorOptions converged;
  converged.solver.tolerance_rel = 1e-12;
  converged.solver.tolerance_abs = 1e-20;
  converged.solver.max_iterations = kMaxSimulatorIterations;
  return Simulator(scene, converged);
}

TEST(UrdfMesh, ABoxFromAnStlRestsAndSlidesAsTheBoxShape) {
  const TempFolder folder;
  UrdfSceneOptions options;
  options.mesh_directory = folder.path();
  folder.Write("box.stl", BinaryStl(BoxMesh(kHalf)));
  const std::string size = Number(2 * kHalf.x()) + " " + Number(2 * kHalf.y()) + " " +
                           Number(2 * kHalf.z());
  Simulator box = PushedBox("<box size=\"" + size + "\"/>", options);
  Simulator hull = PushedBox(MeshTag("box.stl"), options);
  ASSERT_EQ(hull.scene().colliders[0].shape.type, ShapeType::kConvexHull);
  double worst = 0.0, rest_speed = 0.0;
  for (int k = 0; k < 2000; ++k) {  // slides (μ = 1: stops after v²/(2μg) = 1.3 cm), rests
    box.Step();
    hull.Step();
    const BodyState& a = box.state()[0];
    const BodyState& b = hull.state()[0];
    worst = std::max({worst, (a.position - b.position).norm(),
                      a.orientation.angularDistance(b.orientation),
                      (a.linear_velocity - b.linear_velocity).norm()});
    if (k >= 1000) {
      rest_speed = std::max(rest_speed, b.linear_velocity.norm() + b.angular_velocity.norm());
    }
  }
  ::testing::Test::RecordProperty("worst_difference", Scientific(worst));
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(rest_speed, 1e-9);  // at rest, no jitter
  EXPECT_NEAR(hull.state()[0].position.x(), 0.25 / (2.0 * 9.81), 2e-3);
}

// The one error line of `geometry` as the collision "c" of link "b": it names them, the file
// and what is allowed.
std::string MeshError(const std::string& geometry, const std::string& file,
                      const UrdfSceneOptions& options = {}) {
  const std::string message = LoadError(BoxRobot(geometry), options);
  ExpectContains(message, {"link \"b\" > collision \"c\"", file, "allowed"});
  return message;
}

TEST(UrdfMesh, EveryBadMeshIsRefusedWithOneLineNamingTheLinkAndTheFile) {
  const TempFolder folder;
  UrdfSceneOptions options;
  options.mesh_directory = folder.path();
  options.ros_package_path = folder.path() + "/ws";
  folder.Write("ws/p/package.xml", "<package><name>p</name></package>");
  folder.Write("ws/p/box.stl", BinaryStl(BoxMesh(kHalf)));
  folder.Write("ws/outside.stl", BinaryStl(BoxMesh(kHalf)));
  folder.Write("box.stl", BinaryStl(BoxMesh(kHalf)));
  folder.Write("empty.stl", "");
  folder.Write("garbage.stl", "solid nothing here\n12 34 oops\n");
  // flat: a square of two triangles; thin: a box 2 µm thick
  TriangleMesh square;
  square.vertices = {{0, 0, 0}, {0.1, 0, 0}, {0.1, 0.1, 0}, {0, 0.1, 0}};
  square.triangles = {{0, 1, 2}, {0, 2, 3}};
  folder.Write("flat.stl", BinaryStl(square));
  folder.Write("thin.obj", Obj(BoxMesh({0.1, 0.1, 1e-6})));
  folder.Write("folder.stl/x", "");
  const std::string fifo = folder.path() + "/pipe.stl";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const UrdfScene before = SceneFromUrdf(BoxRobot(MeshTag("box.stl")), options);

  ExpectContains(MeshError(MeshTag("missing.stl"), "missing.stl", options), {"no such file"});
  ExpectContains(MeshError(MeshTag("empty.stl"), "empty.stl", options), {"is empty"});
  ExpectContains(MeshError(MeshTag("garbage.stl"), "garbage.stl", options), {"assimp"});
  ExpectContains(MeshError(MeshTag("flat.stl"), "flat.stl", options),
                 {"coplanar or collinear"});
  ExpectContains(MeshError(MeshTag("thin.obj"), "thin.obj", options), {"thin"});
  ExpectContains(MeshError(MeshTag("box.stl", "1e4 1e4 1e4"), "box.stl", options),
                 {"reaches", "at most 1000 m"});
  ExpectContains(MeshError(MeshTag("folder.stl"), "folder.stl", options), {"is a directory"});
  ExpectContains(MeshError(MeshTag(fifo), "pipe.stl", options), {"is a FIFO"});
  ExpectContains(MeshError(MeshTag("/dev/zero"), "/dev/zero", options), {"character device"});
  for (const char* scale : {"0 1 1", "1 -1 1", "1 1 1e7", "1e-7 1 1"}) {
    ExpectContains(MeshError(MeshTag("box.stl", scale), "box.stl", options),
                   {"scale", "[1e-06, 1e+06]"});
  }
  ExpectContains(MeshError(MeshTag("package://p/../outside.stl"), "package://p/../outside.stl",
                           options),
                 {"escapes its package"});
  ExpectContains(MeshError(MeshTag("package://nowhere/box.stl"), "package://nowhere/box.stl",
                           options),
                 {"not on ROS_PACKAGE_PATH"});
  ExpectContains(MeshError(MeshTag("http://example.com/box.stl"), "http://example.com/box.stl",
                           options),
                 {"unknown scheme"});
  // larger than the loader's byte bound (options.max_bytes, the URDF's): 684 bytes > 600
  UrdfSceneOptions small = options;
  small.max_bytes = 600;
  ExpectContains(MeshError(MeshTag("box.stl"), "box.stl", small), {"more than the bound"});
  // a NaN scale is refused by the XML checks, naming the link's collision
  ExpectContains(LoadError(BoxRobot(MeshTag("box.stl", "1 nan 1")), options),
                 {"link \"b\" > collision \"c\"", "mesh", "not a finite number"});
  // nothing changed: the good mesh loads as before (the same hull)
  EXPECT_EQ(SceneFromUrdf(BoxRobot(MeshTag("box.stl")), options).scene.colliders[0].shape.hull,
            before.scene.colliders[0].shape.hull);
}

}  // namespace
}  // namespace nonsmooth_sim::scene_io
