// The twenty-sided die from a mesh (urdf/d20.urdf, meshes/d20.stl, config/d20.yaml; docs/scenes.md
// section 6): the shipped example of a mesh collision. A regular icosahedron of circumradius
// 0.011 m, 0.00405 kg, μ = 0.3, R = 0.5 mm, ε = 0, tossed as the cubic die (die_test.cpp).
//
// What must hold: the loader's hull is the icosahedron (12 vertices at the circumradius, 20
// triangular faces, the volume (5/12)(3 + √5)a³); the die lands, tumbles and rests on one face:
// that face's outward normal points down, S at the inradius above the floor (within a few
// slops), three contacts that no longer change, speeds at round-off, no drift, no energy gained
// (moreau at Δt = 1e-4, as the cubic die's test). Measured: first contact 0.115 s, settled on
// three corners at 0.245 s, face tilt 8.5e-5 rad, S 2.5e-7 m below the inradius.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "nonsmooth_sim/core/constants.h"
#include "scene_test_support.h"

namespace nonsmooth_sim {
namespace {

using scene_test::LoadShippedScene;

constexpr double kCircumradius = 0.011;  // [m], scripts/dev/make_d20
const double kEdge = kCircumradius / std::sin(2.0 * kPi / 5.0);
// inradius of the icosahedron: φ²a / (2√3)
const double kInradius = (3.0 + std::sqrt(5.0)) / 2.0 * kEdge / (2.0 * std::sqrt(3.0));

const ConvexHull& HullOf(const Scene& scene) {
  const Collider& c = scene.colliders[static_cast<std::size_t>(FindCollider(scene, "d20_hull"))];
  EXPECT_EQ(c.shape.type, ShapeType::kConvexHull);
  return *c.shape.hull;
}

// assimp reads STL coordinates as float: the hull is the analytic one to 1e-9 m (measured 2e-10)
TEST(D20, TheMeshHullIsTheIcosahedron) {
  const ConvexHull& hull = HullOf(LoadShippedScene("d20"));
  ASSERT_EQ(hull.vertices.size(), 12u);
  for (const Eigen::Vector3d& v : hull.vertices) EXPECT_NEAR(v.norm(), kCircumradius, 1e-9);
  EXPECT_EQ(hull.face_count, 20);
  for (int f = 0; f < hull.face_count; ++f) {
    EXPECT_EQ(hull.faces[static_cast<std::size_t>(hull.face_start[static_cast<std::size_t>(f)])], 3);
    // each face at the inradius from the centre
    EXPECT_NEAR(hull.face_normal[static_cast<std::size_t>(f)].dot(
                    hull.face_centroid[static_cast<std::size_t>(f)]),
                kInradius, 1e-9);
  }
  EXPECT_NEAR(HullVolume(hull), 5.0 / 12.0 * (3.0 + std::sqrt(5.0)) * std::pow(kEdge, 3),
              1e-7 * HullVolume(hull));
}

TEST(D20, LandsTumblesAndRestsOnOneFace) {
  const scene_test::Toss toss = scene_test::TossShippedScene("d20", 2.0);
  const BodyState& s = toss.end;
  // the face it rests on: the one whose outward normal is closest to −ẑ
  const Scene scene = LoadShippedScene("d20");
  const ConvexHull& hull = HullOf(scene);
  const Eigen::Matrix3d r = s.orientation.normalized().toRotationMatrix();
  double down = -1.0;
  for (const Eigen::Vector3d& n : hull.face_normal) down = std::max(down, -(r * n).z());
  std::printf("first contact %.4f s, turned %.2f rad on the floor, contacts settled at %.4f s "
              "(%zu contacts), face tilt %.2e rad, z_S - inradius = %.2e m, drift %.2e m, max "
              "speed %.2e m/s over the last second, max penetration %.2e m\n",
              toss.first_contact, toss.turned_on_floor, toss.last_change, toss.end_contacts,
              std::acos(std::min(1.0, down)), s.position.z() - kInradius,
              (s.position - toss.position_at_1s).norm(), toss.max_speed_late, toss.max_penetration);
  EXPECT_GT(toss.first_contact, 0.0);
  EXPECT_GT(toss.turned_on_floor, 0.3);
  EXPECT_EQ(toss.end_contacts, 3u);
  EXPECT_GT(down, std::cos(1e-3));
  EXPECT_NEAR(s.position.z(), kInradius, 5.0 * kGapCorrectionSlop);
  EXPECT_LT(toss.last_change, 1.0);
  EXPECT_LT(toss.max_speed_late, 1e-12);
  EXPECT_LT((s.position - toss.position_at_1s).norm(), 1e-12);
  EXPECT_LE(toss.max_energy_excess, 0.0) << "at t = " << toss.max_energy_excess_time;
  EXPECT_TRUE(toss.finite);
}

}  // namespace
}  // namespace nonsmooth_sim
