// Plane–body of revolution: the profile's support point, the far ends of straight stretches next
// to it, or four face points for a flat disc lying flat. See plane_revolution.h.
#include "nonsmooth_sim/core/collision/plane_revolution.h"

#include "nonsmooth_sim/core/collision/plane_contact.h"
#include "nonsmooth_sim/core/collision/plane_cylinder.h"

namespace nonsmooth_sim {

int CollidePlaneRevolution(const Shape& /*plane*/, const Eigen::Isometry3d& pose_plane,
                           const Shape& body, const Eigen::Isometry3d& pose_body, double margin,
                           ContactGeometry* out) {
  if (!body.revolution) return 0;
  const RevolutionProfile& profile = *body.revolution;
  const int arcs = static_cast<int>(profile.arcs.size());
  const MeridianDirection split =
      SplitDirection(-(pose_body.linear().transpose() * PlaneNormal(pose_plane)));
  // a flat disc at the pole facing the plane, lying flat: four face points
  const bool top = split.u.y() > 0.0;
  const double disc = top ? profile.top_disc_radius : profile.bottom_disc_radius;
  if (disc > 0.0 && 2.0 * disc * split.u.x() <= kFlatFaceTolerance) {
    const double rho = DiscPatchRadius(disc);
    const Eigen::Vector3d centre(0.0, 0.0, top ? profile.top_z : profile.bottom_z);
    ContactGeometry face[4];
    for (int j = 0; j < 4; ++j) {
      const Eigen::Vector3d offset = (j < 2 ? rho : -rho) * Eigen::Vector3d::Unit(j % 2);
      face[j] = PlaneContact(pose_plane, pose_body * (centre + offset),
                             /*feature=*/2 * arcs + 3 + j, /*face_point=*/true);
    }
    ShareFaceGap(face, 4);
    if (face[0].gap > margin) return 0;
    for (int j = 0; j < 4; ++j) out[j] = face[j];
    return 4;
  }
  int count = 0;
  const auto add = [&](const Eigen::Vector2d& rho_z, const Eigen::Vector3d& radial, int feature) {
    const ContactGeometry contact =
        PlaneContact(pose_plane, pose_body * AtAzimuth(rho_z, radial), feature);
    if (contact.gap <= margin) out[count++] = contact;
  };
  int k = 0;
  add(ProfilePoint(profile, split.u, &k), split.radial, /*feature=*/0);
  // the stretch before arc k: to the previous arc, or across a flat disc at the top
  if (k > 0 && profile.arcs[k - 1].stretch > 0.0) {
    add(ArcEnd(profile, k - 1), split.radial, 1 + 2 * k);
  } else if (k == 0 && profile.top_disc_radius > 0.0) {
    add(ArcStart(profile, 0), -split.radial, 1);
  }
  // the stretch after arc k
  if (k + 1 < arcs && profile.arcs[k].stretch > 0.0) {
    add(ArcStart(profile, k + 1), split.radial, 2 + 2 * k);
  } else if (k + 1 == arcs && profile.bottom_disc_radius > 0.0) {
    add(ArcEnd(profile, k), -split.radial, 2 + 2 * k);
  }
  return count;
}

}  // namespace nonsmooth_sim
