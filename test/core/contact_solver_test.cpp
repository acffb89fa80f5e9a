// ContactSolver: exact answers for single contacts, problems with a constructed solution on
// coupled rigid-body Delassus matrices, an independent check of the inclusion (17), the paper's
// central claim (E_F directly = S_F through the transformation), exact and cylinder iterated on
// A⁻¹D (40)-(47) against on D (37) (same solution, far fewer iterations on a sliding Tippe-Top
// contact), the iteration counts of (43) against (46) on a badly scaled problem, and the API
// contract (validation, statistics, warm start, no allocation).
//
// Sign convention (contact_solver.h): -ξ_i ∈ N_{C_i}(Λ_i) with C_i the set of admissible Λ_i.
#include "nonsmooth_sim/core/contact_solver.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "allocation_counter.h"  // the NoHeapAllocation tests: the heap allocation count
#include "nonsmooth_sim/core/ball_contact_solve.h"
#include "dense_transformation.h"  // ContactMapDiagonal, ProblemMapDiagonal

namespace nonsmooth_sim {
namespace {

constexpr std::uint64_t kSeed = 1620091;
constexpr double kPi = 3.14159265358979323846;
constexpr double kInverseGoldenRatio = 0.618033988749895;  // golden-section search

ContactLaw MakeLaw(FrictionSet set, double mu, double rbar) {
  ContactLaw law;
  law.friction_set = set;
  law.mu = mu;
  law.rbar = rbar;
  return law;
}

SolverOptions Tight(SolverType type) {
  SolverOptions options;
  options.type = type;
  options.tolerance_rel = 1e-13;
  options.tolerance_abs = 1e-16;
  options.max_iterations = 200000;
  return options;
}

// λ_max(D^{-1/2} G D^{-1/2}), D = diag(G)
double ScaledMaxEigenvalue(const Eigen::MatrixXd& g) {
  const Eigen::VectorXd d = g.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd scaled = d.asDiagonal() * g * d.asDiagonal();
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(scaled).eigenvalues().maxCoeff();
}

// Tight options with a relaxation α inside the convergence condition stated in contact_solver.h
// (with margin: α ≤ 1.6/λ_max), for coupled problems.
SolverOptions Convergent(SolverType type, const ContactProblem& problem) {
  double lambda_max = ScaledMaxEigenvalue(problem.G);
  if (type == SolverType::kGaussSeidel) {
    lambda_max = 0.0;
    for (const ContactBlock& contact : problem.contacts) {
      const int dim = ContactDimension(contact.law);
      lambda_max = std::max(lambda_max, ScaledMaxEigenvalue(problem.G.block(
                                            contact.offset, contact.offset, dim, dim)));
    }
  }
  SolverOptions options = Tight(type);
  options.relaxation = std::min(1.0, 1.6 / lambda_max);
  return options;
}

constexpr std::array<SolverType, 3> kAllSolverTypes = {
    SolverType::kJacobi, SolverType::kModifiedJacobi, SolverType::kGaussSeidel};

ContactProblem SingleContact(const ContactLaw& law, const Eigen::VectorXd& g_diagonal,
                             const Eigen::VectorXd& c) {
  ContactProblem problem;
  problem.contacts = {{0, law}};
  problem.G = g_diagonal.asDiagonal();
  problem.c = c;
  return problem;
}

// ---- the Coulomb-Contensou boundary (51)-(52), written out independently, for μλ_N = 1, R̄ = 1 --
struct Boundary {
  double t;    // b_T(u)
  double tau;  // b_τ(u)
};
// Beyond this u the closed forms cancel (absolute error ~ u³·1e-16 in b_τ); there the curve is
// within 1e-7 of the rim (1, 0), which the checks below use instead.
constexpr double kMaxU = 1e3;
Boundary ContensouCurve(double u) {
  if (u <= 1.0) return {3.0 * kPi / 32.0 * (-u * u * u + 4.0 * u), (3 * std::pow(u, 4) - 8 * u * u + 8) / 8.0};
  const double arcsin = std::asin(1.0 / u);
  const double root = std::sqrt(u * u - 1.0);
  return {3.0 / 16.0 * ((-u * u * u + 4.0 * u) * arcsin + (u * u + 2.0) / u * root),
          ((3 * std::pow(u, 4) - 8 * u * u + 8) * arcsin + (-3 * u * u + 6) * root) / (4.0 * kPi)};
}
// outward normal of B_F's cross-section at u in the normalised coordinates (b_T, b_τ): on both
// branches of (51)-(52) db_τ/du = -u (16/3π) db_T/du (for u ≤ 1 by differentiating the
// polynomials), so the normal (-b_τ', b_T') is ∝ (16u/3π, 1)
Eigen::Vector2d ContensouNormal(double u) {
  return Eigen::Vector2d(16.0 * u / (3.0 * kPi), 1.0).normalized();
}

// ---- independent check of the inclusion (17): normal complementarity, Λ_F ∈ F, and
// -ξ_F ∈ N_F(Λ_F) through the support function: σ_F(-ξ_F) = -ξ_F·Λ_F ----
// support function of the law's friction set of radius rho in direction d = (d_T1, d_T2, d_τ)
double Support(const ContactLaw& law, int dim, const Eigen::Vector3d& d, double rho) {
  const double d_t = d.head<2>().norm();
  const double d_tau = std::abs(d.z());
  if (dim == 3) return rho * d_t;
  switch (law.friction_set) {
    case FrictionSet::kCylinder: return rho * (d_t + law.rbar * d_tau);
    case FrictionSet::kEllipsoid:
    case FrictionSet::kSphere: return rho * std::hypot(d_t, law.rbar * d_tau);
    case FrictionSet::kExact: {
      // max over the boundary curve: dense sampling in u = tan(θ), then golden section; for
      // u > kMaxU the rim value d_t (low by at most R̄ d_τ b_τ(kMaxU) ≈ 3e-4 R̄ d_τ, and only
      // where d_τ is negligible)
      const auto value = [&](double theta) {
        const double u = std::tan(theta);
        if (theta >= kPi / 2 || u > kMaxU) return d_t;
        const Boundary b = ContensouCurve(u);
        return d_t * b.t + law.rbar * d_tau * b.tau;
      };
      constexpr int kSamples = 2000;
      int best = 0;
      for (int k = 1; k <= kSamples; ++k) {
        if (value(k * kPi / 2 / kSamples) > value(best * kPi / 2 / kSamples)) best = k;
      }
      double lo = std::max(0, best - 1) * kPi / 2 / kSamples;
      double hi = std::min(kSamples, best + 1) * kPi / 2 / kSamples;
      for (int k = 0; k < 100; ++k) {
        const double a = hi - (hi - lo) * kInverseGoldenRatio;
        const double b = lo + (hi - lo) * kInverseGoldenRatio;
        (value(a) < value(b) ? lo : hi) = value(a) < value(b) ? a : b;
      }
      return rho * std::max(value(0.5 * (lo + hi)), value(best * kPi / 2 / kSamples));
    }
    case FrictionSet::kCoulomb: break;
  }
  return rho * d_t;
}

// level ≤ 1 ⇔ inside the friction set of radius rho > 0
double Level(const ContactLaw& law, int dim, const Eigen::Vector3d& p, double rho) {
  const double t = p.head<2>().norm() / rho;
  const double s = std::abs(p.z()) / (law.rbar * rho);
  if (dim == 3) return t;
  switch (law.friction_set) {
    case FrictionSet::kCylinder: return std::max(t, s);
    case FrictionSet::kEllipsoid:
    case FrictionSet::kSphere: return std::hypot(t, s);
    case FrictionSet::kExact: {
      // b_T increases, b_τ decreases along the curve: find u with b_T(u) = t, compare b_τ(u)
      const Boundary rim = ContensouCurve(kMaxU);
      if (t >= rim.t) return std::max(t, 1.0 + (s - rim.tau));
      double lo = 0.0;
      double hi = std::atan(kMaxU);
      for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (ContensouCurve(std::tan(mid)).t < t ? lo : hi) = mid;
      }
      const double b_tau = ContensouCurve(std::tan(0.5 * (lo + hi))).tau;
      return 1.0 + (s - b_tau);
    }
    case FrictionSet::kCoulomb: break;
  }
  return t;
}

::testing::AssertionResult SatisfiesInclusion(const ContactProblem& problem,
                                              const Eigen::VectorXd& lambda, double tolerance) {
  const Eigen::VectorXd xi = problem.G * lambda + problem.c;
  const double lambda_scale = std::max(lambda.cwiseAbs().maxCoeff(), 1e-300);
  const double xi_scale =
      std::max({problem.c.cwiseAbs().maxCoeff(), (problem.G * lambda).cwiseAbs().maxCoeff(), 1e-300});
  for (std::size_t i = 0; i < problem.contacts.size(); ++i) {
    const ContactBlock& contact = problem.contacts[i];
    const int dim = ContactDimension(contact.law);
    const double lambda_n = lambda[contact.offset];
    const double xi_n = xi[contact.offset];
    // Signorini: Λ_N ≥ 0, ξ_N ≥ 0, Λ_N ξ_N = 0
    if (lambda_n < -tolerance * lambda_scale || xi_n < -tolerance * xi_scale ||
        std::abs(lambda_n * xi_n) > tolerance * lambda_scale * xi_scale) {
      return ::testing::AssertionFailure()
             << "contact " << i << ": normal Λ_N = " << lambda_n << ", ξ_N = " << xi_n;
    }
    if (dim == 1) continue;
    Eigen::Vector3d lambda_f = Eigen::Vector3d::Zero();
    Eigen::Vector3d xi_f = Eigen::Vector3d::Zero();
    lambda_f.head(dim - 1) = lambda.segment(contact.offset + 1, dim - 1);
    xi_f.head(dim - 1) = xi.segment(contact.offset + 1, dim - 1);
    const double rho = contact.law.mu * std::max(lambda_n, 0.0);
    // τ in units of N s: divide by R̄
    const double tau_unit = dim == 4 ? contact.law.rbar : 1.0;
    if (rho <= tolerance * lambda_scale) {
      if (lambda_f.head<2>().norm() + std::abs(lambda_f.z()) / tau_unit > tolerance * lambda_scale) {
        return ::testing::AssertionFailure() << "contact " << i << ": friction without Λ_N";
      }
      continue;
    }
    const double level = Level(contact.law, dim, lambda_f, rho);
    if (level > 1.0 + tolerance) {
      return ::testing::AssertionFailure()
             << "contact " << i << ": Λ_F outside the set, level " << level;
    }
    const Eigen::Vector3d d = -xi_f;
    const double gap = Support(contact.law, dim, d, rho) - d.dot(lambda_f);
    const double scale = rho * (d.head<2>().norm() + tau_unit * std::abs(d.z()));
    // ξ_F below tolerance·ξ_scale counts as zero (round-off of GΛ + c at stiction)
    if (gap > tolerance * std::max(scale, xi_scale * rho)) {
      return ::testing::AssertionFailure()
             << "contact " << i << ": -ξ_F not in N_F(Λ_F): σ(-ξ) + ξ·Λ = " << gap
             << " (scale " << scale << ")";
    }
  }
  return ::testing::AssertionSuccess();
}

// ---- rigid-body Delassus matrices (16): a chain ground - body 0 - body 1 - ..., one contact per
// link, so that G = Wᵀ M⁻¹ W is positive definite (6 velocities per body, ≤ 4 per contact) ----
Eigen::Vector3d RandomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::Vector3d v(normal(rng), normal(rng), normal(rng));
  return v.normalized();
}

