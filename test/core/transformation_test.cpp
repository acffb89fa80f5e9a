// Section 4 of Möller, Leine, Glocker (ESMC 2009) checked numerically with the maps of
// dense_transformation.h and transformation.h:
// the normal cone map (20)/(25), the prox identity (23)/(31) under R = A⁻ᵀR̂A⁻¹ (29), and on a
// fixed-point problem that the AᵀA-norm prox of (38) is not the Euclidean one while (40) has the
// fixed point of (36).
//
// The reference projections are independent of the library: prox in an S-norm onto an ellipsoid
// {y : ||By|| ≤ ρ} from its Lagrange condition S(y - v) + μBᵀBy = 0, with μ ≥ 0 found by
// bisection on the monotone ||By(μ)||; boxes are checked through their vertices.
#include "dense_transformation.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

namespace nonsmooth_sim {
namespace {

constexpr std::uint64_t kSeed = 20090701;
constexpr int kTrials = 200;
// relative accuracy of the bisection reference projection, with margin for the round-off of the
// maps themselves (condition numbers of A and S are at most 10 here)
constexpr double kTolerance = 1e-9;

Eigen::MatrixXd RandomOrthogonal(int n, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd q(n, n);
  // Gram-Schmidt on Gaussian columns (twice, for orthogonality to round-off)
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) q(i, j) = normal(rng);
    for (int pass = 0; pass < 2; ++pass) {
      for (int k = 0; k < j; ++k) q.col(j) -= q.col(k).dot(q.col(j)) * q.col(k);
    }
    q.col(j).normalize();
  }
  return q;
}

// U diag(s) Vᵀ with singular values in [0.3, 3]: non-singular, condition ≤ 10
Eigen::MatrixXd RandomNonSingular(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> singular(0.3, 3.0);
  Eigen::VectorXd s(n);
  for (int i = 0; i < n; ++i) s[i] = singular(rng);
  return RandomOrthogonal(n, rng) * s.asDiagonal() * RandomOrthogonal(n, rng).transpose();
}

Eigen::MatrixXd RandomSpd(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> eigen(0.3, 3.0);
  Eigen::VectorXd s(n);
  for (int i = 0; i < n; ++i) s[i] = eigen(rng);
  const Eigen::MatrixXd q = RandomOrthogonal(n, rng);
  return q * s.asDiagonal() * q.transpose();
}

Eigen::VectorXd RandomVector(int n, double scale, std::mt19937_64& rng) {
  std::normal_distribution<double> normal(0.0, scale);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = normal(rng);
  return v;
}

// argmin_{||B y|| ≤ rho} ||v - y||_S, S symmetric positive definite, B non-singular.
Eigen::VectorXd ReferenceProx(const Eigen::VectorXd& v, const Eigen::MatrixXd& s,
                              const Eigen::MatrixXd& b, double rho) {
  if ((b * v).norm() <= rho) return v;
  const Eigen::MatrixXd btb = b.transpose() * b;
  const Eigen::VectorXd sv = s * v;
  const auto point = [&](double mu) -> Eigen::VectorXd { return (s + mu * btb).ldlt().solve(sv); };
  double lo = 0.0;
  double hi = 1.0;
  while ((b * point(hi)).norm() > rho) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-17 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((b * point(mid)).norm() > rho ? lo : hi) = mid;
  }
  return point(0.5 * (lo + hi));
}

bool Near(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double tolerance) {
  return (a - b).norm() <= tolerance * std::max(1.0, std::max(a.norm(), b.norm()));
}

// x = prox_C(x + y) with C = {||B x|| ≤ 1}: the prox characterisation (7) of y ∈ N_C(x)
bool InNormalConeOfEllipsoid(const Eigen::VectorXd& y, const Eigen::VectorXd& x,
                             const Eigen::MatrixXd& b) {
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(x.size(), x.size());
  return Near(ReferenceProx(x + y, identity, b, 1.0), x, kTolerance);
}

