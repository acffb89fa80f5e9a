// The Tippe-Top exported from CAD (issue 32): its outer surface — the convex hull of its two
// spheres, R1 = 15 mm at a1 = 3 mm and R2 = 5 mm at a2 = 16 mm, joined by a cone — written here as
// a binary STL (a UV mesh: 90 rings of 40 vertices, about 2° apart on the meridian), loaded from
// urdf/tippe_top.urdf with its two sphere collisions replaced by that mesh:
//  - with <body_of_revolution axis="0 0 1"/> (docs/urdf.md, "Bodies of revolution") it is the
//    smooth body its profile describes and inverts when the shipped two-sphere model does, within
//    2 ms: the time its axis first tilts past π − θ*, where the cone lies on the floor and the peg
//    touches (cos θ* = (R1 − R2)/(a2 − a1));
//  - as a plain convex hull (256 vertices, the loader's default cap) it rolls on facets; what it
//    does is printed (docs/urdf.md gives the numbers).
// Every run is what `simulate --urdf FILE --initial config/tippe_top.yaml` does: moreau2 at the
// default step 1e-4 s, the paper's set `sphere`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "../scene_io/mesh_fixtures.h"
#include "nonsmooth_sim/core/constants.h"
#include "scene_test_support.h"

namespace nonsmooth_sim {
namespace {

using scene_test::AxisE3;
using scene_test::SourcePath;

constexpr double kR1 = 0.015, kA1 = 0.003, kR2 = 0.005, kA2 = 0.016;
constexpr int kSectors = 40;
// the cone's normal angle from e3: where both spheres' supports are equal
const double kConeTheta = std::acos((kR1 - kR2) / (kA2 - kA1));

// The meridian (ρ, z) from the top pole to the bottom one, about 2° apart on each sphere.
std::vector<Eigen::Vector2d> Meridian() {
  std::vector<Eigen::Vector2d> points;
  const int peg = 20, big = 71;
  for (int i = 0; i <= peg; ++i) {
    const double t = kConeTheta * i / peg;
    points.emplace_back(kR2 * std::sin(t), kA2 + kR2 * std::cos(t));
  }
  for (int i = 0; i <= big; ++i) {
    const double t = kConeTheta + (kPi - kConeTheta) * i / big;
    points.emplace_back(kR1 * std::sin(t), kA1 + kR1 * std::cos(t));
  }
  return points;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void Replace(std::string* text, const std::string& from, const std::string& to) {
  const std::size_t at = text->find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text->replace(at, from.size(), to);
}

// urdf/tippe_top.urdf with its collisions replaced by the mesh (as a body of revolution or not).
Scene MeshTippeTop(const std::string& stl, bool revolution) {
  std::string urdf = ReadText(SourcePath("urdf/tippe_top.urdf"));
  const std::size_t first = urdf.find("<collision name=\"big_sphere\">");
  const std::size_t last = urdf.find("</collision>", urdf.find("<collision name=\"peg_sphere\">"));
  EXPECT_NE(first, std::string::npos);
  EXPECT_NE(last, std::string::npos);
  urdf.replace(first, last + 12 - first,
               "<collision name=\"body\"><geometry><mesh filename=\"file://" + stl +
                   "\"/></geometry></collision>");
  if (revolution) {
    Replace(&urdf, "<nonsmooth_sim reference=\"tippe_top\">",
            "<nonsmooth_sim reference=\"tippe_top\"><collision name=\"body\">"
            "<body_of_revolution axis=\"0 0 1\"/></collision>");
  }
  Scene scene = scene_io::SceneFromUrdf(urdf).scene;
  scene.initial_state =
      scene_io::InitialStateFromYamlFile(scene, SourcePath("config/tippe_top.yaml"));
  return scene;
}

struct Inversion {
  std::optional<double> tilt_past_cone;  // first time the axis tilts past π − θ* [s]
  double final_tilt = 0.0;               // at 3 s [rad]
  double max_energy_excess = 0.0;        // [J]
};

Inversion Invert(const Scene& scene) {
  SimulatorOptions options;
  options.integrator = Integrator::kMoreau2;
  options.time_step = 1e-4;
  Simulator sim(scene, options);
  scene_test::Runner run(&sim);
  Inversion result;
  while (sim.time() < 3.0 && run.finite()) {
    run.Step();
    const double tilt = std::acos(std::clamp(AxisE3(sim.state()[0]).z(), -1.0, 1.0));
    if (!result.tilt_past_cone && tilt >= kPi - kConeTheta) result.tilt_past_cone = sim.time();
    result.final_tilt = tilt;
  }
  result.max_energy_excess = run.max_energy_excess();
  return result;
}

class MeshTippeTopTest : public testing::Test {
 protected:
  const scene_io::mesh_test::TempFolder folder_;
  const std::string stl_ = folder_.Write(
      "tippe_top.stl",
      scene_io::mesh_test::BinaryStl(scene_io::mesh_test::RevolutionMesh(Meridian(), kSectors)));
};

TEST_F(MeshTippeTopTest, BodyOfRevolutionInvertsWithTheTwoSphereModel) {
  Scene analytic = scene_test::LoadShippedScene("tippe_top");
  const Scene smooth = MeshTippeTop(stl_, /*revolution=*/true);
  ASSERT_EQ(smooth.bodies.size(), 1u);
  const Collider* body = nullptr;
  for (const Collider& c : smooth.colliders) {
    if (c.body == 0) body = &c;
  }
  ASSERT_NE(body, nullptr);
  ASSERT_EQ(body->shape.type, ShapeType::kRevolution);
  const Inversion reference = Invert(analytic);
  const Inversion mesh = Invert(smooth);
  ASSERT_TRUE(reference.tilt_past_cone && mesh.tilt_past_cone);
  std::printf("axis past pi - theta* = %.2f deg: two spheres %.5f s, mesh as body of revolution "
              "%.5f s (%+.2f ms); tilt at 3 s %.2f, %.2f deg; energy excess %.1e, %.1e J\n",
              (kPi - kConeTheta) * 180 / kPi, *reference.tilt_past_cone, *mesh.tilt_past_cone,
              1e3 * (*mesh.tilt_past_cone - *reference.tilt_past_cone),
              reference.final_tilt * 180 / kPi, mesh.final_tilt * 180 / kPi,
              reference.max_energy_excess, mesh.max_energy_excess);
  EXPECT_NEAR(*mesh.tilt_past_cone, *reference.tilt_past_cone, 2e-3);
  // both end upside down on the peg
  EXPECT_GT(reference.final_tilt, 0.9 * kPi);
  EXPECT_GT(mesh.final_tilt, 0.9 * kPi);
  EXPECT_LE(mesh.max_energy_excess, 1e-9);
}

TEST_F(MeshTippeTopTest, PlainHullIsReportedForWhatItDoes) {
  const Scene hull = MeshTippeTop(stl_, /*revolution=*/false);
  ASSERT_EQ(hull.colliders.size(), 2u);  // the ground and the hull
  EXPECT_EQ(hull.colliders[0].shape.type, ShapeType::kConvexHull);
  EXPECT_EQ(hull.colliders[0].shape.hull->vertices.size(), 256u);
  const Inversion faceted = Invert(hull);
  const Inversion reference = Invert(scene_test::LoadShippedScene("tippe_top"));
  std::printf("plain hull (256 vertices): axis past pi - theta* at %s s (two spheres %.5f s); "
              "tilt at 3 s %.2f deg; energy excess %.1e J\n",
              faceted.tilt_past_cone ? std::to_string(*faceted.tilt_past_cone).c_str() : "never",
              *reference.tilt_past_cone, faceted.final_tilt * 180 / kPi,
              faceted.max_energy_excess);
  EXPECT_LE(faceted.max_energy_excess, 1e-9);
}

}  // namespace
}  // namespace nonsmooth_sim
