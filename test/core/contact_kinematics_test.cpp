// The contact kinematics against an independent world-frame derivation: W and γ of a sphere
// on the ground and of contacts over two bodies match the world-frame (relative) velocity of
// the contact points, and the Delassus blocks match WᵀM⁻¹W.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "nonsmooth_sim/core/collision/collision_table.h"
#include "nonsmooth_sim/core/contact/contact_frame.h"
#include "nonsmooth_sim/core/contact/contact_jacobian.h"
#include "nonsmooth_sim/core/rigid_body_dynamics.h"
#include "nonsmooth_sim/core/scene.h"

namespace nonsmooth_sim {
namespace {

// Random poses and velocities with a fixed seed.
class RandomMotion {
 public:
  explicit RandomMotion(std::uint64_t seed) : random_(seed) {}
  double Uniform() { return uniform_(random_); }
  Eigen::Vector3d Vector() { return Eigen::Vector3d(Uniform(), Uniform(), Uniform()); }
  Eigen::Vector3d UnitVector() {
    Eigen::Vector3d v = Vector();
    while (v.norm() < 0.1) v = Vector();
    return v.normalized();
  }
  Eigen::Matrix3d Rotation() {
    return Eigen::Quaterniond(Eigen::Vector4d(Uniform(), Uniform(), Uniform(), Uniform()))
        .normalized()
        .toRotationMatrix();
  }

 private:
  std::mt19937_64 random_;
  std::uniform_real_distribution<double> uniform_{-1.0, 1.0};
};

// Pose and velocity u = (v_S, K_ω) of one free body.
struct BodyMotion {
  Eigen::Vector3d position;
  Eigen::Matrix3d rotation;  // A, K → world
  Eigen::Vector3d linear_velocity;
  Eigen::Vector3d angular_velocity_body;

