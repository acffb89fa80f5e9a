// Meshes as bodies of revolution (mesh/mesh_revolution.h, <body_of_revolution> in docs/urdf.md):
// a UV cylinder and an icosphere fitted to the closed forms of their shapes; the axis found
// through the centroid whatever the mesh's pose; a box, a hexagonal prism and a mesh given the
// wrong axis refused with the deviation; and the loader's element checked strictly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <utility>
#include <vector>

#include "mesh_fixtures.h"
#include "nonsmooth_sim/collision_fcl/fcl_pairs.h"
#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/mesh/mesh_revolution.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"
#include "urdf_fixtures.h"

namespace nonsmooth_sim::scene_io {
namespace {

using mesh::FitBodyOfRevolution;
using namespace mesh_test;  // NOLINT
using namespace urdf_test;  // NOLINT

constexpr int kSectors = 48;

std::string FitError(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& axis,
                     std::optional<double> tolerance = {}) {
  try {
    FitBodyOfRevolution(points, axis, tolerance);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "fitted";
  return "";
}

TEST(MeshRevolution, CylinderKeepsItsFlatFacesAndItsRadius) {
  constexpr double kR = 0.02, kL = 0.005;
  // rims only, as CAD exports a cylinder, about (0.1, 0.2, 0.3)
  std::vector<Eigen::Vector3d> points =
      RevolutionMesh({{kR, kL}, {kR, -kL}}, kSectors).vertices;
  for (Eigen::Vector3d& p : points) p += Eigen::Vector3d(0.1, 0.2, 0.3);
  const mesh::BodyOfRevolution fit = FitBodyOfRevolution(points, Eigen::Vector3d::UnitZ(), {});
  EXPECT_LT((fit.frame.translation() - Eigen::Vector3d(0.1, 0.2, 0.3)).norm(), 1e-15);
  const RevolutionProfile& profile = *fit.shape.revolution;
  // the default tolerance is 1 % of the size; the rims rounded within half of it
  EXPECT_NEAR(fit.tolerance, 0.01 * std::hypot(kR, kL), 1e-15);
  EXPECT_GT(profile.top_disc_radius, kR - 3 * fit.tolerance);
  EXPECT_NEAR(profile.top_z, kL, 1e-15);
  EXPECT_NEAR(profile.bottom_z, -kL, 1e-15);
  // the deviation: the rims' rounding τ/2, more than the sectors' sagitta between the vertices
  const double sagitta = kR * (1.0 - std::cos(kPi / kSectors));
  EXPECT_NEAR(fit.deviation, std::max(sagitta, 0.5 * fit.tolerance), 1e-12);
  EXPECT_EQ(fit.shape.type, ShapeType::kRevolution);
  ASSERT_NE(fit.shape.hull, nullptr);  // its tessellation, for FCL
}

TEST(MeshRevolution, IcosphereIsItsSphere) {
  constexpr double kRadius = 0.05;
  const mesh::BodyOfRevolution fit =
      FitBodyOfRevolution(IcosphereMesh(3, kRadius).vertices, Eigen::Vector3d(1, 1, 0), {});
  // 642 vertices on the sphere, not in rings: every support within the deviation of the sphere's
  EXPECT_LT(fit.frame.translation().norm(), 1e-12);
  EXPECT_NEAR(fit.frame.linear().col(2).dot(Eigen::Vector3d(1, 1, 0).normalized()), 1.0, 1e-15);
  for (int i = 0; i <= 90; ++i) {
    const double theta = kPi * i / 90;
    const Eigen::Vector3d d(std::sin(theta), 0.0, std::cos(theta));
    EXPECT_NEAR(d.dot(RevolutionSupport(*fit.shape.revolution, d)), kRadius, fit.deviation);
  }
  EXPECT_LT(fit.deviation, 0.01 * kRadius);
}

// A mesh finer than the colliding hull's largest cap (4 096 vertices): every vertex counts, so
// the fit is as close as the mesh (a capped hull, a subset's, refused this one at 1.6e-4 m).
TEST(MeshRevolution, FineMeshesCountEveryVertex) {
  constexpr double kRadius = 0.015;
  constexpr int kRings = 100;
  std::vector<Eigen::Vector2d> meridian;
  for (int i = 0; i <= kRings; ++i) {
    const double t = kPi * i / kRings;
    meridian.emplace_back(kRadius * std::sin(t), kRadius * std::cos(t));
  }
  const TriangleMesh mesh = RevolutionMesh(meridian, kRings);
  ASSERT_GT(mesh.vertices.size(), static_cast<std::size_t>(kMaxHullVerticesBound));
  const auto fit = FitBodyOfRevolution(mesh.vertices, Eigen::Vector3d::UnitZ(), {});
  EXPECT_LT(fit.frame.translation().norm(), 1e-15);
  // the sectors' sagitta ρ(1 − cos(π/100)) at most, the arcs' R(1 − cos(π/200)) short of R
  EXPECT_LE(fit.deviation, kRadius * (1.0 - std::cos(kPi / kRings)));
  for (const RevolutionArc& arc : fit.shape.revolution->arcs) {
    EXPECT_NEAR(arc.radius, kRadius * std::cos(0.5 * kPi / kRings), 1e-12);
  }
}

TEST(MeshRevolution, FoundAboutATiltedAxisAsAboutZ) {
  std::vector<Eigen::Vector2d> meridian;
  for (int i = 0; i <= 60; ++i) {
    const double t = kPi * i / 60;
    meridian.emplace_back(0.02 * std::sin(t), 0.03 * std::cos(t));  // a prolate spheroid
  }
  const std::vector<Eigen::Vector3d> upright = RevolutionMesh(meridian, kSectors).vertices;
  const Eigen::Matrix3d turn = Rpy(0.3, -0.7, 1.1);
  std::vector<Eigen::Vector3d> tilted;
  for (const Eigen::Vector3d& p : upright) tilted.push_back(turn * p);
  const auto a = FitBodyOfRevolution(upright, Eigen::Vector3d::UnitZ(), {});
  const auto b = FitBodyOfRevolution(tilted, turn.col(2), {});
  ASSERT_EQ(a.shape.revolution->arcs.size(), b.shape.revolution->arcs.size());
  for (std::size_t k = 0; k < a.shape.revolution->arcs.size(); ++k) {
    EXPECT_NEAR(a.shape.revolution->arcs[k].radius, b.shape.revolution->arcs[k].radius, 1e-12);
  }
  // (the tessellation's sectors fall elsewhere between the mesh's: each within their sagitta)
  const double sagitta = 0.02 * (1.0 - std::cos(kPi / kSectors));
  EXPECT_LE(a.deviation, sagitta);
  EXPECT_LE(b.deviation, sagitta);
}

TEST(MeshRevolution, WhatIsNotABodyOfRevolutionIsRefusedWithItsDeviation) {
  // a box: its corners' circle sticks out of its faces by √(a² + b²) − a
  const std::string box = FitError(BoxMesh({0.02, 0.02, 0.01}).vertices, Eigen::Vector3d::UnitZ());
  std::printf("%s\n", box.c_str());
  ExpectContains(box, {"is not a body of revolution about the axis (0 0 1)", "within the tolerance",
                       "0.00828", "allowed:"});
  // a hexagonal prism: 1 − cos 30° = 13 % of its radius
  const std::string prism =
      FitError(RevolutionMesh({{0.02, 0.01}, {0.02, -0.01}}, 6).vertices, Eigen::Vector3d::UnitZ());
  ExpectContains(prism, {"is not a body of revolution", "0.00268"});
  // accepted with a tolerance above its deviation
  EXPECT_NO_THROW(FitBodyOfRevolution(RevolutionMesh({{0.02, 0.01}, {0.02, -0.01}}, 6).vertices,
                                      Eigen::Vector3d::UnitZ(), 0.003));
  // the wrong axis
  ExpectContains(FitError(RevolutionMesh({{0.02, 0.05}, {0.02, -0.05}}, kSectors).vertices,
                          Eigen::Vector3d::UnitX()),
                 {"is not a body of revolution about the axis (1 0 0)"});
  ExpectContains(FitError(BoxMesh({1, 1, 1}).vertices, Eigen::Vector3d::Zero()),
                 {"is not a direction"});
}

// Against other shapes through FCL (fcl_pairs.h): a sphere and a box placed `offset` beyond the
// body's support point along a random direction d (its normal there) are `offset` away, within
// the tessellation's sagitta (GJK runs on it: 48 sectors, 64 normal angles).
TEST(MeshRevolution, OtherShapesThroughFclWithinTheTessellation) {
  constexpr double kRadius = 0.05;
  const Shape body = FitBodyOfRevolution(IcosphereMesh(3, kRadius).vertices,
                                         Eigen::Vector3d::UnitZ(), {}).shape;
  // a triangle of a 48 × 64 grid cell on the sphere: its circumradius β = half the cell's
  // diagonal, its sagitta R(1 − cos β); half as much again for the profile's uneven arcs (an
  // icosphere's vertices are not in rings)
  const double beta = 0.5 * std::hypot(2 * kPi / 48, kPi / 64);
  const double sagitta = 1.5 * kRadius * (1.0 - std::cos(beta));
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d d = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const Eigen::Vector3d p = RevolutionSupport(*body.revolution, d);
    const double offset = i % 4 == 0 ? -1e-3 : 1e-3 * (1 + i % 7);
    Eigen::Isometry3d sphere_pose = origin, box_pose = origin;
    sphere_pose.translation() = p + (0.02 + offset) * d;
    box_pose.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), d)
                            .toRotationMatrix();
    box_pose.translation() = p + (0.01 + offset) * d;
    for (const auto& [other, pose] : {std::pair{Shape::Sphere(0.02), sphere_pose},
                                      std::pair{Shape::Box({0.03, 0.03, 0.01}), box_pose}}) {
      ContactGeometry out[kMaxPairContacts];
      const int n = CollideFcl(body, origin, other, pose, 0.1, out);
      ASSERT_GE(n, 1) << ShapeTypeName(other.type);
      double gap = INFINITY;
      for (int j = 0; j < n; ++j) gap = std::min(gap, out[j].gap);
      EXPECT_NEAR(gap, offset, sagitta) << ShapeTypeName(other.type) << " along " << d.transpose();
      EXPECT_GT(out[0].normal.dot(d), 0.99);
    }
  }
}

