// Meshes as convex hulls (mesh/mesh_hull.h, scene_io/mesh_source.h): a box, a tetrahedron and an
// icosphere written as binary STL, ASCII STL, OBJ and DAE (mesh_fixtures.h) load as their analytic
// hulls: the same vertices (each an input point as a float: exactly from a binary STL, to 6e-8 m
// from text), the volume of the written triangles, the support function of the points in 500
// directions (seed 12345); a scale
// scales them; the vertex cap holds; a hull is computed once per (contents, scale, cap).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "mesh_fixtures.h"
#include "nonsmooth_sim/mesh/mesh_hull.h"
#include "nonsmooth_sim/scene_io/mesh_source.h"
#include "nonsmooth_sim/scene_io/urdf_scene.h"

namespace nonsmooth_sim::scene_io {
namespace {

using namespace mesh_test;  // NOLINT

// The mesh with its coordinates as a binary STL holds them: the floats read back from its bytes
// (the triangles' corners, in the mesh's triangle order).
TriangleMesh AsFloats(const TriangleMesh& m) {
  const std::string stl = BinaryStl(m);
  TriangleMesh floats = m;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    for (int corner = 0; corner < 3; ++corner) {
      float x[3];
      std::memcpy(x, stl.data() + 84 + 50 * t + 12 + 12 * corner, sizeof x);
      floats.vertices[m.triangles[t][corner]] = Eigen::Vector3d(x[0], x[1], x[2]);
    }
  }
  return floats;
}

enum class Format { kBinaryStl, kAsciiStl, kObj, kDae };
const Format kFormats[] = {Format::kBinaryStl, Format::kAsciiStl, Format::kObj, Format::kDae};

std::string Write(const TempFolder& folder, const std::string& name, const TriangleMesh& m,
                  Format format) {
  switch (format) {
    case Format::kBinaryStl: return folder.Write(name + "_binary.stl", BinaryStl(m));
    case Format::kAsciiStl: return folder.Write(name + "_ascii.stl", AsciiStl(m));
    case Format::kObj: return folder.Write(name + ".obj", Obj(m));
    case Format::kDae: return folder.Write(name + ".dae", Dae(m));
  }
  return "";
}

std::shared_ptr<const ConvexHull> Load(const std::string& path,
                                       const Eigen::Vector3d& scale = Eigen::Vector3d::Ones(),
                                       int cap = kDefaultMaxHullVertices) {
  return LoadMeshHull(path, scale, cap, kMaxInputBytes);
}

// The hull against the analytic one of the (float) mesh `m`: every vertex of `m` is a vertex of
// the hull (all are extreme here) and each hull vertex one of m's within `tolerance` [m]; the
// volume; the support function in random unit directions. A binary STL holds the floats
// themselves (tolerance 0); text formats go through assimp's own decimal parser, which is not
// correctly rounded: measured one float ulp off on a few coordinates (3e-8 m at 0.3 m).
void ExpectHullOf(const TriangleMesh& m, const ConvexHull& hull, double tolerance,
                  const std::string& where) {
  EXPECT_EQ(hull.vertices.size(), m.vertices.size()) << where;
  for (const Eigen::Vector3d& v : hull.vertices) {
    double nearest = 1e300;
    for (const Eigen::Vector3d& p : m.vertices) nearest = std::min(nearest, (p - v).norm());
    EXPECT_LE(nearest, tolerance) << where << ": " << v.transpose();
  }
  const double volume = MeshVolume(m);
  const double size = 0.3;  // the largest coordinate of the shapes
  EXPECT_NEAR(HullVolume(hull), volume, 1e-13 + 3 * size * size * tolerance) << where;
  std::mt19937 rng(12345);
  std::normal_distribution<double> normal;
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d d =
        Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    double brute = -1e300;
    for (const Eigen::Vector3d& p : m.vertices) brute = std::max(brute, d.dot(p));
    EXPECT_NEAR(d.dot(hull.vertices[HullSupportVertex(hull, d)]), brute, tolerance)
        << where << " d " << k;
  }
}

TEST(MeshHull, EachFormatLoadsAsTheAnalyticHullOfTheShape) {
  const TempFolder folder;
  const std::pair<std::string, TriangleMesh> shapes[] = {
      {"box", BoxMesh({0.1, 0.2, 0.3})},
      {"tetrahedron", TetrahedronMesh(0.1, 0.2, 0.3)},
      {"icosphere", IcosphereMesh(2, 0.1)}};
  for (const auto& [name, mesh] : shapes) {
    for (Format format : kFormats) {
      const std::string path = Write(folder, name, mesh, format);
      const auto hull = Load(path);
      ExpectHullOf(AsFloats(mesh), *hull, format == Format::kBinaryStl ? 0.0 : 6e-8, path);
    }
  }
  // the counts of the analytic hulls
  EXPECT_EQ(Load(Write(folder, "box", BoxMesh({0.1, 0.2, 0.3}), Format::kObj))->face_count, 6);
  EXPECT_EQ(Load(Write(folder, "icosphere", IcosphereMesh(2, 0.1), Format::kObj))->vertices.size(),
            162u);
}