Eigen::MatrixXd ChainDelassus(const std::vector<ContactLaw>& laws, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const int m = static_cast<int>(laws.size());
  const int k = 6 * m;
  Eigen::MatrixXd m_inverse = Eigen::MatrixXd::Zero(k, k);
  std::vector<Eigen::Vector3d> com(m);
  for (int b = 0; b < m; ++b) {
    const double mass = 0.5 + 1.5 * unit(rng);
    const Eigen::Vector3d principal(0.05 + 0.25 * unit(rng), 0.05 + 0.25 * unit(rng),
                                    0.05 + 0.25 * unit(rng));
    const Eigen::Matrix3d rotation =
        Eigen::AngleAxisd(2 * kPi * unit(rng), RandomUnit(rng)).toRotationMatrix();
    const Eigen::Matrix3d inertia = rotation * principal.asDiagonal() * rotation.transpose();
    m_inverse.block<3, 3>(6 * b, 6 * b) = Eigen::Matrix3d::Identity() / mass;
    m_inverse.block<3, 3>(6 * b + 3, 6 * b + 3) = inertia.inverse();
    com[b] = 0.3 * RandomUnit(rng);
  }
  int n = 0;
  for (const ContactLaw& law : laws) n += ContactDimension(law);
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(k, n);
  int offset = 0;
  for (int i = 0; i < m; ++i) {
    const int dim = ContactDimension(laws[i]);
    const Eigen::Vector3d point = com[i] + 0.3 * RandomUnit(rng);
    const Eigen::Vector3d normal = RandomUnit(rng);
    const Eigen::Vector3d t1 = normal.unitOrthogonal();
    const Eigen::Vector3d t2 = normal.cross(t1);
    const Eigen::Vector3d directions[3] = {normal, t1, t2};
    // force +d on body i at the point, -d on body i-1 (the ground for i = 0)
    const auto add = [&](int column, int body, double sign, const Eigen::Vector3d& force,
                         const Eigen::Vector3d& torque) {
      w.block<3, 1>(6 * body, column) += sign * force;
      w.block<3, 1>(6 * body + 3, column) += sign * torque;
    };
    for (int c = 0; c < std::min(dim, 3); ++c) {
      const Eigen::Vector3d& d = directions[c];
      add(offset + c, i, 1.0, d, (point - com[i]).cross(d));
      if (i > 0) add(offset + c, i - 1, -1.0, d, (point - com[i - 1]).cross(d));
    }
    if (dim == 4) {
      // drilling: a pure torque about the normal
      add(offset + 3, i, 1.0, Eigen::Vector3d::Zero(), normal);
      if (i > 0) add(offset + 3, i - 1, -1.0, Eigen::Vector3d::Zero(), normal);
    }
    offset += dim;
  }
  return w.transpose() * m_inverse * w;
}