  // world frame: v_P = v_S + (Aω) × (P - r_S)
  Eigen::Vector3d PointVelocity(const Eigen::Vector3d& point) const {
    return linear_velocity + (rotation * angular_velocity_body).cross(point - position);
  }
  Eigen::Vector3d AngularVelocityWorld() const { return rotation * angular_velocity_body; }
};

BodyMotion RandomBodyMotion(RandomMotion* random) {
  BodyMotion m;
  m.position = random->Vector();
  m.rotation = random->Rotation();
  m.linear_velocity = random->Vector();
  m.angular_velocity_body = 10.0 * random->Vector();
  return m;
}

// A contact of B (a body) with A (a body, or the world if body_a = kWorld) at P_B on B and P_A on
// A, its W through contact_jacobian.h.
struct TwoSidedContact {
  int body_a = kWorld;
  int body_b = 0;
  Eigen::Vector3d point_a, point_b;
  ContactFrame frame;
  ContactJacobian jacobian;
};

TwoSidedContact MakeContact(const std::vector<BodyMotion>& bodies,
                            const std::vector<BodyInertia>& inertia, int body_a, int body_b,
                            RandomMotion* random) {
  TwoSidedContact c;
  c.body_a = body_a;
  c.body_b = body_b;
  c.frame = MakeContactFrame(random->UnitVector(), nullptr, random->UnitVector());
  c.point_b = bodies[static_cast<std::size_t>(body_b)].position + 0.1 * random->Vector();
  // point_b - point_a = gap · n
  c.point_a = c.point_b - 0.01 * random->Uniform() * c.frame.normal;
  c.jacobian.linear = ContactLinearRows(c.frame);
  const int sides[2] = {body_b, body_a};
  const Eigen::Vector3d* points[2] = {&c.point_b, &c.point_a};
  for (int s = 0; s < 2; ++s) {
    ContactSide& side = c.jacobian.side[s];
    side.body = sides[s];
    side.sign = s == 0 ? 1.0 : -1.0;
    if (side.body < 0) continue;
    const BodyMotion& m = bodies[static_cast<std::size_t>(side.body)];
    SetAngularRows(ContactAngularRows(c.frame, *points[s], m.position, m.rotation),
                   inertia[static_cast<std::size_t>(side.body)], &side);
  }
  return c;
}

// γ = Σ_sides SideVelocity (contact_jacobian.h)
Eigen::Vector4d RelativeVelocity(const TwoSidedContact& c, const std::vector<BodyMotion>& bodies) {
  Eigen::Vector4d gamma = Eigen::Vector4d::Zero();
  for (const ContactSide& side : c.jacobian.side) {
    if (side.body < 0) continue;
    const BodyMotion& m = bodies[static_cast<std::size_t>(side.body)];
    gamma += SideVelocity(c.jacobian, side, m.linear_velocity, m.angular_velocity_body);
  }
  return gamma;
}

// The same from the world frame: velocity of P_B minus that of P_A along n, t1, t2 and the spin of
// B minus that of A about n (the world does not move).
Eigen::Vector4d WorldRelativeVelocity(const TwoSidedContact& c,
                                      const std::vector<BodyMotion>& bodies) {
  const BodyMotion& b = bodies[static_cast<std::size_t>(c.body_b)];
  Eigen::Vector3d v = b.PointVelocity(c.point_b);
  Eigen::Vector3d omega = b.AngularVelocityWorld();
  if (c.body_a != kWorld) {
    const BodyMotion& a = bodies[static_cast<std::size_t>(c.body_a)];
    v -= a.PointVelocity(c.point_a);
    omega -= a.AngularVelocityWorld();
  }
  return Eigen::Vector4d(c.frame.normal.dot(v), c.frame.tangent1.dot(v), c.frame.tangent2.dot(v),
                         c.frame.normal.dot(omega));
}

// W (6·bodies × 4) from the world formula applied to the unit generalized velocities: row k of W
// is γ for u = e_k, u = (v_S0, K_ω0, v_S1, K_ω1, ...).
Eigen::MatrixXd ExplicitW(const TwoSidedContact& c, const std::vector<BodyMotion>& bodies) {
  Eigen::MatrixXd w(6 * bodies.size(), 4);
  for (std::size_t k = 0; k < 6 * bodies.size(); ++k) {
    std::vector<BodyMotion> unit = bodies;
    for (std::size_t b = 0; b < unit.size(); ++b) {
      unit[b].linear_velocity.setZero();
      unit[b].angular_velocity_body.setZero();
    }
    BodyMotion& m = unit[k / 6];
    if (k % 6 < 3) {
      m.linear_velocity[static_cast<Eigen::Index>(k % 6)] = 1.0;
    } else {
      m.angular_velocity_body[static_cast<Eigen::Index>(k % 6 - 3)] = 1.0;
    }
    w.row(static_cast<Eigen::Index>(k)) = WorldRelativeVelocity(c, unit).transpose();
  }
  return w;
}

// M⁻¹ = diag(M_0⁻¹, M_1⁻¹, ...) (10)
Eigen::MatrixXd InverseMassMatrix(const std::vector<BodyInertia>& inertia) {
  const Eigen::Index n = static_cast<Eigen::Index>(6 * inertia.size());
  Eigen::MatrixXd m_inverse = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t b = 0; b < inertia.size(); ++b) {
    m_inverse.block<6, 6>(static_cast<Eigen::Index>(6 * b), static_cast<Eigen::Index>(6 * b)) =
        MassMatrix(inertia[b]).inverse();
  }
  return m_inverse;
}

// G_ij by contact_jacobian.h: Σ over the sides of i and j on one body of SideDelassusBlock, or
// OwnDelassusBlock for a side with itself (as the simulator forms G_ii).
Eigen::Matrix4d DelassusBlock(const std::vector<BodyInertia>& inertia, const TwoSidedContact& i,
                              const TwoSidedContact& j) {
  Eigen::Matrix4d block = Eigen::Matrix4d::Zero();
  for (const ContactSide& s : i.jacobian.side) {
    if (s.body < 0) continue;
    for (const ContactSide& t : j.jacobian.side) {
      if (t.body != s.body) continue;
      const BodyInertia& body = inertia[static_cast<std::size_t>(s.body)];
      block += &s == &t ? OwnDelassusBlock(body, s)
                        : SideDelassusBlock(body, i.jacobian, s, j.jacobian, t);
    }
  }
  return block;
}

// W Λ by contact_jacobian.h: sign (LᵀΛ, JᵀΛ) on the body of each side.
Eigen::VectorXd GeneralizedImpulse(const TwoSidedContact& c, std::size_t bodies,
                                   const Eigen::Vector4d& lambda) {
  Eigen::VectorXd impulse = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(6 * bodies));
  for (const ContactSide& side : c.jacobian.side) {
    if (side.body < 0) continue;
    const Eigen::Index offset = 6 * side.body;
    impulse.segment<3>(offset) += side.sign * (c.jacobian.linear.transpose() * lambda);
    impulse.segment<3>(offset + 3) += side.sign * (side.angular.transpose() * lambda);
  }
  return impulse;
}

