// An independent reference for a convex body ROLLING WITHOUT SLIPPING on the plane z = 0 under
// gravity g = 9.81 m/s² along −z: the classic non-holonomic equations with the contact force
// eliminated, integrated by Boost.Odeint's Runge–Kutta–Fehlberg 7(8) at tolerances ~1e-12. Written
// without any code of the package (Eigen and Boost.Odeint only), so that the simulator's
// integrators can be held to it (Euler's disk in steady rolling, the rattleback's spin reversal).
//
// Notation: A the rotation body → world (unit quaternion q), S the centre of mass (origin of the
// body frame), ω = ω_B the angular velocity in BODY axes, Θ the inertia about S in body axes,
// d = Aᵀ(0, 0, −1) the world's "down" in body axes, r = r_SP(d) the contact point P (the lowest
// point of the convex surface: its support point in the direction d) relative to S, body axes,
// and ∂r/∂d its Jacobian. Every vector below is in body axes unless marked _w.
//
//   (R1) contact on the plane:  z_P = z_S + ẑ·A r = 0   ⇒   z_S = d·r
//   (R2) rolling:               v_P = 0   ⇒   v_S = −ω × r        (v_S,w = A v_S)
//   (R3) kinematics:            q̇ = ½ q ⊗ (0, ω),   ḋ = −ω × d = d × ω
//   (R4) P moves over the surface at the body-fixed rate  ρ̇ = (∂r/∂d) ḋ
//   (R5) Newton with (R2):      F = m (a_S − g d),   a_S = −ω̇ × r − ω × ρ̇ − ω × (ω × r)
//   (R6) Euler about S, Θ ω̇ + ω × Θ ω = r × F, with (R5) inserted: the equation of the angular
//        momentum about the contact point,
//          Θ_P ω̇ = −ω × Θ ω − m r × (ω × (ω × r + ρ̇)) − m g r × d,   Θ_P = Θ − m [r]×[r]×
//        (Θ_P: the inertia about P; the ρ̇ term is the motion of P over the surface, without it
//        the energy is not conserved for a curved surface).
//   (R7) energy (conserved: the contact force does no work on a rolling body)
//          E = ½ m |ω × r|² + ½ ωᵀ Θ ω + m g d·r
//
// State integrated: (x_S, y_S, q, ω_B), 9 numbers; z_S follows from (R1), v_S from (R2). The
// quaternion is integrated as is (the exact flow of (R3) keeps |q|; the right-hand side and every
// state handed out use q/|q|, so a drift of |q| at the step tolerance changes nothing).
//
// Accuracy, measured (rolling_reference_test.cpp): energy kept to 2e-11 of E over 10 s; the
// rattleback's first spin reversal from its rolling shipped start moves by 4e-9 s from tolerance
// 1e-10 to 1e-12 and not at all (to 1e-10 s) from 1e-12 to 1e-14.
//
// A second, differently written formulation for cross-checks is in rolling_lagrange.h.
#ifndef NONSMOOTH_SIM_TEST_REFERENCE_ROLLING_REFERENCE_H_
#define NONSMOOTH_SIM_TEST_REFERENCE_ROLLING_REFERENCE_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace nonsmooth_sim::reference {

inline constexpr double kGravity = 9.81;  ///< g [m/s²], along −z

/// The contact point of a convex surface for a downward direction d, body axes.
struct SupportPoint {
  Eigen::Vector3d r;      ///< r_SP, S → the lowest point P [m]
  Eigen::Matrix3d dr_dd;  ///< ∂r/∂d at that d (as a function of any d, not only unit ones) [m]
};

/// A rigid body that rolls on one smooth convex surface.
struct RollingBody {
  std::string name;
  double mass = 0.0;                                      ///< m [kg]
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();      ///< Θ about S, body axes [kg m²]
  std::function<SupportPoint(const Eigen::Vector3d&)> contact;  ///< d (unit, body) → P, ∂P/∂d
};

/// Euler's disk of urdf/euler_disk.urdf: a cylinder a = 0.0375 m, h = 0.012 m touching with the
/// sharp rim of its lower face (the one towards d). Undefined when lying flat (d ∥ e3).
RollingBody EulerDisk();

