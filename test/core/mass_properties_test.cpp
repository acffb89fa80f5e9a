// Inertia about the centre of mass (parallel-axis theorem) and rotated inertia.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/core/rigid_body_dynamics.h"

namespace nonsmooth_sim {
namespace {

TEST(MassProperties, ParallelAxisAndRotation) {
  // a point mass m at r from O has Θ_O = m(|r|²I - rrᵀ) and nothing about itself
  const Eigen::Vector3d r(0.1, -0.2, 0.3);
  const double m = 2.0;
  const Eigen::Matrix3d about_o =
      m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  EXPECT_LT(InertiaAboutCenterOfMass(about_o, m, r).norm(), 1e-15);
  // rotating diag(1, 2, 3) by 90° about z swaps the x and y moments
  const Eigen::Matrix3d rz =
      Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d rotated = RotateInertia(Eigen::Vector3d(1, 2, 3).asDiagonal(), rz);
  EXPECT_NEAR(rotated(0, 0), 2.0, 1e-15);
  EXPECT_NEAR(rotated(1, 1), 1.0, 1e-15);
  EXPECT_NEAR(rotated(2, 2), 3.0, 1e-15);
}

}  // namespace
}  // namespace nonsmooth_sim
