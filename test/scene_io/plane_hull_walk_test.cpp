// The plane–hull contact's walk on the hull's edges (plane_hull.h: a descent to the lowest vertex,
// the vertices within the margin by their neighbours, the facing face among theirs) against the
// scan of every vertex and face it replaces (the same hull with `connected` false): the same
// contacts, bit for bit, for qhull's hulls of an icosphere, of random points and of a fine
// mesh capped at 256 vertices, at random poses, resting on a face, and at every margin.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "mesh_fixtures.h"
#include "nonsmooth_sim/core/collision/plane_hull.h"
#include "nonsmooth_sim/mesh/mesh_hull.h"

namespace nonsmooth_sim::scene_io {
namespace {

using namespace mesh_test;  // NOLINT

bool SameBits(const ContactGeometry& a, const ContactGeometry& b) {
  const auto same = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  return same(a.gap, b.gap) && same(a.point_a, b.point_a) && same(a.point_b, b.point_b) &&
         same(a.normal, b.normal) && a.feature == b.feature && a.face_point == b.face_point;
}

void ExpectWalkEqualsScan(const std::shared_ptr<const ConvexHull>& hull, const char* name) {
  ASSERT_TRUE(hull->connected) << name;
  auto scanned = std::make_shared<ConvexHull>(*hull);
  scanned->connected = false;  // every vertex and face
  const Shape walk = Shape::Hull(hull), scan = Shape::Hull(scanned);
  const Eigen::Isometry3d ground = Eigen::Isometry3d::Identity();
  std::mt19937 rng(21);
  std::normal_distribution<double> normal(0.0, 1.0);
  int contacts = 0, face_points = 0;
  for (int i = 0; i < 3000; ++i) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    if (i % 3 == 0) {
      // resting on a face: its normal turned to −z
      const int f = i / 3 % hull->face_count;
      pose.linear() = Eigen::Quaterniond::FromTwoVectors(hull->face_normal[f],
                                                         -Eigen::Vector3d::UnitZ())
                          .toRotationMatrix();
    } else {
      pose.linear() = Eigen::Quaterniond(normal(rng), normal(rng), normal(rng), normal(rng))
                          .normalized()
                          .toRotationMatrix();
    }
    // the lowest vertex at a small height (some within, some beyond each margin)
    double lowest = INFINITY;
    for (const Eigen::Vector3d& v : hull->vertices) lowest = std::min(lowest, (pose * v).z());
    pose.translation().z() = -lowest + 1e-3 * normal(rng);
    for (const double margin : {0.0, 1e-9, 1e-3, 1e-2}) {
      ContactGeometry a[kMaxPairContacts], b[kMaxPairContacts];
      const int n = CollidePlaneHull(Shape::Plane(), ground, walk, pose, margin, a);
      ASSERT_EQ(n, CollidePlaneHull(Shape::Plane(), ground, scan, pose, margin, b)) << name;
      for (int k = 0; k < n; ++k) {
        EXPECT_TRUE(SameBits(a[k], b[k])) << name << " pose " << i << " margin " << margin;
        face_points += a[k].face_point;
      }
      contacts += n;
    }
  }
  EXPECT_GT(contacts, 0) << name;
  EXPECT_GT(face_points, 0) << name;  // the flat faces' branch ran
}

TEST(PlaneHullWalk, GivesTheContactsOfTheFullScan) {
  ExpectWalkEqualsScan(mesh::HullOfPoints(IcosphereMesh(3, 0.05).vertices, 4096), "icosphere");
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uniform(-0.03, 0.03);
  std::vector<Eigen::Vector3d> cloud;
  for (int i = 0; i < 500; ++i) cloud.emplace_back(uniform(rng), uniform(rng), 2 * uniform(rng));
  ExpectWalkEqualsScan(mesh::HullOfPoints(cloud, 4096), "random points");
  std::vector<Eigen::Vector2d> meridian;
  for (int i = 0; i <= 90; ++i) {
    const double t = 3.14159265358979323846 * i / 90;
    meridian.emplace_back(0.015 * std::sin(t), 0.003 + 0.015 * std::cos(t));
  }
  ExpectWalkEqualsScan(mesh::HullOfPoints(RevolutionMesh(meridian, 40).vertices, 256),
                       "a fine mesh capped at 256 vertices");
}

}  // namespace
}  // namespace nonsmooth_sim::scene_io
