// Plane–cylinder: per face, its lowest rim point, or one patch when the face lies flat.
#include "nonsmooth_sim/core/collision/plane_cylinder.h"

#include "nonsmooth_sim/core/collision/plane_contact.h"

namespace nonsmooth_sim {

int CollidePlaneCylinder(const Shape& /*plane*/, const Eigen::Isometry3d& pose_plane,
                         const Shape& cylinder, const Eigen::Isometry3d& pose_cylinder,
                         double margin, ContactGeometry* out) {
  const double r = cylinder.radius;
  const Eigen::Vector3d n = PlaneNormal(pose_plane);
  const Eigen::Vector3d u = pose_cylinder.linear().col(2);
  const double u_n = u.dot(n);
  // n_⊥ = n − (u·n) u, |n_⊥| = sin(tilt) (computed from the vector: accurate at small tilts)
  const Eigen::Vector3d n_perp = n - u_n * u;
  const double sin_tilt = n_perp.norm();
  const bool flat = 2.0 * r * sin_tilt <= kFlatFaceTolerance;
  int count = 0;
  for (int k = 0; k < 2; ++k) {
    const double s = k == 0 ? -1.0 : 1.0;
    // face centre f_k = c + s_k l u
    const Eigen::Vector3d face_centre = pose_cylinder.translation() + s * cylinder.half_length * u;
    ContactGeometry contact;
    if (!flat) {
      // rim point f_k − r n_⊥/|n_⊥|
      contact = PlaneContact(pose_plane, face_centre - (r / sin_tilt) * n_perp, /*feature=*/k);
    } else if (s * u_n < 0.0) {
      // the flat face facing the plane: one patch at its centre
      contact = PlaneContact(pose_plane, face_centre, /*feature=*/2 + k, DiscPatchRadius(r));
    } else {
      // the flat face facing away lies 2l above the other one
      continue;
    }
    if (contact.gap <= margin) out[count++] = contact;
  }
  return count;
}

}  // namespace nonsmooth_sim
