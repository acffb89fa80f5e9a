// The paper's central claim (E_F directly = S_F through the transformation) and the iteration
// counts of (43) against (46) on badly scaled problems (contact_solver_support.h).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "contact_solver_support.h"
#include "dense_transformation.h"  // ContactMapDiagonal

namespace nonsmooth_sim {
namespace {

using namespace contact_solver_support;  // NOLINT(build/namespaces)

// ============================== the paper's central claim ==============================

TEST(CentralClaim, EllipsoidDirectlyAndSphereThroughTheTransformationAgree) {
  std::mt19937_64 rng(kSeed + 4);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int on_boundary = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int m = 1 + trial % 3;
    std::vector<ContactLaw> laws;
    for (int i = 0; i < m; ++i) {
      laws.push_back(MakeLaw(FrictionSet::kEllipsoid, 0.1 + 0.5 * unit(rng), 0.005 + 0.1 * unit(rng)));
    }
    ContactProblem ellipsoid = trial % 2 == 0 ? RandomProblem(laws, rng)
                                              : Construct(laws, RandomRegimes(m, rng), rng).problem;
    ContactProblem sphere = ellipsoid;
    for (ContactBlock& contact : sphere.contacts) contact.law.friction_set = FrictionSet::kSphere;
    double min_rbar = 1.0;
    for (const ContactLaw& law : laws) min_rbar = std::min(min_rbar, law.rbar);
    for (SolverType type : kAllSolverTypes) {
      // (43) on S_F needs ~ max/min of diag(Ĝ_ii) ∝ 1/R̄² iterations (see BadlyScaled): only
      // the better scaled trials for it
      if (type == SolverType::kJacobi && min_rbar < 0.03) continue;
      ContactSolver solver;
      Eigen::VectorXd direct = Eigen::VectorXd::Zero(ellipsoid.c.size());
      Eigen::VectorXd transformed = direct;
      const SolverOptions options = Convergent(type, ellipsoid);
      const SolverStatistics direct_stats = solver.Solve(ellipsoid, options, &direct);
      const SolverStatistics transformed_stats = solver.Solve(sphere, options, &transformed);
      ASSERT_TRUE(direct_stats.converged && transformed_stats.converged)
          << "trial " << trial << " " << SolverTypeName(type) << ": " << Describe(ellipsoid)
          << " iterations " << direct_stats.iterations << " / " << transformed_stats.iterations;
      EXPECT_TRUE(NearSolution(ellipsoid, transformed, direct, 1e-9))
          << "trial " << trial << " " << SolverTypeName(type);
      EXPECT_EQ(direct_stats.friction_projected, transformed_stats.friction_projected);
      for (bool projected : direct_stats.friction_projected) on_boundary += projected ? 1 : 0;
    }
  }
  EXPECT_GT(on_boundary, 30);
}

// ============================== (43) against (46) ==============================

TEST(BadlyScaled, ModifiedIterationNeedsFarFewerIterations) {
  // The sphere law maps Λ_τ to Λ̂_τ = Λ_τ/R̄, so Ĝ_ττ = R̄²G_ττ: R̄ is chosen to make the diagonal of
  // Ĝ_ii span 1e4. A sticking contact (non-projecting) is where (46) takes effect.
  std::mt19937_64 rng(kSeed + 5);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<ContactLaw> laws = {MakeLaw(FrictionSet::kSphere, 0.4, 1.0)};
    Constructed constructed = Construct(laws, {Regime::kSticking}, rng);
    ContactProblem& problem = constructed.problem;
    const Eigen::Vector4d diagonal = problem.G.diagonal();
    const double rbar = 1e-2 * std::sqrt(diagonal.head<3>().maxCoeff() / diagonal[3]);
    problem.contacts[0].law.rbar = rbar;
    // rebuild the sticking solution inside the rescaled set: Λ_τ scales with R̄
    const Eigen::VectorXd xi = problem.G * constructed.solution + problem.c;
    constructed.solution[3] *= rbar;
    problem.c = xi - problem.G * constructed.solution;
    const Eigen::Vector4d a = ContactMapDiagonal(problem.contacts[0].law);
    const Eigen::Vector4d g_hat_diagonal = a.cwiseProduct(a).cwiseProduct(diagonal);
    ASSERT_NEAR(g_hat_diagonal.maxCoeff() / g_hat_diagonal.minCoeff(), 1e4, 1e-6 * 1e4);

    SolverOptions options = Tight(SolverType::kJacobi);
    options.tolerance_rel = 1e-10;
    options.max_iterations = 1000000;
    options.direct_solve = false;  // the iteration itself, without the direct solve
    ContactSolver solver;
    Eigen::VectorXd lambda_43 = Eigen::VectorXd::Zero(4);
    const SolverStatistics stats_43 = solver.Solve(problem, options, &lambda_43);
    options.type = SolverType::kModifiedJacobi;
    Eigen::VectorXd lambda_46 = Eigen::VectorXd::Zero(4);
    const SolverStatistics stats_46 = solver.Solve(problem, options, &lambda_46);
    ASSERT_TRUE(stats_43.converged && stats_46.converged);
    EXPECT_TRUE(NearSolution(problem, lambda_46, constructed.solution, 1e-7));
    EXPECT_TRUE(NearSolution(problem, lambda_43, constructed.solution, 1e-5));
    EXPECT_GE(stats_43.iterations, 10 * stats_46.iterations)
        << "(43): " << stats_43.iterations << ", (46): " << stats_46.iterations;
    std::printf("badly scaled trial %d: (43) %d iterations, (46) %d iterations\n", trial,
                stats_43.iterations, stats_46.iterations);
  }
}

TEST(BadlyScaled, ModifiedIterationSolvesADiagonalStictionProblemInOneStep) {
  // ellipsoid law on its original set: G_ττ = 1e4 G_NN. (43) steps r = 1/max_k G_kk for every
  // component, so Λ_N converges at 1 - 1e-4 per iteration; (46) steps each component by 1/G_kk,
  // which solves a diagonal problem exactly in one iteration (the second only confirms it).
  const ContactLaw law = MakeLaw(FrictionSet::kEllipsoid, 0.3, 0.02);
  const Eigen::Vector4d g(1.0, 2.0, 2.0, 1e4);
  const Eigen::Vector4d expected(1.0, 0.1, -0.05, 0.001);
  const ContactProblem problem = SingleContact(law, g, -g.cwiseProduct(expected));
  SolverOptions options = Tight(SolverType::kModifiedJacobi);
  options.tolerance_rel = 1e-10;
  options.direct_solve = false;  // the iteration itself, without the direct solve
  for (SolverType type : {SolverType::kModifiedJacobi, SolverType::kGaussSeidel}) {
    options.type = type;
    ContactSolver solver;
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(4);
    const SolverStatistics stats = solver.Solve(problem, options, &lambda);
    EXPECT_EQ(stats.iterations, 2) << SolverTypeName(type);
    EXPECT_LT((lambda - expected).norm(), 1e-14);
  }
  // (43) needs ln(1e10)/1e-4 ≈ 230000 iterations for the distance 1e-10 (see StoppingRule)
  options.type = SolverType::kJacobi;
  options.max_iterations = 1000000;
  ContactSolver solver;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(4);
  const SolverStatistics stats = solver.Solve(problem, options, &lambda);
  EXPECT_TRUE(stats.converged);
  EXPECT_GT(stats.iterations, 10000);
  EXPECT_LT((lambda - expected).norm(), 1e-9);
}

}  // namespace
}  // namespace nonsmooth_sim
