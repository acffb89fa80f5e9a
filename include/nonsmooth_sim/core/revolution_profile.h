// A smooth convex body of revolution about the z axis of its shape frame, given by its profile
// (the meridian section's boundary, ρ ≥ 0) as circular arcs joined tangentially, with straight
// segments (a cone or a cylinder's side) between them and, at a pole, a flat disc or not.
//
// Built from points of the meridian (MakeRevolutionProfile): their convex hull in the (ρ, z)
// half-plane, mirrored about the axis, is a convex polygon; each of its corners is rounded by the
// arc tangent to its two edges at the distance t = min(|e_in|/2, |e_out|/2, τ/tan(α/4)) from the
// corner (α the corner's turn, τ the rounding tolerance): the arc then passes within t tan(α/4) ≤ τ
// of the corner. For points sampled on a smooth profile the first two bounds act and the arcs
// through the edge midpoints are concentric with the true circles of curvature (radius short by
// R(1 − cos(α/2)) ≈ Rα²/8); a sharp corner (a cylinder's rim) stays sharp within τ. The result is
// convex and G1 (its normal is continuous), and its support point is in closed form:
//
//   u(θ) = (sin θ, cos θ) in (ρ, z), θ ∈ [0, π] the angle of a direction from +z;
//   p(θ) = c_k + r_k u(θ) for the arc k whose normal range [θ_{k-1}, θ_k] holds θ.
//
// Points closer than kMergeFraction τ are merged first (mesh vertices of one ring in float).
#ifndef NONSMOOTH_SIM_CORE_REVOLUTION_PROFILE_H_
#define NONSMOOTH_SIM_CORE_REVOLUTION_PROFILE_H_

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace nonsmooth_sim {

struct RevolutionArc {
  double theta_end = 0.0;  ///< its normals run from the previous arc's theta_end (0 first) [rad]
  double cos_end = 1.0;    ///< cos(theta_end): the lookup compares cosines (no trigonometry)
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  ///< (ρ, z) [m]
  double radius = 0.0;                               ///< [m], > 0
  /// length of the straight stretch from its end to the next arc's start [m] (0: they meet,
  /// within kMergeFraction τ)
  double stretch = 0.0;
};

struct RevolutionProfile {
  /// From the top (θ = 0, normal +z) to the bottom (θ = π); the last ends at π.
  std::vector<RevolutionArc> arcs;
  /// Radii of the flat discs at the top and the bottom (0: a rounded pole) [m].
  double top_disc_radius = 0.0;
  double bottom_disc_radius = 0.0;
  double top_z = 0.0;     ///< the top's height (max z) [m]
  double bottom_z = 0.0;  ///< the bottom's height (min z) [m]
  double bounding_radius = 0.0;  ///< max |x| over the body [m]
  double rounding = 0.0;         ///< τ it was built with [m]
};

inline constexpr double kMergeFraction = 0.1;

/// The profile through the meridian points (ρ_i ≥ 0 — the sign is dropped —, z_i) rounded within
/// `rounding` (see the top). Throws std::invalid_argument for a non-finite point or rounding ≤ 0,
/// and for points that span no area (fewer than 3 distinct, or all on a line).
std::shared_ptr<const RevolutionProfile> MakeRevolutionProfile(
    const std::vector<Eigen::Vector2d>& meridian, double rounding);

/// The meridian point (ρ ≥ 0, z) whose outward normal is u = (sin θ, cos θ), θ ∈ [0, π] (unit),
/// and the index of its arc: the first whose cos_end ≤ cos θ.
Eigen::Vector2d ProfilePoint(const RevolutionProfile& profile, const Eigen::Vector2d& u,
                             int* arc = nullptr);
/// The same for the normal angle θ.
Eigen::Vector2d ProfilePoint(const RevolutionProfile& profile, double theta, int* arc = nullptr);

/// The start point (normal angle of the previous arc's end) of arc k, (ρ, z).
Eigen::Vector2d ArcStart(const RevolutionProfile& profile, int k);
/// The end point of arc k, (ρ, z).
Eigen::Vector2d ArcEnd(const RevolutionProfile& profile, int k);

/// The direction d (shape frame, any length > 0) split as the profile sees it: u = (sin θ, cos θ)
/// = (|d_xy|, d_z)/|d| with θ its angle from +z, `radial` its unit horizontal part (x̂ when
/// d ∥ z).
struct MeridianDirection {
  Eigen::Vector2d u = Eigen::Vector2d(0.0, 1.0);
  Eigen::Vector3d radial = Eigen::Vector3d::UnitX();
};
MeridianDirection SplitDirection(const Eigen::Vector3d& d);

/// (ρ, z) at the azimuth `radial` (unit, horizontal) → the shape frame.
inline Eigen::Vector3d AtAzimuth(const Eigen::Vector2d& rho_z, const Eigen::Vector3d& radial) {
  return Eigen::Vector3d(rho_z.x() * radial.x(), rho_z.x() * radial.y(), rho_z.y());
}

/// Support point of the body in the direction d of its frame (the point maximising d·x).
Eigen::Vector3d RevolutionSupport(const RevolutionProfile& profile, const Eigen::Vector3d& d);

/// Volume of the body (Pappus: 2π ∫ ρ dA over the half-section) [m³].
double RevolutionVolume(const RevolutionProfile& profile);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_REVOLUTION_PROFILE_H_
