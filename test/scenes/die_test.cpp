// A die tossed with some spin (urdf/die.urdf, config/die.yaml; docs/scenes.md section 6): a
// 0.016 m cube of 0.0045 kg, μ = 0.3, R = 0.5 mm, ε = 0, thrown from 0.028 m above the floor at
// (0.3, 0.1, 0.3) m/s spinning at 27 rad/s.
//
// What must hold: it lands (first contact at 0.111 s), tumbles on its corners and edges (turns on the
// floor rather than sticking where it first touched), and rests on one face: a body axis vertical,
// S at half the side above the floor (penetration within a few slops), no jitter (the set of
// contacts does not change any more, speeds at round-off), no drift, no sinking.
//
// Δt = 1e-4 s: the landing speed ~0.8 m/s moves a corner 80 µm per step; the die spins at
// 27 rad/s (Δt|ω| = 0.003).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "scene_test_support.h"

namespace nonsmooth_sim {
namespace {

constexpr double kHalfSide = 0.008;  // [m]

TEST(Die, LandsTumblesAndRestsOnOneFace) {
  const scene_test::Toss toss = scene_test::TossShippedScene("die", 2.0);
  const BodyState& s = toss.end;
  // the face it rests on: the body axis closest to the vertical
  const Eigen::Matrix3d r = s.orientation.normalized().toRotationMatrix();
  const double vertical = r.row(2).cwiseAbs().maxCoeff();  // max_j |e_j·ẑ|
  std::printf("first contact %.4f s, turned %.2f rad on the floor, contacts settled at %.4f s "
              "(%zu contacts), axis tilt %.2e rad, z_S - s/2 = %.2e m, drift %.2e m, max speed "
              "%.2e m/s and penetration %.2e m over the last second, max penetration %.2e m\n",
              toss.first_contact, toss.turned_on_floor, toss.last_change, toss.end_contacts,
              std::acos(std::min(1.0, vertical)), s.position.z() - kHalfSide,
              (s.position - toss.position_at_1s).norm(), toss.max_speed_late,
              toss.max_penetration_late, toss.max_penetration);
  // lands and tumbles
  EXPECT_GT(toss.first_contact, 0.1);
  EXPECT_LT(toss.first_contact, 0.2);
  EXPECT_GT(toss.turned_on_floor, 0.3);
  // rests on one face (measured: on four corners, axis tilt 2.2e-4 rad, S 2.4e-6 m low, the
  // deepest corner 4.3e-6 m in the floor: the landing leaves it tilted into the floor and the gap
  // correction lifts only to the highest closed contact (-0.7e-6 m, above the slop), so the tilt
  // stays; it is a few slops, constant, not a sinking)
  EXPECT_GT(vertical, std::cos(1e-3));
  EXPECT_NEAR(s.position.z(), kHalfSide, 5.0 * kGapCorrectionSlop);
  // no jitter: the contacts stopped changing within 0.2 s of landing; at rest to round-off
  EXPECT_LT(toss.last_change, toss.first_contact + 0.2);
  EXPECT_LT(toss.max_speed_late, 1e-12);
  // no drift, no sinking
  EXPECT_LT((s.position - toss.position_at_1s).norm(), 1e-12);
  EXPECT_LT(toss.max_penetration_late, 5.0 * kGapCorrectionSlop);
  EXPECT_LE(toss.max_energy_excess, 0.0) << "at t = " << toss.max_energy_excess_time;
  EXPECT_TRUE(toss.finite);
}

}  // namespace
}  // namespace nonsmooth_sim