/// The rattleback of urdf/rattleback.urdf: ellipsoid, semi-axes (0.20, 0.03, 0.02) m, centre O
/// at +0.01 m on body z; m = 1 kg; Θ_xy = URDF ixy = −2e-5 kg m² (the tensor entry, as in
/// docs/scenes.md). `theta_xy` replaces Θ_xy (the mirrored body: +2e-5; symmetric: 0).
RollingBody Rattleback(double theta_xy = -2e-5);

/// One state of a rolling body (every part consistent with (R1), (R2)).
struct RollingState {
  double t = 0.0;                                             ///< time [s]
  Eigen::Vector3d position = Eigen::Vector3d::Zero();         ///< r_S, world [m]
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< body → world, unit
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();            ///< ω, BODY axes [rad/s]
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();         ///< v_S, world [m/s]

  /// ω in world axes [rad/s].
  Eigen::Vector3d OmegaWorld() const { return orientation * omega; }
};

/// The rolling-consistent state for an orientation (normalised here) and ω in body axes: z_S by
/// (R1) (the surface touches z = 0), v_S by (R2); x_S, y_S as given.
RollingState RollingStart(const RollingBody& body, const Eigen::Quaterniond& orientation,
                          const Eigen::Vector3d& omega_body,
                          const Eigen::Vector2d& xy = Eigen::Vector2d::Zero());

/// The rolling state right after a perfectly sticking impulse at P (an infinite friction
/// coefficient) on a body that touches with the given orientation, ω (body axes) and v_S (world;
/// e.g. a start that slips): the impulse has no moment about P, so the angular momentum about P,
///   L_P = Θ ω − m r × v_S   (body axes),
/// is kept: ω' = Θ_P⁻¹ (Θ ω − m r × v_S), Θ_P of (R6); z_S, v_S' from (R1), (R2).
RollingState StickingImpulseStart(const RollingBody& body, const Eigen::Quaterniond& orientation,
                                  const Eigen::Vector3d& omega_body,
                                  const Eigen::Vector3d& velocity,
                                  const Eigen::Vector2d& xy = Eigen::Vector2d::Zero());

/// E = ½ m |v_S|² + ½ ωᵀ Θ ω + m g z_S [J] of any state (R7 when rolling).
double Energy(const RollingBody& body, const RollingState& state);

/// ω̇ of (R6) for the downward direction d (unit, body axes) and ω (body axes) [rad/s²].
Eigen::Vector3d AngularAcceleration(const RollingBody& body, const Eigen::Vector3d& down,
                                    const Eigen::Vector3d& omega);

/// The states at `times` (ascending, from start.t on) of the rolling motion from `start` (only
/// x_S, y_S, q and ω are read; the rest follows from (R1), (R2)). `tolerance`: absolute and
/// relative error bound of each Runge–Kutta–Fehlberg 7(8) step.
std::vector<RollingState> Integrate(const RollingBody& body, const RollingState& start,
                                    const std::vector<double>& times, double tolerance = 1e-12);

/// The first time after start.t at which the spin about the world vertical, ω_w·ẑ, changes sign
/// (bisection on the integrator to 1e-10 s); none if it keeps its sign until t_end.
std::optional<double> FirstSpinReversal(const RollingBody& body, const RollingState& start,
                                        double t_end, double tolerance = 1e-12);

/// The eigenvalues of the linearisation of the reduced equations, in body axes, x = (d, ω),
///   ḋ = d × ω (R3),   ω̇ = (R6),
/// about the upright steady spin d = (0, 0, −1), ω = (0, 0, omega_z) (an equilibrium whenever
/// the contact point is on the body's z axis; not for the rim of Euler's disk). The Jacobian is
/// taken by central finite differences; sorted by descending real part [1/s]. Of the six, one
/// belongs to |d| (zero: (R3) keeps it) and one to the spin ω_z (zero).
Eigen::VectorXcd LinearStabilityExponents(const RollingBody& body, double omega_z);

}  // namespace nonsmooth_sim::reference

#endif  // NONSMOOTH_SIM_TEST_REFERENCE_ROLLING_REFERENCE_H_
