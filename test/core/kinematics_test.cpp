// The kinematic map F(q) (10): the orientation rate is ½ p ⊗ (0, ω).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/rigid_body_dynamics.h"

namespace nonsmooth_sim {
namespace {

TEST(Kinematics, OrientationRateIsHalfPTimesOmega) {
  // F(q) (10): d/dt p = ½ p ⊗ (0, ω); a small step of AdvanceOrientation matches the exact
  // rotation p ⊗ exp(ωh/2) to O(h²)
  const Eigen::Quaterniond p(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -1, 2).normalized()));
  const Eigen::Vector3d omega(1.0, 2.0, -3.0);
  const double h = 1e-5;
  const Eigen::Quaterniond exact =
      p * Eigen::Quaterniond(Eigen::AngleAxisd(omega.norm() * h, omega.normalized()));
  const Eigen::Quaterniond step = AdvanceOrientation(p, omega, h);
  EXPECT_LT((step.coeffs() - exact.coeffs()).norm(), 10.0 * h * h * omega.squaredNorm());
  EXPECT_GT((step.coeffs() - p.coeffs()).norm(), 0.1 * h * omega.norm());
}

}  // namespace
}  // namespace nonsmooth_sim
