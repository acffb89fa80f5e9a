// The Tippe-Top scene of Leine & Glocker (2003), used by Möller, Leine, Glocker (ESMC 2009),
// with the parameters of ../shared/reference/tippe-top.md.
#ifndef NONSMOOTH_SIM_CORE_TIPPE_TOP_H_
#define NONSMOOTH_SIM_CORE_TIPPE_TOP_H_

#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/core/scene.h"

namespace nonsmooth_sim {

struct TippeTopParameters {
  double mass = 6e-3;              ///< m [kg]
  double inertia_equatorial = 8e-7;  ///< A = B [kg m²]
  double inertia_axial = 7e-7;     ///< C [kg m²]
  double big_radius = 0.015;       ///< R1 [m]
  double peg_radius = 0.005;       ///< R2 [m]
  double big_offset = 0.003;       ///< a1: S → M1 along +e3 [m]
  double peg_offset = 0.016;       ///< a2: S → M2 along +e3 [m]
  double gravity = 9.81;           ///< g [m/s²]
  double mu = 0.3;                 ///< both contacts
  double contact_radius = 5e-4;    ///< R [m]; R̄ = 3πR/16 (50)
  double restitution = 0.0;        ///< ε
  double rolling_resistance = 0.0; ///< μ_r [m], both contacts (0: no rolling components)
  FrictionSet friction_set = FrictionSet::kSphere;
};

struct TippeTopInitialConditions {
  double inclination = 0.1;  ///< θ0 [rad], tilt of e3 about the world x axis
  double spin = 180.0;       ///< ω about the tilted e3 [rad/s]
};

/// R̄ = 3πR/16, eq. (50).
constexpr double AverageFrictionRadius(double contact_radius) {
  return 3.0 * kPi * contact_radius / 16.0;
}

/// Colliders of MakeTippeTopScene(), in this order.
inline constexpr int kBigSphere = 0;
inline constexpr int kPegSphere = 1;
inline constexpr int kTippeTopGround = 2;

/// Body "tippe_top", sphere colliders "big_sphere" (kBigSphere) and "peg_sphere" (kPegSphere) and
/// the ground plane "ground" (kTippeTopGround) with GroundLaw(), so that the top's law decides;
/// the big sphere just touches the floor: z_S0 = R1 - a1 cos θ0.
Scene MakeTippeTopScene(const TippeTopParameters& parameters = {},
                        const TippeTopInitialConditions& initial = {});

/// The state for the given initial conditions (centre of mass at rest, big sphere touching).
BodyState TippeTopInitialState(const TippeTopParameters& parameters,
                               const TippeTopInitialConditions& initial);

/// Jellett's integral of a body touching the ground z = 0 with sphere collider `sphere`:
/// J = L_S · (r_S - r_P) with P the lowest point of the sphere [kg m³/s] (Tippe-Top:
/// J = L_S · (R1 ẑ - a1 e3)). Throws std::invalid_argument unless `sphere` is a sphere on a body.
double JellettIntegral(const Scene& scene, const std::vector<BodyState>& state, int sphere);

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_TIPPE_TOP_H_
