// Plane–convex hull: the lowest vertices, or face points for a face lying flat.
#include "nonsmooth_sim/core/collision/plane_hull.h"

#include <algorithm>
#include <cmath>

#include "nonsmooth_sim/core/collision/plane_contact.h"

namespace nonsmooth_sim {
namespace {

// Inserts `c` into out[0..count) kept sorted by gap (lowest first), at most `capacity` entries.
void InsertLowest(const ContactGeometry& c, ContactGeometry* out, int* count, int capacity) {
  if (*count == capacity && !(c.gap < out[capacity - 1].gap)) return;
  int i = *count < capacity ? (*count)++ : capacity - 1;
  for (; i > 0 && c.gap < out[i - 1].gap; --i) out[i] = out[i - 1];
  out[i] = c;
}

}  // namespace

int CollidePlaneHull(const Shape& /*plane*/, const Eigen::Isometry3d& pose_plane,
                     const Shape& shape, const Eigen::Isometry3d& pose_hull, double margin,
                     ContactGeometry* out) {
  if (!shape.hull) return 0;
  const ConvexHull& hull = *shape.hull;
  const int vertex_count = static_cast<int>(hull.vertices.size());
  // m = R_Hᵀ n: the plane's normal in the hull frame
  const Eigen::Vector3d m = pose_hull.linear().transpose() * PlaneNormal(pose_plane);
  // the face facing the plane: f* = argmin ν_f·m (first on ties)
  int face = 0;
  for (int f = 1; f < hull.face_count; ++f) {
    if (hull.face_normal[f].dot(m) < hull.face_normal[face].dot(m)) face = f;
  }
  const int start = hull.face_start[face];
  const int face_size = hull.faces[start];
  const int* face_vertices = &hull.faces[start + 1];
  // its height varies by max − min of m·v over its vertices
  double low = m.dot(hull.vertices[face_vertices[0]]);
  double high = low;
  for (int k = 1; k < face_size; ++k) {
    const double h = m.dot(hull.vertices[face_vertices[k]]);
    low = std::min(low, h);
    high = std::max(high, h);
  }
  const bool flat = high - low <= kFlatFaceTolerance;

  int count = 0;
  if (flat) {
    // towards up to kMaxHullFacePoints of its vertices, evenly spaced, at R̄_f from c_f
    const int points = std::min(face_size, kMaxHullFacePoints);
    const Eigen::Vector3d& c = hull.face_centroid[face];
    const double rbar = hull.face_patch_radius[face];
    ContactGeometry face_points[kMaxHullFacePoints];
    for (int j = 0; j < points; ++j) {
      const Eigen::Vector3d& p = hull.vertices[face_vertices[j * face_size / points]];
      const double reach = (p - c).norm();
      const Eigen::Vector3d local = c + (std::min(rbar, reach) / reach) * (p - c);
      face_points[j] = PlaneContact(pose_plane, pose_hull * local,
                                    /*feature=*/vertex_count + kMaxHullFacePoints * face + j,
                                    /*face_point=*/true);
    }
    ShareFaceGap(face_points, points);
    if (face_points[0].gap <= margin) {
      for (int j = 0; j < points; ++j) out[count++] = face_points[j];
    }
  }
  // the lowest vertices within the margin (those of a flat face are replaced by its points)
  const int first_vertex = count;
  int vertices_found = 0;
  for (int i = 0; i < vertex_count; ++i) {
    if (flat && std::find(face_vertices, face_vertices + face_size, i) !=
                    face_vertices + face_size) {
      continue;
    }
    const ContactGeometry vertex = PlaneContact(pose_plane, pose_hull * hull.vertices[i],
                                                /*feature=*/i);
    if (vertex.gap <= margin) {
      InsertLowest(vertex, out + first_vertex, &vertices_found, kMaxPairContacts - first_vertex);
    }
  }
  return count + vertices_found;
}

}  // namespace nonsmooth_sim
