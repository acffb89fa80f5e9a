// Plane–convex hull (plane_hull.h) and the hull's face data (shape.h, MakeConvexHull).
//
// Hulls written here by hand from analytic solids (a box off its frame's origin, an octahedron):
// their volumes and face drilling radii against the closed forms and numeric integration; at 1000
// random poses (seed 12345; never flat) the returned points against the vertices enumerated
// independently (the lowest ones within the margin); a hull of a box against the box's closed
// form (plane_box.h), tilted and resting on each face; and a box hull resting on the ground for
// 2 s (no drift, no jitter) and tumbling onto it as the box does (to round-off until a face
// lands flat, see that test).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <random>
#include <vector>

#include "collision_test_util.h"
#include "nonsmooth_sim/core/collision/plane_box.h"
#include "nonsmooth_sim/core/collision/plane_hull.h"
#include "nonsmooth_sim/core/simulator.h"
#include "scene_builders.h"
#include "../measured_value.h"

namespace nonsmooth_sim {
namespace {

using test::Scientific;

using namespace collision_test;  // NOLINT

const Shape kPlane = Shape::Plane();
const Eigen::Isometry3d kGround = Eigen::Isometry3d::Identity();

// The octahedron |x/a| + |y/b| + |z/c| ≤ 1 shifted by `c0`: vertices ±a x̂, ±b ŷ, ±c ẑ.
std::shared_ptr<const ConvexHull> Octahedron(const Eigen::Vector3d& s, const Eigen::Vector3d& c0) {
  std::vector<Eigen::Vector3d> v = {
      c0 + Eigen::Vector3d(s.x(), 0, 0), c0 - Eigen::Vector3d(s.x(), 0, 0),
      c0 + Eigen::Vector3d(0, s.y(), 0), c0 - Eigen::Vector3d(0, s.y(), 0),
      c0 + Eigen::Vector3d(0, 0, s.z()), c0 - Eigen::Vector3d(0, 0, s.z())};
  std::vector<int> faces;
  for (int i = 0; i < 8; ++i) {
    const int x = (i & 1) ? 0 : 1, y = (i & 2) ? 2 : 3, z = (i & 4) ? 4 : 5;
    // counter-clockwise seen from outside: the orientation of (x, y, z) flips with each sign
    const int signs = ((i & 1) ? 0 : 1) + ((i & 2) ? 0 : 1) + ((i & 4) ? 0 : 1);
    if (signs % 2 == 0) {
      faces.insert(faces.end(), {3, x, y, z});
    } else {
      faces.insert(faces.end(), {3, x, z, y});
    }
  }
  return MakeConvexHull(v, faces);
}

// Every face normal is outward and unit: every vertex lies on or below every face's plane.
void ExpectOutwardFaces(const ConvexHull& hull) {
  for (int f = 0; f < hull.face_count; ++f) {
    EXPECT_NEAR(hull.face_normal[f].norm(), 1.0, 1e-15);
    for (const Eigen::Vector3d& v : hull.vertices) {
      EXPECT_LE(hull.face_normal[f].dot(v - hull.face_centroid[f]), 1e-15) << "face " << f;
    }
  }
}

// Mean distance of the triangle (p, q, r) from `c`: midpoint rule over n² sub-triangles.
double TriangleMeanDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& q,
                            const Eigen::Vector3d& r, const Eigen::Vector3d& c, int n = 1200) {
  double sum = 0.0;
  int count = 0;
  const Eigen::Vector3d u = (q - p) / n, w = (r - p) / n;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; i + j < n; ++j) {
      // the upward sub-triangle and (if inside) the downward one, by their centroids
      sum += (p + (i + 1.0 / 3) * u + (j + 1.0 / 3) * w - c).norm(), ++count;
      if (i + j + 1 < n) sum += (p + (i + 2.0 / 3) * u + (j + 2.0 / 3) * w - c).norm(), ++count;
    }
  }
  return sum / count;
}

