// Shared by the ContactSolver tests (contact_solver_*_test.cpp): laws and options, an independent
// check of the inclusion (17) (the support function and level set of every friction set, the
// Coulomb-Contensou boundary (51)-(52) written out independently), rigid-body Delassus matrices of
// a chain of bodies, problems with a constructed solution and random problems without one, and
// one sliding, drilling contact of the Tippe-Top.
//
// Sign convention (contact_solver.h): -ξ_i ∈ N_{C_i}(Λ_i) with C_i the set of admissible Λ_i.
#ifndef NONSMOOTH_SIM_TEST_CORE_CONTACT_SOLVER_SUPPORT_H_
#define NONSMOOTH_SIM_TEST_CORE_CONTACT_SOLVER_SUPPORT_H_

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "nonsmooth_sim/core/constants.h"
#include "nonsmooth_sim/core/contact_solver.h"

namespace nonsmooth_sim::contact_solver_support {

inline constexpr std::uint64_t kSeed = 1620091;
inline constexpr double kInverseGoldenRatio = 0.618033988749895;  // golden-section search

inline ContactLaw MakeLaw(FrictionSet set, double mu, double rbar) {
  ContactLaw law;
  law.friction_set = set;
  law.mu = mu;
  law.rbar = rbar;
  return law;
}

inline SolverOptions Tight(SolverType type) {
  SolverOptions options;
  options.type = type;
  options.tolerance_rel = 1e-13;
  options.tolerance_abs = 1e-16;
  options.max_iterations = 200000;
  return options;
}

// λ_max(D^{-1/2} G D^{-1/2}), D = diag(G)
inline double ScaledMaxEigenvalue(const Eigen::MatrixXd& g) {
  const Eigen::VectorXd d = g.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd scaled = d.asDiagonal() * g * d.asDiagonal();
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(scaled).eigenvalues().maxCoeff();
}

// Tight options with a relaxation α inside the convergence condition stated in contact_solver.h
// (with margin: α ≤ 1.6/λ_max), for coupled problems.
inline SolverOptions Convergent(SolverType type, const ContactProblem& problem) {
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

inline ContactProblem SingleContact(const ContactLaw& law, const Eigen::VectorXd& g_diagonal,
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
inline constexpr double kMaxU = 1e3;
inline Boundary ContensouCurve(double u) {
  if (u <= 1.0) return {3.0 * kPi / 32.0 * (-u * u * u + 4.0 * u), (3 * std::pow(u, 4) - 8 * u * u + 8) / 8.0};
  const double arcsin = std::asin(1.0 / u);
  const double root = std::sqrt(u * u - 1.0);
  return {3.0 / 16.0 * ((-u * u * u + 4.0 * u) * arcsin + (u * u + 2.0) / u * root),
          ((3 * std::pow(u, 4) - 8 * u * u + 8) * arcsin + (-3 * u * u + 6) * root) / (4.0 * kPi)};
}
// outward normal of B_F's cross-section at u in the normalised coordinates (b_T, b_τ): on both
// branches of (51)-(52) db_τ/du = -u (16/3π) db_T/du (for u ≤ 1 by differentiating the
// polynomials), so the normal (-b_τ', b_T') is ∝ (16u/3π, 1)
inline Eigen::Vector2d ContensouNormal(double u) {
  return Eigen::Vector2d(16.0 * u / (3.0 * kPi), 1.0).normalized();
}

// ---- independent check of the inclusion (17): normal complementarity, Λ_F ∈ F, and
// -ξ_F ∈ N_F(Λ_F) through the support function: σ_F(-ξ_F) = -ξ_F·Λ_F ----
// support function of the law's friction set of radius rho in direction d = (d_T1, d_T2, d_τ)
inline double Support(const ContactLaw& law, int dim, const Eigen::Vector3d& d, double rho) {
  const double d_t = d.head<2>().norm();
  const double d_tau = std::abs(d.z());
  if (dim == 3) return rho * d_t;
  switch (law.friction_set) {
    case FrictionSet::kCylinder: return rho * (d_t + law.rbar * d_tau);
    case FrictionSet::kEllipsoid:
    case FrictionSet::kSphere:
    case FrictionSet::kRolling:  // the 3-D part: E_F, as the sphere row
    case FrictionSet::kRollingDecoupled: return rho * std::hypot(d_t, law.rbar * d_tau);
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
inline double Level(const ContactLaw& law, int dim, const Eigen::Vector3d& p, double rho) {
  const double t = p.head<2>().norm() / rho;
  const double s = std::abs(p.z()) / (law.rbar * rho);
  if (dim == 3) return t;
  switch (law.friction_set) {
    case FrictionSet::kCylinder: return std::max(t, s);
    case FrictionSet::kEllipsoid:
    case FrictionSet::kSphere:
    case FrictionSet::kRolling:  // the 3-D part: E_F, as the sphere row
    case FrictionSet::kRollingDecoupled: return std::hypot(t, s);
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

inline ::testing::AssertionResult SatisfiesInclusion(const ContactProblem& problem,
                                                     const Eigen::VectorXd& lambda,
                                                     double tolerance) {
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
inline Eigen::Vector3d RandomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::Vector3d v(normal(rng), normal(rng), normal(rng));
  return v.normalized();
}

inline Eigen::MatrixXd ChainDelassus(const std::vector<ContactLaw>& laws, std::mt19937_64& rng) {
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
inline void FrictionBoundaryPoint(const ContactLaw& law, int dim, double rho, std::mt19937_64& rng,
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
    case FrictionSet::kSphere:
    case FrictionSet::kRolling:  // without μ_r: the sphere row (theory.md, "Rolling resistance")
    case FrictionSet::kRollingDecoupled: {
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

inline Constructed Construct(const std::vector<ContactLaw>& laws,
                             const std::vector<Regime>& regimes, std::mt19937_64& rng) {
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
inline std::string Describe(const ContactProblem& problem,
                            const std::vector<Regime>& regimes = {}) {
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

inline std::vector<ContactLaw> RandomLaws(int m, std::mt19937_64& rng) {
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

inline std::vector<Regime> RandomRegimes(int m, std::mt19937_64& rng) {
  std::vector<Regime> regimes;
  for (int i = 0; i < m; ++i) regimes.push_back(static_cast<Regime>(rng() % 3));
  return regimes;
}

// |Λ - Λ*| per component against the scale of its contact (τ in units of R̄)
inline ::testing::AssertionResult NearSolution(const ContactProblem& problem,
                                               const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                                               double tolerance) {
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

// Random problems without a known solution: velocities and gravity on the chain of bodies.
inline ContactProblem RandomProblem(const std::vector<ContactLaw>& laws, std::mt19937_64& rng) {
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

// the options with the drilling sets iterated unmapped, on D (37)
inline SolverOptions Unmapped(SolverOptions options) {
  options.map_drilling_sets = false;
  return options;
}

// One contact of the Tippe-Top (tippe-top.md: m = 6 g, Θ_S = diag(8, 8, 7)·1e-7 kg m², big sphere
// R1 = 15 mm at a1 = 3 mm from S, μ = 0.3, R = 0.5 mm), e3 tilted by θ about the world x axis,
// spinning at 180 rad/s about e3 with S at rest: the contact point slides and drills. G and c of
// (16) for one step Δt = 1e-4 s, W: N = ẑ, T1 = x̂, T2 = ŷ at the contact point, τ about ẑ.
inline ContactProblem TippeTopSlidingContact(double inclination, FrictionSet set) {
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

}  // namespace nonsmooth_sim::contact_solver_support

#endif  // NONSMOOTH_SIM_TEST_CORE_CONTACT_SOLVER_SUPPORT_H_
