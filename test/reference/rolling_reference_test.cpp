// Checks of the rolling reference (rolling_reference.h, rolling_lagrange.h) on its own, before
// scene tests hold the simulator to it: the contact geometry against brute force and finite
// differences, energy (rolling does no work), Euler's disk on its closed form (D1), (D2)
// (docs/scenes.md §1), the two formulations against each other, the rattleback's spin reversal
// and the linear stability of its upright spin. Each check prints what it measured.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

#include "rolling_lagrange.h"
#include "rolling_reference.h"

namespace nonsmooth_sim::reference {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<double> Times(double t_end, double dt) {
  std::vector<double> times;
  for (int i = 0; i * dt <= t_end + 1e-12; ++i) times.push_back(i * dt);
  return times;
}

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

Eigen::Vector3d Down(const RollingState& s) {
  return s.orientation.conjugate() * Eigen::Vector3d(0.0, 0.0, -1.0);
}

// The shipped start of config/rattleback.yaml ([qx, qy, qz, qw], ω in body axes): 1° about
// (1, 1, 0)/√2, −5 rad/s about the world vertical.
Eigen::Quaterniond ShippedRattlebackOrientation() {
  return Eigen::Quaterniond(0.9999619230641712, 0.006170592427165337, 0.006170592427165337, 0.0);
}
Eigen::Vector3d ShippedRattlebackOmega() {
  return Eigen::Vector3d(0.06170357469913462, -0.06170357469913462, -4.999238475781956);
}

// The shipped start made rolling as the brief words it: q and ω as shipped, z_S and v_S from
// (R1), (R2) (the YAML's v_S = 0 slips at 0.12 m/s).
RollingState RattlebackRollingStart(const RollingBody& body) {
  return RollingStart(body, ShippedRattlebackOrientation(), ShippedRattlebackOmega());
}

// The shipped start as shipped (v_S = 0, slipping) after a sticking impulse at P
// (StickingImpulseStart: L_P kept).
RollingState RattlebackStuckStart(const RollingBody& body) {
  return StickingImpulseStart(body, ShippedRattlebackOrientation(), ShippedRattlebackOmega(),
                              /*velocity=*/Eigen::Vector3d::Zero());
}

// --------------------------------------------------------------------------------------------
// Geometry

// Uniform random unit vectors (fixed seed), all but a cap around ±e3 (the rim is undefined there).
std::vector<Eigen::Vector3d> RandomDirections(int count) {
  std::mt19937 generator(20261204);
  std::normal_distribution<double> normal;
  std::vector<Eigen::Vector3d> out;
  while (static_cast<int>(out.size()) < count) {
    const Eigen::Vector3d d(normal(generator), normal(generator), normal(generator));
    if (std::abs(d.normalized().z()) < 0.99) out.push_back(d.normalized());
  }
  return out;
}

// For random d: no surface sample is lower than P (the lowest point maximises d·p), P is no lower
// than the best sample by more than the grid allows, and ∂r/∂d matches finite differences.
void ExpectLowestAndJacobian(const RollingBody& body,
                             const std::vector<Eigen::Vector3d>& surface_samples,
                             double sample_resolution) {
  double worst_jacobian = 0.0;
  double worst_excess = -1e300;  // max over d of (max over samples of d·s) − d·P
  for (const Eigen::Vector3d& d : RandomDirections(200)) {
    const SupportPoint p = body.contact(d);
    double best = -1e300;
    for (const Eigen::Vector3d& s : surface_samples) best = std::max(best, d.dot(s));
    // no sample is lower than P; P is no lower than the best sample by more than the grid allows
    worst_excess = std::max(worst_excess, best - d.dot(p.r));
    EXPECT_LE(best, d.dot(p.r) + 1e-15);
    EXPECT_GE(best, d.dot(p.r) - sample_resolution);
    // ∂r/∂d by central differences, h = 1e-6 (error ~h² |r'''| + 1e-16 |r|/h ≈ 1e-10 m)
    constexpr double kH = 1e-6;
    for (int i = 0; i < 3; ++i) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e(i) = kH;
      const Eigen::Vector3d fd = (body.contact(d + e).r - body.contact(d - e).r) / (2.0 * kH);
      worst_jacobian = std::max(worst_jacobian, (fd - p.dr_dd.col(i)).norm());
    }
  }
  std::printf("%s: max(d·sample) − d·P = %.2e m (≤ 0); |∂r/∂d − finite differences| ≤ %.2e m\n",
              body.name.c_str(), worst_excess, worst_jacobian);
  EXPECT_LT(worst_jacobian, 1e-8);
}