TEST(NormalConeTransformation, EllipsoidMembershipIsPreserved_20_25) {
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int members = 0;
  int non_members = 0;
  int wrong_map_agrees = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const int n = 2 + trial % 2;
    // C = {x : ||Bx|| ≤ 1}: a ball (B = I) in the first trials, ellipsoids after
    const Eigen::MatrixXd b =
        trial < 20 ? Eigen::MatrixXd::Identity(n, n) : RandomNonSingular(n, rng);
    const Eigen::MatrixXd a = RandomNonSingular(n, rng);
    const Eigen::MatrixXd ba = b * a;  // A⁻¹C = {x̂ : ||BAx̂|| ≤ 1} (19)
    // a boundary point and an element of its normal cone (the constraint gradient BᵀBx)
    Eigen::VectorXd u = RandomVector(n, 1.0, rng);
    u.normalize();
    const Eigen::VectorXd x = b.lu().solve(u);
    const Eigen::VectorXd y = (0.1 + 2.0 * unit(rng)) * b.transpose() * b * x;
    // a vector outside the cone: add a component tangent to the boundary
    Eigen::VectorXd tangent = RandomVector(n, 1.0, rng);
    const Eigen::VectorXd normal = b.transpose() * u;
    tangent -= tangent.dot(normal) / normal.squaredNorm() * normal;
    const Eigen::VectorXd y_out = y + tangent.normalized() * (0.5 + unit(rng)) * y.norm();

    const Eigen::VectorXd x_hat = TransformPercussion(a, x);
    ASSERT_TRUE(InNormalConeOfEllipsoid(y, x, b));
    ASSERT_FALSE(InNormalConeOfEllipsoid(y_out, x, b));
    // (25): y ∈ N_C(x) ⇔ Aᵀy ∈ N_{A⁻¹C}(A⁻¹x)
    EXPECT_TRUE(InNormalConeOfEllipsoid(TransformVelocity(a, y), x_hat, ba)) << "trial " << trial;
    EXPECT_FALSE(InNormalConeOfEllipsoid(TransformVelocity(a, y_out), x_hat, ba))
        << "trial " << trial;
    ++members;
    ++non_members;
    // mapping y like a point (A⁻¹y) instead of Aᵀy breaks (25) for a general A
    wrong_map_agrees += InNormalConeOfEllipsoid(TransformPercussion(a, y), x_hat, ba) ? 1 : 0;

    // interior point: only y = 0 is in the normal cone, on both sides
    const Eigen::VectorXd x_in = x * (0.2 + 0.7 * unit(rng));
    const Eigen::VectorXd x_in_hat = TransformPercussion(a, x_in);
    EXPECT_TRUE(InNormalConeOfEllipsoid(Eigen::VectorXd::Zero(n), x_in_hat, ba));
    EXPECT_FALSE(InNormalConeOfEllipsoid(TransformVelocity(a, y), x_in_hat, ba));
  }
  EXPECT_EQ(members, kTrials);
  EXPECT_EQ(non_members, kTrials);
  EXPECT_LT(wrong_map_agrees, kTrials / 2);
}

TEST(NormalConeTransformation, BoxMembershipIsPreserved_20_25) {
  // C = [-h, h]³; A⁻¹C = {x̂ : -h ≤ Ax̂ ≤ h} is a parallelepiped whose vertices are A⁻¹v. The
  // definition (1) on a polytope: z ∈ N(x) ⇔ zᵀ(v - x) ≤ 0 for every vertex v.
  std::mt19937_64 rng(kSeed + 1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto in_cone = [](const Eigen::Vector3d& z, const Eigen::Vector3d& x,
                          const std::vector<Eigen::Vector3d>& vertices) {
    for (const Eigen::Vector3d& v : vertices) {
      if (z.dot(v - x) > 1e-12 * std::max(1.0, z.norm() * (v - x).norm())) return false;
    }
    return true;
  };
  for (int trial = 0; trial < kTrials; ++trial) {
    const Eigen::Vector3d h(0.5 + unit(rng), 0.5 + unit(rng), 0.5 + unit(rng));
    const Eigen::MatrixXd a = RandomNonSingular(3, rng);
    std::vector<Eigen::Vector3d> vertices;
    std::vector<Eigen::Vector3d> vertices_hat;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d v((corner & 1 ? 1 : -1) * h.x(), (corner & 2 ? 1 : -1) * h.y(),
                              (corner & 4 ? 1 : -1) * h.z());
      vertices.push_back(v);
      vertices_hat.push_back(TransformPercussion(a, v));
    }
    // a point on a face, an edge or a vertex (1-3 active coordinates) and a normal-cone element
    Eigen::Vector3d x;
    Eigen::Vector3d y = Eigen::Vector3d::Zero();
    const int active = 1 + trial % 3;
    for (int k = 0; k < 3; ++k) {
      const double sign = unit(rng) < 0.5 ? -1.0 : 1.0;
      if (k < active) {
        x[k] = sign * h[k];
        y[k] = sign * (0.1 + unit(rng));
      } else {
        x[k] = (2.0 * unit(rng) - 1.0) * 0.9 * h[k];
      }
    }
    // not in the cone: a non-zero component along an inactive coordinate, or a wrong sign
    Eigen::Vector3d y_out = y;
    if (active < 3) {
      y_out[2] = 0.3 + unit(rng);
    } else {
      y_out[0] = -y_out[0];
    }
    ASSERT_TRUE(in_cone(y, x, vertices));
    ASSERT_FALSE(in_cone(y_out, x, vertices));
    const Eigen::Vector3d x_hat = TransformPercussion(a, x);
    EXPECT_TRUE(in_cone(TransformVelocity(a, y), x_hat, vertices_hat)) << "trial " << trial;
    EXPECT_FALSE(in_cone(TransformVelocity(a, y_out), x_hat, vertices_hat)) << "trial " << trial;
  }
}

