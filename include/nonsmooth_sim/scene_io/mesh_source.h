// A URDF <mesh filename scale>: where its file is and the convex hull it becomes (urdf_scene.h;
// docs/urdf.md, "Meshes").
//
// Where (ResolveMeshFilename), as ROS resolves it (resource_retriever), and without ROS:
//  - package://pkg/rel: pkg's folder is found on ROS_PACKAGE_PATH as rospack finds it: each
//    folder of the path in turn, searched depth-first (at most kMaxPackageSearchDepth levels,
//    kMaxPackageSearchFolders folders), for a folder holding a package.xml whose <name> is pkg;
//    the search neither enters a package nor a folder holding CATKIN_IGNORE, nor hidden folders.
//    rel must stay inside the package: after removing "." and "x/.." it may not start with "..".
//  - file:///abs/path, an absolute path, or a path relative to `base_directory` (the URDF file's
//    folder; the current folder for a URDF text).
//
// What (LoadMeshHull): the file read whole, with ReadBoundedFile's rules (a regular file, at most
// max_bytes: no device, FIFO or directory), its vertices read by assimp (mesh/mesh_hull.h),
// multiplied by the scale, and their convex hull by qhull, capped at max_vertices vertices. The
// hull must be a solid of the loader's sizes: its thinnest width at least kMinLength and its
// farthest vertex from the link frame at most kMaxLength (urdf_scene.h, "Bounds").
// The hull of each (file contents, format, scale, cap) is computed once per process and shared
// (a cache of at most kMaxCachedMeshHulls hulls, safe to use from several threads). A body
// of revolution (LoadMeshRevolution) is fitted to the file's vertices at each load.
#ifndef NONSMOOTH_SIM_SCENE_IO_MESH_SOURCE_H_
#define NONSMOOTH_SIM_SCENE_IO_MESH_SOURCE_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <cstddef>
#include <memory>
#include <string>

#include "nonsmooth_sim/core/shape.h"

namespace nonsmooth_sim::scene_io {

inline constexpr int kMaxPackageSearchDepth = 8;
inline constexpr int kMaxPackageSearchFolders = 100000;
/// Each component of a <mesh scale> in [kMinMeshScale, kMaxMeshScale] (a mesh in µm is 1e-6;
/// the hull's own size is bounded after scaling).
inline constexpr double kMinMeshScale = 1e-6;
inline constexpr double kMaxMeshScale = 1e6;
inline constexpr std::size_t kMaxCachedMeshHulls = 256;

/// The file of a <mesh filename>. Throws std::invalid_argument with the reason ("package
/// \"p\" is not on ROS_PACKAGE_PATH (...)", "escapes its package by \"..\"", ...).
std::string ResolveMeshFilename(const std::string& filename, const std::string& base_directory,
                                const std::string& ros_package_path);

/// The hull of the mesh file `path` scaled by `scale` (each component in [kMinMeshScale,
/// kMaxMeshScale]), see the top. Throws std::invalid_argument with the reason and what is
/// allowed.
std::shared_ptr<const ConvexHull> LoadMeshHull(const std::string& path,
                                               const Eigen::Vector3d& scale,
                                               int max_vertices, std::size_t max_bytes);

/// A mesh read as a smooth body of revolution (mesh/mesh_revolution.h).
struct MeshRevolution {
  Shape shape;               ///< revolution, in `frame`
  Eigen::Isometry3d frame;   ///< the shape's frame in the mesh's (scaled) frame
  double deviation = 0.0;    ///< [m]
  double tolerance = 0.0;    ///< [m]
};

/// The mesh file `path`, scaled, as a body of revolution about `axis` within `tolerance` (unset:
/// 1 % of its size): the file as LoadMeshHull reads it (its hull checked the same way), then
/// mesh::FitBodyOfRevolution. Throws std::invalid_argument with the reason and what is allowed.
MeshRevolution LoadMeshRevolution(const std::string& path, const Eigen::Vector3d& scale,
                                  const Eigen::Vector3d& axis, std::optional<double> tolerance,
                                  std::size_t max_bytes);

}  // namespace nonsmooth_sim::scene_io

#endif  // NONSMOOTH_SIM_SCENE_IO_MESH_SOURCE_H_
