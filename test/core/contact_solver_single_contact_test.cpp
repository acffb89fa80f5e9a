// ContactSolver on single contacts with exact answers (separation, stiction, sliding with and
// without drilling) and two coupled frictionless contacts against the enumerated LCP
// (contact_solver_support.h).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "contact_solver_support.h"

namespace nonsmooth_sim {
namespace {

using namespace contact_solver_support;  // NOLINT(build/namespaces)

// ============================== single contacts with exact answers ==============================

TEST(SingleContact, SeparationGivesZero) {
  for (FrictionSet set : kAllFrictionSets) {
    for (double mu : {0.0, 0.4}) {
      const ContactLaw law = MakeLaw(set, mu, 0.05);
      const int dim = ContactDimension(law);
      const Eigen::VectorXd g = Eigen::Vector4d(2.0, 3.0, 3.0, 50.0).head(dim);
      // c_N > 0: the contact opens, whatever the tangential velocities
      const Eigen::VectorXd c = Eigen::Vector4d(0.5, 0.3, -0.2, 0.1).head(dim);
      for (SolverType type : kAllSolverTypes) {
        ContactSolver solver;
        Eigen::VectorXd lambda = Eigen::VectorXd::Ones(dim);  // a wrong warm start
        const SolverStatistics stats = solver.Solve(SingleContact(law, g, c), Tight(type), &lambda);
        EXPECT_TRUE(stats.converged);
        EXPECT_EQ(lambda, Eigen::VectorXd::Zero(dim)) << FrictionSetName(set) << " μ=" << mu;
        EXPECT_TRUE(stats.normal_projected[0]);
      }
    }
  }
}

TEST(SingleContact, StictionIsTheUnconstrainedSolution) {
  // Λ* = (1, 0.1, -0.05, 0.001) lies inside every set with μ = 0.3, R̄ = 0.02; c = -GΛ*
  const Eigen::Vector4d expected(1.0, 0.1, -0.05, 0.001);
  const Eigen::Vector4d g(2.0, 3.0, 5.0, 700.0);
  for (FrictionSet set : kAllFrictionSets) {
    const ContactLaw law = MakeLaw(set, 0.3, 0.02);
    const int dim = ContactDimension(law);
    const Eigen::VectorXd c = -g.head(dim).cwiseProduct(expected.head(dim));
    for (SolverType type : kAllSolverTypes) {
      ContactSolver solver;
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(dim);
      const SolverStatistics stats =
          solver.Solve(SingleContact(law, g.head(dim), c), Tight(type), &lambda);
      ASSERT_TRUE(stats.converged) << FrictionSetName(set);
      for (int k = 0; k < dim; ++k) {
        // (43) converges at 1 - g_N/g_τ per iteration: error ≈ 350 × the last change
        EXPECT_NEAR(lambda[k], expected[k], 1e-10 * std::abs(expected[k]))
            << FrictionSetName(set) << " " << SolverTypeName(type) << " component " << k;
      }
      EXPECT_FALSE(stats.friction_projected[0]);
      EXPECT_FALSE(stats.normal_projected[0]);
    }
  }
}

TEST(SingleContact, SlidingWithoutDrillingOpposesTheSlip) {
  // G = diag(2, 3, 3), c = (-2, 4, -3): Λ_N = 1, |c_T| = 5 > g_T μΛ_N = 0.9, so
  // Λ_T = -μΛ_N c_T/|c_T| = (-0.24, 0.18) and ξ_T = c_T + g_T Λ_T = (3.28, -2.46) ∥ -Λ_T.
  const Eigen::Vector3d g(2.0, 3.0, 3.0);
  const Eigen::Vector3d c(-2.0, 4.0, -3.0);
  const Eigen::Vector3d expected(1.0, -0.24, 0.18);
  // coulomb, and every law without drilling (R̄ = 0 → the disk)
  for (FrictionSet set : kAllFrictionSets) {
    const ContactLaw law = MakeLaw(set, 0.3, set == FrictionSet::kCoulomb ? 0.05 : 0.0);
    ASSERT_EQ(ContactDimension(law), 3);
    for (SolverType type : kAllSolverTypes) {
      ContactSolver solver;
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(3);
      const SolverStatistics stats = solver.Solve(SingleContact(law, g, c), Tight(type), &lambda);
      ASSERT_TRUE(stats.converged);
      EXPECT_LT((lambda - expected).norm(), 1e-12) << FrictionSetName(set);
      EXPECT_TRUE(stats.friction_projected[0]);
      const Eigen::Vector2d xi_t = c.tail<2>() + g.tail<2>().cwiseProduct(lambda.tail<2>());
      EXPECT_NEAR(xi_t.normalized().dot(lambda.tail<2>().normalized()), -1.0, 1e-12);
    }
  }
}

TEST(SingleContact, SlidingAndSpinningWithDrilling) {
  const double rbar = 0.02;
  const double mu = 0.3;
  // Λ_N = -c_N/g_N = 1.5, radius ρ = 0.45
  const Eigen::Vector4d g(2.0, 3.0, 3.0, 400.0);
  const double lambda_n = 1.5;
  const double rho = mu * lambda_n;
  for (FrictionSet set : {FrictionSet::kCylinder, FrictionSet::kEllipsoid, FrictionSet::kSphere,
                          FrictionSet::kExact}) {
    const ContactLaw law = MakeLaw(set, mu, rbar);
    std::vector<std::pair<Eigen::Vector4d, Eigen::Vector4d>> cases;  // (c, exact Λ)
    // pure sliding (c_τ = 0): every set's equator is the disk: Λ_T = -ρ c_T/|c_T|, Λ_τ = 0
    cases.push_back({Eigen::Vector4d(-3.0, 2.4, -3.2, 0.0),
                     Eigen::Vector4d(lambda_n, -rho * 0.6, rho * 0.8, 0.0)});
    // pure spin (c_T = 0): Λ_T = 0, Λ_τ = -sign(c_τ) R̄ρ (|c_τ| = 5 > g_τ R̄ρ = 3.6)
    cases.push_back({Eigen::Vector4d(-3.0, 0.0, 0.0, 5.0),
                     Eigen::Vector4d(lambda_n, 0.0, 0.0, -rbar * rho)});
    // R̄ c_τ = 4 is comparable to |c_T| = 4: both friction components matter
    const Eigen::Vector4d spin_and_slide(-3.0, 2.4, -3.2, 200.0);
    if (set == FrictionSet::kCylinder) {
      // C_F is a product: the disk and the interval separately
      cases.push_back({spin_and_slide, Eigen::Vector4d(lambda_n, -rho * 0.6, rho * 0.8, -rbar * rho)});
    } else if (set != FrictionSet::kExact) {
      // E_F: Λ_k = -c_k / (g_k + ν m_k) with m = (1, 1, 1/R̄²)/ρ² and ν > 0 on the boundary
      const auto point = [&](double nu) {
        const double t = 1.0 / (g[1] + nu / (rho * rho));
        const double s = 1.0 / (g[3] + nu / (rbar * rbar * rho * rho));
        return Eigen::Vector4d(lambda_n, -spin_and_slide[1] * t, -spin_and_slide[2] * t,
                               -spin_and_slide[3] * s);
      };
      const auto level = [&](double nu) {
        const Eigen::Vector4d p = point(nu);
        return std::pow(p.segment<2>(1).norm() / rho, 2) + std::pow(p[3] / (rbar * rho), 2);
      };
      double lo = 0.0;
      double hi = 1.0;
      while (level(hi) > 1.0) hi *= 2.0;
      for (int k = 0; k < 200; ++k) (level(0.5 * (lo + hi)) > 1.0 ? lo : hi) = 0.5 * (lo + hi);
      cases.push_back({spin_and_slide, point(0.5 * (lo + hi))});
    }
    for (const auto& [c, expected] : cases) {
      for (SolverType type : kAllSolverTypes) {
        ContactSolver solver;
        Eigen::VectorXd lambda = Eigen::VectorXd::Zero(4);
        const ContactProblem problem = SingleContact(law, g, c);
        const SolverStatistics stats = solver.Solve(problem, Tight(type), &lambda);
        ASSERT_TRUE(stats.converged) << FrictionSetName(set) << " " << SolverTypeName(type);
        EXPECT_TRUE(NearSolution(problem, lambda, expected, 1e-9))
            << FrictionSetName(set) << " " << SolverTypeName(type) << " c = " << c.transpose();
        EXPECT_TRUE(stats.friction_projected[0]);
        EXPECT_TRUE(SatisfiesInclusion(problem, lambda, 1e-8))
            << FrictionSetName(set) << " " << SolverTypeName(type) << " c = " << c.transpose()
            << " Λ = " << lambda.transpose();
      }
    }
    // coupled slide and spin on B_F: no closed form, the inclusion is checked independently
    if (set == FrictionSet::kExact) {
      ContactSolver solver;
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(4);
      const ContactProblem problem = SingleContact(law, g, spin_and_slide);
      ASSERT_TRUE(solver.Solve(problem, Tight(SolverType::kModifiedJacobi), &lambda).converged);
      EXPECT_TRUE(SatisfiesInclusion(problem, lambda, 1e-7));
      EXPECT_GT(lambda.segment<2>(1).norm(), 0.1 * rho);
      EXPECT_GT(std::abs(lambda[3]), 0.1 * rbar * rho);
    }
  }
}

TEST(SingleContact, FrictionlessContactHasOneComponent) {
  const ContactLaw law = MakeLaw(FrictionSet::kExact, 0.0, 0.05);
  ASSERT_EQ(ContactDimension(law), 1);
  for (SolverType type : kAllSolverTypes) {
    ContactSolver solver;
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(1);
    solver.Solve(SingleContact(law, Eigen::VectorXd::Constant(1, 4.0), Eigen::VectorXd::Constant(1, -3.0)),
                 Tight(type), &lambda);
    EXPECT_DOUBLE_EQ(lambda[0], 0.75);
    solver.Solve(SingleContact(law, Eigen::VectorXd::Constant(1, 4.0), Eigen::VectorXd::Constant(1, 3.0)),
                 Tight(type), &lambda);
    EXPECT_EQ(lambda[0], 0.0);
  }
}

TEST(SingleContact, FrictionRadiusUsesTheNewNormalPercussion) {
  // One iteration from Λ = 0: Λ_N¹ = -r c_N > 0 and the friction set already has radius μΛ_N¹
  // (with the old Λ_N = 0 it would be the point 0). G = I, so r = α = 1.
  const ContactLaw law = MakeLaw(FrictionSet::kCoulomb, 0.5, 0.0);
  SolverOptions options = Tight(SolverType::kModifiedJacobi);
  options.max_iterations = 1;
  ContactSolver solver;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(3);
  solver.Solve(SingleContact(law, Eigen::Vector3d::Ones(), Eigen::Vector3d(-2.0, 30.0, -40.0)),
               options, &lambda);
  EXPECT_DOUBLE_EQ(lambda[0], 2.0);
  EXPECT_NEAR(lambda[1], -1.0 * 0.6, 1e-15);
  EXPECT_NEAR(lambda[2], 1.0 * 0.8, 1e-15);
}

TEST(FrictionlessContacts, TwoCoupledContactsMatchTheEnumeratedLcp) {
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const ContactLaw law = MakeLaw(FrictionSet::kSphere, 0.0, 0.0);
  int gauss_seidel_faster = 0;
  int interior = 0;
  for (int trial = 0; trial < 50; ++trial) {
    ContactProblem problem;
    problem.contacts = {{0, law}, {1, law}};
    const double coupling = 0.9 * unit(rng);
    problem.G = Eigen::Matrix2d{{1.0, coupling}, {coupling, 1.0}} * (1.0 + unit(rng) * 0.5);
    problem.c = Eigen::Vector2d(unit(rng), unit(rng));
    // the LCP 0 ≤ Λ ⊥ GΛ + c ≥ 0 by enumeration of the four active sets
    Eigen::Vector2d expected = Eigen::Vector2d::Constant(std::nan(""));
    for (int active = 0; active < 4; ++active) {
      Eigen::Vector2d candidate = Eigen::Vector2d::Zero();
      if (active == 3) {
        candidate = problem.G.ldlt().solve(-problem.c);
      } else if (active > 0) {
        const int k = active - 1;
        candidate[k] = -problem.c[k] / problem.G(k, k);
      }
      const Eigen::Vector2d xi = problem.G * candidate + problem.c;
      if ((candidate.array() >= 0).all() && (xi.array() >= -1e-14).all()) expected = candidate;
    }
    ASSERT_TRUE(expected.allFinite());
    int iterations[2] = {0, 0};
    for (SolverType type : kAllSolverTypes) {
      ContactSolver solver;
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(2);
      const SolverStatistics stats = solver.Solve(problem, Tight(type), &lambda);
      ASSERT_TRUE(stats.converged);
      EXPECT_LT((lambda - expected).norm(), 1e-11) << SolverTypeName(type);
      if (type == SolverType::kModifiedJacobi) iterations[0] = stats.iterations;
      if (type == SolverType::kGaussSeidel) iterations[1] = stats.iterations;
    }
    // both contacts closed: a linear system where Gauss-Seidel converges at the square of the
    // Jacobi rate (2 × 2, consistently ordered)
    if ((expected.array() > 0).all() && std::abs(coupling) > 0.3) {
      ++interior;
      gauss_seidel_faster += iterations[1] < iterations[0] ? 1 : 0;
    }
  }
  EXPECT_GT(interior, 3);
  EXPECT_EQ(gauss_seidel_faster, interior);
}

}  // namespace
}  // namespace nonsmooth_sim