TEST(ProxTransformation, ProxIdentityUnderTransformedMetric_23_31) {
  std::mt19937_64 rng(kSeed + 2);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int projected = 0;
  int wrong_metric_agrees = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const int n = 2 + trial % 2;
    const Eigen::MatrixXd b = RandomNonSingular(n, rng);
    const double rho = 0.5 + unit(rng);
    const Eigen::MatrixXd a = RandomNonSingular(n, rng);
    const Eigen::MatrixXd r_hat = RandomSpd(n, rng);
    const Eigen::VectorXd x = RandomVector(n, 2.0, rng);
    const Eigen::VectorXd y = RandomVector(n, 2.0, rng);

    // (31) with R = A⁻ᵀR̂A⁻¹ (29)
    const Eigen::MatrixXd r = MetricOnOriginal(a, r_hat);
    const Eigen::VectorXd lhs = ReferenceProx(x + r.ldlt().solve(y), r, b, rho);
    const Eigen::VectorXd x_hat = TransformPercussion(a, x);
    const Eigen::VectorXd rhs_hat =
        ReferenceProx(x_hat + r_hat.ldlt().solve(TransformVelocity(a, y)), r_hat, b * a, rho);
    EXPECT_TRUE(Near(lhs, RestorePercussion(a, rhs_hat), kTolerance)) << "trial " << trial;
    projected += (b * (x + r.ldlt().solve(y))).norm() > rho ? 1 : 0;

    // (23): prox^R_C(x) = A prox^{AᵀRA}_{A⁻¹C}(A⁻¹x) for an arbitrary R
    const Eigen::MatrixXd r_any = RandomSpd(n, rng);
    const Eigen::VectorXd direct = ReferenceProx(x, r_any, b, rho);
    const Eigen::VectorXd mapped = ReferenceProx(x_hat, MetricOnTransformed(a, r_any), b * a, rho);
    EXPECT_TRUE(Near(direct, RestorePercussion(a, mapped), kTolerance)) << "trial " << trial;

    // without (29) (R = R̂) the identity fails
    const Eigen::VectorXd wrong = ReferenceProx(x + r_hat.ldlt().solve(y), r_hat, b, rho);
    wrong_metric_agrees += Near(wrong, RestorePercussion(a, rhs_hat), 1e-6) ? 1 : 0;
  }
  EXPECT_GT(projected, kTrials / 2) << "most samples must exercise the boundary";
  EXPECT_LT(wrong_metric_agrees, kTrials / 4);
}

