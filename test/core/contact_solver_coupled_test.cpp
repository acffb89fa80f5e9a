// ContactSolver on coupled rigid-body Delassus matrices (contact_solver_support.h): every scheme
// finds the constructed solution, the schemes agree on random problems, and the padded block form
// the Simulator assembles reproduces the dense one.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "contact_solver_support.h"

namespace nonsmooth_sim {
namespace {

using namespace contact_solver_support;  // NOLINT(build/namespaces)

// ============================== coupled problems ==============================

TEST(ConstructedProblems, EverySchemeFindsTheConstructedSolution) {
  std::mt19937_64 rng(kSeed + 1);
  for (int trial = 0; trial < 60; ++trial) {
    const int m = 1 + trial % 3;
    const Constructed constructed = Construct(RandomLaws(m, rng), RandomRegimes(m, rng), rng);
    for (SolverType type : kAllSolverTypes) {
      const SolverOptions options = Convergent(type, constructed.problem);
      ContactSolver solver;
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(constructed.solution.size());
      const SolverStatistics stats = solver.Solve(constructed.problem, options, &lambda);
      ASSERT_TRUE(stats.converged) << "trial " << trial << " " << SolverTypeName(type)
                                   << " residual " << stats.residual << ": "
                                   << Describe(constructed.problem, constructed.regimes);
      EXPECT_TRUE(NearSolution(constructed.problem, lambda, constructed.solution, 1e-8))
          << "trial " << trial << " " << SolverTypeName(type);
      EXPECT_TRUE(SatisfiesInclusion(constructed.problem, lambda, 1e-7)) << "trial " << trial;
      for (int i = 0; i < m; ++i) {
        const Regime regime = constructed.regimes[i];
        EXPECT_EQ(stats.normal_projected[i], regime == Regime::kSeparated);
        if (ContactDimension(constructed.problem.contacts[i].law) > 1) {
          EXPECT_EQ(stats.friction_projected[i], regime != Regime::kSticking)
              << "trial " << trial << " contact " << i;
        }
      }
    }
  }
}

TEST(ConstructedProblems, WarmStartFromTheSolutionStopsAfterOneIteration) {
  std::mt19937_64 rng(kSeed + 2);
  for (int trial = 0; trial < 20; ++trial) {
    const int m = 1 + trial % 3;
    const Constructed constructed = Construct(RandomLaws(m, rng), RandomRegimes(m, rng), rng);
    for (SolverType type : kAllSolverTypes) {
      SolverOptions options = Convergent(type, constructed.problem);
      options.tolerance_rel = 1e-10;
      ContactSolver solver;
      Eigen::VectorXd lambda = constructed.solution;
      const SolverStatistics stats = solver.Solve(constructed.problem, options, &lambda);
      EXPECT_TRUE(stats.converged);
      EXPECT_EQ(stats.iterations, 1) << "trial " << trial << " " << SolverTypeName(type) << ": "
                                     << Describe(constructed.problem, constructed.regimes);
    }
  }
}

TEST(RandomProblems, JacobiModifiedJacobiAndGaussSeidelAgree) {
  std::mt19937_64 rng(kSeed + 3);
  int sliding = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int m = 1 + trial % 3;
    const ContactProblem problem = RandomProblem(RandomLaws(m, rng), rng);
    Eigen::VectorXd reference;
    for (SolverType type : kAllSolverTypes) {
      ContactSolver solver;
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(problem.c.size());
      const SolverStatistics stats = solver.Solve(problem, Convergent(type, problem), &lambda);
      ASSERT_TRUE(stats.converged) << "trial " << trial << " " << SolverTypeName(type) << ": "
                                   << Describe(problem);
      EXPECT_TRUE(SatisfiesInclusion(problem, lambda, 1e-7))
          << "trial " << trial << " " << SolverTypeName(type);
      if (type == SolverType::kJacobi) {
        reference = lambda;
        for (bool projected : stats.friction_projected) sliding += projected ? 1 : 0;
      } else {
        EXPECT_TRUE(NearSolution(problem, lambda, reference, 1e-8))
            << "trial " << trial << " " << SolverTypeName(type);
      }
    }
  }
  EXPECT_GT(sliding, 10);
}

// The block form (what the Simulator assembles): the same problem in padded 4 x 4 blocks, with
// arbitrary finite values beyond each contact's dimension, gives the dense form's percussions bit
// for bit, zero beyond the dimension; the padding is ignored, not merely small.
TEST(BlockProblems, PaddingIsIgnoredAndTheDenseSolutionIsReproduced) {
  std::mt19937_64 rng(kSeed + 11);
  std::uniform_real_distribution<double> garbage(-1e3, 1e3);
  int padded = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int m = 1 + trial % 4;
    const ContactProblem dense = RandomProblem(RandomLaws(m, rng), rng);
    BlockContactProblem blocks;
    blocks.Resize(m);
    std::vector<Eigen::Vector4d> block_lambda(static_cast<std::size_t>(m));
    for (int i = 0; i < m; ++i) {
      const ContactBlock& a = dense.contacts[static_cast<std::size_t>(i)];
      const int da = ContactDimension(a.law);
      padded += 4 - da;
      blocks.laws[static_cast<std::size_t>(i)] = a.law;
      Eigen::Vector4d& c = blocks.c[static_cast<std::size_t>(i)];
      for (int k = 0; k < 4; ++k) c[k] = k < da ? dense.c[a.offset + k] : garbage(rng);
      for (int k = 0; k < 4; ++k) block_lambda[static_cast<std::size_t>(i)][k] = garbage(rng);
      for (int j = 0; j < m; ++j) {
        const ContactBlock& b = dense.contacts[static_cast<std::size_t>(j)];
        const int db = ContactDimension(b.law);
        Eigen::Matrix4d& g = blocks.G[static_cast<std::size_t>(i * m + j)];
        for (int l = 0; l < 4; ++l) {
          for (int k = 0; k < 4; ++k) {
            g(l, k) = l < da && k < db ? dense.G(a.offset + l, b.offset + k) : garbage(rng);
          }
        }
      }
    }
    // the warm start: zero in the dense form, garbage beyond the dimension in the block form
    for (int i = 0; i < m; ++i) {
      const int da = ContactDimension(dense.contacts[static_cast<std::size_t>(i)].law);
      for (int k = 0; k < da; ++k) block_lambda[static_cast<std::size_t>(i)][k] = 0.0;
    }
    for (SolverType type : kAllSolverTypes) {
      const SolverOptions options = Convergent(type, dense);
      ContactSolver dense_solver;
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(dense.c.size());
      const SolverStatistics expected = dense_solver.Solve(dense, options, &lambda);
      ContactSolver block_solver;
      std::vector<Eigen::Vector4d> solution = block_lambda;
      SolverStatistics stats;
      block_solver.SolvePrevalidated(blocks, options, &solution, &stats);
      EXPECT_EQ(stats.iterations, expected.iterations) << trial;
      EXPECT_EQ(stats.converged, expected.converged) << trial;
      for (int i = 0; i < m; ++i) {
        const ContactBlock& a = dense.contacts[static_cast<std::size_t>(i)];
        const int da = ContactDimension(a.law);
        for (int k = 0; k < 4; ++k) {
          const double want = k < da ? lambda[a.offset + k] : 0.0;
          EXPECT_EQ(solution[static_cast<std::size_t>(i)][k], want)
              << "trial " << trial << " " << SolverTypeName(type) << " contact " << i << " k " << k;
        }
      }
    }
  }
  EXPECT_GT(padded, 20);  // the laws drawn include 1- and 3-component contacts
}

