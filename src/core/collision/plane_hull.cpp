// Plane–convex hull: the lowest vertices, or face points for a face lying flat.
#include "nonsmooth_sim/core/collision/plane_hull.h"

#include <algorithm>
#include <bitset>
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

// The vertices with gap ≤ margin, ascending, into `low` (at most kMaxHullVerticesBound): on a
// hull whose edges connect its vertices, a descent along them to the lowest vertex, then a walk
// over the neighbours within the margin (a linear function's sublevel set on a convex
// polyhedron's vertices is connected along its edges); otherwise every vertex. Returns how many.
int VerticesWithin(const ConvexHull& hull, const Eigen::Vector3d& m, double base, double margin,
                   int* low) {
  const int vertex_count = static_cast<int>(hull.vertices.size());
  const auto gap = [&](int i) { return base + m.dot(hull.vertices[static_cast<std::size_t>(i)]); };
  int count = 0;
  if (!hull.connected || vertex_count > kMaxHullVerticesBound) {
    for (int i = 0; i < vertex_count && count < kMaxHullVerticesBound; ++i) {
      if (gap(i) <= margin) low[count++] = i;
    }
    return count;
  }
  // steepest descent: to the lowest neighbour while one is lower
  int lowest = 0;
  double lowest_gap = gap(0);
  for (int from = -1; from != lowest;) {
    from = lowest;
    for (int k = hull.neighbour_start[from]; k < hull.neighbour_start[from + 1]; ++k) {
      const int j = hull.neighbours[static_cast<std::size_t>(k)];
      const double g = gap(j);
      if (g < lowest_gap) lowest = j, lowest_gap = g;
    }
  }
  if (!(lowest_gap <= margin)) return 0;
  std::bitset<kMaxHullVerticesBound> seen;
  seen.set(static_cast<std::size_t>(lowest));
  low[count++] = lowest;
  for (int next = 0; next < count; ++next) {
    const int i = low[next];
    for (int k = hull.neighbour_start[i]; k < hull.neighbour_start[i + 1]; ++k) {
      const int j = hull.neighbours[static_cast<std::size_t>(k)];
      if (seen.test(static_cast<std::size_t>(j))) continue;
      seen.set(static_cast<std::size_t>(j));
      if (gap(j) <= margin) low[count++] = j;
    }
  }
  std::sort(low, low + count);
  return count;
}

}  // namespace

int CollidePlaneHull(const Shape& /*plane*/, const Eigen::Isometry3d& pose_plane,
                     const Shape& shape, const Eigen::Isometry3d& pose_hull, double margin,
                     ContactGeometry* out) {
  if (!shape.hull) return 0;
  const ConvexHull& hull = *shape.hull;
  const int vertex_count = static_cast<int>(hull.vertices.size());
  // m = R_Hᵀ n: the plane's normal in the hull frame; a vertex's gap is base + m·v
  const Eigen::Vector3d m = pose_hull.linear().transpose() * PlaneNormal(pose_plane);
  const double base = PlaneHeight(pose_plane, pose_hull.translation());
  int low[kMaxHullVerticesBound];
  const int low_count = VerticesWithin(hull, m, base, margin, low);
  if (low_count == 0) return 0;
  // the face facing the plane, f* = argmin ν_f·m (the first on ties), among the faces of the
  // vertices within the margin (a face with none cannot touch)
  int face = -1;
  double facing = INFINITY;
  const auto consider = [&](int f) {
    const double value = hull.face_normal[static_cast<std::size_t>(f)].dot(m);
    if (value < facing || (value == facing && f < face)) face = f, facing = value;
  };
  if (hull.connected && vertex_count <= kMaxHullVerticesBound) {
    for (int n = 0; n < low_count; ++n) {
      for (int k = hull.vertex_face_start[low[n]]; k < hull.vertex_face_start[low[n] + 1]; ++k) {
        consider(hull.vertex_faces[static_cast<std::size_t>(k)]);
      }
    }
  } else {
    for (int f = 0; f < hull.face_count; ++f) consider(f);
  }
  const int start = hull.face_start[face];
  const int face_size = hull.faces[start];
  const int* face_vertices = &hull.faces[start + 1];
  // its height varies by max − min of m·v over its vertices
  double lowest = m.dot(hull.vertices[face_vertices[0]]);
  double highest = lowest;
  for (int k = 1; k < face_size; ++k) {
    const double h = m.dot(hull.vertices[face_vertices[k]]);
    lowest = std::min(lowest, h);
    highest = std::max(highest, h);
  }
  const bool flat = highest - lowest <= kFlatFaceTolerance;

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
  for (int n = 0; n < low_count; ++n) {
    const int i = low[n];
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