TEST(RollingGeometry, EllipsoidContactIsTheLowestPointWithTheRightJacobian) {
  // surface points O + diag(s) u on a fine grid of unit vectors u
  std::vector<Eigen::Vector3d> samples;
  constexpr int kN = 600;
  for (int i = 0; i <= kN; ++i) {
    const double theta = kPi * i / kN;
    for (int j = 0; j < 2 * kN; ++j) {
      const double phi = kPi * j / kN;
      const Eigen::Vector3d u(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                              std::cos(theta));
      samples.push_back(Eigen::Vector3d(0.0, 0.0, 0.01) +
                        Eigen::Vector3d(0.20, 0.03, 0.02).cwiseProduct(u));
    }
  }
  // grid spacing π/600 on a radius ≤ 0.2 m: the best sample is within ~(0.2 (π/600))² of P
  ExpectLowestAndJacobian(Rattleback(), samples, 1e-5);
}

TEST(RollingGeometry, DiskContactIsTheLowestRimPointWithTheRightJacobian) {
  // the two rim circles (a linear function's maximum over a cylinder is on one of them)
  std::vector<Eigen::Vector3d> samples;
  constexpr int kN = 20000;
  for (int j = 0; j < kN; ++j) {
    const double phi = 2.0 * kPi * j / kN;
    for (double z : {-0.006, 0.006}) {
      samples.push_back(Eigen::Vector3d(0.0375 * std::cos(phi), 0.0375 * std::sin(phi), z));
    }
  }
  ExpectLowestAndJacobian(EulerDisk(), samples, 0.0375 * std::pow(2.0 * kPi / kN, 2));
}

// --------------------------------------------------------------------------------------------
// Energy (R7)

// Largest |E(t) − E0| over samples 0.01 s apart, relative to E0, and relative to the kinetic
// energy at the start (a stricter scale: E0 carries the arbitrary potential of z = 0).
struct EnergyDrift {
  double relative_to_energy = 0.0;
  double relative_to_kinetic = 0.0;
};

EnergyDrift MeasureEnergyDrift(const RollingBody& body, const RollingState& start, double t_end) {
  const double e0 = Energy(body, start);
  const double kinetic0 = e0 - body.mass * kGravity * start.position.z();
  double worst = 0.0;
  for (const RollingState& s : Integrate(body, start, Times(t_end, 0.01))) {
    worst = std::max(worst, std::abs(Energy(body, s) - e0));
  }
  return {worst / e0, worst / kinetic0};
}

TEST(RollingEnergy, ConservedOverTenSecondsByBothBodies) {
  const auto t0 = std::chrono::steady_clock::now();
  // the rattleback through its reversal
  const RollingBody rattleback = Rattleback();
  const EnergyDrift r = MeasureEnergyDrift(rattleback, RattlebackRollingStart(rattleback), 10.0);
  // Euler's disk off its steady state (ω of the shipped start × 0.9): it nutates
  const RollingBody disk = EulerDisk();
  const RollingState disk_start = RollingStart(
      disk, Eigen::Quaterniond(0.9659258262890683, 0.25881904510252074, 0.0, 0.0),
      0.9 * Eigen::Vector3d(0.0, 23.644792592829546, 3.783166814852728));
  const EnergyDrift e = MeasureEnergyDrift(disk, disk_start, 10.0);
  std::printf("energy over 10 s, max |E − E0|/E0 (and /T0): rattleback %.2e (%.2e), "
              "Euler's disk %.2e (%.2e); %.2f s\n",
              r.relative_to_energy, r.relative_to_kinetic, e.relative_to_energy,
              e.relative_to_kinetic, Seconds(t0));
  EXPECT_LE(r.relative_to_energy, 1e-10);
  EXPECT_LE(e.relative_to_energy, 1e-10);
}

