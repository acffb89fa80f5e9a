// Plane–box: the corners, or four face points for a face lying flat.
#include "nonsmooth_sim/core/collision/plane_box.h"

#include <cmath>

#include "nonsmooth_sim/core/collision/plane_contact.h"

namespace nonsmooth_sim {

double RectanglePatchRadius(double a, double b) {
  const double d = std::hypot(a, b);
  // ln((b + d)/a) = ln(1 + (b + d − a)/a) with d − a = b²/(d + a): no cancellation for b ≪ a
  const double log_a = std::log1p((b + b * b / (d + a)) / a);
  const double log_b = std::log1p((a + a * a / (d + b)) / b);
  // [2ab d + a³ ln((b + d)/a) + b³ ln((a + d)/b)] / (6ab)
  return (2.0 * a * b * d + a * a * a * log_a + b * b * b * log_b) / (6.0 * a * b);
}

int CollidePlaneBox(const Shape& /*plane*/, const Eigen::Isometry3d& pose_plane, const Shape& box,
                    const Eigen::Isometry3d& pose_box, double margin, ContactGeometry* out) {
  const Eigen::Matrix3d& rotation = pose_box.linear();
  const Eigen::Vector3d& h = box.half_extents;
  // m = R_Bᵀ n: the plane's normal in the box frame
  const Eigen::Vector3d m = rotation.transpose() * PlaneNormal(pose_plane);
  // the face facing the plane: j* = argmax |m_j| (first on ties), side = (m_j* < 0)
  int axis = 0;
  for (int j = 1; j < 3; ++j) {
    if (std::abs(m[j]) > std::abs(m[axis])) axis = j;
  }
  const int side = m[axis] < 0.0 ? 1 : 0;
  const int p = (axis + 1) % 3;
  const int q = (axis + 2) % 3;
  // its height varies by 2(|m_p| h_p + |m_q| h_q) across it
  const bool flat = 2.0 * (std::abs(m[p]) * h[p] + std::abs(m[q]) * h[q]) <= kFlatFaceTolerance;

  int count = 0;
  if (flat) {
    // four points on the face c + (±h_j*) e_j* along its diagonals, at the distance R̄ of the
    // rectangle from its centre: (±f h_p, ±f h_q) with f = R̄ / |(h_p, h_q)|
    const double f = RectanglePatchRadius(h[p], h[q]) / std::hypot(h[p], h[q]);
    ContactGeometry face[4];
    for (int j = 0; j < 4; ++j) {
      Eigen::Vector3d local = Eigen::Vector3d::Zero();
      local[axis] = side == 1 ? h[axis] : -h[axis];
      local[p] = (j & 1 ? f : -f) * h[p];
      local[q] = (j & 2 ? f : -f) * h[q];
      face[j] = PlaneContact(pose_plane, pose_box * local,
                             /*feature=*/8 + 4 * (2 * axis + side) + j, /*face_point=*/true);
    }
    ShareFaceGap(face, 4);
    if (face[0].gap <= margin) {
      for (const ContactGeometry& point : face) out[count++] = point;
    }
  }
  for (int i = 0; i < 8; ++i) {
    // corner i lies on face (j*, bit j* of i): replaced by the face points when that face is flat
    const int corner_side = (i >> axis) & 1;
    if (flat && corner_side == side) continue;
    // x_i = c + R_B (σ_i ∘ h)
    const Eigen::Vector3d local((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                                (i & 4) ? h.z() : -h.z());
    const ContactGeometry corner = PlaneContact(pose_plane, pose_box * local, /*feature=*/i);
    if (corner.gap <= margin) out[count++] = corner;
  }
  return count;
}

}  // namespace nonsmooth_sim
