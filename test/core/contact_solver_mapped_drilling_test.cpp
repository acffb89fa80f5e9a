// Exact and cylinder iterated on A⁻¹D (40)-(47) against on D (37): the map follows the option,
// the same solution and projections either way, far fewer iterations on a sliding Tippe-Top
// contact, no heap allocation (contact_solver_support.h).
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "allocation_counter.h"  // NoHeapAllocationEitherWay: the heap allocation count
#include "contact_solver_support.h"
#include "dense_transformation.h"  // ContactMapDiagonal, ProblemMapDiagonal

namespace nonsmooth_sim {
namespace {

using namespace contact_solver_support;  // NOLINT(build/namespaces)

// ======================= exact and cylinder on A⁻¹D (40)-(47) vs on D (37) =======================

TEST(MappedDrillingSets, TheMapFollowsTheOption) {
  const double rbar = 3e-4;
  SolverOptions mapped;
  ASSERT_TRUE(mapped.map_drilling_sets);  // the documented default
  const SolverOptions unmapped = Unmapped(mapped);
  for (FrictionSet set : kAllFrictionSets) {
    const ContactLaw law = MakeLaw(set, 0.3, rbar);
    const bool drilling = ContactDimension(law) == 4;
    const Eigen::Vector4d a(1.0, 1.0, 1.0, rbar);
    const bool maps_with_option = set == FrictionSet::kExact || set == FrictionSet::kCylinder;
    // sphere and the rolling rows (S_F without rolling components) are always mapped
    const bool always = set == FrictionSet::kSphere || set == FrictionSet::kRolling ||
                        set == FrictionSet::kRollingDecoupled;
    EXPECT_EQ(ContactMapDiagonal(law, /*map_drilling_sets=*/true),
              drilling && (maps_with_option || always) ? a : Eigen::Vector4d::Ones())
        << FrictionSetName(set);
    EXPECT_EQ(ContactMapDiagonal(law, /*map_drilling_sets=*/false),
              drilling && always ? a : Eigen::Vector4d::Ones())
        << FrictionSetName(set);
    // the one-argument form is the paper's choice: only the always-mapped rows
    EXPECT_EQ(ContactMapDiagonal(law), ContactMapDiagonal(law, false)) << FrictionSetName(set);
    // R̄ = 0 or μ = 0: no drilling component, nothing mapped
    EXPECT_EQ(ContactMapDiagonal(MakeLaw(set, 0.3, 0.0), true), Eigen::Vector4d::Ones());
    EXPECT_EQ(ContactMapDiagonal(MakeLaw(set, 0.0, rbar), true), Eigen::Vector4d::Ones());
  }
  // stacked: exact (4), frictionless (1), cylinder (4), ellipsoid (4)
  ContactProblem problem;
  problem.contacts = {{0, MakeLaw(FrictionSet::kExact, 0.3, rbar)},
                      {4, MakeLaw(FrictionSet::kExact, 0.0, rbar)},
                      {5, MakeLaw(FrictionSet::kCylinder, 0.3, 2 * rbar)},
                      {9, MakeLaw(FrictionSet::kEllipsoid, 0.3, rbar)}};
  problem.G = Eigen::MatrixXd::Identity(13, 13);
  problem.c = Eigen::VectorXd::Zero(13);
  Eigen::VectorXd expected(13);
  expected << 1, 1, 1, rbar, 1, 1, 1, 1, 2 * rbar, 1, 1, 1, 1;
  EXPECT_EQ(ProblemMapDiagonal(problem, mapped), expected);
  EXPECT_EQ(ProblemMapDiagonal(problem, unmapped), Eigen::VectorXd::Ones(13));
}

TEST(MappedDrillingSets, InverseMappedSetsAreTheSetsWithUnitRbar) {
  // the premise of the mapped prox: x ∈ B_F(R̄) ⇔ A⁻¹x ∈ B_F(1), the same for C_F, with
  // A = diag(1, 1, R̄) (56); checked on points scattered around the boundary and on the curve
  // (51)-(52) itself
  std::mt19937_64 rng(kSeed + 8);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int inside = 0;
  int outside = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const double rbar = 1e-4 + 0.1 * unit(rng);
    const double radius = 0.01 + unit(rng);
    const double angle = 2 * kPi * unit(rng);
    const double t = 1.3 * radius * unit(rng);
    const Eigen::Vector3d x(t * std::cos(angle), t * std::sin(angle),
                            (2 * unit(rng) - 1) * 1.3 * rbar * radius);
    const Eigen::Vector3d x_hat(x.x(), x.y(), x.z() / rbar);  // A⁻¹x
    const bool in_exact = ProxCoulombContensou(x, radius, rbar).region == ProxRegion::kInterior;
    EXPECT_EQ(in_exact,
              ProxCoulombContensou(x_hat, radius, 1.0).region == ProxRegion::kInterior)
        << "x = " << x.transpose() << " R̄ = " << rbar << " radius = " << radius;
    EXPECT_EQ(ProxCylinder(x, radius, rbar).region == ProxRegion::kInterior,
              ProxCylinder(x_hat, radius, 1.0).region == ProxRegion::kInterior);
    (in_exact ? inside : outside) += 1;
    const double u = 4.0 * unit(rng);
    const CoulombContensouBoundaryPoint b = CoulombContensouBoundary(u, radius, rbar);
    const CoulombContensouBoundaryPoint b_hat = CoulombContensouBoundary(u, radius, 1.0);
    EXPECT_EQ(b.b_t, b_hat.b_t);
    EXPECT_NEAR(b.b_tau / rbar, b_hat.b_tau, 1e-14 * radius);
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
}

TEST(MappedDrillingSets, OneJacobiStepOnTheMappedSetIsExactForAUnitScaledDiagonalProblem) {
  // G = diag(1, 1, 1, 400), R̄ = 0.05: Ĝ = AᵀGA = I. In the mapped coordinates r̂ = α = 1 and one
  // step from 0 lands on the solution (normal first, then the friction set of radius μΛ_N¹):
  // Λ_N = 1, ρ = 0.3; Λ̂_F = prox(-ĉ_F) with ĉ_τ = R̄c_τ. On the original sets r = 1/400 and the
  // first iterate is 400 times smaller. Closed forms:
  //   cylinder, c = (-1, 0.5, 0, 10): Λ̂_F = (-0.3, 0, -0.3) (disk and interval separately)
  //   exact, c = (-1, 0, 0, 10): the pole of B_F, Λ̂_τ = -b_τ(0) = -ρ (R̄ = 1)
  //   exact, c = (-1, 0.5, 0, 0): the rim, Λ̂_T = (-ρ, 0)
  const double rbar = 0.05;
  const Eigen::Vector4d g(1.0, 1.0, 1.0, 400.0);
  struct Case {
    FrictionSet set;
    Eigen::Vector4d c;
    Eigen::Vector4d mapped_first;  // = the solution
    Eigen::Vector4d unmapped_first;
  };
  const double r = 1.0 / 400.0;  // unmapped: α / max_k G_kk
  const std::vector<Case> cases = {
      {FrictionSet::kCylinder, Eigen::Vector4d(-1.0, 0.5, 0.0, 10.0),
       Eigen::Vector4d(1.0, -0.3, 0.0, -0.3 * rbar),
       // Λ_N = r, ρ = 0.3r; z_T = -0.5r → -ρ, z_τ = -10r → -R̄ρ
       Eigen::Vector4d(r, -0.3 * r, 0.0, -rbar * 0.3 * r)},
      {FrictionSet::kExact, Eigen::Vector4d(-1.0, 0.0, 0.0, 10.0),
       Eigen::Vector4d(1.0, 0.0, 0.0, -0.3 * rbar), Eigen::Vector4d(r, 0.0, 0.0, -rbar * 0.3 * r)},
      {FrictionSet::kExact, Eigen::Vector4d(-1.0, 0.5, 0.0, 0.0),
       Eigen::Vector4d(1.0, -0.3, 0.0, 0.0), Eigen::Vector4d(r, -0.3 * r, 0.0, 0.0)},
  };
  for (const Case& test : cases) {
    const ContactProblem problem = SingleContact(MakeLaw(test.set, 0.3, rbar), g, test.c);
    SolverOptions options = Tight(SolverType::kJacobi);
    options.max_iterations = 1;
    ContactSolver solver;
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(4);
    solver.Solve(problem, options, &lambda);
    EXPECT_LT((lambda - test.mapped_first).cwiseAbs().maxCoeff(), 1e-15)
        << FrictionSetName(test.set) << " mapped: " << lambda.transpose();
    lambda.setZero();
    solver.Solve(problem, Unmapped(options), &lambda);
    EXPECT_LT((lambda - test.unmapped_first).cwiseAbs().maxCoeff(), 1e-15)
        << FrictionSetName(test.set) << " unmapped: " << lambda.transpose();
    // to convergence: the mapped iteration confirms the first iterate, every scheme
    for (SolverType type : kAllSolverTypes) {
      ContactSolver full;
      Eigen::VectorXd mapped = Eigen::VectorXd::Zero(4);
      Eigen::VectorXd unmapped = Eigen::VectorXd::Zero(4);
      const SolverStatistics mapped_stats = full.Solve(problem, Tight(type), &mapped);
      const SolverStatistics unmapped_stats = full.Solve(problem, Unmapped(Tight(type)), &unmapped);
      ASSERT_TRUE(mapped_stats.converged && unmapped_stats.converged) << SolverTypeName(type);
      const std::string what =
          std::string(FrictionSetName(test.set)) + " " + std::string(SolverTypeName(type));
      EXPECT_EQ(mapped_stats.iterations, 2) << what;
      // unmapped, the tangential components (where c_T ≠ 0) crawl at 1 - G_TT/G_ττ per iteration,
      // under (43) also the normal one; under (46) pure spin is solved at once there too (Λ_N
      // steps 1/G_NN, and the first z_τ already leaves the set: the pole)
      if (type == SolverType::kJacobi || test.c[1] != 0.0) {
        EXPECT_GT(unmapped_stats.iterations, 100) << what;
      } else {
        EXPECT_EQ(unmapped_stats.iterations, 2) << what;
      }
      EXPECT_LT((mapped - test.mapped_first).cwiseAbs().maxCoeff(), 1e-15);
      EXPECT_TRUE(NearSolution(problem, unmapped, test.mapped_first, 1e-10)) << unmapped.transpose();
      EXPECT_TRUE(mapped_stats.friction_projected[0] && unmapped_stats.friction_projected[0]);
    }
  }
}

// exact and cylinder laws, and now and then one of the others, for the mapped-vs-unmapped checks
std::vector<ContactLaw> DrillingLaws(int m, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ContactLaw> laws;
  for (int i = 0; i < m; ++i) {
    const double pick = unit(rng);
    const double mu = 0.1 + 0.5 * unit(rng);
    const double rbar = 0.03 + 0.07 * unit(rng);
    const FrictionSet set = pick < 0.45   ? FrictionSet::kExact
                            : pick < 0.9  ? FrictionSet::kCylinder
                            : pick < 0.95 ? FrictionSet::kSphere
                                          : FrictionSet::kCoulomb;
    laws.push_back(MakeLaw(set, mu, rbar));
  }
  return laws;
}

// Solves `problem` mapped (default) and unmapped with the same options; both must converge, agree
// to `tolerance` (NearSolution) and report the same projections. Adds the sliding exact/cylinder
// contacts to *sliding.
void ExpectMappedEqualsUnmapped(const ContactProblem& problem, const SolverOptions& options,
                              double tolerance, const std::string& what, int* sliding,
                              Eigen::VectorXd* solution = nullptr) {
  ASSERT_TRUE(options.map_drilling_sets);
  ContactSolver solver;
  Eigen::VectorXd mapped = Eigen::VectorXd::Zero(problem.c.size());
  Eigen::VectorXd unmapped = mapped;
  const SolverStatistics mapped_stats = solver.Solve(problem, options, &mapped);
  const SolverStatistics unmapped_stats = solver.Solve(problem, Unmapped(options), &unmapped);
  if (solution != nullptr) *solution = mapped;
  ASSERT_TRUE(mapped_stats.converged && unmapped_stats.converged)
      << what << ": " << Describe(problem) << " iterations " << mapped_stats.iterations << " / "
      << unmapped_stats.iterations;
  EXPECT_TRUE(NearSolution(problem, mapped, unmapped, tolerance)) << what;
  EXPECT_EQ(mapped_stats.friction_projected, unmapped_stats.friction_projected) << what;
  EXPECT_EQ(mapped_stats.normal_projected, unmapped_stats.normal_projected) << what;
  for (std::size_t i = 0; i < problem.contacts.size(); ++i) {
    const ContactLaw& law = problem.contacts[i].law;
    const bool drilling_set =
        law.friction_set == FrictionSet::kExact || law.friction_set == FrictionSet::kCylinder;
    if (drilling_set && mapped_stats.friction_projected[i] && !mapped_stats.normal_projected[i]) {
      ++*sliding;
    }
  }
}

TEST(MappedDrillingSets, SameSolutionAndProjectionsAsUnmappedOnConstructedProblems) {
  std::mt19937_64 rng(kSeed + 9);
  int sliding = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int m = 1 + trial % 3;
    const Constructed constructed = Construct(DrillingLaws(m, rng), RandomRegimes(m, rng), rng);
    for (SolverType type : kAllSolverTypes) {
      const std::string what = "trial " + std::to_string(trial) + " " +
                               std::string(SolverTypeName(type)) + " " +
                               Describe(constructed.problem, constructed.regimes);
      Eigen::VectorXd mapped;
      ExpectMappedEqualsUnmapped(constructed.problem, Convergent(type, constructed.problem), 1e-9,
                               what, &sliding, &mapped);
      EXPECT_TRUE(NearSolution(constructed.problem, mapped, constructed.solution, 1e-8)) << what;
    }
  }
  EXPECT_GT(sliding, 60);
}

TEST(MappedDrillingSets, SameSolutionAndProjectionsAsUnmappedOnRandomProblems) {
  std::mt19937_64 rng(kSeed + 10);
  int sliding = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const int m = 1 + trial % 3;
    const ContactProblem problem = RandomProblem(DrillingLaws(m, rng), rng);
    for (SolverType type : kAllSolverTypes) {
      const std::string what = "trial " + std::to_string(trial) + " " +
                               std::string(SolverTypeName(type)) + " " + Describe(problem);
      Eigen::VectorXd mapped;
      ExpectMappedEqualsUnmapped(problem, Convergent(type, problem), 1e-9, what, &sliding, &mapped);
      EXPECT_TRUE(SatisfiesInclusion(problem, mapped, 1e-7)) << what;
    }
  }
  EXPECT_GT(sliding, 60);
}