// The loader: <body_of_revolution> turns the collision's <mesh> into the fitted body, placed by
// the collision's <origin>; its element is strict.
class UrdfBodyOfRevolution : public testing::Test {
 protected:
  std::string Urdf(const std::string& element, const std::string& geometry = "") const {
    const std::string mesh = "<mesh filename=\"" + stl_ + "\"/>";
    return Robot(kUnitInertial + "<collision name=\"c\"><origin xyz=\"0 0 0.5\"/><geometry>" +
                     (geometry.empty() ? mesh : geometry) + "</geometry></collision>",
                 Extension("<collision name=\"c\">" + element + "</collision>"));
  }
  const TempFolder folder_;
  const std::string stl_ = folder_.Write(
      "c.stl", BinaryStl(RevolutionMesh({{0.0, 0.0625}, {0.03125, 0.0}, {0.0, -0.0625}}, 64)));
};

TEST_F(UrdfBodyOfRevolution, MeshBecomesTheFittedBodyAtTheCollisionsOrigin) {
  const UrdfScene urdf = SceneFromUrdf(Urdf("<body_of_revolution axis=\"0 0 2\"/>"));
  const Collider& c = urdf.scene.colliders.front();
  ASSERT_EQ(c.shape.type, ShapeType::kRevolution);
  // a double cone: its centroid at the origin, so the collider at the collision's origin
  EXPECT_LT((c.pose.translation() - Eigen::Vector3d(0, 0, 0.5)).norm(), 1e-12);
  EXPECT_NEAR(c.shape.revolution->top_z, 0.0625, 1e-12);
  EXPECT_NEAR(c.shape.revolution->bottom_z, -0.0625, 1e-12);
  EXPECT_EQ(SceneFromUrdf(Urdf("<body_of_revolution/>")).scene.colliders.front().shape.type,
            ShapeType::kRevolution);
}

