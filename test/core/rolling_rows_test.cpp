// The rolling rows of the contact Jacobian (contact_jacobian.h, ContactRollingRows) against the
// world-frame definitions: γ_R is the angular velocity of B minus that of A about t1, t2, and
// W_R Λ_R is the torque Λ_R1 t1 + Λ_R2 t2 on B, its opposite on A.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <random>

#include "nonsmooth_sim/core/contact/contact_frame.h"
#include "nonsmooth_sim/core/contact/contact_jacobian.h"

namespace nonsmooth_sim {
namespace {

constexpr std::uint64_t kSeed = 0x2011;

Eigen::Matrix3d RandomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

Eigen::Vector3d RandomVector(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return Eigen::Vector3d(n(rng), n(rng), n(rng));
}

TEST(RollingRows, RelativeAngularVelocityAboutTheTangentsOfTwoBodies) {
  std::mt19937_64 rng(kSeed);
  for (int k = 0; k < 200; ++k) {
    const ContactFrame frame = MakeContactFrame(RandomVector(rng).normalized(), nullptr, Eigen::Vector3d::UnitX());
    const Eigen::Matrix3d rotation_b = RandomRotation(rng);
    const Eigen::Matrix3d rotation_a = RandomRotation(rng);
    const Eigen::Vector3d omega_b = RandomVector(rng);  // world
    const Eigen::Vector3d omega_a = RandomVector(rng);
    // body-frame angular velocities K_ω = Aᵀω; side B sign +1, side A sign -1
    const Eigen::Vector2d gamma =
        ContactRollingRows(frame, rotation_b) * (rotation_b.transpose() * omega_b) -
        ContactRollingRows(frame, rotation_a) * (rotation_a.transpose() * omega_a);
    const Eigen::Vector3d relative = omega_b - omega_a;
    EXPECT_NEAR(gamma[0], frame.tangent1.dot(relative), 1e-13);
    EXPECT_NEAR(gamma[1], frame.tangent2.dot(relative), 1e-13);
    // no part along the normal: spinning about n is drilling, not rolling
    const Eigen::Vector2d spin = ContactRollingRows(frame, rotation_b) *
                                 (rotation_b.transpose() * (3.0 * frame.normal));
    EXPECT_NEAR(spin.norm(), 0.0, 1e-13);
    // W_R Λ_R on B: the body-frame torque Aᵀ(Λ_R1 t1 + Λ_R2 t2)
    const Eigen::Vector2d lambda_r(0.7, -0.2);
    const Eigen::Vector3d torque_body = ContactRollingRows(frame, rotation_b).transpose() * lambda_r;
    const Eigen::Vector3d torque_world = rotation_b * torque_body;
    EXPECT_LT((torque_world - (0.7 * frame.tangent1 - 0.2 * frame.tangent2)).norm(), 1e-13);
  }
}

}  // namespace
}  // namespace nonsmooth_sim
