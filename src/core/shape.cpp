// Shapes: names, factories, validation, bounding radius, volume and unit-density inertia.
//
// Inertia about the shape frame's origin (the centroid: every solid shape is symmetric about it),
// per unit density, m = V:
//   sphere     I = (2/5) m r² · 1
//   ellipsoid  I_xx = m (b² + c²)/5, cyclically
//   box        I_xx = m (b² + c²)/3, cyclically (half-extents)
//   cylinder   I_zz = m r²/2,  I_xx = I_yy = m (r²/4 + l²/3)
//   capsule    the cylinder (m_c = 2πr²l) plus two hemispheres (together m_s = 4πr³/3):
//              I_zz = m_c r²/2 + (2/5) m_s r²,
//              I_xx = m_c (r²/4 + l²/3) + m_s (2r²/5 + l² + 3lr/4)
// The hemisphere term: a hemisphere of mass m_h has I = (2/5) m_h r² about a diameter of its flat
// face and its centroid 3r/8 from that face; moved by the parallel-axis theorem to the capsule's
// centre, l from the face: (2/5) m_h r² − m_h (3r/8)² + m_h (l + 3r/8)² = m_h (2r²/5 + l² + 3lr/4).
//
// A convex hull's faces (MakeConvexHull): area, centroid and outward normal from the fan of
// triangles (p_0, p_k, p_k+1); the drilling radius of a uniform pressure, R̄ = (1/A) ∫ |x − c| dA,
// summed over the edges (p, q) of the face: in polar coordinates about c, the triangle (c, p, q)
// lies below the edge's line at distance d from c, and with t the coordinate along the edge from
// the foot of c (t_p, t_q at its ends),
//   ∫∫ ρ² dρ dψ = (d³/3) ∫ sec³ψ dψ = [F(t)]_{t_p}^{t_q},  F(t) = (d t √(d² + t²) + d³ asinh(t/d))/6
// (the rectangle's R̄ of plane_box.h is the case of four edges).
#include "nonsmooth_sim/core/shape.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "nonsmooth_sim/core/constants.h"