// ---- problems with a constructed solution: pick Λ*, ξ* satisfying the inclusion per contact,
// then c = ξ* - GΛ* ----
enum class Regime { kSeparated, kSticking, kSliding };

struct Constructed {
  ContactProblem problem;
  Eigen::VectorXd solution;
  std::vector<Regime> regimes;
};

// a boundary point of the friction set (radius rho) and an outward normal there
void FrictionBoundaryPoint(const ContactLaw& law, int dim, double rho, std::mt19937_64& rng,
                           Eigen::Vector3d* point, Eigen::Vector3d* normal) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double angle = 2 * kPi * unit(rng);
  const Eigen::Vector3d e(std::cos(angle), std::sin(angle), 0.0);
  const double sign = unit(rng) < 0.5 ? -1.0 : 1.0;
  const Eigen::Vector3d up(0.0, 0.0, sign);
  if (dim == 3) {
    *point = rho * e;
    *normal = e;
    return;
  }
  const double rbar = law.rbar;
  switch (law.friction_set) {
    case FrictionSet::kCylinder: {
      const int where = static_cast<int>(3 * unit(rng));
      if (where == 0) {  // side
        *point = rho * e + (0.9 * (2 * unit(rng) - 1)) * rbar * rho * up;
        *normal = e;
      } else if (where == 1) {  // cap
        *point = (0.9 * unit(rng)) * rho * e + rbar * rho * up;
        *normal = up;
      } else {  // edge: any positive combination
        *point = rho * e + rbar * rho * up;
        *normal = (0.1 + unit(rng)) * e + (0.1 + unit(rng)) * up;
      }
      return;
    }
    case FrictionSet::kEllipsoid:
    case FrictionSet::kSphere: {
      const double phi = (unit(rng) - 0.5) * 0.98 * kPi;
      *point = rho * std::cos(phi) * e + rbar * rho * std::sin(phi) * Eigen::Vector3d::UnitZ();
      // the gradient of (55)
      *normal = Eigen::Vector3d(point->x() / (rho * rho), point->y() / (rho * rho),
                                point->z() / (rbar * rho * rbar * rho));
      return;
    }
    case FrictionSet::kExact: {
      const double u = 0.05 + 3.0 * unit(rng);
      const Boundary b = ContensouCurve(u);
      const Eigen::Vector2d n = ContensouNormal(u);
      *point = rho * b.t * e + rbar * rho * b.tau * up;
      // the cross-section normal (n_t, n_s) in units of (ρ, R̄ρ): back to (N s, N m s)
      *normal = n.x() * e + n.y() / rbar * up;
      return;
    }
    case FrictionSet::kCoulomb: break;
  }
  *point = rho * e;
  *normal = e;
}

Constructed Construct(const std::vector<ContactLaw>& laws, const std::vector<Regime>& regimes,
                      std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Constructed out;
  out.regimes = regimes;
  out.problem.G = ChainDelassus(laws, rng);
  const Eigen::Index n = out.problem.G.rows();
  out.solution = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd xi = Eigen::VectorXd::Zero(n);
  int offset = 0;
  for (std::size_t i = 0; i < laws.size(); ++i) {
    const int dim = ContactDimension(laws[i]);
    out.problem.contacts.push_back({offset, laws[i]});
    const Regime regime = dim == 1 && regimes[i] == Regime::kSliding ? Regime::kSticking : regimes[i];
    out.regimes[i] = regime;
    if (regime == Regime::kSeparated) {
      xi[offset] = 0.2 + unit(rng);
      for (int k = 1; k < dim; ++k) xi[offset + k] = 2 * unit(rng) - 1;
    } else {
      const double lambda_n = 0.5 + 1.5 * unit(rng);
      out.solution[offset] = lambda_n;
      if (dim > 1) {
        Eigen::Vector3d point;
        Eigen::Vector3d normal;
        FrictionBoundaryPoint(laws[i], dim, laws[i].mu * lambda_n, rng, &point, &normal);
        if (regime == Regime::kSticking) {
          out.solution.segment(offset + 1, dim - 1) = (0.1 + 0.7 * unit(rng)) * point.head(dim - 1);
        } else {
          out.solution.segment(offset + 1, dim - 1) = point.head(dim - 1);
          // -ξ_F along the outward normal, sized so that |ξ_T| + R̄|ξ_τ| ∈ [0.2, 1.2]
          const double tau_unit = dim == 4 ? laws[i].rbar : 0.0;
          const double size =
              (0.2 + unit(rng)) / (normal.head<2>().norm() + tau_unit * std::abs(normal.z()));
          xi.segment(offset + 1, dim - 1) = (-size * normal).head(dim - 1);
        }
      }
    }
    offset += dim;
  }
  out.problem.c = xi - out.problem.G * out.solution;
  return out;
}

// "sphere(μ=0.3, R̄=0.02) sliding, ..." for failure messages
std::string Describe(const ContactProblem& problem, const std::vector<Regime>& regimes = {}) {
  std::string text;
  for (std::size_t i = 0; i < problem.contacts.size(); ++i) {
    const ContactLaw& law = problem.contacts[i].law;
    text += std::string(FrictionSetName(law.friction_set)) + "(mu=" + std::to_string(law.mu) +
            ", rbar=" + std::to_string(law.rbar) + ")";
    if (i < regimes.size()) {
      text += regimes[i] == Regime::kSeparated ? " separated"
              : regimes[i] == Regime::kSticking ? " sticking"
                                                : " sliding";
    }
    text += "; ";
  }
  return text;
}

