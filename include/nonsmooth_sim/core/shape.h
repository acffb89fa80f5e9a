// Convex shapes of colliders, each in its own frame (the shape frame, placed on a body or in the
// world by Collider::pose). Every shape is symmetric about its frame's origin except the plane
// and the convex hull.
//
//   type        parameters                                       solid in the shape frame
//   plane       -                                                z ≤ 0 (a half-space, normal +z)
//   sphere      radius r                                         |x| ≤ r
//   capsule     radius r, half_length l (segment along z)        dist(x, [-l ẑ, l ẑ]) ≤ r
//   ellipsoid   semi_axes (a, b, c) along x, y, z                (x/a)² + (y/b)² + (z/c)² ≤ 1
//   cylinder    radius r, half_length l (axis along z)           x² + y² ≤ r², |z| ≤ l
//   box         half_extents (a, b, c)                           |x| ≤ a, |y| ≤ b, |z| ≤ c
//   convex_hull hull: vertices v_i (and its faces)                the convex hull of the v_i
//   revolution  profile about z (revolution_profile.h)           ρ ≤ the profile's ρ at z
//
// URDF conventions: <cylinder radius length> has its axis along z and length = 2l; <box size>
// is the full size (2a, 2b, 2c). A convex hull comes from a mesh (mesh/mesh_hull.h): its
// vertices are in the shape frame (the mesh's frame, scaled), not centred on its origin; its
// inertia is never taken from it (a body's mass and inertia are its URDF <inertial>). A body of
// revolution comes from a mesh too (mesh/mesh_revolution.h): its profile, and the hull of a
// tessellation of it for the pairs FCL collides (the plane's is closed form). The types
// are ordered: the collision table (collision_table.h) is indexed by them and a pair function
// takes its shapes in this order.
#ifndef NONSMOOTH_SIM_CORE_SHAPE_H_
#define NONSMOOTH_SIM_CORE_SHAPE_H_

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "nonsmooth_sim/core/revolution_profile.h"

namespace nonsmooth_sim {

enum class ShapeType : int {
  kPlane = 0,
  kSphere,
  kCapsule,
  kEllipsoid,
  kCylinder,
  kBox,
  kConvexHull,
  kRevolution
};
inline constexpr int kShapeTypeCount = 8;

/// "plane", "sphere", "capsule", "ellipsoid", "cylinder", "box", "convex_hull", "revolution".
std::string_view ShapeTypeName(ShapeType type);
std::optional<ShapeType> ShapeTypeFromName(std::string_view name);

/// A convex polyhedron in its shape frame, built once by MakeConvexHull (from a mesh's hull:
/// mesh/mesh_hull.h) and shared, read-only, by every collider that uses it.
struct ConvexHull {
  std::vector<Eigen::Vector3d> vertices;  ///< [m], each a vertex of the hull
  /// the faces, flat: for each its vertex count n, then n indices into `vertices`,
  /// counter-clockwise seen from outside (FCL's Convex layout)
  std::vector<int> faces;
  int face_count = 0;
  // per face, computed by MakeConvexHull:
  std::vector<int> face_start;                 ///< index in `faces` of its count n
  std::vector<Eigen::Vector3d> face_normal;    ///< unit, outward
  std::vector<Eigen::Vector3d> face_centroid;  ///< of its area [m]
  /// mean distance of its area from its centroid, the drilling radius R̄ of a uniform pressure
  /// on it [m] (plane_hull.h)
  std::vector<double> face_patch_radius;
  double bounding_radius = 0.0;  ///< max |v_i| [m]
  // per vertex, compressed (vertex i's entries are [start[i], start[i + 1])), by MakeConvexHull:
  std::vector<int> neighbour_start;  ///< its neighbours along the faces' edges, ascending
  std::vector<int> neighbours;
  std::vector<int> vertex_face_start;  ///< the faces it is a vertex of, ascending
  std::vector<int> vertex_faces;
  /// every vertex on a face: the edges connect them all (walks on them find supports)
  bool connected = false;
};

/// Vertices of a mesh's hull, at most (as MuJoCo's maxhullvert): the loader's default
/// (UrdfSceneOptions::max_hull_vertices) and the largest it accepts.
inline constexpr int kDefaultMaxHullVertices = 256;
inline constexpr int kMaxHullVerticesBound = 4096;

/// The hull of `vertices` with the faces `faces` (flat, as ConvexHull::faces, counter-clockwise
/// from outside, each face planar and the polyhedron convex: a convex hull's facets): fills the
/// per-face data. Throws std::invalid_argument for fewer than 4 vertices or 4 faces, an index out
/// of range, a face with fewer than 3 vertices or a zero area, or a non-finite vertex.
std::shared_ptr<const ConvexHull> MakeConvexHull(std::vector<Eigen::Vector3d> vertices,
                                                 std::vector<int> faces);

/// Support point of the hull in the direction d of its frame: the vertex maximising d·v (the
/// first on ties).
int HullSupportVertex(const ConvexHull& hull, const Eigen::Vector3d& d);

/// Volume of the hull [m³] (sum of the tetrahedra from its first vertex over its faces).
double HullVolume(const ConvexHull& hull);

struct Shape {
  ShapeType type = ShapeType::kSphere;
  double radius = 0.0;       ///< sphere, capsule, cylinder [m]
  double half_length = 0.0;  ///< capsule (segment), cylinder (axis) [m]
  /// ellipsoid semi-axes, box half-extents, along the shape frame's x, y, z [m]
  Eigen::Vector3d half_extents = Eigen::Vector3d::Zero();
  /// convex_hull: its vertices and faces (shared; null for the other types); revolution: the
  /// hull of a tessellation of its surface, for FCL (may be null)
  std::shared_ptr<const ConvexHull> hull;
  /// revolution: its profile (shared; null for the other types)
  std::shared_ptr<const RevolutionProfile> revolution;

  static Shape Plane();
  static Shape Sphere(double radius);
  static Shape Capsule(double radius, double half_length);
  static Shape Ellipsoid(const Eigen::Vector3d& semi_axes);
  static Shape Cylinder(double radius, double half_length);
  static Shape Box(const Eigen::Vector3d& half_extents);
  static Shape Hull(std::shared_ptr<const ConvexHull> hull);
  static Shape Revolution(std::shared_ptr<const RevolutionProfile> profile,
                          std::shared_ptr<const ConvexHull> tessellation = nullptr);
};

/// Radius of the smallest sphere about the shape frame's origin that holds the shape [m]
/// (+inf for a plane). Used by the broad phase.
double BoundingRadius(const Shape& shape);

/// Throws std::invalid_argument naming `where` and the bad parameter (every length finite and
/// > 0 where the type uses it; a capsule or cylinder half_length ≥ 0 resp. > 0; a convex hull
/// present, with at least 4 vertices, all finite; a revolution's profile present, with arcs).
void ValidateShape(const Shape& shape, const std::string& where);

/// Volume [m³] and inertia about the shape frame's origin in its axes per unit density [m⁵]
/// (the plane: not defined, throws std::invalid_argument). Used to build scenes of uniform
/// bodies in code and tests. A convex hull or a body of revolution: its volume; its inertia is not
/// defined here (throws: a body with a mesh takes its inertia from its URDF <inertial>).
double ShapeVolume(const Shape& shape);
Eigen::Matrix3d ShapeUnitInertia(const Shape& shape);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_SHAPE_H_