// One contact (the Simulator's lone-contact islands): SolveOnePrevalidated gives the block
// solve's percussion, iterations, residual and flags bit for bit, for every set and solver, also
// from a solver whose workspace a larger problem sized before (it reads slot 0 alone) and with
// the exact prox's hint carried in and out.
TEST(BlockProblems, OneContactSolveReproducesTheBlockSolve) {
  std::mt19937_64 rng(kSeed + 12);
  int sliding = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const ContactProblem dense = RandomProblem(RandomLaws(1, rng), rng);
    const ContactLaw& law = dense.contacts[0].law;
    const int dim = ContactDimension(law);
    BlockContactProblem blocks;
    blocks.Resize(1);
    blocks.laws[0] = law;
    blocks.G[0].setZero();
    blocks.c[0].setZero();
    blocks.G[0].topLeftCorner(dim, dim) = dense.G;
    blocks.c[0].head(dim) = dense.c;
    for (SolverType type : kAllSolverTypes) {
      const SolverOptions options = Convergent(type, dense);
      ContactSolver block_solver;
      std::vector<Eigen::Vector4d> expected(1, Eigen::Vector4d::Zero());
      std::vector<double> expected_hint(1, std::numeric_limits<double>::quiet_NaN());
      SolverStatistics expected_stats;
      block_solver.SolvePrevalidated(blocks, options, &expected, &expected_stats, &expected_hint);

      ContactSolver one_solver;
      if (trial % 2 == 1) {  // a workspace left by a problem of three contacts
        const ContactProblem larger = RandomProblem(RandomLaws(3, rng), rng);
        Eigen::VectorXd lambda = Eigen::VectorXd::Zero(larger.c.size());
        one_solver.Solve(larger, Convergent(type, larger), &lambda);
      }
      Eigen::Vector4d lambda = Eigen::Vector4d::Zero();
      double hint = std::numeric_limits<double>::quiet_NaN();
      SolverStatistics stats;
      one_solver.SolveOnePrevalidated(blocks.G[0], blocks.c[0], law, options, &lambda, &stats,
                                      &hint);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(lambda[k], expected[0][k]) << trial << " k " << k;
      EXPECT_EQ(stats.iterations, expected_stats.iterations) << trial;
      EXPECT_EQ(stats.converged, expected_stats.converged) << trial;
      EXPECT_EQ(stats.residual, expected_stats.residual) << trial;
      EXPECT_EQ(stats.max_change, expected_stats.max_change) << trial;
      EXPECT_EQ(stats.friction_projected[0], expected_stats.friction_projected[0]) << trial;
      EXPECT_EQ(stats.normal_projected[0], expected_stats.normal_projected[0]) << trial;
      if (std::isnan(expected_hint[0])) {
        EXPECT_TRUE(std::isnan(hint)) << trial;
      } else {
        EXPECT_EQ(hint, expected_hint[0]) << trial;
      }
      sliding += expected_stats.friction_projected[0] ? 1 : 0;
    }
  }
  EXPECT_GT(sliding, 10);  // the boundary of the friction sets is reached, not only the interior
}

}  // namespace
}  // namespace nonsmooth_sim