// The fixed-point problem of one contact's friction part with a fixed ellipsoid C = {||Bx|| ≤ 1}
// and A = B⁻¹, so that A⁻¹C is the unit ball: (36) on C against (38) and (40) on the ball.
TEST(ProxTransformation, EuclideanProxOnMappedSetNeedsTheNormalCone_38_40) {
  std::mt19937_64 rng(kSeed + 3);
  constexpr int kN = 3;
  constexpr int kMaxIterations = 20000;
  constexpr double kConverged = 1e-15;
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(kN, kN);
  int naive_differs = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::MatrixXd b = RandomNonSingular(kN, rng);
    const Eigen::MatrixXd a = b.inverse();
    const Eigen::MatrixXd g = RandomSpd(kN, rng);
    // ξ = GΛ + c with c large: the solution is on the boundary (sliding)
    const Eigen::VectorXd c = RandomVector(kN, 10.0, rng);

    // (37): Λ = prox_C(Λ - r(GΛ + c)), Euclidean prox on the ellipsoid C
    const double r = 1.0 / g.diagonal().maxCoeff();
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(kN);
    for (int k = 0; k < kMaxIterations; ++k) {
      const Eigen::VectorXd next = ReferenceProx(lambda - r * (g * lambda + c), identity, b, 1.0);
      const double change = (next - lambda).norm();
      lambda = next;
      if (change <= kConverged * lambda.norm()) break;
    }

    // (43): the same inclusion through (41) on the ball A⁻¹C with its closed-form prox (59)
    const Eigen::MatrixXd g_hat = TransformDelassus(g, a);
    const Eigen::VectorXd c_hat = TransformVelocity(a, c);
    const double r_hat = 1.0 / g_hat.diagonal().maxCoeff();
    Eigen::VectorXd lambda_hat = Eigen::VectorXd::Zero(kN);
    for (int k = 0; k < kMaxIterations; ++k) {
      const Eigen::VectorXd next =
          ProxBall(lambda_hat - r_hat * (g_hat * lambda_hat + c_hat), 1.0).point;
      const double change = (next - lambda_hat).norm();
      lambda_hat = next;
      if (change <= kConverged * lambda_hat.norm()) break;
    }
    // (47)
    EXPECT_TRUE(Near(RestorePercussion(a, lambda_hat), lambda, 1e-8)) << "trial " << trial;

    // (38): one step of (37) rewritten with (23) needs the prox in the AᵀA norm on the ball ...
    const Eigen::VectorXd z = lambda - r * (g * lambda + c) + RandomVector(kN, 0.5, rng);
    const Eigen::VectorXd step_37 = ReferenceProx(z, identity, b, 1.0);
    const Eigen::VectorXd z_hat = TransformPercussion(a, z);
    const Eigen::VectorXd step_38 = RestorePercussion(
        a, ReferenceProx(z_hat, MetricOnTransformed(a, identity), identity, 1.0));
    EXPECT_TRUE(Near(step_38, step_37, kTolerance)) << "trial " << trial;
    // ... which is not the Euclidean prox on the ball
    const Eigen::VectorXd naive = RestorePercussion(a, ProxBall(z_hat, 1.0).point);
    naive_differs += Near(naive, step_37, 1e-3) ? 0 : 1;
  }
  EXPECT_GT(naive_differs, 30);
}

TEST(ContensouMap, MapsTheBallOntoTheEllipsoid_56_57) {
  std::mt19937_64 rng(kSeed + 4);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < kTrials; ++trial) {
    const double rbar = 1e-4 + unit(rng) * 1e-2;
    const double radius = 1e-6 + unit(rng);
    const Eigen::Matrix3d a = ContensouMap(rbar);
    EXPECT_TRUE(a.isDiagonal());
    Eigen::Vector3d p = RandomVector(3, 1.0, rng);
    p *= radius / p.norm();  // on the boundary of S_F (58)
    const Eigen::Vector3d e = a * p;
    // on the boundary of E_F (55)
    const double level = std::pow(e.head<2>().norm() / radius, 2) +
                         std::pow(e.z() / (rbar * radius), 2);
    EXPECT_NEAR(level, 1.0, 1e-12);
  }
  EXPECT_THROW(ContensouMap(0.0), std::invalid_argument);
  EXPECT_THROW(ContensouMap(-1.0), std::invalid_argument);
  EXPECT_THROW(ContensouMap(std::nan("")), std::invalid_argument);
}