TEST(MeshHull, ADaeUnitAndAScaleScaleTheHull) {
  const TempFolder folder;
  const TriangleMesh box = BoxMesh({0.125, 0.25, 0.5});  // exact in float
  // <unit meter="0.001">: a mesh in millimetres
  TriangleMesh in_mm = box;
  for (Eigen::Vector3d& v : in_mm.vertices) v *= 1000.0;
  const auto from_mm = Load(folder.Write("mm.dae", Dae(in_mm, 0.001)));
  EXPECT_NEAR(HullVolume(*from_mm), MeshVolume(box), 1e-12);
  // <up_axis>Z_UP</up_axis> is not turned: the box's long side stays along z
  EXPECT_NEAR(from_mm->vertices[HullSupportVertex(*from_mm, Eigen::Vector3d::UnitZ())].z(), 0.5,
              1e-6);
  // scale (2, 0.5, 3): each vertex scaled, the volume by 3
  const Eigen::Vector3d scale(2.0, 0.5, 3.0);
  const auto scaled = Load(folder.Write("box.stl", BinaryStl(box)), scale);
  EXPECT_NEAR(HullVolume(*scaled), 3.0 * MeshVolume(box), 1e-15);
  for (const Eigen::Vector3d& v : scaled->vertices) {
    EXPECT_EQ(v.cwiseAbs(), Eigen::Vector3d(0.25, 0.125, 1.5));
  }
}

TEST(MeshHull, TheVertexCapHoldsAndKeepsInputPoints) {
  const TempFolder folder;
  const TriangleMesh sphere = AsFloats(IcosphereMesh(3, 0.1));  // 642 vertices
  ASSERT_EQ(sphere.vertices.size(), 642u);
  const std::string path = folder.Write("sphere.stl", BinaryStl(sphere));
  for (int cap : {4, 16, 64, 256}) {
    const auto hull = Load(path, Eigen::Vector3d::Ones(), cap);
    EXPECT_LE(static_cast<int>(hull->vertices.size()), cap);
    EXPECT_GE(static_cast<int>(hull->vertices.size()), 4);
    for (const Eigen::Vector3d& v : hull->vertices) {
      EXPECT_NEAR(v.norm(), 0.1, 1e-8) << cap;  // an input point
    }
    // inside the sphere's mesh (measured with 64 vertices: 0.848 of its volume)
    const double ratio = HullVolume(*hull) / MeshVolume(sphere);
    EXPECT_LT(ratio, 1.0 + 1e-12) << cap;
    if (cap >= 64) {
      EXPECT_GT(ratio, 0.8) << cap;
    }
  }
  // uncapped: all 642
  EXPECT_EQ(Load(path, Eigen::Vector3d::Ones(), kMaxHullVerticesBound)->vertices.size(), 642u);
}

TEST(MeshHull, AHullIsComputedOncePerContentsScaleAndCap) {
  const TempFolder folder;
  const TriangleMesh box = BoxMesh({0.1, 0.2, 0.3});
  const std::string a = folder.Write("a.stl", BinaryStl(box));
  const std::string b = folder.Write("copy/b.stl", BinaryStl(box));
  const auto first = Load(a);
  EXPECT_EQ(Load(a), first);  // the same object
  EXPECT_EQ(Load(b), first);  // the same contents
  EXPECT_NE(Load(a, Eigen::Vector3d(1.0, 1.0, 2.0)), first);
  EXPECT_NE(Load(a, Eigen::Vector3d::Ones(), 6), first);
  // a changed file is read again
  folder.Write("a.stl", BinaryStl(BoxMesh({0.1, 0.2, 0.4})));
  EXPECT_NEAR(HullVolume(*Load(a)), 8 * 0.1 * 0.2 * 0.4, 1e-8);
}

TEST(MeshHull, DegeneratePointSetsAreRefused) {
  // coplanar, collinear, too few
  const std::vector<Eigen::Vector3d> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  for (const auto& points : {square, line}) {
    try {
      mesh::HullOfPoints(points, 64);
      ADD_FAILURE() << "no error";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("coplanar or collinear"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_THROW(mesh::HullOfPoints({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 64), std::invalid_argument);
}

}  // namespace
}  // namespace nonsmooth_sim::scene_io