std::vector<ContactLaw> RandomLaws(int m, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ContactLaw> laws;
  for (int i = 0; i < m; ++i) {
    const int pick = static_cast<int>(7 * unit(rng));
    const double mu = 0.1 + 0.5 * unit(rng);
    const double rbar = 0.02 + 0.08 * unit(rng);
    if (pick == 5) {
      laws.push_back(MakeLaw(FrictionSet::kSphere, 0.0, rbar));  // frictionless, dim 1
    } else if (pick == 6) {
      laws.push_back(MakeLaw(FrictionSet::kEllipsoid, mu, 0.0));  // no drilling, dim 3
    } else {
      laws.push_back(MakeLaw(kAllFrictionSets[pick], mu, rbar));
    }
  }
  return laws;
}

std::vector<Regime> RandomRegimes(int m, std::mt19937_64& rng) {
  std::vector<Regime> regimes;
  for (int i = 0; i < m; ++i) regimes.push_back(static_cast<Regime>(rng() % 3));
  return regimes;
}

// |Λ - Λ*| per component against the scale of its contact (τ in units of R̄)
::testing::AssertionResult NearSolution(const ContactProblem& problem, const Eigen::VectorXd& a,
                                        const Eigen::VectorXd& b, double tolerance) {
  const double scale = std::max(1.0, b.cwiseAbs().maxCoeff());
  for (const ContactBlock& contact : problem.contacts) {
    const int dim = ContactDimension(contact.law);
    for (int k = 0; k < dim; ++k) {
      const double unit = k == 3 ? contact.law.rbar : 1.0;
      const int index = contact.offset + k;
      if (std::abs(a[index] - b[index]) > tolerance * scale * unit) {
        return ::testing::AssertionFailure() << "component " << index << ": " << a[index]
                                             << " vs " << b[index];
      }
    }
  }
  return ::testing::AssertionSuccess();
}

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

// Random problems without a known solution: velocities and gravity on the chain of bodies.
ContactProblem RandomProblem(const std::vector<ContactLaw>& laws, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  ContactProblem problem;
  problem.G = ChainDelassus(laws, rng);
  int offset = 0;
  for (const ContactLaw& law : laws) {
    problem.contacts.push_back({offset, law});
    offset += ContactDimension(law);
  }
  problem.c.resize(offset);
  for (int k = 0; k < offset; ++k) problem.c[k] = normal(rng);
  // mostly approaching normals
  for (const ContactBlock& contact : problem.contacts) {
    problem.c[contact.offset] = -std::abs(problem.c[contact.offset]) + 0.2;
  }
  return problem;
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

// ============================== the direct solve of one ball-set contact ==============================

// A constructed one-contact problem handed to SolveBallContact in the solver's coordinates: Ĝ =
// AGA, ĉ = Ac with A = diag(1, 1, 1, R̄) for sphere (S_F = A⁻¹E_F is the unit-metric ball), A = I
// and D = diag(1, 1, R̄) for ellipsoid (E_F itself), A = I and D = I for the disk; Λ = AΛ̂.
struct BallCase {
  Eigen::Matrix4d g_hat = Eigen::Matrix4d::Identity();
  Eigen::Vector4d c_hat = Eigen::Vector4d::Zero();
  Eigen::Vector4d scale = Eigen::Vector4d::Ones();
  Eigen::Vector3d metric = Eigen::Vector3d::Ones();
  int dim = 1;
};

BallCase MapForBallSolve(const ContactProblem& problem) {
  const ContactLaw& law = problem.contacts[0].law;
  BallCase out;
  out.dim = ContactDimension(law);
  if (out.dim == 4 && law.friction_set == FrictionSet::kSphere) out.scale[3] = law.rbar;
  if (out.dim == 4 && law.friction_set == FrictionSet::kEllipsoid) out.metric.z() = law.rbar;
  const Eigen::VectorXd a = out.scale.head(out.dim);
  out.g_hat.topLeftCorner(out.dim, out.dim) = a.asDiagonal() * problem.G * a.asDiagonal();
  out.c_hat.head(out.dim) = a.cwiseProduct(problem.c);
  return out;
}

// Constructed single contacts (separated, sticking, sliding) with the three ball sets, down to
// R̄ = 1e-4 m, where Ĝ_ττ/Ĝ_TT of the mapped sphere law is ~1e-8: the direct solve finds the
// constructed solution and satisfies the inclusion (17) by the independent check.
TEST(BallContactSolve, FindsTheConstructedSolutionOfEveryRegime) {
  std::mt19937_64 rng(kSeed + 40);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const FrictionSet sets[] = {FrictionSet::kSphere, FrictionSet::kEllipsoid, FrictionSet::kCoulomb};
  int regimes_seen[3] = {0, 0, 0};
  for (int trial = 0; trial < 300; ++trial) {
    const FrictionSet set = sets[trial % 3];
    const double rbar = std::pow(10.0, -4.0 + 3.0 * unit(rng));
    const ContactLaw law = MakeLaw(set, 0.1 + 0.5 * unit(rng), rbar);
    const Regime regime = static_cast<Regime>(trial / 3 % 3);
    const Constructed constructed = Construct({law}, {regime}, rng);
    const BallCase ball = MapForBallSolve(constructed.problem);
    Eigen::Vector4d lambda_hat = Eigen::Vector4d::Constant(-7.0);  // overwritten on success
    ASSERT_TRUE(SolveBallContact(ball.g_hat, ball.c_hat, ball.dim, law.mu, ball.metric,
                                 &lambda_hat))
        << trial << " " << Describe(constructed.problem, constructed.regimes);
    const Eigen::VectorXd lambda = ball.scale.cwiseProduct(lambda_hat).head(ball.dim);
    EXPECT_TRUE(NearSolution(constructed.problem, lambda, constructed.solution, 1e-9))
        << trial << " " << Describe(constructed.problem, constructed.regimes);
    EXPECT_TRUE(SatisfiesInclusion(constructed.problem, lambda, 1e-9))
        << trial << " " << Describe(constructed.problem, constructed.regimes);
    for (int k = ball.dim; k < 4; ++k) EXPECT_EQ(lambda_hat[k], 0.0) << trial;
    ++regimes_seen[static_cast<int>(constructed.regimes[0])];
  }
  for (int seen : regimes_seen) EXPECT_GT(seen, 50);
}

// Closed forms: a separating contact gets zero; a sticking one the unconstrained solution -G⁻¹c.
TEST(BallContactSolve, SeparationAndStictionHaveTheirClosedForms) {
  Eigen::Matrix4d g;
  g << 2.0, 0.3, -0.1, 0.05,  //
      0.3, 1.5, 0.2, 0.01,    //
      -0.1, 0.2, 1.2, -0.02,  //
      0.05, 0.01, -0.02, 0.1;
  Eigen::Vector4d lambda;
  ASSERT_TRUE(SolveBallContact(g, Eigen::Vector4d(0.5, 1.0, -1.0, 0.3), 4, 0.5,
                               Eigen::Vector3d::Ones(), &lambda));
  EXPECT_EQ(lambda, Eigen::Vector4d::Zero());
  const Eigen::Vector4d stick(1.0, 0.05, -0.03, 0.01);  // ||Λ_F|| = 0.06 < μΛ_N = 0.5
  ASSERT_TRUE(SolveBallContact(g, -g * stick, 4, 0.5, Eigen::Vector3d::Ones(), &lambda));
  EXPECT_LT((lambda - stick).cwiseAbs().maxCoeff(), 1e-14);
  // invalid: a non-positive G_NN or friction metric leaves Λ as it was
  lambda.setConstant(3.0);
  Eigen::Matrix4d singular = g;
  singular(0, 0) = 0.0;
  EXPECT_FALSE(SolveBallContact(singular, -g * stick, 4, 0.5, Eigen::Vector3d::Ones(), &lambda));
  EXPECT_FALSE(SolveBallContact(g, -g * stick, 4, 0.5, Eigen::Vector3d(1.0, 1.0, 0.0), &lambda));
  EXPECT_EQ(lambda, Eigen::Vector4d::Constant(3.0));
}

// One body touching the ground at `points` contacts below and beside its centre of mass (unit
// normal ẑ, tangents x̂, ŷ, drilling about ẑ): G = Wᵀ M⁻¹ W of (16) with random mass, principal
// inertia and lever arms, and free velocities that approach, slip slowly and spin.
ContactProblem BodyOnGround(const ContactLaw& law, int points, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double mass = 0.5 + unit(rng);
  const Eigen::Vector3d inertia(0.01 + 0.1 * unit(rng), 0.01 + 0.1 * unit(rng),
                                0.01 + 0.1 * unit(rng));
  const Eigen::Vector3d directions[3] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                                         Eigen::Vector3d::UnitY()};
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(6, 4 * points);
  ContactProblem problem;
  problem.c = Eigen::VectorXd::Zero(4 * points);
  for (int p = 0; p < points; ++p) {
    const Eigen::Vector3d arm(0.1 * (2 * unit(rng) - 1), 0.1 * (2 * unit(rng) - 1),
                              -0.05 - 0.1 * unit(rng));
    for (int k = 0; k < 3; ++k) {
      w.block<3, 1>(0, 4 * p + k) = directions[k];
      w.block<3, 1>(3, 4 * p + k) = arm.cross(directions[k]);
    }
    w.block<3, 1>(3, 4 * p + 3) = Eigen::Vector3d::UnitZ();
    problem.contacts.push_back({4 * p, law});
    problem.c.segment<4>(4 * p) = Eigen::Vector4d(
        -1.0, 0.05 * (2 * unit(rng) - 1), 0.05 * (2 * unit(rng) - 1), 2.0 * (2 * unit(rng) - 1));
  }
  Eigen::Matrix<double, 6, 6> m_inverse = Eigen::Matrix<double, 6, 6>::Zero();
  m_inverse.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() / mass;
  m_inverse.bottomRightCorner<3, 3>() = inertia.cwiseInverse().asDiagonal();
  problem.G = w.transpose() * m_inverse * w;
  return problem;
}