namespace nonsmooth_sim {
namespace {

constexpr ShapeType kAllShapeTypes[kShapeTypeCount] = {
    ShapeType::kPlane,    ShapeType::kSphere, ShapeType::kCapsule,   ShapeType::kEllipsoid,
    ShapeType::kCylinder, ShapeType::kBox,    ShapeType::kConvexHull, ShapeType::kRevolution};

// "<where>: <what> = <value>: must be <allowed>"
[[noreturn]] void Reject(const std::string& where, const std::string& what, double value,
                         const std::string& allowed) {
  std::ostringstream s;
  s << where << ": " << what << " = " << value << ": must be " << allowed;
  throw std::invalid_argument(s.str());
}

void RequirePositive(const std::string& where, const std::string& what, double value) {
  if (!(std::isfinite(value) && value > 0.0)) Reject(where, what, value, "finite, > 0 [m]");
}

void RequireNonNegative(const std::string& where, const std::string& what, double value) {
  if (!(std::isfinite(value) && value >= 0.0)) Reject(where, what, value, "finite, >= 0 [m]");
}

void RequirePositiveAxes(const std::string& where, const std::string& what,
                         const Eigen::Vector3d& axes) {
  constexpr const char* kAxisNames[3] = {".x", ".y", ".z"};
  for (int i = 0; i < 3; ++i) RequirePositive(where, what + kAxisNames[i], axes[i]);
}

[[noreturn]] void RejectPlane(const char* what) {
  throw std::invalid_argument(std::string(what) + ": not defined for a plane (a half-space)");
}

Eigen::Matrix3d Diagonal(double xx, double yy, double zz) {
  return Eigen::Vector3d(xx, yy, zz).asDiagonal();
}

// F(t) of the edge integral (top of the file), d > 0.
double EdgeIntegral(double d, double t) {
  return (d * t * std::hypot(d, t) + d * d * d * std::asinh(t / d)) / 6.0;
}

[[noreturn]] void RejectHull(const std::string& reason) {
  throw std::invalid_argument("MakeConvexHull: " + reason);
}


}  // namespace

std::string_view ShapeTypeName(ShapeType type) {
  switch (type) {
    case ShapeType::kPlane: return "plane";
    case ShapeType::kSphere: return "sphere";
    case ShapeType::kCapsule: return "capsule";
    case ShapeType::kEllipsoid: return "ellipsoid";
    case ShapeType::kCylinder: return "cylinder";
    case ShapeType::kBox: return "box";
    case ShapeType::kConvexHull: return "convex_hull";
    case ShapeType::kRevolution: return "revolution";
  }
  return "unknown";
}

std::optional<ShapeType> ShapeTypeFromName(std::string_view name) {
  for (ShapeType type : kAllShapeTypes) {
    if (ShapeTypeName(type) == name) return type;
  }
  return std::nullopt;
}

Shape Shape::Plane() {
  Shape shape;
  shape.type = ShapeType::kPlane;
  return shape;
}

Shape Shape::Sphere(double radius) {
  Shape shape;
  shape.type = ShapeType::kSphere;
  shape.radius = radius;
  return shape;
}

Shape Shape::Capsule(double radius, double half_length) {
  Shape shape;
  shape.type = ShapeType::kCapsule;
  shape.radius = radius;
  shape.half_length = half_length;
  return shape;
}

Shape Shape::Ellipsoid(const Eigen::Vector3d& semi_axes) {
  Shape shape;
  shape.type = ShapeType::kEllipsoid;
  shape.half_extents = semi_axes;
  return shape;
}

Shape Shape::Cylinder(double radius, double half_length) {
  Shape shape;
  shape.type = ShapeType::kCylinder;
  shape.radius = radius;
  shape.half_length = half_length;
  return shape;
}

Shape Shape::Box(const Eigen::Vector3d& half_extents) {
  Shape shape;
  shape.type = ShapeType::kBox;
  shape.half_extents = half_extents;
  return shape;
}

Shape Shape::Hull(std::shared_ptr<const ConvexHull> hull) {
  Shape shape;
  shape.type = ShapeType::kConvexHull;
  shape.hull = std::move(hull);
  return shape;
}

Shape Shape::Revolution(std::shared_ptr<const RevolutionProfile> profile,
                        std::shared_ptr<const ConvexHull> tessellation) {
  Shape shape;
  shape.type = ShapeType::kRevolution;
  shape.revolution = std::move(profile);
  shape.hull = std::move(tessellation);
  return shape;
}

std::shared_ptr<const ConvexHull> MakeConvexHull(std::vector<Eigen::Vector3d> vertices,
                                                 std::vector<int> faces) {
  auto hull = std::make_shared<ConvexHull>();
  const int n = static_cast<int>(vertices.size());
  if (n < 4) RejectHull(std::to_string(n) + " vertices: must be at least 4");
  for (const Eigen::Vector3d& v : vertices) {
    if (!v.allFinite()) RejectHull("a vertex is not finite");
    hull->bounding_radius = std::max(hull->bounding_radius, v.norm());
  }
  hull->vertices = std::move(vertices);
  hull->faces = std::move(faces);
  const std::vector<Eigen::Vector3d>& x = hull->vertices;
  const std::vector<int>& f = hull->faces;
  std::size_t i = 0;
  while (i < f.size()) {
    const int count = f[i];
    if (count < 3 || i + 1 + static_cast<std::size_t>(count) > f.size()) {
      RejectHull("face " + std::to_string(hull->face_count) + ": bad vertex count");
    }
    for (int k = 1; k <= count; ++k) {
      if (f[i + k] < 0 || f[i + k] >= n) RejectHull("a face index is out of range");
    }
    // the fan (p_0, p_k, p_k+1): area vector and centroid
    const Eigen::Vector3d& p0 = x[f[i + 1]];
    Eigen::Vector3d area_vector = Eigen::Vector3d::Zero();
    Eigen::Vector3d moment = Eigen::Vector3d::Zero();
    for (int k = 2; k < count; ++k) {
      const Eigen::Vector3d& p = x[f[i + k]];
      const Eigen::Vector3d& q = x[f[i + k + 1]];
      const Eigen::Vector3d a = 0.5 * (p - p0).cross(q - p0);
      area_vector += a;
      moment += a.norm() * (p0 + p + q) / 3.0;
    }
    const double area = area_vector.norm();
    if (!(area > 0.0)) RejectHull("face " + std::to_string(hull->face_count) + ": zero area");
    const Eigen::Vector3d c = moment / area;
    // R̄ = (1/A) Σ_edges [F(t)]_{t_p}^{t_q}
    double integral = 0.0;
    for (int k = 1; k <= count; ++k) {
      const Eigen::Vector3d& p = x[f[i + k]];
      const Eigen::Vector3d& q = x[f[i + (k % count) + 1]];
      const double length = (q - p).norm();
      if (!(length > 0.0)) continue;
      const Eigen::Vector3d e = (q - p) / length;
      const double t_p = e.dot(p - c);
      const Eigen::Vector3d foot = p - t_p * e;
      const double d = (foot - c).norm();
      if (!(d > 0.0)) continue;
      integral += EdgeIntegral(d, t_p + length) - EdgeIntegral(d, t_p);
    }
    hull->face_start.push_back(static_cast<int>(i));
    hull->face_normal.push_back(area_vector / area);
    hull->face_centroid.push_back(c);
    hull->face_patch_radius.push_back(integral / area);
    ++hull->face_count;
    i += static_cast<std::size_t>(count) + 1;
  }
  if (hull->face_count < 4) {
    RejectHull(std::to_string(hull->face_count) + " faces: must be at least 4");
  }
  // each vertex's neighbours along the faces' edges and its faces
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(n));
  std::vector<std::vector<int>> incident(static_cast<std::size_t>(n));
  for (int face = 0; face < hull->face_count; ++face) {
    const int start = hull->face_start[static_cast<std::size_t>(face)];
    const int count = f[static_cast<std::size_t>(start)];
    for (int k = 1; k <= count; ++k) {
      const int a = f[static_cast<std::size_t>(start + k)];
      const int b = f[static_cast<std::size_t>(start + k % count + 1)];
      neighbours[static_cast<std::size_t>(a)].push_back(b);
      neighbours[static_cast<std::size_t>(b)].push_back(a);
      incident[static_cast<std::size_t>(a)].push_back(face);
    }
  }
  hull->connected = true;
  const auto compress = [](std::vector<std::vector<int>>& lists, std::vector<int>* start,
                           std::vector<int>* flat) {
    start->push_back(0);
    for (std::vector<int>& list : lists) {
      std::sort(list.begin(), list.end());
      list.erase(std::unique(list.begin(), list.end()), list.end());
      flat->insert(flat->end(), list.begin(), list.end());
      start->push_back(static_cast<int>(flat->size()));
    }
  };
  for (const std::vector<int>& list : incident) hull->connected = hull->connected && !list.empty();
  compress(neighbours, &hull->neighbour_start, &hull->neighbours);
  compress(incident, &hull->vertex_face_start, &hull->vertex_faces);
  return hull;
}