void ExpectOrthonormalFrame(const ContactFrame& frame) {
  EXPECT_NEAR(frame.normal.norm(), 1.0, 1e-14);
  EXPECT_NEAR(frame.tangent1.norm(), 1.0, 1e-14);
  EXPECT_NEAR(frame.tangent1.dot(frame.normal), 0.0, 1e-14);
  // t1 × t2 = n
  EXPECT_LT((frame.tangent1.cross(frame.tangent2) - frame.normal).norm(), 1e-14);
}

TEST(ContactKinematics, SphereOnGroundMatchesTheWorldFrameVelocityOfTheContactPoint) {
  // a sphere collider on one body against the ground plane: the collision table gives the lowest
  // point P = r_S + A c - ρẑ with g = P·ẑ and n = ẑ; the ground's frame is t1 = x̂, t2 = ŷ; then
  // γ = (v_P·ẑ, v_P·x̂, v_P·ŷ, (Aω)·ẑ) and G = WᵀM⁻¹W (16)
  RandomMotion random(20240607);
  const BodyInertia body = MakeBodyInertia(0.3, Eigen::Vector3d(1e-3, 2e-3, 2.5e-3).asDiagonal());
  for (int trial = 0; trial < 100; ++trial) {
    const std::vector<BodyMotion> bodies = {RandomBodyMotion(&random)};
    const BodyMotion& m = bodies[0];
    const Eigen::Vector3d center = 0.1 * random.Vector();
    const double radius = 0.05 + 0.05 * std::abs(random.Uniform());

    const Collider ground = GroundPlane();
    Eigen::Isometry3d sphere_pose = Eigen::Isometry3d::Identity();
    sphere_pose.linear() = m.rotation;
    sphere_pose.translation() = m.position + m.rotation * center;
    ContactGeometry geometry[kMaxPairContacts];
    ASSERT_EQ(CollisionTable::Defaults().Collide(ground.shape, ground.pose, Shape::Sphere(radius),
                                                 sphere_pose,
                                                 std::numeric_limits<double>::infinity(), geometry),
              1);
    const Eigen::Vector3d p = m.position + m.rotation * center - radius * Eigen::Vector3d::UnitZ();
    EXPECT_NEAR(geometry[0].gap, p.z(), 1e-14);
    EXPECT_LT((geometry[0].point_b - p).norm(), 1e-14);
    EXPECT_LT((geometry[0].point_a - Eigen::Vector3d(p.x(), p.y(), 0.0)).norm(), 1e-14);
    EXPECT_LT((geometry[0].normal - Eigen::Vector3d::UnitZ()).norm(), 1e-15);

    TwoSidedContact c;
    c.body_b = 0;
    c.point_b = geometry[0].point_b;
    c.point_a = geometry[0].point_a;
    c.frame = MakeContactFrame(geometry[0].normal, nullptr, ground.pose.linear().col(0));
    EXPECT_LT((c.frame.tangent1 - Eigen::Vector3d::UnitX()).norm(), 1e-15);
    EXPECT_LT((c.frame.tangent2 - Eigen::Vector3d::UnitY()).norm(), 1e-15);
    c.jacobian.linear = ContactLinearRows(c.frame);
    c.jacobian.side[0].body = 0;
    c.jacobian.side[0].sign = 1.0;
    SetAngularRows(ContactAngularRows(c.frame, c.point_b, m.position, m.rotation), body,
                   &c.jacobian.side[0]);
    c.jacobian.side[1].body = kWorld;

    const Eigen::Vector4d gamma =
        SideVelocity(c.jacobian, c.jacobian.side[0], m.linear_velocity, m.angular_velocity_body);
    const Eigen::Vector3d v_p = m.PointVelocity(p);
    const Eigen::Vector3d omega_world = m.AngularVelocityWorld();
    EXPECT_NEAR(gamma[kNormal], v_p.z(), 1e-12);
    EXPECT_NEAR(gamma[kTangent1], v_p.x(), 1e-12);
    EXPECT_NEAR(gamma[kTangent2], v_p.y(), 1e-12);
    EXPECT_NEAR(gamma[kDrilling], omega_world.z(), 1e-12);

    // W (6 × 4) from the world formula; G = WᵀM⁻¹W (16)
    const Eigen::MatrixXd w = ExplicitW(c, bodies);
    const Eigen::Matrix4d g = w.transpose() * InverseMassMatrix({body}) * w;
    const Eigen::Matrix4d block =
        SideDelassusBlock(body, c.jacobian, c.jacobian.side[0], c.jacobian, c.jacobian.side[0]);
    EXPECT_LT((block - g).norm(), 1e-9 * g.norm());
    const Eigen::Matrix4d own = OwnDelassusBlock(body, c.jacobian.side[0]);
    EXPECT_LT((own - g).norm(), 1e-9 * g.norm());
    // and W Λ = (LᵀΛ, JᵀΛ), the impulse the simulator applies
    const Eigen::Vector4d lambda(0.3, -0.1, 0.2, 0.05);
    EXPECT_LT((GeneralizedImpulse(c, 1, lambda) - w * lambda).norm(), 1e-12);
  }
}