// The solver's fallback on the rattleback's kind of contact (sphere law, R̄ = 1 mm: Ĝ_ττ/Ĝ_TT
// ~1e-6), solved cold: most of these problems have not converged after kDirectSolveAfter
// iterations (the budget without the fallback), and with a larger budget each converges by the
// stopping rule within three iterations of the direct solve, satisfying (17) by the independent
// check.
TEST(BallContactSolve, SolverFallsBackWhereTheIterationCreeps) {
  std::mt19937_64 rng(kSeed + 41);
  constexpr int kTrials = 100;
  int creeping = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const ContactProblem problem = BodyOnGround(MakeLaw(FrictionSet::kSphere, 0.3, 1e-3), 1, rng);
    SolverOptions options;
    options.max_iterations = kDirectSolveAfter;
    ContactSolver solver;
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(4);
    const SolverStatistics plain = solver.Solve(problem, options, &lambda);
    if (plain.converged) continue;
    ++creeping;
    options.max_iterations = 1000;
    lambda.setZero();
    const SolverStatistics direct = solver.Solve(problem, options, &lambda);
    EXPECT_TRUE(direct.converged) << trial << " residual " << direct.residual;
    EXPECT_GT(direct.iterations, kDirectSolveAfter) << trial;
    EXPECT_LE(direct.iterations, kDirectSolveAfter + 3) << trial;
    EXPECT_TRUE(SatisfiesInclusion(problem, lambda, 1e-8)) << trial;
  }
  EXPECT_GT(creeping, kTrials / 2);
}

// The same on islands of two and three contacts on one body (the rolling dumbbell's and the
// crowd's kind; the drilling torques of the contacts act on the same ω_z, so the percussions are
// not unique): where Gauss-Seidel has not converged after kDirectSolveAfter iterations, block
// Gauss-Seidel sweeps with each contact solved directly give a start from which it converges,
// satisfying (17). Every island of two does; of three (a statically indeterminate support: twelve
// components on six velocities) measured 25 of 30, the others' sweeps still drift after 200 (a
// change of 1e-5 to 1e-3 of |Λ| per sweep along the indeterminate directions) and the iteration
// from there does not converge either.
TEST(BallContactSolve, SolverFallsBackOnCreepingIslands) {
  std::mt19937_64 rng(kSeed + 42);
  constexpr int kTrials = 60;
  int creeping[2] = {0, 0};
  int converged[2] = {0, 0};
  for (int trial = 0; trial < kTrials; ++trial) {
    const int points = 2 + trial % 2;
    const ContactProblem problem =
        BodyOnGround(MakeLaw(FrictionSet::kSphere, 0.3, 1e-3), points, rng);
    SolverOptions options;
    options.tolerance_rel = 1e-10;
    options.max_iterations = kDirectSolveAfter;
    ContactSolver solver;
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(problem.c.size());
    const SolverStatistics plain = solver.Solve(problem, options, &lambda);
    if (plain.converged) continue;
    ++creeping[points - 2];
    options.max_iterations = 1000;
    lambda.setZero();
    const SolverStatistics direct = solver.Solve(problem, options, &lambda);
    if (!direct.converged) continue;
    ++converged[points - 2];
    EXPECT_TRUE(SatisfiesInclusion(problem, lambda, 1e-8)) << trial;
  }
  std::printf("creeping islands that converge after the direct sweeps: two contacts %d of %d, "
              "three %d of %d\n", converged[0], creeping[0], converged[1], creeping[1]);
  EXPECT_GT(creeping[0], kTrials / 4);
  EXPECT_GT(creeping[1], kTrials / 4);
  EXPECT_EQ(converged[0], creeping[0]);
  EXPECT_GE(4 * converged[1], 3 * creeping[1]);
}


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