int HullSupportVertex(const ConvexHull& hull, const Eigen::Vector3d& d) {
  int best = 0;
  double best_height = d.dot(hull.vertices[0]);
  for (int i = 1; i < static_cast<int>(hull.vertices.size()); ++i) {
    const double height = d.dot(hull.vertices[static_cast<std::size_t>(i)]);
    if (height > best_height) best = i, best_height = height;
  }
  return best;
}

double HullVolume(const ConvexHull& hull) {
  // Σ over the faces' fans of the tetrahedra (v_0, p_0, p_k, p_k+1)
  const std::vector<Eigen::Vector3d>& x = hull.vertices;
  const Eigen::Vector3d& o = x[0];
  double six_volume = 0.0;
  for (int face = 0; face < hull.face_count; ++face) {
    const int start = hull.face_start[static_cast<std::size_t>(face)];
    const int count = hull.faces[static_cast<std::size_t>(start)];
    const Eigen::Vector3d p0 = x[hull.faces[start + 1]] - o;
    for (int k = 2; k < count; ++k) {
      six_volume += p0.dot((x[hull.faces[start + k]] - o).cross(x[hull.faces[start + k + 1]] - o));
    }
  }
  return six_volume / 6.0;
}

double BoundingRadius(const Shape& shape) {
  switch (shape.type) {
    case ShapeType::kPlane: return std::numeric_limits<double>::infinity();
    case ShapeType::kSphere: return shape.radius;
    // the farthest points are the poles of the end spheres
    case ShapeType::kCapsule: return shape.radius + shape.half_length;
    case ShapeType::kEllipsoid: return shape.half_extents.maxCoeff();
    // the farthest points are on the rims
    case ShapeType::kCylinder: return std::hypot(shape.radius, shape.half_length);
    // the farthest points are the corners
    case ShapeType::kBox: return shape.half_extents.norm();
    // the farthest vertex from the shape frame's origin
    case ShapeType::kConvexHull: return shape.hull ? shape.hull->bounding_radius : 0.0;
    case ShapeType::kRevolution:
      return shape.revolution ? shape.revolution->bounding_radius : 0.0;
  }
  return std::numeric_limits<double>::infinity();
}