TEST_F(UrdfBodyOfRevolution, BadElementsAreRefusedWithOneLine) {
  ExpectContains(LoadError(Urdf("<body_of_revolution axis=\"0 0 0\"/>")),
                 {"body_of_revolution", "is not a direction"});
  ExpectContains(LoadError(Urdf("<body_of_revolution axis=\"0 1\"/>")), {"expected 3"});
  ExpectContains(LoadError(Urdf("<body_of_revolution tolerance=\"-1\"/>")),
                 {"tolerance", "> 0"});
  ExpectContains(LoadError(Urdf("<body_of_revolution tolerance=\"1e9\"/>")),
                 {"tolerance", "out of range"});
  ExpectContains(LoadError(Urdf("<body_of_revolution size=\"1\"/>")), {"size"});
  ExpectContains(LoadError(Urdf("<body_of_revolution/>", "<sphere radius=\"0.1\"/>")),
                 {"link \"b\" > collision \"c\"", "has none; allowed: a <mesh> collision"});
  // a mesh that is not one: the link, the collision, the file and the deviation
  ExpectContains(LoadError(Urdf("<body_of_revolution axis=\"1 0 0\"/>")),
                 {"link \"b\" > collision \"c\": mesh", "c.stl", "is not a body of revolution"});
}

}  // namespace
}  // namespace nonsmooth_sim::scene_io
