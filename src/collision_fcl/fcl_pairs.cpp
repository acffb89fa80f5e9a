// FCL-based pair functions: shapes mapped to FCL geometries on the stack, FCL's contacts and
// nearest points mapped to ContactGeometry, MPR's penetration refined by separated distances
// (fcl_pairs.h).
#include "nonsmooth_sim/collision_fcl/fcl_pairs.h"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <memory>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <variant>
#include <vector>

#include "nonsmooth_sim/core/collision/closest_points.h"

namespace nonsmooth_sim {
namespace {

// A contact normal shorter than this is FCL's zero normal of exactly touching shapes.
constexpr double kFclMinNormalNorm = 0.5;
// GJK's stopping tolerance of the distance queries (FCL's own GJK, GST_INDEP): distances then
// agree with the closed forms to ~1e-12 m and normals to ~1e-6 (FCL's default 1e-6 with its
// libccd GJK: ~1e-6 m and ~1e-2, test/collision_fcl).
constexpr double kDistanceTolerance = 1e-13;
// Fixed-point iterations of the refinement, and their stopping rules: |n_{k+1} − n_k| (GJK's
// nearest points jitter the normal at ~1e-6 at a separation ε) or the gain in PG(n_k) [m].
constexpr int kMaxRefinements = 8;
constexpr double kRefinedNormalChange = 1e-6;
constexpr double kRefinedGapChange = 1e-11;
// |n_i − n| up to which FCL's box–box contact normal is the refined normal n (both are then the
// same face normal, to round-off and GJK's error).
constexpr double kManifoldNormalTolerance = 1e-6;

// FCL's lengths: full cylinder/capsule length lz = 2l, full box sides 2h.
// A convex hull: fcl::Convex over the hull's own vertex and face arrays (shared, not copied),
// built once per hull and thread (ConvexOf).
using FclGeometry = std::variant<std::monostate, fcl::Sphered, fcl::Capsuled, fcl::Ellipsoidd,
                                 fcl::Cylinderd, fcl::Boxd, std::shared_ptr<const fcl::Convexd>>;

// Hulls whose fcl::Convex a thread keeps; beyond it, those of freed hulls are dropped.
constexpr std::size_t kCachedConvexes = 64;

// The fcl::Convex of `hull`: its constructor builds the vertex adjacency (FCL walks it for
// support points above 32 vertices, and checks the topology), too costly for every call. Kept per
// thread (no lock) by the hull's address, checked against a weak_ptr: a hull freed and another
// allocated at its address is not mistaken for it.
std::shared_ptr<const fcl::Convexd> ConvexOf(const std::shared_ptr<const ConvexHull>& hull) {
  struct Entry {
    std::weak_ptr<const ConvexHull> hull;
    std::shared_ptr<const fcl::Convexd> convex;
  };
  thread_local std::unordered_map<const ConvexHull*, Entry> cache;
  Entry& entry = cache[hull.get()];
  if (entry.convex && entry.hull.lock() == hull) return entry.convex;
  // non-owning (aliasing an empty shared_ptr): the cache must not keep a hull alive; an entry is
  // used only while its hull lives
  const std::shared_ptr<const std::vector<Eigen::Vector3d>> vertices(std::shared_ptr<void>(),
                                                                     &hull->vertices);
  const std::shared_ptr<const std::vector<int>> faces(std::shared_ptr<void>(), &hull->faces);
  entry.hull = hull;
  entry.convex = std::make_shared<const fcl::Convexd>(vertices, hull->face_count, faces,
                                                      /*throw_if_invalid=*/false);
  const std::shared_ptr<const fcl::Convexd> convex = entry.convex;
  if (cache.size() > kCachedConvexes) {
    for (auto it = cache.begin(); it != cache.end();) {
      it = it->second.hull.expired() ? cache.erase(it) : std::next(it);
    }
  }
  return convex;
}

void MakeGeometry(const Shape& shape, FclGeometry* geometry) {
  switch (shape.type) {
    case ShapeType::kPlane: return;
    case ShapeType::kSphere: geometry->emplace<fcl::Sphered>(shape.radius); return;
    case ShapeType::kCapsule:
      geometry->emplace<fcl::Capsuled>(shape.radius, 2.0 * shape.half_length);
      return;
    case ShapeType::kEllipsoid: geometry->emplace<fcl::Ellipsoidd>(shape.half_extents); return;
    case ShapeType::kCylinder:
      geometry->emplace<fcl::Cylinderd>(shape.radius, 2.0 * shape.half_length);
      return;
    case ShapeType::kBox: geometry->emplace<fcl::Boxd>(2.0 * shape.half_extents); return;
    case ShapeType::kConvexHull:
    case ShapeType::kRevolution:  // the hull of its tessellation
      if (shape.hull) geometry->emplace<std::shared_ptr<const fcl::Convexd>>(ConvexOf(shape.hull));
      return;
  }
}

const fcl::CollisionGeometryd* Pointer(const FclGeometry& geometry) {
  return std::visit(
      [](const auto& g) -> const fcl::CollisionGeometryd* {
        using G = std::decay_t<decltype(g)>;
        if constexpr (std::is_same_v<G, std::monostate>) {
          return nullptr;
        } else if constexpr (std::is_same_v<G, std::shared_ptr<const fcl::Convexd>>) {
          return g.get();
        } else {
          return &g;
        }
      },
      geometry);
}

// True for the pairs FCL collides by a formula of its own, not by MPR.
bool FclHasOwnFormula(ShapeType a, ShapeType b) {
  if (a > b) std::swap(a, b);
  return (a == ShapeType::kSphere && b == ShapeType::kCylinder) ||
         (a == ShapeType::kBox && b == ShapeType::kBox);
}

// Support point of the solid shape in the world direction d (unit): the point maximising d·x.
Eigen::Vector3d Support(const Shape& shape, const Eigen::Isometry3d& pose,
                        const Eigen::Vector3d& d_world) {
  const Eigen::Vector3d d = pose.linear().transpose() * d_world;
  const auto sign = [](double x) { return x >= 0.0 ? 1.0 : -1.0; };
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  switch (shape.type) {
    case ShapeType::kPlane: break;
    case ShapeType::kSphere: x = shape.radius * d; break;
    case ShapeType::kCapsule:
      x = shape.radius * d + sign(d.z()) * shape.half_length * Eigen::Vector3d::UnitZ();
      break;
    case ShapeType::kEllipsoid: {
      // S² d/|S d| (plane_ellipsoid.h)
      const Eigen::Vector3d s_d = shape.half_extents.cwiseProduct(d);
      x = shape.half_extents.cwiseProduct(s_d) / s_d.norm();
      break;
    }
    case ShapeType::kCylinder: {
      const double rho = d.head<2>().norm();
      if (rho > 0.0) x.head<2>() = (shape.radius / rho) * d.head<2>();
      x.z() = sign(d.z()) * shape.half_length;
      break;
    }
    case ShapeType::kBox:
      for (int j = 0; j < 3; ++j) x[j] = sign(d[j]) * shape.half_extents[j];
      break;
    case ShapeType::kConvexHull:
      if (shape.hull) x = shape.hull->vertices[HullSupportVertex(*shape.hull, d)];
      break;
    case ShapeType::kRevolution:
      if (shape.revolution) x = RevolutionSupport(*shape.revolution, d);
      break;
  }
  return pose * x;
}

// Gap along the unit direction n: min over B of n·x − max over A of n·y. A lower bound of the
// signed distance for every n, equal to it for the optimal n.
double ProjectionGap(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                     const Eigen::Isometry3d& pose_b, const Eigen::Vector3d& n) {
  return n.dot(Support(b, pose_b, -n)) - n.dot(Support(a, pose_a, n));
}

struct Distance {
  double distance = 0.0;
  Eigen::Vector3d point_a = Eigen::Vector3d::Zero();
  Eigen::Vector3d point_b = Eigen::Vector3d::Zero();
};

// GJK distance with nearest points (world) of separated shapes; FCL's GJK, tolerance above.
// FCL's signed distance is not used for penetration: with libccd its EPA asserts (aborts the
// process: Debian's libfcl keeps assertions) on some configurations, and with GST_INDEP it goes
// through GST_INDEP's collide, whose EPA contacts have negative depths and normals in o1's frame.
Distance FclDistance(const fcl::CollisionGeometryd* a, const Eigen::Isometry3d& pose_a,
                     const fcl::CollisionGeometryd* b, const Eigen::Isometry3d& pose_b) {
  const fcl::DistanceRequestd request(/*enable_nearest_points=*/true,
                                      /*enable_signed_distance=*/false, /*rel_err=*/0.0,
                                      /*abs_err=*/0.0, kDistanceTolerance, fcl::GST_INDEP);
  fcl::DistanceResultd result;
  fcl::distance(a, pose_a, b, pose_b, request, result);
  return {result.min_distance, result.nearest_points[0], result.nearest_points[1]};
}

// ε of the refinement [m]: large against GJK's error in the nearest points, small against the
// shapes.
double RefinementSeparation(const Shape& a, const Shape& b) {
  return kFclRefinementSeparation * std::min(BoundingRadius(a), BoundingRadius(b));
}

// The fixed point of RefinedContact from one start n₀: the iterate with the largest PG (each
// PG(n_k) is a lower bound of the signed distance).
ContactGeometry RefineFrom(const Shape& a, const Eigen::Isometry3d& pose_a,
                           const fcl::CollisionGeometryd* fcl_a, const Shape& b,
                           const Eigen::Isometry3d& pose_b, const fcl::CollisionGeometryd* fcl_b,
                           Eigen::Vector3d n, double separation) {
  ContactGeometry best;
  best.gap = -std::numeric_limits<double>::infinity();
  for (int k = 0; k < kMaxRefinements; ++k) {
    // move B along n_k until PG(n_k) = ε, then GJK on the separated shapes
    const double gap = ProjectionGap(a, pose_a, b, pose_b, n);
    // converged: the gap no longer improves (it is stationary in n: an error δ in n moves it
    // by O(δ²), so this stops long before n stops jittering at GJK's error)
    if (gap <= best.gap + kRefinedGapChange) break;
    const Eigen::Vector3d shift = (separation - gap) * n;
    const Distance nearest =
        FclDistance(fcl_a, pose_a, fcl_b, Eigen::Translation3d(shift) * pose_b);
    if (gap > best.gap) {
      best.normal = n;
      best.gap = gap;
      best.point_b = nearest.point_b - shift;
      best.point_a = best.point_b - gap * n;
    }
    // n_{k+1} = (p_b − p_a)/|p_b − p_a| (n_k if GJK found no direction)
    const Eigen::Vector3d next = NormalizedOr(nearest.point_b - nearest.point_a, n);
    if ((next - n).norm() <= kRefinedNormalChange) break;
    n = next;
  }
  return best;
}

// The contact of shapes that penetrate or nearly touch, from a guess of its normal.
// Fixed point: move B along n_k until its gap along n_k is ε (by s = ε − PG(n_k)), take the
// normal of the now separated shapes from GJK's nearest points, n_{k+1} = (p_b − p_a)/|p_b − p_a|.
// At a fixed point n* B was moved along the normal of the deepest points, which keeps them the
// nearest points: gap = PG(n*), point_b = p_b − s n*. Started from the guess, and again from the
// best face normal (a box's axes, a cylinder's axis, a cylinder's barrel normal at the other
// shape's deepest point: where flat faces touch, the least penetration is along one of them) if
// that separates better than the first fixed point; the larger PG wins.
ContactGeometry RefinedContact(const Shape& a, const Eigen::Isometry3d& pose_a,
                               const fcl::CollisionGeometryd* fcl_a, const Shape& b,
                               const Eigen::Isometry3d& pose_b,
                               const fcl::CollisionGeometryd* fcl_b, const Eigen::Vector3d& guess) {
  const double separation = RefinementSeparation(a, b);
  ContactGeometry best = RefineFrom(a, pose_a, fcl_a, b, pose_b, fcl_b, guess, separation);
  double face_gap = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d face_normal = Eigen::Vector3d::Zero();
  const auto consider = [&](const Eigen::Vector3d& n) {
    const double gap = ProjectionGap(a, pose_a, b, pose_b, n);
    if (gap > face_gap) face_gap = gap, face_normal = n;
  };
  for (const auto& [shape, pose] : {std::pair{&a, &pose_a}, std::pair{&b, &pose_b}}) {
    // a hull's face normals (outward from A, inward to B)
    if (shape->type == ShapeType::kConvexHull && shape->hull) {
      const double sign = shape == &a ? 1.0 : -1.0;
      for (const Eigen::Vector3d& normal : shape->hull->face_normal) {
        consider(sign * (pose->linear() * normal));
      }
      continue;
    }
    // a box's three axes, a cylinder's axis, both ways
    if (shape->type != ShapeType::kBox && shape->type != ShapeType::kCylinder) continue;
    for (int j = shape->type == ShapeType::kBox ? 0 : 2; j < 3; ++j) {
      consider(pose->linear().col(j));
      consider(-pose->linear().col(j));
    }
  }
  // a cylinder's barrel normal at the other shape's point deepest in it (along the guess)
  const auto barrel = [&](const Shape& cylinder, const Eigen::Isometry3d& pose,
                          const Eigen::Vector3d& deepest, double sign) {
    const Eigen::Vector3d axis = pose.linear().col(2);
    const Eigen::Vector3d r = deepest - pose.translation();
    const Eigen::Vector3d radial = r - axis.dot(r) * axis;
    if (cylinder.type == ShapeType::kCylinder && radial.norm() > 0.0) {
      consider(sign * radial.normalized());
    }
  };
  barrel(a, pose_a, Support(b, pose_b, -guess), 1.0);
  barrel(b, pose_b, Support(a, pose_a, guess), -1.0);
  // a second fixed point from the face normal if it separates better than the first one's
  if (face_gap > best.gap) {
    const ContactGeometry from_face =
        RefineFrom(a, pose_a, fcl_a, b, pose_b, fcl_b, face_normal, separation);
    if (from_face.gap > best.gap) best = from_face;
  }
  return best;
}

// Box–box separated by less than the margin, or exactly touching, with the contact c: FCL's
// clipping on B moved into A by s = gap + ε along n (penetrating by ε), moved back. A box resting
// on a box then has its four corners (or its clipped face) as contacts before it touches, as
// after: gap_i = −depth_i + s (n_i·n), point_b_i = p_i − (depth_i/2) n_i + s n. Contacts whose
// normal is not n (FCL chose another axis) are not used; without any, c alone.
int BoxBoxManifold(const fcl::CollisionGeometryd* a, const Eigen::Isometry3d& pose_a,
                   const fcl::CollisionGeometryd* b, const Eigen::Isometry3d& pose_b,
                   const ContactGeometry& c, double separation, double margin,
                   ContactGeometry* out) {
  const double s = c.gap + separation;
  const fcl::CollisionRequestd request(/*num_max_contacts=*/kMaxPairContacts,
                                       /*enable_contact=*/true);
  fcl::CollisionResultd result;
  fcl::collide(a, pose_a, b, Eigen::Translation3d(-s * c.normal) * pose_b, request, result);
  const int found = std::min<int>(static_cast<int>(result.numContacts()), kMaxPairContacts);
  int count = 0;
  for (int i = 0; i < found; ++i) {
    const fcl::Contactd& contact = result.getContact(i);
    // only the clipping along c's normal (FCL may pick another axis for a corner or an edge)
    if (!((contact.normal - c.normal).norm() <= kManifoldNormalTolerance)) continue;
    ContactGeometry& m = out[count];
    m = ContactGeometry{};
    m.normal = contact.normal.normalized();
    m.gap = -contact.penetration_depth + s * m.normal.dot(c.normal);
    m.point_b = contact.pos - 0.5 * contact.penetration_depth * m.normal + s * c.normal;
    m.point_a = m.point_b - m.gap * m.normal;
    m.feature = i;
    if (m.gap <= margin) ++count;
  }
  if (count > 0) return count;
  out[0] = c;
  return 1;
}

// cos of the largest angle between the contact normal and two faces' normals for which they
// touch face to face (HullManifold): 1e-3 rad.
constexpr double kFaceToFaceCos = 1.0 - 5e-7;

// A box as a hull (its corners and faces), for HullManifold.
std::shared_ptr<const ConvexHull> BoxAsHull(const Eigen::Vector3d& h) {
  std::vector<Eigen::Vector3d> v;
  for (int i = 0; i < 8; ++i) {
    v.emplace_back((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  }
  return MakeConvexHull(std::move(v), {4, 0, 2, 3, 1, 4, 4, 5, 7, 6, 4, 0, 4, 6, 2,
                                       4, 1, 3, 7, 5, 4, 0, 1, 5, 4, 4, 2, 6, 7, 3});
}

// The face of `hull` (at `pose`) whose outward normal is closest to the world direction d, and
// the cosine between them.
std::pair<int, double> FacingFace(const ConvexHull& hull, const Eigen::Isometry3d& pose,
                                  const Eigen::Vector3d& d) {
  const Eigen::Vector3d local = pose.linear().transpose() * d;
  int best = 0;
  for (int f = 1; f < hull.face_count; ++f) {
    if (hull.face_normal[f].dot(local) > hull.face_normal[best].dot(local)) best = f;
  }
  return {best, hull.face_normal[best].dot(local)};
}

// A hull (or a box) against a hull (or a box), with the contact c: when a face of each lies along
// c's normal n (within 1e-3 rad), they touch face to face and one point does not hold a body
// resting on the other (it rocks about it). The face of B is clipped against the face of A
// (Sutherland–Hodgman, in A's face plane: B's polygon against each edge of A's), and each corner
// of the overlap on B's face is a contact (gap = n·(x − p_A), its height above A's face along n;
// point_b = x, point_a = x − gap n), those with gap ≤ margin, at most kMaxPairContacts (evenly
// spaced around the overlap). Otherwise, or without any, c alone.
int HullManifold(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
                 const Eigen::Isometry3d& pose_b, const ContactGeometry& c, double margin,
                 ContactGeometry* out) {
  const std::shared_ptr<const ConvexHull> hull_a =
      a.type == ShapeType::kBox ? BoxAsHull(a.half_extents) : a.hull;
  const std::shared_ptr<const ConvexHull> hull_b =
      b.type == ShapeType::kBox ? BoxAsHull(b.half_extents) : b.hull;
  const auto [face_a, cos_a] = FacingFace(*hull_a, pose_a, c.normal);
  const auto [face_b, cos_b] = FacingFace(*hull_b, pose_b, -c.normal);
  out[0] = c;
  if (!(cos_a >= kFaceToFaceCos && cos_b >= kFaceToFaceCos)) return 1;
  const auto corners = [](const ConvexHull& hull, const Eigen::Isometry3d& pose, int face) {
    std::vector<Eigen::Vector3d> x;
    const int start = hull.face_start[face];
    for (int k = 1; k <= hull.faces[start]; ++k) {
      x.push_back(pose * hull.vertices[hull.faces[start + k]]);
    }
    return x;
  };
  // A's face, counter-clockwise about its outward normal n_A; B's, reversed to the same sense
  const std::vector<Eigen::Vector3d> reference = corners(*hull_a, pose_a, face_a);
  std::vector<Eigen::Vector3d> polygon = corners(*hull_b, pose_b, face_b);
  std::reverse(polygon.begin(), polygon.end());
  const Eigen::Vector3d n_a = pose_a.linear() * hull_a->face_normal[face_a];
  // clip by each edge (p, q) of A's face: keep the side n_A × (q − p) points to
  for (std::size_t e = 0; e < reference.size() && !polygon.empty(); ++e) {
    const Eigen::Vector3d& p = reference[e];
    const Eigen::Vector3d& q = reference[(e + 1) % reference.size()];
    const Eigen::Vector3d inward = n_a.cross(q - p);
    std::vector<Eigen::Vector3d> clipped;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const Eigen::Vector3d& x = polygon[i];
      const Eigen::Vector3d& y = polygon[(i + 1) % polygon.size()];
      const double sx = inward.dot(x - p);
      const double sy = inward.dot(y - p);
      if (sx >= 0.0) clipped.push_back(x);
      if ((sx >= 0.0) != (sy >= 0.0)) clipped.push_back(x + (sx / (sx - sy)) * (y - x));
    }
    polygon = std::move(clipped);
  }
  const Eigen::Vector3d& origin = reference.front();
  const int found = static_cast<int>(polygon.size());
  const int keep = std::min(found, kMaxPairContacts);
  int count = 0;
  for (int j = 0; j < keep; ++j) {
    const Eigen::Vector3d& x = polygon[static_cast<std::size_t>(j * found / keep)];
    ContactGeometry& m = out[count];
    m = ContactGeometry{};
    m.normal = c.normal;
    m.gap = c.normal.dot(x - origin);
    m.point_b = x;
    m.point_a = x - m.gap * m.normal;
    m.feature = j;
    if (m.gap <= margin) ++count;
  }
  if (count > 0) return count;
  out[0] = c;
  return 1;
}

}  // namespace

int CollideFcl(const Shape& a, const Eigen::Isometry3d& pose_a, const Shape& b,
               const Eigen::Isometry3d& pose_b, double margin, ContactGeometry* out) {
  FclGeometry geometry_a;
  FclGeometry geometry_b;
  MakeGeometry(a, &geometry_a);
  MakeGeometry(b, &geometry_b);
  const fcl::CollisionGeometryd* fcl_a = Pointer(geometry_a);
  const fcl::CollisionGeometryd* fcl_b = Pointer(geometry_b);
  if (fcl_a == nullptr || fcl_b == nullptr) return 0;
  const Eigen::Vector3d centre_line =
      NormalizedOr(pose_b.translation() - pose_a.translation(), DegenerateNormal());
  const double separation = RefinementSeparation(a, b);

  // penetrating: FCL's contacts
  const fcl::CollisionRequestd request(/*num_max_contacts=*/kMaxPairContacts,
                                       /*enable_contact=*/true);
  fcl::CollisionResultd result;
  fcl::collide(fcl_a, pose_a, fcl_b, pose_b, request, result);
  const int count = std::min<int>(static_cast<int>(result.numContacts()), kMaxPairContacts);
  if (count > 0) {
    bool own_formula = FclHasOwnFormula(a.type, b.type);
    for (int i = 0; i < count; ++i) {
      own_formula = own_formula && result.getContact(i).normal.norm() > kFclMinNormalNorm;
    }
    if (own_formula) {
      // gap = −depth, points p ± (depth/2) n
      for (int i = 0; i < count; ++i) {
        const fcl::Contactd& contact = result.getContact(i);
        const double depth = contact.penetration_depth;
        ContactGeometry& c = out[i];
        c = ContactGeometry{};
        c.normal = contact.normal.normalized();
        c.gap = -depth;
        c.point_a = contact.pos + 0.5 * depth * c.normal;
        c.point_b = contact.pos - 0.5 * depth * c.normal;
        c.feature = i;
      }
      return count;
    }
  } else if (margin < 0.0) {
    return 0;
  }

  ContactGeometry c;
  if (count > 0) {
    // MPR (or a zero normal): refined from MPR's normal, or the line of centres
    const Eigen::Vector3d& mpr = result.getContact(0).normal;
    c = RefinedContact(
        a, pose_a, fcl_a, b, pose_b, fcl_b,
        mpr.norm() > kFclMinNormalNorm ? Eigen::Vector3d(mpr.normalized()) : centre_line);
  } else {
    // separated: GJK's nearest points; refined where too close to give a direction
    const Distance nearest = FclDistance(fcl_a, pose_a, fcl_b, pose_b);
    if (nearest.distance > margin) return 0;
    if (nearest.distance > separation) {
      c.point_a = nearest.point_a;
      c.point_b = nearest.point_b;
      c.gap = (c.point_b - c.point_a).norm();
      c.normal = (c.point_b - c.point_a) / c.gap;
    } else {
      c = RefinedContact(a, pose_a, fcl_a, b, pose_b, fcl_b,
                         NormalizedOr(nearest.point_b - nearest.point_a, centre_line));
    }
  }
  if (!std::isfinite(c.gap) || !(c.gap <= margin)) return 0;  // (non-finite: GJK failed)
  if (a.type == ShapeType::kBox && b.type == ShapeType::kBox) {
    return BoxBoxManifold(fcl_a, pose_a, fcl_b, pose_b, c, separation, margin, out);
  }
  const auto polyhedral = [](const Shape& s) {
    return s.type == ShapeType::kBox || (s.type == ShapeType::kConvexHull && s.hull);
  };
  if (polyhedral(a) && polyhedral(b)) return HullManifold(a, pose_a, b, pose_b, c, margin, out);
  out[0] = c;
  return 1;
}

void RegisterFclPairs(CollisionTable* table) {
  constexpr ShapeType kPairs[][2] = {{ShapeType::kSphere, ShapeType::kEllipsoid},
                                     {ShapeType::kSphere, ShapeType::kCylinder},
                                     {ShapeType::kCapsule, ShapeType::kEllipsoid},
                                     {ShapeType::kCapsule, ShapeType::kCylinder},
                                     {ShapeType::kCapsule, ShapeType::kBox},
                                     {ShapeType::kEllipsoid, ShapeType::kEllipsoid},
                                     {ShapeType::kEllipsoid, ShapeType::kCylinder},
                                     {ShapeType::kEllipsoid, ShapeType::kBox},
                                     {ShapeType::kCylinder, ShapeType::kCylinder},
                                     {ShapeType::kCylinder, ShapeType::kBox},
                                     {ShapeType::kBox, ShapeType::kBox},
                                     {ShapeType::kSphere, ShapeType::kConvexHull},
                                     {ShapeType::kCapsule, ShapeType::kConvexHull},
                                     {ShapeType::kEllipsoid, ShapeType::kConvexHull},
                                     {ShapeType::kCylinder, ShapeType::kConvexHull},
                                     {ShapeType::kBox, ShapeType::kConvexHull},
                                     {ShapeType::kConvexHull, ShapeType::kConvexHull},
                                     {ShapeType::kSphere, ShapeType::kRevolution},
                                     {ShapeType::kCapsule, ShapeType::kRevolution},
                                     {ShapeType::kEllipsoid, ShapeType::kRevolution},
                                     {ShapeType::kCylinder, ShapeType::kRevolution},
                                     {ShapeType::kBox, ShapeType::kRevolution},
                                     {ShapeType::kConvexHull, ShapeType::kRevolution},
                                     {ShapeType::kRevolution, ShapeType::kRevolution}};
  for (const auto& pair : kPairs) table->Register(pair[0], pair[1], &CollideFcl);
}

}  // namespace nonsmooth_sim