TEST(ContactKinematics, ContactsOverTwoBodiesMatchTheWorldFrameRelativeVelocity) {
  // random poses: contact 0 between bodies 0 (A) and 1 (B), contact 1 between 1 (A) and 0 (B),
  // contact 2 of body 1 (B) with the world (A), each with a random frame and points P_A, P_B.
  // SideVelocity summed over the sides is the velocity of P_B minus that of P_A along n, t1, t2
  // and the spin of B minus that of A about n; the SideDelassusBlock sums are W_iᵀ M⁻¹ W_j with
  // W_i the 12 × 4 matrix of the world formula.
  RandomMotion random(20240611);
  const std::vector<BodyInertia> inertia = {
      MakeBodyInertia(0.3, Eigen::Vector3d(1e-3, 2e-3, 2.5e-3).asDiagonal()),
      MakeBodyInertia(1.7, (Eigen::Matrix3d() << 4e-2, 1e-3, -2e-3,  //
                            1e-3, 3e-2, 5e-4,                        //
                            -2e-3, 5e-4, 2e-2)
                               .finished())};
  const Eigen::MatrixXd m_inverse = InverseMassMatrix(inertia);
  for (int trial = 0; trial < 100; ++trial) {
    const std::vector<BodyMotion> bodies = {RandomBodyMotion(&random), RandomBodyMotion(&random)};
    const TwoSidedContact contacts[3] = {MakeContact(bodies, inertia, 0, 1, &random),
                                         MakeContact(bodies, inertia, 1, 0, &random),
                                         MakeContact(bodies, inertia, kWorld, 1, &random)};
    Eigen::MatrixXd w[3];
    for (int i = 0; i < 3; ++i) {
      const TwoSidedContact& c = contacts[i];
      ExpectOrthonormalFrame(c.frame);
      const Eigen::Vector4d gamma = RelativeVelocity(c, bodies);
      const Eigen::Vector4d expected = WorldRelativeVelocity(c, bodies);
      EXPECT_LT((gamma - expected).norm(), 1e-12) << "contact " << i << ": " << gamma.transpose()
                                                  << " vs " << expected.transpose();
      w[i] = ExplicitW(c, bodies);
      ASSERT_EQ(w[i].rows(), 12);
      const Eigen::Vector4d lambda(0.3, -0.1, 0.2, 0.05);
      EXPECT_LT((GeneralizedImpulse(c, 2, lambda) - w[i] * lambda).norm(), 1e-12) << i;
    }
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const Eigen::Matrix4d g = w[i].transpose() * m_inverse * w[j];
        EXPECT_LT((DelassusBlock(inertia, contacts[i], contacts[j]) - g).norm(), 1e-9 * g.norm())
            << "G_" << i << j;
      }
    }
  }
}

}  // namespace
}  // namespace nonsmooth_sim