TEST(MappedDrillingSets, TippeTopSlidingContactNeedsFarFewerIterationsMapped) {
  // G_ττ ≫ G_TT on the original sets: the projecting step α/G_ττ crawls; mapped, Ĝ_ττ = R̄²G_ττ
  // is the smallest diagonal entry and the step is α/max(Ĝ_NN, Ĝ_TT). The inclinations of the
  // rising phase (the run starts at θ = 0.1); cold start, tolerance 1e-10 (measured: 5 mapped
  // against 184 / 52 unmapped at θ = 0.1 / 0.5; the ratio shrinks as the slip grows with θ, at
  // θ = 1.2 it is 6 against 31)
  for (double inclination : {0.1, 0.3, 0.5}) {
    for (FrictionSet set : {FrictionSet::kExact, FrictionSet::kCylinder}) {
      const ContactProblem problem = TippeTopSlidingContact(inclination, set);
      ASSERT_GT(problem.G(3, 3), 1000.0 * std::max(problem.G(1, 1), problem.G(2, 2)));
      for (SolverType type : {SolverType::kModifiedJacobi, SolverType::kGaussSeidel}) {
        SolverOptions options;
        options.type = type;
        options.tolerance_rel = 1e-10;
        options.tolerance_abs = 1e-20;
        options.max_iterations = 1000000;
        const std::string what = std::string(FrictionSetName(set)) + " θ = " +
                                 std::to_string(inclination) + " " +
                                 std::string(SolverTypeName(type));
        ContactSolver solver;
        Eigen::VectorXd mapped = Eigen::VectorXd::Zero(4);
        Eigen::VectorXd unmapped = mapped;
        const SolverStatistics mapped_stats = solver.Solve(problem, options, &mapped);
        const SolverStatistics unmapped_stats = solver.Solve(problem, Unmapped(options), &unmapped);
        ASSERT_TRUE(mapped_stats.converged && unmapped_stats.converged) << what;
        EXPECT_TRUE(mapped_stats.friction_projected[0] && unmapped_stats.friction_projected[0])
            << what;
        EXPECT_GE(unmapped_stats.iterations, 5 * mapped_stats.iterations)
            << what << ": mapped " << mapped_stats.iterations << ", unmapped "
            << unmapped_stats.iterations;
        // sliding and drilling: both friction parts are active
        EXPECT_GT(std::abs(mapped[3]), 1e-3 * problem.contacts[0].law.rbar * 0.3 * mapped[0]);
        EXPECT_TRUE(NearSolution(problem, mapped, unmapped, 1e-7)) << what;
        EXPECT_TRUE(SatisfiesInclusion(problem, mapped, 1e-7)) << what;
      }
    }
  }
}