// ======================= exact and cylinder on A⁻¹D (40)-(47) vs on D (37) =======================

SolverOptions Unmapped(SolverOptions options) {
  options.map_drilling_sets = false;
  return options;
}

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

// One contact of the Tippe-Top (tippe-top.md: m = 6 g, Θ_S = diag(8, 8, 7)·1e-7 kg m², big sphere
// R1 = 15 mm at a1 = 3 mm from S, μ = 0.3, R = 0.5 mm), e3 tilted by θ about the world x axis,
// spinning at 180 rad/s about e3 with S at rest: the contact point slides and drills. G and c of
// (16) for one step Δt = 1e-4 s, W: N = ẑ, T1 = x̂, T2 = ŷ at the contact point, τ about ẑ.
ContactProblem TippeTopSlidingContact(double inclination, FrictionSet set) {
  constexpr double kMass = 6e-3;
  constexpr double kBigRadius = 0.015;
  constexpr double kBigOffset = 0.003;
  constexpr double kDt = 1e-4;
  const double rbar = 3.0 * kPi * 5e-4 / 16.0;  // (50)
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(inclination, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d inertia =
      rotation * Eigen::Vector3d(8e-7, 8e-7, 7e-7).asDiagonal() * rotation.transpose();
  Eigen::Matrix<double, 6, 6> m_inverse = Eigen::Matrix<double, 6, 6>::Zero();
  m_inverse.topLeftCorner<3, 3>() = Eigen::Matrix3d::Identity() / kMass;
  m_inverse.bottomRightCorner<3, 3>() = inertia.inverse();
  const Eigen::Vector3d arm =
      kBigOffset * rotation.col(2) - kBigRadius * Eigen::Vector3d::UnitZ();  // S → contact
  Eigen::Matrix<double, 6, 4> w = Eigen::Matrix<double, 6, 4>::Zero();
  const Eigen::Vector3d directions[3] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                                         Eigen::Vector3d::UnitY()};
  for (int k = 0; k < 3; ++k) {
    w.block<3, 1>(0, k) = directions[k];
    w.block<3, 1>(3, k) = arm.cross(directions[k]);
  }
  w.block<3, 1>(3, 3) = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d omega = 180.0 * rotation.col(2);
  Eigen::Matrix<double, 6, 1> u;
  u << Eigen::Vector3d::Zero(), omega;
  Eigen::Matrix<double, 6, 1> h;
  h << Eigen::Vector3d(0.0, 0.0, -kMass * 9.81), -omega.cross(inertia * omega);
  ContactProblem problem;
  problem.contacts = {{0, MakeLaw(set, 0.3, rbar)}};
  problem.G = w.transpose() * m_inverse * w;
  problem.c = w.transpose() * (u + m_inverse * h * kDt);
  return problem;
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

// ============================== the stopping rule ==============================

// |Λ - Λ*| within the bound of the stopping rule, tolerance_abs + tolerance_rel·|Λ*|, per component
::testing::AssertionResult WithinTolerance(const Eigen::VectorXd& lambda,
                                           const Eigen::VectorXd& solution,
                                           const SolverOptions& options) {
  for (Eigen::Index k = 0; k < lambda.size(); ++k) {
    const double bound = options.tolerance_abs + options.tolerance_rel * std::abs(solution[k]);
    if (std::abs(lambda[k] - solution[k]) > bound) {
      return ::testing::AssertionFailure()
             << "component " << k << ": " << lambda[k] << " vs " << solution[k] << ", error "
             << std::abs(lambda[k] - solution[k]) / bound << " times the tolerance";
    }
  }
  return ::testing::AssertionSuccess();
}

TEST(StoppingRule, JacobiDoesNotClaimConvergenceFarFromTheSolution) {
  // The diagonal stiction problem above, G = diag(1, 2, 2, 1e4): (43) steps r = 1e-4 for every
  // component, so the error of Λ_N shrinks by 1 - 1e-4 per iteration and its change is 1e-4 times
  // its error. The unscaled increment test |ΔΛ_N| ≤ 1e-6 |Λ_N| would pass at an error of 1e-2
  // (after ≈ 46000 iterations), 1e4 times the tolerance; with s_N = G_ττ/G_NN = 1e4 the rule
  // asks for an error ≤ 1e-6, ≈ 138000 iterations. The solution is known in closed form.
  const ContactLaw law = MakeLaw(FrictionSet::kEllipsoid, 0.3, 0.02);
  const Eigen::Vector4d g(1.0, 2.0, 2.0, 1e4);
  const Eigen::Vector4d expected(1.0, 0.1, -0.05, 0.001);
  const ContactProblem problem = SingleContact(law, g, -g.cwiseProduct(expected));
  SolverOptions options;
  options.type = SolverType::kJacobi;
  options.tolerance_rel = 1e-6;
  options.tolerance_abs = 1e-16;
  options.max_iterations = 60000;
  options.direct_solve = false;  // the iteration itself, without the direct solve
  ContactSolver solver;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(4);
  const SolverStatistics stalled = solver.Solve(problem, options, &lambda);
  // Λ_N^ν = 1 - (1 - 1e-4)^ν (never projected): error e^-6 ≈ 2.5e-3 after 60000 iterations, its
  // last change 1e-4 times that, below its tolerance 1e-6·Λ_N. Flagged all the same.
  const double error_n = std::pow(1.0 - 1e-4, options.max_iterations);
  EXPECT_NEAR(lambda[0], expected[0] - error_n, 1e-12);
  EXPECT_GT(error_n, 1000 * options.tolerance_rel);
  EXPECT_LE(stalled.max_change, options.tolerance_rel * lambda[0]);
  EXPECT_FALSE(stalled.converged);
  EXPECT_GT(stalled.residual, 1.0);
  EXPECT_EQ(stalled.iterations, options.max_iterations);
  // given enough iterations it converges, and then truly: within the tolerance of Λ*
  options.max_iterations = 1000000;
  lambda.setZero();
  const SolverStatistics stats = solver.Solve(problem, options, &lambda);
  ASSERT_TRUE(stats.converged);
  EXPECT_LE(stats.residual, 1.0);
  EXPECT_GT(stats.iterations, 100000);
  EXPECT_TRUE(WithinTolerance(lambda, expected, options));
  // (46) and Gauss-Seidel step each component by 1/G_kk: s_k = 1, solved in one iteration and
  // confirmed in the second, as with the plain increment test
  for (SolverType type : {SolverType::kModifiedJacobi, SolverType::kGaussSeidel}) {
    options.type = type;
    lambda.setZero();
    const SolverStatistics natural = solver.Solve(problem, options, &lambda);
    EXPECT_TRUE(natural.converged);
    EXPECT_EQ(natural.iterations, 2) << SolverTypeName(type);
  }
}

TEST(StoppingRule, ConvergedSlidingContactsAreWithinTheTolerance) {
  // The sliding Tippe-Top contact (projecting friction block) at the simulator's default
  // tolerance, against a reference solved to 1e-11: every converged answer must lie within the
  // tolerance of the reference. On the original sets the iterate creeps along the boundary at
  // r̂_F = α/G_ττ (G_ττ ≈ 3000 G_TT) and the unscaled increment test stopped up to 9 times the
  // tolerance away (ellipsoid and the direct exact/cylinder at θ = 0.1, measured before s_k).
  // Mapped (sphere; exact, cylinder by default) the block contracts much faster than σ_τ ≈ 3000
  // assumes; the cap q/(1 - q) keeps the 3 iterations per solve of the plain test (measured with
  // it: 3; σ_k alone needs 4).
  for (double inclination : {0.1, 0.3, 0.5, 1.2}) {
    for (FrictionSet set : {FrictionSet::kSphere, FrictionSet::kExact, FrictionSet::kCylinder,
                            FrictionSet::kEllipsoid}) {
      const ContactProblem problem = TippeTopSlidingContact(inclination, set);
      SolverOptions tight;
      tight.tolerance_rel = 1e-11;
      tight.tolerance_abs = 1e-22;
      tight.max_iterations = 100000;
      ContactSolver solver;
      Eigen::VectorXd reference = Eigen::VectorXd::Zero(4);
      ASSERT_TRUE(solver.Solve(problem, tight, &reference).converged);
      ASSERT_TRUE(SatisfiesInclusion(problem, reference, 1e-9));
      for (SolverType type : kAllSolverTypes) {
        for (bool map : {true, false}) {
          SolverOptions options;
          options.type = type;
          options.map_drilling_sets = map;
          const std::string what =
              std::string(FrictionSetName(set)) + " θ = " + std::to_string(inclination) + " " +
              std::string(SolverTypeName(type)) + (map ? " mapped" : " direct");
          Eigen::VectorXd lambda = Eigen::VectorXd::Zero(4);
          const SolverStatistics stats = solver.Solve(problem, options, &lambda);
          EXPECT_TRUE(stats.friction_projected[0]) << what;
          EXPECT_EQ(stats.converged, stats.residual <= 1.0) << what;
          if (stats.converged) {
            EXPECT_TRUE(WithinTolerance(lambda, reference, options)) << what;
          }
          const bool iterated_mapped =
              set == FrictionSet::kSphere || (map && set != FrictionSet::kEllipsoid);
          if (type != SolverType::kJacobi && iterated_mapped) {
            EXPECT_TRUE(stats.converged) << what;
            EXPECT_LE(stats.iterations, 3) << what;
          }
        }
      }
    }
  }
}

// ============================== API contract ==============================

TEST(SolverContract, OneIterationWithZeroToleranceIsFiniteAndUnconverged) {
  const ContactLaw law = MakeLaw(FrictionSet::kSphere, 0.3, 0.02);
  const ContactProblem problem =
      SingleContact(law, Eigen::Vector4d(2.0, 3.0, 3.0, 400.0), Eigen::Vector4d(-1.0, 0.5, 0.2, 3.0));
  for (SolverType type : kAllSolverTypes) {
    SolverOptions options;
    options.type = type;
    options.tolerance_abs = 0.0;
    options.tolerance_rel = 0.0;
    options.max_iterations = 1;
    ContactSolver solver;
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(4);
    const SolverStatistics stats = solver.Solve(problem, options, &lambda);
    EXPECT_FALSE(stats.converged);
    EXPECT_EQ(stats.iterations, 1);
    EXPECT_TRUE(lambda.allFinite());
    EXPECT_GT(lambda[0], 0.0);
    EXPECT_TRUE(std::isfinite(stats.max_change));
    EXPECT_GT(stats.max_change, 0.0);
    EXPECT_GT(stats.residual, 1.0);
  }
}

TEST(SolverContract, DivergenceStopsWithTheLastFiniteIterate) {
  // α = 1.99 violates the convergence condition of contact_solver.h on coupled problems: some
  // Jacobi iterations grow without bound. The solver must stop there and return finite numbers.
  std::mt19937_64 rng(kSeed + 7);
  int diverged = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const ContactProblem problem = RandomProblem(RandomLaws(2 + trial % 2, rng), rng);
    SolverOptions options = Tight(SolverType::kModifiedJacobi);
    options.relaxation = 1.99;
    options.max_iterations = 5000;
    ContactSolver solver;
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(problem.c.size());
    const SolverStatistics stats = solver.Solve(problem, options, &lambda);
    EXPECT_TRUE(lambda.allFinite()) << "trial " << trial;
    if (std::isinf(stats.max_change)) {
      ++diverged;
      EXPECT_FALSE(stats.converged);
      EXPECT_TRUE(std::isinf(stats.residual));
      EXPECT_LT(stats.iterations, options.max_iterations);
    }
  }
  EXPECT_GT(diverged, 0);
}