TEST(ConvexHull, BoxAndOctahedronHaveTheirVolumesAndOutwardFaces) {
  const Eigen::Vector3d h(0.1, 0.2, 0.3);
  const auto box = BoxHull(h, Eigen::Vector3d(0.05, -0.02, 0.4));
  EXPECT_EQ(box->face_count, 6);
  EXPECT_NEAR(HullVolume(*box), 8.0 * h.prod(), 1e-16);
  EXPECT_NEAR(ShapeVolume(Shape::Hull(box)), 8.0 * h.prod(), 1e-16);
  ExpectOutwardFaces(*box);
  // the bounding radius: the farthest corner from the frame's origin
  EXPECT_NEAR(BoundingRadius(Shape::Hull(box)), (Eigen::Vector3d(0.05, -0.02, 0.4) +
                                                 Eigen::Vector3d(0.1, -0.2, 0.3)).norm(), 1e-16);
  const auto octahedron = Octahedron({0.1, 0.2, 0.3}, {0.0, 0.1, 0.0});
  EXPECT_EQ(octahedron->face_count, 8);
  EXPECT_NEAR(HullVolume(*octahedron), 4.0 / 3.0 * 0.1 * 0.2 * 0.3, 1e-16);
  ExpectOutwardFaces(*octahedron);
  EXPECT_THROW(ShapeUnitInertia(Shape::Hull(box)), std::invalid_argument);
  EXPECT_NO_THROW(ValidateShape(Shape::Hull(box), "hull"));
  EXPECT_THROW(ValidateShape(Shape::Hull(nullptr), "hull"), std::invalid_argument);
  // too few vertices or faces, an index out of range
  EXPECT_THROW(MakeConvexHull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {3, 0, 1, 2}),
               std::invalid_argument);
  EXPECT_THROW(MakeConvexHull(box->vertices, {4, 0, 2, 3, 9}), std::invalid_argument);
}

TEST(ConvexHull, FacePatchRadiusIsTheMeanDistanceOfTheFace) {
  // a rectangle: plane_box.h's closed form
  const Eigen::Vector3d h(0.1, 0.2, 0.3);
  const auto box = BoxHull(h, Eigen::Vector3d(1.0, 2.0, 3.0));
  const double rbar_z = RectanglePatchRadius(h.x(), h.y());
  const double rbar_x = RectanglePatchRadius(h.y(), h.z());
  EXPECT_NEAR(box->face_patch_radius[0], rbar_z, 1e-15);
  EXPECT_NEAR(box->face_patch_radius[1], rbar_z, 1e-15);
  EXPECT_NEAR(box->face_patch_radius[2], rbar_x, 1e-15);
  EXPECT_NEAR((box->face_centroid[0] - Eigen::Vector3d(1.0, 2.0, 3.0 - h.z())).norm(), 0.0,
              1e-15);
  // a scalene triangle of the octahedron: numeric integration
  const auto octahedron = Octahedron({0.1, 0.25, 0.4}, Eigen::Vector3d::Zero());
  const ConvexHull& o = *octahedron;
  const int* f = &o.faces[o.face_start[3] + 1];
  const double numeric =
      TriangleMeanDistance(o.vertices[f[0]], o.vertices[f[1]], o.vertices[f[2]], o.face_centroid[3]);
  EXPECT_NEAR(o.face_patch_radius[3], numeric, 1e-6 * numeric);  // measured: 2.9e-7 (n = 600: 1.1e-6)
}

// The vertices of `hull` at `pose` with gap ≤ margin, lowest first (independent enumeration).
std::vector<double> LowestGaps(const ConvexHull& hull, const Eigen::Isometry3d& pose,
                               double margin) {
  std::vector<double> gaps;
  for (const Eigen::Vector3d& v : hull.vertices) {
    const double gap = (pose * v).z();
    if (gap <= margin) gaps.push_back(gap);
  }
  std::sort(gaps.begin(), gaps.end());
  if (gaps.size() > static_cast<std::size_t>(kMaxPairContacts)) gaps.resize(kMaxPairContacts);
  return gaps;
}

