// The fixed-point iterations (37), (43), (46) and projected Gauss-Seidel for the inclusion (17).
// The equations and the exact treatment of (46) and of the normal component are in
// contact_solver.h.
#include "nonsmooth_sim/core/contact_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "nonsmooth_sim/core/all_finite.h"
#include "nonsmooth_sim/core/ball_contact_solve.h"
#include "nonsmooth_sim/core/enum_names.h"
#include "nonsmooth_sim/core/transformation.h"

namespace nonsmooth_sim {
namespace {

using internal::ContactWork;

std::string Describe(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

bool IsFiniteNonNegative(double value) { return std::isfinite(value) && value >= 0.0; }

[[noreturn]] void ThrowNotFiniteNonNegative(const std::string& field, const char* unit,
                                            double value) {
  throw std::invalid_argument(field + ": must be finite and >= 0" + unit + ", got " +
                              Describe(value));
}


struct ContactUpdate {
  Eigen::Vector4d next;  // Λ̂_i^{ν+1}, zero where the contact has no component
  bool normal_projected;
  bool friction_projected;
  bool friction_natural_step;  // (46) accepted y: every friction component stepped α/Ĝ_kk
};

// Friction block of one contact: z = Λ̂_F^ν - r ξ̂_F, then (43) or (46). `Vector` is the block's
// fixed-size vector type and `prox` its Euclidean projection for the radius μΛ_N^{ν+1}.
template <bool kModified, typename Vector, typename Prox>
Vector UpdateFriction(const Vector& lambda, const Vector& xi, const Vector& step, double r,
                      const Prox& prox, bool* projected, bool* natural_step) {
  const Vector z = lambda - r * xi;
  const auto p = prox(z);
  *projected = p.region != ProxRegion::kInterior;
  *natural_step = false;
  if (kModified && !*projected) {
    // (46), non-projecting case (44): Q = diag(α / (r̂ Ĝ_kk)), i.e. Λ̂_k - (α / Ĝ_kk) ξ̂_k,
    // accepted only if it stays in the set; otherwise Q = I, which here is the step z of (43)
    const Vector jacobi = lambda - step.cwiseProduct(xi);
    if (prox(jacobi).region == ProxRegion::kInterior) {
      *natural_step = true;
      return jacobi;
    }
  }
  // (37), (43); (46) with Q = I
  return p.point;
}

// One contact: Λ̂_i^{ν+1} from Λ̂_i^ν and ξ̂_i = Σ_j Ĝ_ij Λ̂_j + ĉ_i; `rim_hint` is w's.
template <bool kModified>
ContactUpdate UpdateContact(const ContactWork& w, const Eigen::Vector4d& lambda,
                            const Eigen::Vector4d& xi, double* rim_hint) {
  ContactUpdate update{Eigen::Vector4d::Zero(), false, false, false};
  // normal block {Λ_N ≥ 0}: (43) with r̂_i; (46) on the 1-D block has r̂ = α/Ĝ_NN and Q = 1
  const double r_normal = kModified ? w.r_normal : w.r_contact;
  const Prox1 normal = ProxNonNegative(lambda[0] - r_normal * xi[0]);
  update.next[0] = normal.point;
  update.normal_projected = normal.region != ProxRegion::kInterior;
  if (w.dim == 1) return update;

  // friction block, scaled by the new normal percussion: radius μΛ_N^{ν+1}
  const double radius = w.mu * normal.point;
  const double r = kModified ? w.r_friction : w.r_contact;
  if (w.dim == 3) {
    // planar Coulomb disk ||Λ_T|| ≤ μΛ_N
    const auto disk = [radius](const Eigen::Vector2d& z) { return ProxDisk(z, radius); };
    update.next.segment<2>(1) = UpdateFriction<kModified, Eigen::Vector2d>(
        lambda.segment<2>(1), xi.segment<2>(1), w.step.segment<2>(1), r, disk,
        &update.friction_projected, &update.friction_natural_step);
    return update;
  }
  // (T1, T2, τ) on the law's set in the iterated coordinates (Λ̂ = A⁻¹Λ or Λ): its row's prox
  // (friction_law.h), set_rbar the R̄ of the iterated set (1 on A⁻¹B_F, A⁻¹C_F), rim_hint the
  // warm start of B_F's prox (ContactWork::rim_hint). Inlined, as ScaledChange below: as calls
  // they cost the Tippe-Top about 100 instructions per step (callgrind), 2 %, and 300 (5 %) with
  // `exact`.
  const auto set = [&w, radius, rim_hint](const Eigen::Vector3d& z) {
    return ProxFrictionLaw(w.set, z, radius, w.set_rbar, rim_hint);
  };
  update.next.tail<3>() = UpdateFriction<kModified, Eigen::Vector3d>(
      lambda.tail<3>(), xi.tail<3>(), w.step.tail<3>(), r, set, &update.friction_projected,
      &update.friction_natural_step);
  return update;
}

// Cap on s_k of a projecting friction block: the a-posteriori estimate q/(1 - q) of a linearly
// converging iteration, q = max_{k∈F}|ΔΛ̂_k^ν| / max_{k∈F}|ΔΛ̂_k^{ν-1}| (contact_solver.h);
// +inf (no cap) unless the block's change shrank
double ProjectedChangeCap(const Eigen::Vector4d& change, const Eigen::Vector4d& previous_change) {
  const double now = change.tail<3>().maxCoeff();
  const double before = previous_change.tail<3>().maxCoeff();
  if (!(now < before)) return std::numeric_limits<double>::infinity();
  return std::max(1.0, now / (before - now));
}

// s_k of the stopping rule (contact_solver.h) for the step contact `w` took in its last update;
// `change` and `previous_change` are |ΔΛ̂| of that update and of the one before (σ_k, capped by
// q/(1 - q) on a projecting friction block)
template <bool kModified>
[[gnu::always_inline]] inline Eigen::Array4d ChangeScale(const ContactWork& w,
                                                         const Eigen::Vector4d& change,
                                                         const Eigen::Vector4d& previous_change) {
  // (46): the accepted y stepped every component naturally, as the normal block always does
  if (kModified && w.friction_natural_step) return Eigen::Array4d::Ones();
  Eigen::Array4d scale =
      kModified ? w.change_scale_friction.array() : w.change_scale_contact.array();
  if (w.friction_projected) {
    scale.tail<3>() = scale.tail<3>().min(ProjectedChangeCap(change, previous_change));
  }
  return scale;
}

// The distance measure of the stopping rule in Λ̂ for contact `w` at `lambda` = Λ̂^{ν+1}:
// max(|ΔΛ̂_k|, min(s_k|ΔΛ̂_k|, 2e_k)) with e_k the half-width of the friction set of radius
// ρ = μΛ_N^{ν+1} along k (ρ for T1, T2; R̄ρ/a_τ for τ, i.e. set_rbar·ρ), no bound for the normal
template <bool kModified>
[[gnu::always_inline]] inline Eigen::Array4d ScaledChange(const ContactWork& w,
                                                          const Eigen::Vector4d& lambda,
                                                          const Eigen::Vector4d& change,
                                                          const Eigen::Vector4d& previous_change) {
  const Eigen::Array4d scaled = ChangeScale<kModified>(w, change, previous_change) * change.array();
  const double rho = w.mu * lambda[0];
  const Eigen::Array4d width(std::numeric_limits<double>::infinity(), 2 * rho, 2 * rho,
                             2 * w.set_rbar * rho);
  return scaled.min(width).max(change.array());
}

// max over components of d_k / (tolerance_abs + tolerance_rel |Λ_k|), 0/0 = 0, x/0 = +inf, with
// `distance` = d_k of the stopping rule
double ResidualTerm(const Eigen::Vector4d& distance, const Eigen::Vector4d& lambda,
                    const SolverOptions& options) {
  double residual = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double bound = options.tolerance_abs + options.tolerance_rel * std::abs(lambda[k]);
    if (distance[k] == 0.0) continue;
    residual = std::max(residual, bound > 0.0 ? distance[k] / bound
                                              : std::numeric_limits<double>::infinity());
  }
  return residual;
}

// The direct solve of several contacts (ContinueBlockDirectly): at most this many contacts (a
// fixed-size array of their metrics), sweeps, and the relative change of Λ̂ that ends the sweeps
// (far below any tolerance_rel the iteration then checks).
constexpr std::size_t kMaxDirectContacts = 64;
constexpr int kMaxDirectSweeps = 200;
constexpr double kDirectSweepTolerance = 1e-13;

// The iterated friction set of `w` as {||D⁻¹Λ̂_F|| ≤ μΛ̂_N}, if it is one (its row's ball
// metric, friction_law.h): the disk of 3-component contacts, S_F (mapped, D = I), E_F
// (D = diag(1, 1, R̄)); B_F and C_F are not balls.
bool BallMetricOf(const ContactWork& w, Eigen::Vector3d* metric) {
  *metric = Eigen::Vector3d::Ones();
  switch (LawOf(w.set).ball_metric) {
    case BallMetric::kNone: return false;
    case BallMetric::kUnit: return true;
    case BallMetric::kDrillingRadius: metric->z() = w.set_rbar; return true;
  }
  return false;
}

}  // namespace

void ValidateSolverOptions(const SolverOptions& options) {
  if (!IsOneOf(options.type, kAllSolverTypes)) {
    throw std::invalid_argument("SolverOptions.type: must be one of " + SolverTypeNameList());
  }
  if (!IsFiniteNonNegative(options.tolerance_rel)) {
    ThrowNotFiniteNonNegative("SolverOptions.tolerance_rel", "", options.tolerance_rel);
  }
  if (!IsFiniteNonNegative(options.tolerance_abs)) {
    ThrowNotFiniteNonNegative("SolverOptions.tolerance_abs", " [N s]", options.tolerance_abs);
  }
  if (options.max_iterations < 1 || options.max_iterations > kMaxSolverIterations) {
    throw std::invalid_argument("SolverOptions.max_iterations: must be >= 1 and <= " +
                                std::to_string(kMaxSolverIterations) + ", got " +
                                std::to_string(options.max_iterations));
  }
  if (!(options.relaxation >= kMinRelaxation && options.relaxation < 2.0)) {
    throw std::invalid_argument(
        "SolverOptions.relaxation (alpha of (43)): must be in [" + Describe(kMinRelaxation) +
        ", 2) (the convergence interval (0, 2), bounded below because the iteration contracts "
        "by only 1 - alpha per step), got " + Describe(options.relaxation));
  }
}

void ValidateContactProblem(const ContactProblem& problem) {
  const Eigen::Index n = problem.c.size();
  if (problem.G.rows() != n || problem.G.cols() != n) {
    throw std::invalid_argument("ContactProblem.G: must be n x n with n = size of c = " +
                                std::to_string(n) + ", got " + std::to_string(problem.G.rows()) +
                                " x " + std::to_string(problem.G.cols()));
  }
  Eigen::Index offset = 0;
  for (std::size_t i = 0; i < problem.contacts.size(); ++i) {
    const ContactBlock& contact = problem.contacts[i];
    // the message is only built on failure: validation must not allocate
    const auto name = [i] { return "ContactProblem.contacts[" + std::to_string(i) + "]"; };
    const ContactLaw& law = contact.law;
    if (!IsFiniteNonNegative(law.mu)) ThrowNotFiniteNonNegative(name() + ".law.mu", "", law.mu);
    if (!IsFiniteNonNegative(law.rbar)) {
      ThrowNotFiniteNonNegative(name() + ".law.rbar", " [m]", law.rbar);
    }
    if (!IsFrictionSet(law.friction_set)) {
      throw std::invalid_argument(name() + ".law.friction_set: must be one of " +
                                  FrictionSetNameList());
    }
    if (contact.offset != offset) {
      throw std::invalid_argument(name() + ".offset: must be " + std::to_string(offset) +
                                  " (contacts in order, without gaps), got " +
                                  std::to_string(contact.offset));
    }
    offset += ContactDimension(law);
  }
  if (offset != n) {
    throw std::invalid_argument("ContactProblem.c: size must be the sum of the contact dimensions " +
                                std::to_string(offset) + ", got " + std::to_string(n));
  }
  if (!problem.G.allFinite()) throw std::invalid_argument("ContactProblem.G: must be finite");
  if (!problem.c.allFinite()) throw std::invalid_argument("ContactProblem.c: must be finite");
  for (Eigen::Index k = 0; k < n; ++k) {
    if (!(problem.G(k, k) > 0.0)) {
      throw std::invalid_argument("ContactProblem.G: diagonal entries must be > 0, G(" +
                                  std::to_string(k) + ", " + std::to_string(k) + ") = " +
                                  Describe(problem.G(k, k)));
    }
  }
}

SolverStatistics ContactSolver::Solve(const ContactProblem& problem, const SolverOptions& options,
                                      Eigen::VectorXd* lambda) {
  SolverStatistics statistics;
  Solve(problem, options, lambda, &statistics);
  return statistics;
}

void ContactSolver::Solve(const ContactProblem& problem, const SolverOptions& options,
                          Eigen::VectorXd* lambda, SolverStatistics* statistics) {
  ValidateSolverOptions(options);
  ValidateContactProblem(problem);
  if (lambda == nullptr) throw std::invalid_argument("lambda: must not be null");
  if (statistics == nullptr) throw std::invalid_argument("statistics: must not be null");
  if (lambda->size() != problem.c.size()) {
    throw std::invalid_argument("lambda (warm start): size must be n = " +
                                std::to_string(problem.c.size()) + ", got " +
                                std::to_string(lambda->size()));
  }
  if (!lambda->allFinite()) throw std::invalid_argument("lambda (warm start): must be finite");
  SolvePrevalidated(problem, options, lambda, statistics);
}

void BlockContactProblem::Resize(int m) {
  const std::size_t n = static_cast<std::size_t>(m);
  if (laws.size() == n) return;
  laws.resize(n);
  G.resize(n * n);
  c.resize(n);
}

void ContactSolver::SolvePrevalidated(const ContactProblem& problem, const SolverOptions& options,
                                      Eigen::VectorXd* lambda, SolverStatistics* statistics) {
  // the dense problem in padded blocks (zeros beyond each contact's dimension)
  const int m = static_cast<int>(problem.contacts.size());
  blocks_.Resize(m);
  block_lambda_.resize(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i) {
    const ContactBlock& a = problem.contacts[static_cast<std::size_t>(i)];
    const int da = ContactDimension(a.law);
    blocks_.laws[static_cast<std::size_t>(i)] = a.law;
    Eigen::Vector4d& ci = blocks_.c[static_cast<std::size_t>(i)];
    Eigen::Vector4d& li = block_lambda_[static_cast<std::size_t>(i)];
    ci.setZero();
    li.setZero();
    for (int k = 0; k < da; ++k) {
      ci[k] = problem.c[a.offset + k];
      li[k] = (*lambda)[a.offset + k];
    }
    for (int j = 0; j < m; ++j) {
      const ContactBlock& b = problem.contacts[static_cast<std::size_t>(j)];
      const int db = ContactDimension(b.law);
      Eigen::Matrix4d& block = blocks_.G[static_cast<std::size_t>(i * m + j)];
      block.setZero();
      for (int k = 0; k < db; ++k) {
        for (int l = 0; l < da; ++l) block(l, k) = problem.G(a.offset + l, b.offset + k);
      }
    }
  }
  SolvePrevalidated(blocks_, options, &block_lambda_, statistics, nullptr);
  for (int i = 0; i < m; ++i) {
    const ContactBlock& a = problem.contacts[static_cast<std::size_t>(i)];
    for (int k = 0; k < work_[static_cast<std::size_t>(i)].dim; ++k) {
      (*lambda)[a.offset + k] = block_lambda_[static_cast<std::size_t>(i)][k];
    }
  }
}

void ContactSolver::SolvePrevalidated(const BlockContactProblem& problem,
                                      const SolverOptions& options,
                                      std::vector<Eigen::Vector4d>* lambda,
                                      SolverStatistics* statistics,
                                      std::vector<double>* rim_hints) {
  const std::size_t m = problem.laws.size();
  // every flag is written below (m > 0); a resize is free when the size is the last one
  statistics->friction_projected.resize(m);
  statistics->normal_projected.resize(m);
  statistics->iterations = 0;
  statistics->residual = 0.0;
  statistics->max_change = 0.0;
  statistics->converged = true;
  if (m == 0) return;

  Prepare(problem, options, *lambda, rim_hints);
  // one contact (a top on the ground) is the common island: its loops unrolled
  if (m == 1) {
    IterateOne(options, statistics);
  } else {
    // several contacts: only after Gauss-Seidel, whose sweeps the block sweeps are (a Jacobi
    // scheme outside its convergence range, restarted near a solution that the sweeps have not
    // reached, was seen to pass its stopping rule with the twelve feet of stability_parameters_test carrying
    // the wrong load)
    const int budget = options.max_iterations;
    const bool may_solve_directly = options.direct_solve && budget > kDirectSolveAfter &&
                                    options.type == SolverType::kGaussSeidel;
    IterateOf<false>(options, may_solve_directly ? kDirectSolveAfter : budget, statistics);
    if (may_solve_directly && !statistics->converged) ContinueBlockDirectly(options, statistics);
  }

  for (std::size_t i = 0; i < m; ++i) {
    const ContactWork& w = work_[i];
    // Λ_i = A_iΛ̂_i (47); Λ̂_i is zero beyond the contact's dimension
    (*lambda)[i] = w.scale.cwiseProduct(lambda_hat_[i]);
    statistics->normal_projected[i] = w.normal_projected;
    statistics->friction_projected[i] = w.friction_projected;
    if (rim_hints != nullptr) (*rim_hints)[i] = w.rim_hint;
  }
}

void ContactSolver::SolveOnePrevalidated(const Eigen::Matrix4d& G, const Eigen::Vector4d& c,
                                         const ContactLaw& law, const SolverOptions& options,
                                         Eigen::Vector4d* lambda, SolverStatistics* statistics,
                                         double* rim_hint) {
  // Iterate<kType, true> reads slot 0 of the workspace alone: it only has to exist
  if (statistics->friction_projected.empty()) {
    statistics->friction_projected.resize(1);
    statistics->normal_projected.resize(1);
  }
  if (work_.empty()) ResizeWorkspace(1);
  PrepareContact(0, law, options, c, *lambda,
                 rim_hint != nullptr ? *rim_hint : std::numeric_limits<double>::quiet_NaN());
  const ContactWork& w = work_[0];
  g_hat_[0] = TransformBlock(G, w.scale, w.scale);
  if (w.dim < 4) {
    g_hat_[0].bottomRows(4 - w.dim).setZero();
    g_hat_[0].rightCols(4 - w.dim).setZero();
  }
  PrepareSteps(0, g_hat_[0], options);
  IterateOne(options, statistics);
  *lambda = w.scale.cwiseProduct(lambda_hat_[0]);
  statistics->normal_projected[0] = w.normal_projected;
  statistics->friction_projected[0] = w.friction_projected;
  if (rim_hint != nullptr) *rim_hint = w.rim_hint;
}

template <bool kSingle>
void ContactSolver::IterateOf(const SolverOptions& options, int max_iterations,
                              SolverStatistics* statistics) {
  switch (options.type) {
    case SolverType::kJacobi:
      Iterate<SolverType::kJacobi, kSingle>(options, max_iterations, statistics);
      break;
    case SolverType::kModifiedJacobi:
      Iterate<SolverType::kModifiedJacobi, kSingle>(options, max_iterations, statistics);
      break;
    case SolverType::kGaussSeidel:
      Iterate<SolverType::kGaussSeidel, kSingle>(options, max_iterations, statistics);
      break;
  }
}

[[gnu::always_inline]] inline
void ContactSolver::IterateOne(const SolverOptions& options, SolverStatistics* statistics) {
  const int budget = options.max_iterations;
  const bool may_solve_directly = options.direct_solve && budget > kDirectSolveAfter;
  IterateOf<true>(options, may_solve_directly ? kDirectSolveAfter : budget, statistics);
  if (may_solve_directly && !statistics->converged) ContinueDirectly(options, statistics);
}

[[gnu::cold]]
void ContactSolver::ContinueDirectly(const SolverOptions& options, SolverStatistics* statistics) {
  const int budget = options.max_iterations;
  const ContactWork& w = work_[0];
  const int spent = statistics->iterations;
  Eigen::Vector3d metric;
  Eigen::Vector4d direct;
  if (BallMetricOf(w, &metric) &&
      SolveBallContact(g_hat_[0], c_hat_[0], w.dim, w.mu, metric, &direct)) {
    // from the direct solution, the iteration checks it with the stopping rule (one iteration
    // where it is the fixed point)
    lambda_hat_[0] = direct;
    change_[0].setZero();
    previous_change_[0].setZero();
  }
  // otherwise the iteration goes on where it stopped, with the rest of the budget
  IterateOf<true>(options, budget - spent, statistics);
  statistics->iterations += spent;
}

[[gnu::cold]]
void ContactSolver::ContinueBlockDirectly(const SolverOptions& options,
                                          SolverStatistics* statistics) {
  const int budget = options.max_iterations;
  const int spent = statistics->iterations;
  const std::size_t m = work_.size();
  // each contact's direct solver (its Ĝ_ii, law and set stay over the sweeps)
  BallContactSolver direct[kMaxDirectContacts];
  bool ball = m <= kMaxDirectContacts;
  for (std::size_t i = 0; ball && i < m; ++i) {
    const ContactWork& w = work_[i];
    Eigen::Vector3d metric;
    ball = BallMetricOf(w, &metric) && direct[i].Reset(g_hat_[i * m + i], w.dim, w.mu, metric);
  }
  if (ball) {
    // block Gauss-Seidel: contact i solved directly against the others' current percussions
    for (int sweep = 0; sweep < kMaxDirectSweeps; ++sweep) {
      double change = 0.0;
      double size = 0.0;
      bool solved = true;
      for (std::size_t i = 0; i < m && solved; ++i) {
        Eigen::Vector4d c = c_hat_[i];
        for (std::size_t j = 0; j < m; ++j) {
          if (j != i) c.noalias() += g_hat_[i * m + j] * lambda_hat_[j];
        }
        Eigen::Vector4d next;
        solved = direct[i].Solve(c, &next);
        if (!solved) break;
        change = std::max(change, (next - lambda_hat_[i]).cwiseAbs().maxCoeff());
        size = std::max(size, next.cwiseAbs().maxCoeff());
        lambda_hat_[i] = next;
      }
      if (!solved || !(change > kDirectSweepTolerance * size)) break;
    }
    for (std::size_t i = 0; i < m; ++i) {
      change_[i].setZero();
      previous_change_[i].setZero();
    }
  }
  IterateOf<false>(options, budget - spent, statistics);
  statistics->iterations += spent;
}

[[gnu::always_inline]] inline
void ContactSolver::ResizeWorkspace(std::size_t m) {
  work_.resize(m);
  g_hat_.resize(m * m);
  c_hat_.resize(m);
  lambda_hat_.resize(m);
  lambda_next_.resize(m);
  change_.resize(m);
  previous_change_.resize(m);
}

void ContactSolver::Prepare(const BlockContactProblem& problem, const SolverOptions& options,
                            const std::vector<Eigen::Vector4d>& lambda,
                            const std::vector<double>* rim_hints) {
  const std::size_t m = problem.laws.size();
  ResizeWorkspace(m);
  for (std::size_t i = 0; i < m; ++i) {
    PrepareContact(i, problem.laws[i], options, problem.c[i], lambda[i],
                   rim_hints != nullptr ? (*rim_hints)[i]
                                        : std::numeric_limits<double>::quiet_NaN());
  }
  for (std::size_t i = 0; i < m; ++i) {
    const ContactWork& wi = work_[i];
    for (std::size_t j = 0; j < m; ++j) {
      const ContactWork& wj = work_[j];
      // Ĝ_ij = A_iᵀ G_ij A_j (41), zero beyond the dimensions
      Eigen::Matrix4d& g = g_hat_[i * m + j];
      g = TransformBlock(problem.G[i * m + j], wi.scale, wj.scale);
      if (wi.dim < 4) g.bottomRows(4 - wi.dim).setZero();
      if (wj.dim < 4) g.rightCols(4 - wj.dim).setZero();
    }
  }
  for (std::size_t i = 0; i < m; ++i) PrepareSteps(i, g_hat_[i * m + i], options);
}

[[gnu::always_inline]] inline
void ContactSolver::PrepareContact(std::size_t i, const ContactLaw& law,
                                  const SolverOptions& options, const Eigen::Vector4d& c,
                                  const Eigen::Vector4d& lambda, double rim_hint) {
  ContactWork& w = work_[i];
  w.dim = ContactDimension(law);
  w.mu = law.mu;
  // with R̄ = 0 every law degenerates to the coulomb disk
  w.set = w.dim == 4 ? law.friction_set : kPlanarFrictionSet;
  // A_i: (56) for sphere, and for exact and cylinder if options.map_drilling_sets (40)-(47)
  w.scale = ContactMapDiagonal(law, options.map_drilling_sets);
  // B_F, C_F and E_F scale linearly along τ: A⁻¹ maps the set with R̄ to the one with R̄/a_τ
  // (exactly 1 where a_τ = R̄)
  w.set_rbar = w.scale[3] == law.rbar ? 1.0 : law.rbar / w.scale[3];
  w.normal_projected = false;
  w.friction_projected = false;
  w.friction_natural_step = false;
  w.rim_hint = rim_hint;
  // ĉ_i = A_iᵀc_i, Λ̂_i = A_i⁻¹Λ_i (41), zero beyond the dimension (scalar loops: dim ≤ 4);
  // the absolute tolerance in Λ̂ coordinates. Divisions only where a_k ≠ 1 (x/1 = x exactly).
  c_hat_[i].setZero();
  lambda_hat_[i].setZero();
  w.tolerance_abs_hat.setConstant(options.tolerance_abs);
  for (int k = 0; k < w.dim; ++k) {
    c_hat_[i][k] = w.scale[k] * c[k];
    lambda_hat_[i][k] = lambda[k];
    if (w.scale[k] != 1.0) {
      lambda_hat_[i][k] /= w.scale[k];
      w.tolerance_abs_hat[k] *= 1.0 / w.scale[k];
    }
  }
  change_[i].setZero();
  previous_change_[i].setZero();
}

[[gnu::always_inline]] inline
void ContactSolver::PrepareSteps(std::size_t i, const Eigen::Matrix4d& g_hat_ii,
                                 const SolverOptions& options) {
  const double alpha = options.relaxation;
  const double inverse_alpha = 1.0 / alpha;
  ContactWork& w = work_[i];
  const Eigen::Vector4d diagonal = g_hat_ii.diagonal();
  double max_friction = 0.0;
  w.step.setZero();
  // (46), non-projecting: component k steps α / Ĝ_iikk
  w.step[0] = alpha / diagonal[0];
  // α / max_{k∈F} Ĝ_iikk, as min_{k∈F} α / Ĝ_iikk (rounded division is monotone: the same)
  double min_friction_step = std::numeric_limits<double>::infinity();
  for (int k = 1; k < w.dim; ++k) {
    max_friction = std::max(max_friction, diagonal[k]);
    w.step[k] = alpha / diagonal[k];
    min_friction_step = std::min(min_friction_step, w.step[k]);
  }
  // (46) per block: normal {Λ_N ≥ 0} and friction F, each with its own r̂
  w.r_normal = w.step[0];
  w.r_friction = w.dim > 1 ? min_friction_step : 0.0;
  // r̂_i = α / max_k Ĝ_iikk (43)
  w.r_contact = w.dim > 1 ? std::min(w.r_normal, w.r_friction) : w.r_normal;
  // stopping rule: σ_k = (α/Ĝ_iikk) / r̂_k for the steps r̂_i (43) and r̂_F (46, Q = I); 1 for
  // the normal block of (46) (it steps α/Ĝ_iiNN) and where the contact has no component k
  // (σ_k = max_l Ĝ_iill / Ĝ_iikk: products with 1/α instead of divisions, Solve is per step)
  w.change_scale_contact.setOnes();
  w.change_scale_friction.setOnes();
  const double contact_factor = std::max(diagonal[0], max_friction) * inverse_alpha;
  const double friction_factor = max_friction * inverse_alpha;
  for (int k = 0; k < w.dim; ++k) {
    w.change_scale_contact[k] = w.step[k] * contact_factor;
    if (k > 0) w.change_scale_friction[k] = w.step[k] * friction_factor;
  }
}

template <SolverType kType, bool kSingle>
void ContactSolver::Iterate(const SolverOptions& options, int max_iterations,
                            SolverStatistics* statistics) {
  constexpr bool kModified = kType != SolverType::kJacobi;
  constexpr bool kGaussSeidel = kType == SolverType::kGaussSeidel;
  const std::size_t m = kSingle ? 1 : work_.size();
  const double tolerance_rel = options.tolerance_rel;

  // raw pointers into the workspace: the iterates swap roles every iteration
  ContactWork* const work = work_.data();
  const Eigen::Matrix4d* const g_hat = g_hat_.data();
  const Eigen::Vector4d* const c_hat = c_hat_.data();
  Eigen::Vector4d* current = lambda_hat_.data();
  Eigen::Vector4d* next = lambda_next_.data();
  // |Λ̂^{ν+1} - Λ̂^ν| and |Λ̂^ν - Λ̂^{ν-1}|, swapped like the iterates
  Eigen::Vector4d* change = change_.data();
  Eigen::Vector4d* previous_change = previous_change_.data();

  bool converged = false;
  bool finite = true;
  int iteration = 0;
  while (iteration < max_iterations && !converged && finite) {
    ++iteration;
    converged = true;
    for (std::size_t i = 0; i < m; ++i) {
      ContactWork& w = work[i];
      // ξ̂_i = Σ_j Ĝ_ij Λ̂_j + ĉ_i (41); Gauss-Seidel takes this sweep's Λ̂_j for j < i
      const Eigen::Matrix4d* g_row = g_hat + i * m;
      Eigen::Vector4d xi = c_hat[i];
      for (std::size_t j = 0; j < m; ++j) {
        xi.noalias() += g_row[j] * ((kGaussSeidel && j < i) ? next[j] : current[j]);
      }
      const ContactUpdate update = UpdateContact<kModified>(w, current[i], xi, &w.rim_hint);
      next[i] = update.next;
      w.normal_projected = update.normal_projected;
      w.friction_projected = update.friction_projected;
      w.friction_natural_step = update.friction_natural_step;
      // stopping rule, evaluated in Λ̂: a_k d̂_k ≤ tol_abs + tol_rel a_k|Λ̂_k| with a = diag(A_i)
      // and d̂_k = max(|ΔΛ̂_k|, min(s_k|ΔΛ̂_k|, 2ê_k)) ≥ |ΔΛ̂_k|: the plain increment test is
      // necessary, and s_k is only formed once that passes
      const Eigen::Array4d delta = (update.next - current[i]).array().abs();
      change[i] = delta.matrix();
      if (converged) {
        const Eigen::Array4d bound =
            tolerance_rel * update.next.array().abs() + w.tolerance_abs_hat.array();
        converged =
            (delta <= bound).all() &&
            (ScaledChange<kModified>(w, update.next, change[i], previous_change[i]) <= bound).all();
      }
    }
    std::swap(change, previous_change);
    // keep the last finite iterate if the iteration diverged (NaN fails the test above)
    if (!converged) {
      for (std::size_t i = 0; i < m; ++i) finite = finite && AllFinite(next[i]);
    }
    if (finite) std::swap(current, next);
  }
  if (current != lambda_hat_.data()) lambda_hat_.swap(lambda_next_);

  statistics->iterations = iteration;
  statistics->converged = converged && finite;
  if (!finite) {
    statistics->residual = std::numeric_limits<double>::infinity();
    statistics->max_change = std::numeric_limits<double>::infinity();
    return;
  }
  double residual = 0.0;
  double max_change = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    const ContactWork& w = work_[i];
    // back to the original coordinates Λ = AΛ̂ (47)
    const Eigen::Vector4d lambda = w.scale.cwiseProduct(lambda_hat_[i]);
    // the last iteration's change is in `previous_change` after the swap
    const Eigen::Vector4d distance = w.scale.cwiseProduct(
        ScaledChange<kModified>(w, lambda_hat_[i], previous_change[i], change[i]).matrix());
    residual = std::max(residual, ResidualTerm(distance, lambda, options));
    max_change = std::max(max_change, w.scale.cwiseProduct(previous_change[i]).maxCoeff());
  }
  statistics->residual = residual;
  statistics->max_change = max_change;
}

std::string_view SolverTypeName(SolverType type) {
  switch (type) {
    case SolverType::kJacobi: return "jacobi";
    case SolverType::kModifiedJacobi: return "modified_jacobi";
    case SolverType::kGaussSeidel: return "gauss_seidel";
  }
  return "";
}
std::optional<SolverType> SolverTypeFromName(std::string_view name) {
  return EnumFromName(name, kAllSolverTypes, &SolverTypeName);
}
std::string SolverTypeNameList() { return EnumNameList(kAllSolverTypes, &SolverTypeName); }

}  // namespace nonsmooth_sim