// Why (R6) carries the ρ̇ term: a body whose contact point is taken as fixed on the surface
// (∂r/∂d = 0) gains or loses energy at once. The check above can fail.
TEST(RollingEnergy, WithoutTheMotionOfTheContactPointEnergyIsNotConserved) {
  RollingBody body = Rattleback();
  const auto contact = body.contact;
  body.contact = [contact](const Eigen::Vector3d& d) {
    SupportPoint p = contact(d);
    p.dr_dd.setZero();
    return p;
  };
  const EnergyDrift drift = MeasureEnergyDrift(body, RattlebackRollingStart(body), 1.0);
  std::printf("without ρ̇: max |E − E0|/E0 = %.2e over 1 s\n", drift.relative_to_energy);
  EXPECT_GT(drift.relative_to_energy, 1e-4);
}

// --------------------------------------------------------------------------------------------
// Euler's disk: steady rolling with S at rest (docs/scenes.md §1, config/euler_disk.yaml)

struct DiskAngles {
  double alpha = 0.0;       // inclination of the disc plane to the floor = ∠(e3, ẑ) [rad]
  double precession = 0.0;  // Ω of ω = Ω ẑ + s e3 [rad/s]
};

DiskAngles MeasureDisk(const RollingState& s) {
  const Eigen::Vector3d e3 = s.orientation * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d omega = s.OmegaWorld();
  const double cos_alpha = e3.z();
  // ω − (ω·e3) e3 = Ω (ẑ − cos α e3), whose z component is Ω (1 − cos² α)
  return {std::acos(cos_alpha), (omega - omega.dot(e3) * e3).z() / (1.0 - cos_alpha * cos_alpha)};
}

// (D1) of docs/scenes.md
double SteadyPrecessionRate(const RollingBody& disk, double alpha) {
  constexpr double kA = 0.0375;
  constexpr double kH = 0.012;
  const double a_inertia = disk.inertia(0, 0);
  const double c_inertia = disk.inertia(2, 2);
  return std::sqrt(disk.mass * kGravity * (kA * std::cos(alpha) - 0.5 * kH * std::sin(alpha)) /
                   (std::sin(alpha) * (a_inertia * std::cos(alpha) -
                                       c_inertia * (0.5 * kH / kA) * std::sin(alpha))));
}

// The shipped start, but with the spin scaled by `scale` (1: on (D1)).
RollingState DiskStart(const RollingBody& disk, double scale) {
  // config/euler_disk.yaml: [qx, qy, qz, qw] and ω in body axes
  return RollingStart(disk, Eigen::Quaterniond(0.9659258262890683, 0.25881904510252074, 0.0, 0.0),
                      scale * Eigen::Vector3d(0.0, 23.644792592829546, 3.783166814852728));
}

TEST(EulerDiskReference, ShippedStartIsOnTheClosedForm) {
  const RollingBody disk = EulerDisk();
  const RollingState start = DiskStart(disk, 1.0);
  const DiskAngles angles = MeasureDisk(start);
  const double omega_d1 = SteadyPrecessionRate(disk, kPi / 6.0);
  std::printf("start: α = %.15f°, Ω = %.13f rad/s, (D1) %.13f, z_S = %.17g m, |v_S| = %.2e m/s\n",
              angles.alpha * 180.0 / kPi, angles.precession, omega_d1, start.position.z(),
              start.velocity.norm());
  EXPECT_NEAR(angles.alpha, kPi / 6.0, 1e-14);
  EXPECT_NEAR(angles.precession / omega_d1, 1.0, 1e-13);
  EXPECT_NEAR(start.position.z(), 0.02394615242270663, 1e-16);  // the YAML's z_S
  EXPECT_LT(start.velocity.norm(), 1e-15);  // (D2): S at rest
}