TEST(PlaneHull, RandomPosesGiveTheLowestVerticesWithinTheMargin) {
  std::mt19937 rng(kSeed);
  for (int k = 0; k < kPoses; ++k) {
    const Eigen::Vector3d s(Uniform(rng, 0.05, 0.5), Uniform(rng, 0.05, 0.5),
                            Uniform(rng, 0.05, 0.5));
    const Eigen::Vector3d c0(Uniform(rng, -0.2, 0.2), Uniform(rng, -0.2, 0.2),
                             Uniform(rng, -0.2, 0.2));
    const Shape hull = Shape::Hull(k % 2 == 0 ? BoxHull(s, c0) : Octahedron(s, c0));
    const Eigen::Isometry3d pose = RandomPose(rng, 0.3);
    const double margin = Uniform(rng, -0.2, 0.6);
    ContactGeometry out[kMaxPairContacts];
    const int n = CollidePlaneHull(kPlane, kGround, hull, pose, margin, out);
    const std::vector<double> expected = LowestGaps(*hull.hull, pose, margin);
    ASSERT_EQ(n, static_cast<int>(expected.size())) << "pose " << k;
    for (int i = 0; i < n; ++i) {
      EXPECT_FALSE(out[i].face_point) << k;
      EXPECT_NEAR(out[i].gap, expected[i], 1e-15) << k;
      // a vertex, its feature; the contact frame of collision.h
      EXPECT_LT((out[i].point_b - pose * hull.hull->vertices[out[i].feature]).norm(), 1e-15);
      EXPECT_NEAR(out[i].point_a.z(), 0.0, 1e-15);
      EXPECT_LT((out[i].point_b - out[i].point_a - out[i].gap * out[i].normal).norm(), 1e-15);
      EXPECT_EQ(out[i].normal, Eigen::Vector3d::UnitZ());
    }
  }
}

// The points of a box as a hull and as a box (plane_box.h) are the same set.
void ExpectSameAsBox(const Eigen::Vector3d& h, const Eigen::Isometry3d& pose, double margin,
                     const std::string& where) {
  ContactGeometry hull_points[kMaxPairContacts], box_points[kMaxPairContacts];
  const int n = CollidePlaneHull(kPlane, kGround, Shape::Hull(BoxHull(h)), pose, margin,
                                 hull_points);
  const int m = CollidePlaneBox(kPlane, kGround, Shape::Box(h), pose, margin, box_points);
  ASSERT_EQ(n, m) << where;
  for (int i = 0; i < m; ++i) {
    double nearest = kInf;
    for (int j = 0; j < n; ++j) {
      if (hull_points[j].face_point != box_points[i].face_point) continue;
      nearest = std::min(nearest, (hull_points[j].point_b - box_points[i].point_b).norm() +
                                      std::abs(hull_points[j].gap - box_points[i].gap));
    }
    EXPECT_LT(nearest, 1e-15) << where << " point " << i;
  }
}

TEST(PlaneHull, ABoxHullTouchesAsTheBoxOnEachFaceTiltedAndAtRandomPoses) {
  const Eigen::Vector3d h(0.1, 0.07, 0.05);
  // resting on each of its six faces: four face points at the box's places
  const Eigen::Matrix3d turns[6] = {Eigen::Matrix3d::Identity(),
                                    Rotation(kPi, Eigen::Vector3d::UnitX()),
                                    Rotation(kPi / 2, Eigen::Vector3d::UnitX()),
                                    Rotation(-kPi / 2, Eigen::Vector3d::UnitX()),
                                    Rotation(kPi / 2, Eigen::Vector3d::UnitY()),
                                    Rotation(-kPi / 2, Eigen::Vector3d::UnitY())};
  for (int face = 0; face < 6; ++face) {
    const Eigen::Matrix3d& r = turns[face];
    const double lowest = -(r * BoxHull(h)->vertices[0]).cwiseAbs().z();
    const Eigen::Isometry3d resting =
        Pose(Rotation(0.3, Eigen::Vector3d::UnitZ()) * r, {0.2, -0.1, -lowest - 1e-9});
    ContactGeometry out[kMaxPairContacts];
    ASSERT_EQ(CollidePlaneHull(kPlane, kGround, Shape::Hull(BoxHull(h)), resting, 1e-3, out), 4);
    for (int j = 0; j < 4; ++j) EXPECT_TRUE(out[j].face_point);
    ExpectSameAsBox(h, resting, 1e-3, "face " + std::to_string(face));
    // tilted by 1e-3 rad about x: the lower edge's two corners (the face is no longer flat)
    const Eigen::Isometry3d tilted =
        Pose(Rotation(1e-3, Eigen::Vector3d::UnitX()) * resting.linear(), resting.translation());
    ExpectSameAsBox(h, tilted, 1e-5, "tilted face " + std::to_string(face));
  }
  std::mt19937 rng(kSeed);
  for (int k = 0; k < kPoses; ++k) {
    ExpectSameAsBox(h, RandomPose(rng, 0.2), Uniform(rng, -0.1, 0.3), "pose " + std::to_string(k));
  }
}

