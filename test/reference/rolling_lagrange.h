// A second formulation of rolling without slipping, written differently from rolling_reference.h
// so that the two check each other: the free rigid body in WORLD axes with the contact force as a
// Lagrange multiplier, solved at every evaluation from the acceleration-level constraint.
//
// State: r_S, v_S, q, ω_w (13 numbers, all integrated; nothing is eliminated, z_S and v_S are
// free and stay on (R1), (R2) of rolling_reference.h only as far as the integration is exact).
// With r = A r_SP(d) (world), Θ_w = A Θ Aᵀ:
//   (L1) m v̇_S = F − m g ẑ,    Θ_w ω̇ + ω × Θ_w ω = r × F              (Newton–Euler)
//   (L2) d/dt (v_S + ω × r) = v̇_S + ω̇ × r + ω × ṙ = 0,   ṙ = ω × r + A (∂r/∂d) (d × ω_B)
//   (L3) (L1) in (L2): W F = g ẑ − ω × ṙ − [r]× Θ_w⁻¹ (ω × Θ_w ω),
//        W = I/m + [r]×ᵀ Θ_w⁻¹ [r]×   (the Delassus matrix of the contact, positive definite)
//   (L4) q̇ = ½ (0, ω_w) ⊗ q
// The quaternion is integrated as is and normalised where it is used.
#ifndef NONSMOOTH_SIM_TEST_REFERENCE_ROLLING_LAGRANGE_H_
#define NONSMOOTH_SIM_TEST_REFERENCE_ROLLING_LAGRANGE_H_

#include <vector>

#include "rolling_reference.h"

namespace nonsmooth_sim::reference {

/// The states at `times` (ascending, from start.t on) of (L1)–(L4) from `start` (all of r_S,
/// v_S, q, ω are read), by Runge–Kutta–Fehlberg 7(8) with absolute and relative `tolerance`.
/// The returned velocity and height are the integrated ones (not re-derived from the constraint).
std::vector<RollingState> IntegrateLagrange(const RollingBody& body, const RollingState& start,
                                            const std::vector<double>& times,
                                            double tolerance = 1e-12);

}  // namespace nonsmooth_sim::reference

#endif  // NONSMOOTH_SIM_TEST_REFERENCE_ROLLING_LAGRANGE_H_