TEST(EulerDiskReference, SteadyRollingKeepsAlphaPrecessionAndEnergyForTwentySeconds) {
  const RollingBody disk = EulerDisk();
  const RollingState start = DiskStart(disk, 1.0);
  const double omega_d1 = SteadyPrecessionRate(disk, kPi / 6.0);
  const double e0 = Energy(disk, start);
  const auto t0 = std::chrono::steady_clock::now();
  double d_alpha = 0.0, d_omega = 0.0, d_energy = 0.0, speed = 0.0;
  for (const RollingState& s : Integrate(disk, start, Times(20.0, 0.01))) {
    const DiskAngles angles = MeasureDisk(s);
    d_alpha = std::max(d_alpha, std::abs(angles.alpha - kPi / 6.0));
    d_omega = std::max(d_omega, std::abs(angles.precession / omega_d1 - 1.0));
    d_energy = std::max(d_energy, std::abs(Energy(disk, s) / e0 - 1.0));
    speed = std::max(speed, s.velocity.norm());
  }
  std::printf("20 s of steady rolling: max |α − 30°| = %.2e rad, |Ω/Ω_D1 − 1| = %.2e, "
              "|E/E0 − 1| = %.2e, |v_S| = %.2e m/s; %.2f s\n",
              d_alpha, d_omega, d_energy, speed, Seconds(t0));
  EXPECT_LE(d_alpha, 1e-9);
  EXPECT_LE(d_omega, 1e-9);
  EXPECT_LE(d_energy, 1e-9);
}

// The check above can fail: 0.1 % off (D1) the disc nutates, α swings by far more than 1e-9.
TEST(EulerDiskReference, OffTheClosedFormTheDiscNutates) {
  const RollingBody disk = EulerDisk();
  double d_alpha = 0.0;
  for (const RollingState& s : Integrate(disk, DiskStart(disk, 1.001), Times(1.0, 0.001))) {
    d_alpha = std::max(d_alpha, std::abs(MeasureDisk(s).alpha - kPi / 6.0));
  }
  std::printf("Ω × 1.001: max |α − 30°| = %.2e rad within 1 s\n", d_alpha);
  EXPECT_GT(d_alpha, 1e-5);
}

// --------------------------------------------------------------------------------------------
// The two formulations (rolling_reference.h, body axes, force eliminated; rolling_lagrange.h,
// world axes, force as a multiplier)

TEST(RollingFormulations, LagrangeFormAgreesForTheRattleback) {
  const RollingBody body = Rattleback();
  const RollingState start = RattlebackRollingStart(body);
  const std::vector<double> times = Times(3.0, 0.01);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<RollingState> a = Integrate(body, start, times);
  const double seconds_a = Seconds(t0);
  const auto t1 = std::chrono::steady_clock::now();
  const std::vector<RollingState> b = IntegrateLagrange(body, start, times);
  const double seconds_b = Seconds(t1);
  double d_omega = 0.0, d_position = 0.0, d_angle = 0.0, d_velocity = 0.0, slip = 0.0, gap = 0.0;
  for (size_t i = 0; i < times.size(); ++i) {
    d_omega = std::max(d_omega, (a[i].omega - b[i].omega).norm());
    d_position = std::max(d_position, (a[i].position - b[i].position).norm());
    d_angle = std::max(d_angle, a[i].orientation.angularDistance(b[i].orientation));
    d_velocity = std::max(d_velocity, (a[i].velocity - b[i].velocity).norm());
    // how far the multiplier form, which integrates z_S and v_S, drifts off (R1), (R2)
    const RollingState rolled = RollingStart(body, b[i].orientation, b[i].omega);
    slip = std::max(slip, (b[i].velocity - rolled.velocity).norm());
    gap = std::max(gap, std::abs(b[i].position.z() - rolled.position.z()));
  }
  std::printf("3 s, body-axes vs multiplier form: |Δω| ≤ %.2e rad/s, |Δr_S| ≤ %.2e m, "
              "angle ≤ %.2e rad, |Δv_S| ≤ %.2e m/s; multiplier form's slip %.2e m/s, gap %.2e m; "
              "%.3f s and %.3f s\n",
              d_omega, d_position, d_angle, d_velocity, slip, gap, seconds_a, seconds_b);
  EXPECT_LE(d_omega, 1e-7);
  EXPECT_LE(d_position, 1e-9);
  EXPECT_LE(d_angle, 1e-8);
  EXPECT_LE(d_velocity, 1e-8);
}

