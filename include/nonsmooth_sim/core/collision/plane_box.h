// Plane–box, closed form. The box has half-extents h = (h_0, h_1, h_2) along the columns e_j of
// R_B, centre c, corners x_i = c + Σ_j σ_ij h_j e_j with σ_ij = +1 if bit j of i is set, else −1
// (i = 0..7), faces f = 2j + side (side 0: outward −e_j, side 1: +e_j).
//
// The face facing the plane is the one whose outward normal is most opposite to n: axis
// j* = argmax |m_j| with m = R_Bᵀ n, side = (m_j* < 0). Its height varies by
// 2(|m_p| h_p + |m_q| h_q) across it (p, q the other axes); when that is ≤ kFlatFaceTolerance it
// lies flat and gives four face points (ContactGeometry::face_point) instead of its corners:
//
//   corner      point_b = x_i,                                        feature i (0..7);
//   face point  point_b = c + (side ? +1 : −1) h_j* e_j* ± f h_p e_p ± f h_q e_q,
//               f = R̄ / |(h_p, h_q)|, R̄ = RectanglePatchRadius(h_p, h_q),   feature 8 + 4 face + j,
//
// on the face's diagonals at the distance R̄ of a uniform pressure from its centre: spinning,
// their friction torque is μNR̄ (the uniform pressure's), sliding μN, and they resist tipping
// (see plane_cylinder.h for why not one patch at the centre); they share the face's lowest
// height as their gap (ShareFaceGap).
//
// For every point gap = n·(point_b − o_P), point_a = point_b − gap n (plane_contact.h); the
// points with gap ≤ margin are returned, at most 8 (a flat face: its 4 points and at most the 4
// opposite corners).
#ifndef NONSMOOTH_SIM_CORE_COLLISION_PLANE_BOX_H_
#define NONSMOOTH_SIM_CORE_COLLISION_PLANE_BOX_H_

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/collision/collision.h"

namespace nonsmooth_sim {

/// Drilling radius of a uniform pressure over the rectangle [−a, a] × [−b, b] (a, b > 0): its
/// mean distance from the centre. Over the quarter [0, a] × [0, b], split by its diagonal into two
/// triangles and integrated in polar coordinates (ρ ≤ a/cos φ for φ ≤ φ₀ = atan(b/a)):
///
///   ∫₀^φ₀ ∫₀^{a/cos φ} ρ² dρ dφ = (a³/3) ∫₀^φ₀ sec³φ dφ = (1/6)[a b d + a³ ln((b + d)/a)],
///
/// d = √(a² + b²); with the other triangle (a ↔ b) and divided by the area ab:
///
///   R̄ = [2ab d + a³ ln((b + d)/a) + b³ ln((a + d)/b)] / (6ab)     [m]
///
/// (a square of side s: s(√2 + ln(1 + √2))/6 ≈ 0.3826 s).
double RectanglePatchRadius(double a, double b);

/// CollideFunction of (plane, box).
int CollidePlaneBox(const Shape& plane, const Eigen::Isometry3d& pose_plane, const Shape& box,
                    const Eigen::Isometry3d& pose_box, double margin, ContactGeometry* out);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_COLLISION_PLANE_BOX_H_