void ValidateShape(const Shape& shape, const std::string& where) {
  switch (shape.type) {
    case ShapeType::kPlane: return;
    case ShapeType::kSphere: RequirePositive(where, "radius", shape.radius); return;
    case ShapeType::kCapsule:
      RequirePositive(where, "radius", shape.radius);
      RequireNonNegative(where, "half_length", shape.half_length);
      return;
    case ShapeType::kEllipsoid: RequirePositiveAxes(where, "semi_axes", shape.half_extents); return;
    case ShapeType::kCylinder:
      RequirePositive(where, "radius", shape.radius);
      RequirePositive(where, "half_length", shape.half_length);
      return;
    case ShapeType::kBox: RequirePositiveAxes(where, "half_extents", shape.half_extents); return;
    case ShapeType::kConvexHull:
      if (!shape.hull) throw std::invalid_argument(where + ": convex_hull without its hull");
      if (shape.hull->vertices.size() < 4 || shape.hull->face_count < 4) {
        Reject(where, "hull vertices", static_cast<double>(shape.hull->vertices.size()),
               "at least 4, with at least 4 faces");
      }
      for (const Eigen::Vector3d& v : shape.hull->vertices) {
        if (!v.allFinite()) throw std::invalid_argument(where + ": a hull vertex is not finite");
      }
      RequirePositive(where, "hull bounding radius", shape.hull->bounding_radius);
      return;
    case ShapeType::kRevolution:
      if (!shape.revolution || shape.revolution->arcs.empty()) {
        throw std::invalid_argument(where + ": revolution without its profile");
      }
      RequirePositive(where, "profile bounding radius", shape.revolution->bounding_radius);
      return;
  }
  Reject(where, "type", static_cast<int>(shape.type), "a ShapeType (0 to 7)");
}

double ShapeVolume(const Shape& shape) {
  const double r = shape.radius;
  const double l = shape.half_length;
  const Eigen::Vector3d& h = shape.half_extents;
  switch (shape.type) {
    case ShapeType::kPlane: RejectPlane("ShapeVolume");
    case ShapeType::kSphere: return 4.0 / 3.0 * kPi * r * r * r;
    case ShapeType::kCapsule: return kPi * r * r * (2.0 * l + 4.0 / 3.0 * r);
    case ShapeType::kEllipsoid: return 4.0 / 3.0 * kPi * h.prod();
    case ShapeType::kCylinder: return 2.0 * kPi * r * r * l;
    case ShapeType::kBox: return 8.0 * h.prod();
    case ShapeType::kConvexHull:
      if (!shape.hull) throw std::invalid_argument("ShapeVolume: convex_hull without its hull");
      return HullVolume(*shape.hull);
    case ShapeType::kRevolution:
      if (!shape.revolution) throw std::invalid_argument("ShapeVolume: revolution without profile");
      return RevolutionVolume(*shape.revolution);
  }
  throw std::invalid_argument("ShapeVolume: unknown shape type");
}

Eigen::Matrix3d ShapeUnitInertia(const Shape& shape) {
  const double r = shape.radius;
  const double l = shape.half_length;
  const Eigen::Vector3d h2 = shape.half_extents.cwiseAbs2();
  switch (shape.type) {
    case ShapeType::kPlane: RejectPlane("ShapeUnitInertia");
    case ShapeType::kSphere: {
      const double m = ShapeVolume(shape);
      return Diagonal(0.4 * m * r * r, 0.4 * m * r * r, 0.4 * m * r * r);
    }
    case ShapeType::kCapsule: {
      const double m_c = 2.0 * kPi * r * r * l;        // cylinder
      const double m_s = 4.0 / 3.0 * kPi * r * r * r;  // both hemispheres
      const double zz = 0.5 * m_c * r * r + 0.4 * m_s * r * r;
      const double xx =
          m_c * (0.25 * r * r + l * l / 3.0) + m_s * (0.4 * r * r + l * l + 0.75 * l * r);
      return Diagonal(xx, xx, zz);
    }
    case ShapeType::kEllipsoid: {
      const double m = ShapeVolume(shape);
      return Diagonal(m * (h2.y() + h2.z()) / 5.0, m * (h2.x() + h2.z()) / 5.0,
                      m * (h2.x() + h2.y()) / 5.0);
    }
    case ShapeType::kCylinder: {
      const double m = ShapeVolume(shape);
      const double xx = m * (0.25 * r * r + l * l / 3.0);
      return Diagonal(xx, xx, 0.5 * m * r * r);
    }
    case ShapeType::kBox: {
      const double m = ShapeVolume(shape);
      return Diagonal(m * (h2.y() + h2.z()) / 3.0, m * (h2.x() + h2.z()) / 3.0,
                      m * (h2.x() + h2.y()) / 3.0);
    }
    case ShapeType::kConvexHull:
    case ShapeType::kRevolution:
      throw std::invalid_argument(
          "ShapeUnitInertia: not defined for a convex hull or a body of revolution (its body's "
          "inertia is its URDF <inertial>)");
  }
  throw std::invalid_argument("ShapeUnitInertia: unknown shape type");
}

}  // namespace nonsmooth_sim
