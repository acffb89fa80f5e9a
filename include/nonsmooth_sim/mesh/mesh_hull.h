// Meshes as convex hulls: a mesh file's vertices (assimp: STL binary and ASCII, OBJ, DAE and the
// other formats it reads) and their convex hull (qhull, reentrant libqhull_r), as the core's
// ConvexHull (shape.h). MuJoCo and Drake take a mesh collision the same way; only the vertices
// matter, so a mesh need not be closed or consistently oriented.
//
// A library of its own (cmake/mesh.cmake): the core stays Eigen-only; the scene loader
// (scene_io) reads <mesh> through it. Errors are std::invalid_argument with one line, the reason
// alone (the caller puts the link and the file in front). Nothing here prints or logs.
#ifndef NONSMOOTH_SIM_MESH_MESH_HULL_H_
#define NONSMOOTH_SIM_MESH_MESH_HULL_H_

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/shape.h"

namespace nonsmooth_sim::mesh {

/// The vertices of every mesh of the file whose contents are `bytes`, in the file's root frame
/// (the node transforms of a DAE applied, its <unit> included, its <up_axis> ignored as ROS
/// does: the file's z is the link's z), in metres for a DAE with a <unit>, else the file's units. `extension`
/// ("stl", "obj", "dae", ..., any case) tells assimp the format. Throws std::invalid_argument:
/// "assimp cannot read it as <ext>: <assimp's reason>", "has no vertices".
std::vector<Eigen::Vector3d> ReadMeshVertices(const std::string& bytes,
                                              const std::string& extension);

/// The convex hull of `points` (at least 4 distinct, finite; repeated points are used once) with at most `max_vertices` vertices (in
/// [4, kMaxHullVerticesBound]; as MuJoCo's maxhullvert, qhull's option TA stops once it has
/// added that many: the capped hull is the hull of a subset of the points). Coplanar facets are
/// merged (qhull's default merging in 3-d), so a flat side is one face. Throws
/// std::invalid_argument: fewer than 4 points, a non-finite point, or a degenerate hull ("all
/// points are coplanar or collinear: ...").
std::shared_ptr<const ConvexHull> HullOfPoints(const std::vector<Eigen::Vector3d>& points,
                                               int max_vertices);

/// The hull of every one of `points`, without a cap (HullOfPoints' checks and errors otherwise):
/// to measure a mesh (mesh_revolution.h), not to collide with.
std::shared_ptr<const ConvexHull> FullHullOfPoints(const std::vector<Eigen::Vector3d>& points);

/// The thinnest width of a hull: min over its faces of max_i ν_f·(v_i − p_f) [m] (ν_f its outward
/// normal, p_f a vertex of it); 0 for a flat one.
double HullWidth(const ConvexHull& hull);

}  // namespace nonsmooth_sim::mesh

#endif  // NONSMOOTH_SIM_MESH_MESH_HULL_H_
