// Plane–cylinder: per face, its lowest rim point, or four face points when the face lies flat.
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
    if (!flat) {
      // rim point f_k − r n_⊥/|n_⊥|
      const ContactGeometry contact =
          PlaneContact(pose_plane, face_centre - (r / sin_tilt) * n_perp, /*feature=*/k);
      if (contact.gap <= margin) out[count++] = contact;
      continue;
    }
    // the flat face facing away lies 2l above the other one
    if (!(s * u_n < 0.0)) continue;
    // the flat face facing the plane: four points f_k ± (2r/3) e_x, f_k ± (2r/3) e_y
    const double rho = DiscPatchRadius(r);
    ContactGeometry face[4];
    for (int j = 0; j < 4; ++j) {
      const Eigen::Vector3d axis = pose_cylinder.linear().col(j % 2);
      const Eigen::Vector3d point = face_centre + (j < 2 ? rho : -rho) * axis;
      face[j] = PlaneContact(pose_plane, point, /*feature=*/2 + 4 * k + j, /*face_point=*/true);
    }
    ShareFaceGap(face, 4);
    if (face[0].gap > margin) continue;
    for (const ContactGeometry& point : face) out[count++] = point;
  }
  return count;
}

}  // namespace nonsmooth_sim