TEST(MappedDrillingSets, NoHeapAllocationEitherWay) {
  std::mt19937_64 rng(kSeed + 11);
  std::vector<ContactLaw> laws = {MakeLaw(FrictionSet::kExact, 0.3, 0.05),
                                  MakeLaw(FrictionSet::kCylinder, 0.3, 0.05),
                                  MakeLaw(FrictionSet::kExact, 0.3, 0.04)};
  const ContactProblem large = RandomProblem(laws, rng);
  laws.pop_back();
  const ContactProblem small = RandomProblem(laws, rng);
  for (bool map : {true, false}) {
    SolverOptions options = Convergent(SolverType::kGaussSeidel, large);
    options.map_drilling_sets = map;
    ContactSolver solver;
    SolverStatistics stats;
    Eigen::VectorXd lambda_large = Eigen::VectorXd::Zero(large.c.size());
    Eigen::VectorXd lambda_small = Eigen::VectorXd::Zero(small.c.size());
    solver.Solve(large, options, &lambda_large, &stats);  // sizes the workspace
    const long before = test::HeapAllocations();
    solver.Solve(small, options, &lambda_small, &stats);
    lambda_large.setZero();
    solver.Solve(large, options, &lambda_large, &stats);
    EXPECT_EQ(test::HeapAllocations() - before, 0) << "map_drilling_sets = " << map;
    EXPECT_TRUE(stats.converged);
  }
}

}  // namespace
}  // namespace nonsmooth_sim