// --------------------------------------------------------------------------------------------
// The rattleback's spin reversal (config/rattleback.yaml, docs/scenes.md §2)

double SpinAt(const RollingBody& body, const RollingState& start, double t) {
  return Integrate(body, start, {t}).front().OmegaWorld().z();
}

TEST(RattlebackReference, RollingShippedStartReverses) {
  const RollingBody body = Rattleback();
  const RollingState start = RattlebackRollingStart(body);
  const auto t0 = std::chrono::steady_clock::now();
  const std::optional<double> reversal = FirstSpinReversal(body, start, 10.0);
  const double seconds = Seconds(t0);
  ASSERT_TRUE(reversal.has_value());
  const std::optional<double> looser = FirstSpinReversal(body, start, 10.0, 1e-10);
  ASSERT_TRUE(looser.has_value());
  const double spin_8 = SpinAt(body, start, 8.0);
  std::printf("rolling shipped start (v_S = %.4f m/s): ω_z changes sign at %.10f s "
              "(tolerance 1e-10: %.10f s); ω_z(8 s) = %.6f rad/s; %.3f s\n",
              start.velocity.norm(), *reversal, *looser, spin_8, seconds);
  // the bisection brackets the sign change to 1e-9 s
  EXPECT_LT(SpinAt(body, start, *reversal - 1e-9), 0.0);
  EXPECT_GT(SpinAt(body, start, *reversal + 1e-9), 0.0);
  EXPECT_NEAR(*reversal, *looser, 1e-6);
  EXPECT_GT(*reversal, 2.0);
  EXPECT_LT(*reversal, 3.5);
  EXPECT_GT(spin_8, 4.0);  // it spins the other way, with the energy the rocking gave back
}

// The issue's reference numbers (2.385 s, 4.67 rad/s at 8 s) belong to the shipped start after
// a sticking impulse (L_P kept), not to the start made rolling by v_S = −ω × r alone.
TEST(RattlebackReference, StuckShippedStartReproducesTheIssueNumbers) {
  const RollingBody body = Rattleback();
  const RollingState start = RattlebackStuckStart(body);
  // the impulse keeps L_P = A Θ ω + m (r_S − r_P) × v_S (world) and takes energy
  const RollingState shipped = RattlebackRollingStart(body);  // same pose, z_S
  const Eigen::Vector3d r_ps = shipped.orientation * -body.contact(Down(shipped)).r;  // P → S
  const Eigen::Vector3d l_before = shipped.orientation * (body.inertia * ShippedRattlebackOmega());
  const Eigen::Vector3d l_after = start.orientation * (body.inertia * start.omega) +
                                  body.mass * r_ps.cross(start.velocity);
  const double e_shipped = Energy(body, shipped) - 0.5 * body.mass * shipped.velocity.squaredNorm();
  std::printf("sticking impulse: |ΔL_P| = %.2e kg m²/s, E %.6f → %.6f J\n",
              (l_after - l_before).norm(), e_shipped, Energy(body, start));
  EXPECT_LT((l_after - l_before).norm(), 1e-14 * l_before.norm());
  EXPECT_LT(Energy(body, start), e_shipped);
  const std::optional<double> reversal = FirstSpinReversal(body, start, 10.0);
  ASSERT_TRUE(reversal.has_value());
  const double spin_8 = SpinAt(body, start, 8.0);
  const Eigen::Vector3d omega = start.OmegaWorld();
  std::printf("stuck shipped start (ω_w = (%.4f, %.4f, %.4f) rad/s): ω_z changes sign at "
              "%.10f s, ω_z(8 s) = %.6f rad/s\n",
              omega.x(), omega.y(), omega.z(), *reversal, spin_8);
  EXPECT_NEAR(*reversal, 2.385, 1e-3);
  EXPECT_NEAR(spin_8, 4.67, 5e-3);
}