// sphere and the rolling rows (their 3-D part is S_F) are the rows with LawCoordinates::kMapped
TEST(ContensouMap, OnlyTheMappedLawsWithDrillingAreMapped) {
  ContactLaw law;
  law.mu = 0.3;
  law.rbar = 2e-4;
  for (FrictionSet set : kAllFrictionSets) {
    law.friction_set = set;
    const Eigen::Vector4d expected =
        LawOf(set).coordinates == LawCoordinates::kMapped ? Eigen::Vector4d(1, 1, 1, 2e-4)
                                                          : Eigen::Vector4d::Ones();
    EXPECT_EQ(ContactMapDiagonal(law), expected) << FrictionSetName(set);
  }
  law.friction_set = FrictionSet::kSphere;
  law.rbar = 0.0;  // no drilling component: nothing to map
  EXPECT_EQ(ContactMapDiagonal(law), Eigen::Vector4d::Ones());

  // stacked over a problem: contact 0 sphere (4), contact 1 frictionless (1), contact 2 sphere (4)
  ContactProblem problem;
  ContactLaw sphere;
  sphere.mu = 0.3;
  sphere.rbar = 3e-4;
  sphere.friction_set = FrictionSet::kSphere;
  ContactLaw frictionless = sphere;
  frictionless.mu = 0.0;
  problem.contacts = {{0, sphere}, {4, frictionless}, {5, sphere}};
  problem.G = Eigen::MatrixXd::Identity(9, 9);
  problem.c = Eigen::VectorXd::Zero(9);
  Eigen::VectorXd expected(9);
  expected << 1, 1, 1, 3e-4, 1, 1, 1, 1, 3e-4;
  EXPECT_EQ(ProblemMapDiagonal(problem), expected);
}

TEST(DiagonalMaps, AgreeWithTheDenseMaps_41_47) {
  std::mt19937_64 rng(kSeed + 5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int n = 7;
  Eigen::VectorXd a(n);
  for (int k = 0; k < n; ++k) a[k] = (unit(rng) < 0.5 ? -1.0 : 1.0) * (1e-3 + unit(rng));
  const Eigen::MatrixXd dense = a.asDiagonal();
  const Eigen::MatrixXd g = RandomSpd(n, rng);
  const Eigen::VectorXd v = RandomVector(n, 1.0, rng);
  EXPECT_TRUE(TransformDelassusDiagonal(g, a).isApprox(TransformDelassus(g, dense), 1e-14));
  EXPECT_TRUE(TransformVelocityDiagonal(a, v).isApprox(TransformVelocity(dense, v), 1e-14));
  EXPECT_TRUE(TransformPercussionDiagonal(a, v).isApprox(TransformPercussion(dense, v), 1e-12));
  EXPECT_TRUE(RestorePercussionDiagonal(a, v).isApprox(RestorePercussion(dense, v), 1e-14));
  // Ĝ_ij = A_iᵀ G_ij A_j, blockwise
  const Eigen::Matrix4d block = g.topLeftCorner<4, 4>();
  const Eigen::Vector4d a_i = a.head<4>();
  const Eigen::Vector4d a_j = a.segment<4>(3);
  EXPECT_TRUE(TransformBlock(block, a_i, a_j)
                  .isApprox(Eigen::Matrix4d(a_i.asDiagonal()).transpose() * block *
                                Eigen::Matrix4d(a_j.asDiagonal()),
                            1e-14));
  // the map and its inverse
  EXPECT_TRUE(RestorePercussionDiagonal(a, TransformPercussionDiagonal(a, v)).isApprox(v, 1e-14));
}

TEST(TransformationArguments, RejectsSingularAndMismatchedInput) {
  const Eigen::MatrixXd singular = Eigen::Vector3d(1.0, 0.0, 2.0).asDiagonal();
  const Eigen::VectorXd v = Eigen::VectorXd::Ones(3);
  const auto message = [](auto call) {
    try {
      call();
    } catch (const std::invalid_argument& error) {
      return std::string(error.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message([&] { TransformPercussion(singular, v); }).find("non-singular"),
            std::string::npos);
  EXPECT_NE(message([&] { MetricOnOriginal(singular, Eigen::MatrixXd::Identity(3, 3)); })
                .find("non-singular"),
            std::string::npos);
  EXPECT_NE(message([&] { TransformVelocity(Eigen::MatrixXd::Identity(3, 3), Eigen::VectorXd(2)); })
                .find("xi"),
            std::string::npos);
  EXPECT_NE(message([&] { TransformDelassus(Eigen::MatrixXd(2, 3), Eigen::MatrixXd(2, 3)); })
                .find("A"),
            std::string::npos);
  EXPECT_NE(message([&] { TransformPercussionDiagonal(Eigen::Vector3d(1, 0, 1), v); })
                .find("diagonal of A"),
            std::string::npos);
  EXPECT_THROW(RestorePercussionDiagonal(Eigen::Vector3d(1, std::nan(""), 1), v),
               std::invalid_argument);
}

}  // namespace
}  // namespace nonsmooth_sim