// A box of half extents h as a body resting on the ground; `as_hull`: its collider a hull.
Scene BoxScene(const Eigen::Vector3d& h, bool as_hull, const BodyState& start) {
  Scene scene = test::BoxBodyScene(
      "box", h, as_hull ? Shape::Hull(BoxHull(h)) : Shape::Box(h), /*mass=*/0.5, /*mu=*/0.4);
  test::AddGround(&scene);
  scene.initial_state = {start};
  return scene;
}

// Δt = 1 ms, the solver converged to round-off (as simulator_external_wrench_test.cpp).
SimulatorOptions Converged() {
  SimulatorOptions options;
  options.time_step = 1e-3;
  options.solver.tolerance_rel = 1e-12;
  options.solver.tolerance_abs = 1e-20;
  options.solver.max_iterations = kMaxSimulatorIterations;
  return options;
}

TEST(PlaneHull, ABoxHullRestsWithoutDriftOrJitterForTwoSeconds) {
  const Eigen::Vector3d h(0.1, 0.07, 0.05);
  BodyState start;
  start.position = Eigen::Vector3d(0.3, -0.2, h.z());
  start.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()));
  Simulator sim(BoxScene(h, /*as_hull=*/true, start), Converged());
  double worst_speed = 0.0;
  for (int k = 0; k < 2000; ++k) {
    sim.Step();
    const BodyState& s = sim.state()[0];
    worst_speed = std::max({worst_speed, s.linear_velocity.norm(), s.angular_velocity.norm()});
  }
  const BodyState& end = sim.state()[0];
  ::testing::Test::RecordProperty("worst_speed", Scientific(worst_speed));
  ::testing::Test::RecordProperty("drift_m", Scientific((end.position - start.position).norm()));
  EXPECT_LT(worst_speed, 1e-12);
  EXPECT_LT((end.position - start.position).norm(), 1e-12);
  EXPECT_LT(end.orientation.angularDistance(start.orientation), 1e-12);
}

TEST(PlaneHull, ABoxHullTumblesOntoTheGroundAsTheBox) {
  // dropped tilted and spinning, its centre at 0.2 m: corners and edges bounce until step 216 (as the box
  // to round-off), then a face lands flat at step 217. There four face points take the impact
  // together: their impulses are not unique (statically indeterminate), and the hull lists its
  // face points in another order than the box (counter-clockwise, not plane_box's bit order), so
  // the solver converges to another of the equivalent distributions. Both end at rest on the same
  // face; measured: 0 before step 217, 1.2e-4 m apart at the end.
  const Eigen::Vector3d h(0.1, 0.07, 0.05);
  BodyState start;
  start.position = Eigen::Vector3d(0.0, 0.0, 0.2);
  start.orientation =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 0.5).normalized()));
  start.angular_velocity = Eigen::Vector3d(1.0, -2.0, 3.0);
  start.linear_velocity = Eigen::Vector3d(0.3, 0.1, 0.0);
  Simulator hull(BoxScene(h, true, start), Converged());
  Simulator box(BoxScene(h, false, start), Converged());
  const auto difference = [&] {
    const BodyState& a = hull.state()[0];
    const BodyState& b = box.state()[0];
    return std::max((a.position - b.position).norm(),
                    a.orientation.angularDistance(b.orientation) * h.norm());
  };
  double before_flat = 0.0;
  for (int k = 0; k < 1500; ++k) {
    const StepStatistics a = hull.Step();
    const StepStatistics b = box.Step();
    EXPECT_EQ(a.closed_contacts, b.closed_contacts) << k;
    if (k < 217) before_flat = std::max(before_flat, difference());
  }
  ::testing::Test::RecordProperty("before_flat_m", Scientific(before_flat));
  ::testing::Test::RecordProperty("at_the_end_m", Scientific(difference()));
  EXPECT_LT(before_flat, 1e-12);
  EXPECT_LT(difference(), 1e-3);
  for (Simulator* sim : {&hull, &box}) {
    const BodyState& s = sim->state()[0];
    EXPECT_LT(s.linear_velocity.norm() + s.angular_velocity.norm(), 1e-9);
    EXPECT_NEAR(s.position.z(), h.z(), 1e-6);  // on its largest face
  }
}

}  // namespace
}  // namespace nonsmooth_sim