// The other direction is unstable too, through the slow roll mode (0.2 s⁻¹): it reverses, but
// only after several seconds (tops.md §2: "the stable direction also reverses, after 10-20 s").
TEST(RattlebackReference, CounterclockwiseSpinReversesOnlyLate) {
  const RollingBody body = Rattleback();
  const RollingState start =
      RollingStart(body, ShippedRattlebackOrientation(), -ShippedRattlebackOmega());
  const std::optional<double> reversal = FirstSpinReversal(body, start, 20.0);
  ASSERT_TRUE(reversal.has_value());
  std::printf("+5 rad/s rolling start: ω_z changes sign at %.10f s\n", *reversal);
  EXPECT_GT(*reversal, 8.0);
}

// --------------------------------------------------------------------------------------------
// Linear stability of the upright spin (body axes: an equilibrium)

double LargestRealPart(const Eigen::VectorXcd& eigenvalues) { return eigenvalues(0).real(); }

TEST(RollingStability, ExponentsOfTheUprightSpin) {
  const RollingBody body = Rattleback();
  const Eigen::VectorXcd plus = LinearStabilityExponents(body, 5.0);
  const Eigen::VectorXcd minus = LinearStabilityExponents(body, -5.0);
  for (const auto* e : {&plus, &minus}) {
    std::printf("ω_z = %+g:", e == &plus ? 5.0 : -5.0);
    for (int i = 0; i < e->size(); ++i) std::printf(" %+.6f%+.4fi", (*e)(i).real(), (*e)(i).imag());
    std::printf("\n");
  }
  // +5: the slow roll mode (≈ 34 rad/s) grows; −5: the pitch mode (≈ 109 rad/s)
  EXPECT_NEAR(LargestRealPart(plus), 0.2025, 0.01 * 0.2025);
  EXPECT_NEAR(std::abs(plus(0).imag()), 34.1, 1.0);
  EXPECT_NEAR(LargestRealPart(minus), 2.12, 0.01 * 2.12);
  EXPECT_NEAR(std::abs(minus(0).imag()), 109.4, 1.0);
  // time reversal maps Ω to −Ω and λ to −λ
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(plus(i).real(), -minus(5 - i).real(), 1e-6);
  }
  // the symmetric body (Θ_xy = 0) has no preference: purely imaginary
  const Eigen::VectorXcd symmetric = LinearStabilityExponents(Rattleback(0.0), -5.0);
  EXPECT_LT(symmetric.real().cwiseAbs().maxCoeff(), 1e-6);
}

// The linearisation against the full equations: from upright at −5 rad/s with a tilt of 1e-7
// rad the tilt's envelope grows at the largest exponent.
TEST(RollingStability, SmallTiltGrowsAtTheLargestExponent) {
  const RollingBody body = Rattleback();
  const Eigen::Quaterniond q(Eigen::AngleAxisd(1e-7, Eigen::Vector3d(1.0, 1.0, 0.0).normalized()));
  const RollingState start = RollingStart(body, q, q.conjugate() * Eigen::Vector3d(0, 0, -5.0));
  // envelope: the largest tilt within each window of 0.5 s (many pitch periods of 57 ms)
  const auto envelope = [&](double t_from) {
    double tilt = 0.0;
    for (const RollingState& s : Integrate(body, start, Times(t_from + 0.5, 1e-3))) {
      if (s.t >= t_from) tilt = std::max(tilt, Down(s).head<2>().norm());
    }
    return tilt;
  };
  const double rate = std::log(envelope(4.0) / envelope(2.0)) / 2.0;
  std::printf("tilt envelope growth from upright at −5 rad/s: %.4f 1/s (linear: %.4f)\n", rate,
              LargestRealPart(LinearStabilityExponents(body, -5.0)));
  EXPECT_NEAR(rate, LargestRealPart(LinearStabilityExponents(body, -5.0)), 0.05 * 2.12);
}

}  // namespace
}  // namespace nonsmooth_sim::reference
