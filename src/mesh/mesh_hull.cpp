// Mesh vertices by assimp, their convex hull by qhull (libqhull_r), see mesh_hull.h.
#include "nonsmooth_sim/mesh/mesh_hull.h"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/scene.h>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace nonsmooth_sim::mesh {
namespace {

// Appends the vertices of `node` and its children, each mapped by the product of the transforms
// from the root.
void CollectVertices(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent,
                     std::vector<Eigen::Vector3d>* out) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[i]];
    for (unsigned k = 0; k < mesh.mNumVertices; ++k) {
      const aiVector3D v = transform * mesh.mVertices[k];
      out->emplace_back(v.x, v.y, v.z);
    }
  }
  for (unsigned i = 0; i < node.mNumChildren; ++i) {
    CollectVertices(scene, *node.mChildren[i], transform, out);
  }
}

// qhull's state, freed on every path out.
class Qhull {
 public:
  // qhull's messages go to a memory stream (never to stderr: a library does not print), or to
  // /dev/null if none can be opened
  Qhull() : errors_(open_memstream(&error_text_, &error_size_)) {
    if (errors_ == nullptr) errors_ = std::fopen("/dev/null", "w");
    qh_zero(&qh_, errors_);
  }
  ~Qhull() {
    int long_left = 0;
    int short_left = 0;
    qh_freeqhull(&qh_, !qh_ALL);
    qh_memfreeshort(&qh_, &long_left, &short_left);
    if (errors_ != nullptr) std::fclose(errors_);
    std::free(error_text_);
  }
  Qhull(const Qhull&) = delete;
  Qhull& operator=(const Qhull&) = delete;

  qhT* get() { return &qh_; }
  FILE* errors() { return errors_; }

 private:
  qhT qh_;
  char* error_text_ = nullptr;
  std::size_t error_size_ = 0;
  FILE* errors_;
};

}  // namespace

std::vector<Eigen::Vector3d> ReadMeshVertices(const std::string& bytes,
                                              const std::string& extension) {
  std::string hint = extension;
  std::transform(hint.begin(), hint.end(), hint.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  Assimp::Importer importer;
  // a DAE's coordinates are the link's, as rviz shows them: its <up_axis> is not turned into
  // assimp's y-up (its <unit> is applied)
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // only the positions are used: no normals, no materials, no triangulation of faces needed
  const aiScene* scene =
      importer.ReadFileFromMemory(bytes.data(), bytes.size(), /*pFlags=*/0, hint.c_str());
  if (scene == nullptr || scene->mRootNode == nullptr) {
    throw std::invalid_argument("assimp cannot read it as " + (hint.empty() ? "a mesh" : hint) +
                                ": " + importer.GetErrorString());
  }
  std::vector<Eigen::Vector3d> vertices;
  CollectVertices(*scene, *scene->mRootNode, aiMatrix4x4(), &vertices);
  if (vertices.empty()) throw std::invalid_argument("has no vertices (an empty mesh)");
  return vertices;
}

namespace {

// HullOfPoints with max_vertices = 0: no cap.
std::shared_ptr<const ConvexHull> Hull(const std::vector<Eigen::Vector3d>& input,
                                       int max_vertices) {
  // each point once: an STL repeats every vertex in each of its triangles, and qhull given
  // repeated points may report a vertex that is none of them (measured: 1e-9 m off on an
  // icosphere's STL)
  std::vector<Eigen::Vector3d> points = input;
  const auto less = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::sort(points.begin(), points.end(), less);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 4) {
    throw std::invalid_argument("has " + std::to_string(points.size()) +
                                " distinct vertices: a solid needs at least 4");
  }
  std::vector<coordT> coordinates;
  coordinates.reserve(3 * points.size());
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) throw std::invalid_argument("a vertex is not finite");
    coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
  }
  // default merging in 3-d (C-0, Qx): coplanar facets become one face; TA caps the vertices
  std::string options = "qhull";
  if (max_vertices > 0 && points.size() > static_cast<std::size_t>(max_vertices)) {
    options += " TA" + std::to_string(max_vertices - 4);
  }
  Qhull qhull;
  qhT* qh = qhull.get();
  const int status = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(),
                                  /*ismalloc=*/False, options.data(), /*outfile=*/nullptr,
                                  qhull.errors());
  if (status != 0) {
    throw std::invalid_argument(
        "its convex hull is degenerate: all points are coplanar or collinear (qhull error " +
        std::to_string(status) + "); a collision mesh must enclose a volume");
  }
  // the hull's vertices, numbered in qhull's order
  std::map<int, int> index;  // qhull's point id → ours
  std::vector<Eigen::Vector3d> vertices;
  vertexT* vertex;
  FORALLvertices {
    const int id = qh_pointid(qh, vertex->point);
    index.emplace(id, static_cast<int>(vertices.size()));
    vertices.emplace_back(vertex->point[0], vertex->point[1], vertex->point[2]);
  }
  // the faces: each facet's vertices ordered counter-clockwise about its outward normal
  std::vector<int> faces;
  facetT* facet;
  FORALLfacets {
    const Eigen::Vector3d normal(facet->normal[0], facet->normal[1], facet->normal[2]);
    std::vector<int> ids;
    vertexT** vertexp;
    FOREACHvertex_(facet->vertices) ids.push_back(index.at(qh_pointid(qh, vertex->point)));
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int i : ids) centre += vertices[static_cast<std::size_t>(i)];
    centre /= static_cast<double>(ids.size());
    const Eigen::Vector3d u =
        (vertices[static_cast<std::size_t>(ids[0])] - centre).normalized();
    const Eigen::Vector3d w = normal.cross(u);
    std::vector<std::pair<double, int>> by_angle;
    for (int i : ids) {
      const Eigen::Vector3d r = vertices[static_cast<std::size_t>(i)] - centre;
      by_angle.emplace_back(std::atan2(w.dot(r), u.dot(r)), i);
    }
    std::sort(by_angle.begin(), by_angle.end());
    faces.push_back(static_cast<int>(ids.size()));
    for (const auto& [angle, i] : by_angle) faces.push_back(i);
  }
  try {
    return MakeConvexHull(std::move(vertices), std::move(faces));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("its convex hull is degenerate (") + e.what() + ")");
  }
}

}  // namespace

std::shared_ptr<const ConvexHull> HullOfPoints(const std::vector<Eigen::Vector3d>& points,
                                               int max_vertices) {
  if (max_vertices < 4 || max_vertices > kMaxHullVerticesBound) {
    throw std::invalid_argument("the hull's vertex cap " + std::to_string(max_vertices) +
                                " must be in [4, " + std::to_string(kMaxHullVerticesBound) + "]");
  }
  return Hull(points, max_vertices);
}

std::shared_ptr<const ConvexHull> FullHullOfPoints(const std::vector<Eigen::Vector3d>& points) {
  return Hull(points, 0);
}

double HullWidth(const ConvexHull& hull) {
  double width = std::numeric_limits<double>::infinity();
  for (int f = 0; f < hull.face_count; ++f) {
    const Eigen::Vector3d& n = hull.face_normal[static_cast<std::size_t>(f)];
    const Eigen::Vector3d& p = hull.face_centroid[static_cast<std::size_t>(f)];
    double depth = 0.0;
    for (const Eigen::Vector3d& v : hull.vertices) depth = std::max(depth, -n.dot(v - p));
    width = std::min(width, depth);
  }
  return width;
}

}  // namespace nonsmooth_sim::mesh