TEST(SolverContract, ResidualFollowsTheDocumentedStoppingRule) {
  const ContactLaw law = MakeLaw(FrictionSet::kCoulomb, 0.3, 0.0);
  const ContactProblem problem =
      SingleContact(law, Eigen::Vector3d(2.0, 3.0, 3.0), Eigen::Vector3d(-1.0, 0.05, 0.02));
  SolverOptions options = Tight(SolverType::kModifiedJacobi);
  options.tolerance_rel = 1e-6;
  options.tolerance_abs = 1e-9;
  ContactSolver solver;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(3);
  const SolverStatistics stats = solver.Solve(problem, options, &lambda);
  ASSERT_TRUE(stats.converged);
  EXPECT_LE(stats.residual, 1.0);
  // run one iteration less from the same start: not converged, residual above 1
  if (stats.iterations > 1) {
    options.max_iterations = stats.iterations - 1;
    Eigen::VectorXd partial = Eigen::VectorXd::Zero(3);
    const SolverStatistics shorter = solver.Solve(problem, options, &partial);
    EXPECT_FALSE(shorter.converged);
    EXPECT_GT(shorter.residual, 1.0);
  }
}

std::string InvalidArgumentMessage(const std::function<void()>& call) {
  try {
    call();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "no std::invalid_argument";
}

TEST(SolverContract, InvalidOptionsNameTheField) {
  const auto check = [](const SolverOptions& options, const std::string& field,
                        const std::string& range) {
    const std::string message = InvalidArgumentMessage([&] { ValidateSolverOptions(options); });
    EXPECT_NE(message.find(field), std::string::npos) << message;
    EXPECT_NE(message.find(range), std::string::npos) << message;
    // Solve validates too, before touching anything
    ContactSolver solver;
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(1);
    const ContactProblem problem = SingleContact(MakeLaw(FrictionSet::kSphere, 0.0, 0.0),
                                                 Eigen::VectorXd::Ones(1), -Eigen::VectorXd::Ones(1));
    EXPECT_THROW(solver.Solve(problem, options, &lambda), std::invalid_argument);
    EXPECT_EQ(lambda[0], 0.0);
  };
  SolverOptions options;
  EXPECT_NO_THROW(ValidateSolverOptions(options));
  for (double bad : {-1e-9, std::nan(""), std::numeric_limits<double>::infinity()}) {
    options = SolverOptions();
    options.tolerance_rel = bad;
    check(options, "tolerance_rel", ">= 0");
    options = SolverOptions();
    options.tolerance_abs = bad;
    check(options, "tolerance_abs", ">= 0");
  }
  for (int bad : {0, -5}) {
    options = SolverOptions();
    options.max_iterations = bad;
    check(options, "max_iterations", ">= 1");
  }
  for (double bad : {0.0, 2.0, -0.5, 3.0, std::nan("")}) {
    options = SolverOptions();
    options.relaxation = bad;
    check(options, "relaxation", "(0, 2)");
  }
  options = SolverOptions();
  options.relaxation = 1.999;
  EXPECT_NO_THROW(ValidateSolverOptions(options));
  options.tolerance_rel = 0.0;
  options.tolerance_abs = 0.0;
  EXPECT_NO_THROW(ValidateSolverOptions(options));
}

TEST(SolverContract, InvalidProblemsAreRejected) {
  const ContactLaw law = MakeLaw(FrictionSet::kSphere, 0.3, 0.02);  // dim 4
  const ContactProblem good = SingleContact(law, Eigen::Vector4d::Ones(), -Eigen::Vector4d::Ones());
  EXPECT_NO_THROW(ValidateContactProblem(good));
  const auto rejects = [](const ContactProblem& problem, const std::string& field) {
    const std::string message = InvalidArgumentMessage([&] { ValidateContactProblem(problem); });
    EXPECT_NE(message.find(field), std::string::npos) << message;
  };
  ContactProblem bad = good;
  bad.c = Eigen::VectorXd::Ones(3);
  rejects(bad, "ContactProblem.G");
  bad = good;
  bad.G(1, 2) = std::nan("");
  rejects(bad, "ContactProblem.G");
  bad = good;
  bad.c[3] = std::numeric_limits<double>::infinity();
  rejects(bad, "ContactProblem.c");
  bad = good;
  bad.G(2, 2) = 0.0;
  rejects(bad, "diagonal");
  bad = good;
  bad.contacts[0].offset = 1;
  rejects(bad, "offset");
  bad = good;
  bad.contacts[0].law.mu = -0.1;
  rejects(bad, "law.mu");
  bad = good;
  bad.contacts[0].law.rbar = std::nan("");
  rejects(bad, "law.rbar");
  bad = good;
  bad.contacts[0].law.rbar = 0.0;  // now dim 3, but G and c have 4 rows
  rejects(bad, "sum of the contact dimensions");

  ContactSolver solver;
  Eigen::VectorXd wrong_size = Eigen::VectorXd::Zero(3);
  EXPECT_NE(InvalidArgumentMessage([&] {
              solver.Solve(good, SolverOptions(), &wrong_size);
            }).find("warm start"),
            std::string::npos);
  Eigen::VectorXd not_finite = Eigen::Vector4d(0, std::nan(""), 0, 0);
  EXPECT_THROW(solver.Solve(good, SolverOptions(), &not_finite), std::invalid_argument);
  EXPECT_THROW(solver.Solve(good, SolverOptions(), nullptr), std::invalid_argument);
}

TEST(SolverContract, EmptyProblemConvergesImmediately) {
  ContactSolver solver;
  Eigen::VectorXd lambda(0);
  const SolverStatistics stats = solver.Solve(ContactProblem(), SolverOptions(), &lambda);
  EXPECT_TRUE(stats.converged);
  EXPECT_EQ(stats.iterations, 0);
}

TEST(SolverContract, NoHeapAllocationOnceTheSizeHasBeenSeen) {
  std::mt19937_64 rng(kSeed + 6);
  std::vector<ContactLaw> laws = {MakeLaw(FrictionSet::kSphere, 0.3, 0.02),
                                  MakeLaw(FrictionSet::kEllipsoid, 0.3, 0.02),
                                  MakeLaw(FrictionSet::kCoulomb, 0.3, 0.0)};
  const ContactProblem large = RandomProblem(laws, rng);
  laws.pop_back();
  const ContactProblem small = RandomProblem(laws, rng);
  for (SolverType type : kAllSolverTypes) {
    ContactSolver solver;
    SolverStatistics stats;
    Eigen::VectorXd lambda_large = Eigen::VectorXd::Zero(large.c.size());
    Eigen::VectorXd lambda_small = Eigen::VectorXd::Zero(small.c.size());
    const SolverOptions options = Tight(type);
    solver.Solve(large, options, &lambda_large, &stats);  // sizes the workspace
    const long before = test::HeapAllocations();
    solver.Solve(small, options, &lambda_small, &stats);
    lambda_large.setZero();
    solver.Solve(large, options, &lambda_large, &stats);
    const long after = test::HeapAllocations();
    EXPECT_EQ(after - before, 0) << SolverTypeName(type);
    EXPECT_TRUE(stats.converged);
  }
  // the counter does count: a container (operator new) and an Eigen vector (std::malloc, what
  // the solver's workspace uses); the asm keeps the compiler from eliding either allocation
  long before = test::HeapAllocations();
  std::vector<double> probe(1000);
  asm volatile("" : : "g"(probe.data()) : "memory");
  EXPECT_GT(test::HeapAllocations() - before, 0) << "std::vector";
  before = test::HeapAllocations();
  Eigen::VectorXd eigen_probe(1000);
  asm volatile("" : : "g"(eigen_probe.data()) : "memory");
  EXPECT_GT(test::HeapAllocations() - before, 0) << "Eigen::VectorXd";
}

}  // namespace
}  // namespace nonsmooth_sim
