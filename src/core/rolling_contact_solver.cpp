// The 6-block iteration of islands with a rolling contact, see rolling_contact_solver.h.
#include "nonsmooth_sim/core/rolling_contact_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "nonsmooth_sim/core/all_finite.h"
#include "nonsmooth_sim/core/transformation.h"

namespace nonsmooth_sim {

void RollingBlockProblem::Resize(int m) {
  const std::size_t n = static_cast<std::size_t>(m);
  laws.resize(n);
  G.resize(n * n);
  c.resize(n);
}

Vector6d RollingMapDiagonal(const ContactLaw& law, bool map_drilling_sets) {
  Vector6d a = Vector6d::Ones();
  if (HasRolling(law)) {
    const double rho_r = static_cast<double>(law.rolling_resistance) / law.mu;
    a << 1.0, 1.0, 1.0, law.rbar, rho_r, rho_r;
    return a;
  }
  a.head<4>() = ContactMapDiagonal(law, map_drilling_sets);
  return a;
}

Vector6d RollingContactSolver::Update(Work* work, const Vector6d& current,
                                      const Vector6d& xi) const {
  Work& w = *work;
  Vector6d next = Vector6d::Zero();
  // normal block {Λ_N ≥ 0}: (46) with r̂ = α/Ĝ_NN
  const double normal = current[0] - w.step[0] * xi[0];
  w.normal_projected = normal < 0.0;
  next[0] = std::max(0.0, normal);
  w.friction_projected = false;
  w.natural_step = false;
  if (w.dim == 1) return next;
  const double radius = w.mu * next[0];
  const int nf = w.dim - 1;
  // z with r̂_F, y with each component's α/Ĝ_kk; zero beyond the dimension
  Vector6d z = Vector6d::Zero();
  Vector6d y = Vector6d::Zero();
  for (int k = 1; k < w.dim; ++k) {
    z[k] = current[k] - w.r_friction * xi[k];
    y[k] = current[k] - w.step[k] * xi[k];
  }
  // the friction block's prox: 5-D on a rolling contact, the law's 3-D set otherwise
  const auto prox = [&](const Vector6d& x, ProxRegion* region) {
    Vector6d p = Vector6d::Zero();
    if (nf == 5) {
      const Prox5 r = LawOf(w.set).prox5(x.tail<5>(), radius);
      p.tail<5>() = r.point;
      *region = r.region;
    } else {
      const Prox3 r = ProxFrictionLaw(w.set, x.segment<3>(1), radius, w.set_rbar, &w.rim_hint);
      p.segment(1, nf) = r.point.head(nf);
      *region = r.region;
    }
    return p;
  };
  ProxRegion region = ProxRegion::kInterior;
  const Vector6d pz = prox(z, &region);
  if (region != ProxRegion::kInterior) {
    w.friction_projected = true;
    next.tail<5>() = pz.tail<5>();
    return next;
  }
  ProxRegion y_region = ProxRegion::kInterior;
  prox(y, &y_region);
  w.natural_step = y_region == ProxRegion::kInterior;
  next.tail<5>() = w.natural_step ? y.tail<5>() : z.tail<5>();
  return next;
}

Vector6d RollingContactSolver::Distance(const Work& w, const Vector6d& lambda) {
  Vector6d scale = Vector6d::Ones();
  if (!w.natural_step && w.dim > 1) {
    // σ_k = (α/Ĝ_kk)/r̂_F, capped by q/(1 - q) where the prox acted
    double cap = std::numeric_limits<double>::infinity();
    const double now = w.change.tail<5>().maxCoeff();
    const double before = w.previous_change.tail<5>().maxCoeff();
    if (w.friction_projected && now < before) cap = std::max(1.0, now / (before - now));
    for (int k = 1; k < w.dim; ++k) scale[k] = std::min(w.step[k] / w.r_friction, cap);
  }
  const double width = 2.0 * w.mu * lambda[0];
  Vector6d distance = w.change;
  for (int k = 1; k < w.dim; ++k) {
    const double half = k == 3 ? w.set_rbar * width : width;
    distance[k] = std::max(w.change[k], std::min(scale[k] * w.change[k], half));
  }
  return distance;
}

void RollingContactSolver::SolvePrevalidated(const RollingBlockProblem& problem,
                                             const SolverOptions& options,
                                             std::vector<Vector6d>* lambda,
                                             SolverStatistics* statistics,
                                             std::vector<double>* rim_hints) {
  const std::size_t m = problem.laws.size();
  work_.resize(m);
  g_hat_.resize(m * m);
  c_hat_.resize(m);
  lambda_hat_.resize(m);
  lambda_next_.resize(m);
  if (statistics->friction_projected.size() < m) {
    statistics->friction_projected.resize(m);
    statistics->normal_projected.resize(m);
  }
  const double alpha = options.relaxation;
  for (std::size_t i = 0; i < m; ++i) {
    const ContactLaw& law = problem.laws[i];
    Work& w = work_[i];
    w.dim = ContactDimensionWithRolling(law);
    w.mu = law.mu;
    w.set = w.dim >= 4 ? law.friction_set : kPlanarFrictionSet;
    w.scale = RollingMapDiagonal(law, options.map_drilling_sets);
    w.set_rbar = w.scale[3] == law.rbar ? 1.0 : law.rbar / w.scale[3];
    w.rim_hint =
        rim_hints != nullptr ? (*rim_hints)[i] : std::numeric_limits<double>::quiet_NaN();
    c_hat_[i].setZero();
    lambda_hat_[i].setZero();
    w.change.setZero();
    w.previous_change.setZero();
    w.tolerance_abs_hat.setConstant(options.tolerance_abs);
    for (int k = 0; k < w.dim; ++k) {
      c_hat_[i][k] = w.scale[k] * problem.c[i][k];
      lambda_hat_[i][k] = (*lambda)[i][k] / w.scale[k];
      w.tolerance_abs_hat[k] /= w.scale[k];
    }
  }
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t j = 0; j < m; ++j) {
      // Ĝ_ij = A_iᵀ G_ij A_j (41), zero beyond the dimensions
      Matrix6d& g = g_hat_[i * m + j];
      g = work_[i].scale.asDiagonal() * problem.G[i * m + j] * work_[j].scale.asDiagonal();
      if (work_[i].dim < 6) g.bottomRows(6 - work_[i].dim).setZero();
      if (work_[j].dim < 6) g.rightCols(6 - work_[j].dim).setZero();
    }
    Work& w = work_[i];
    const Matrix6d& gii = g_hat_[i * m + i];
    w.step.setZero();
    double max_friction = 0.0;
    for (int k = 0; k < w.dim; ++k) {
      w.step[k] = alpha / gii(k, k);
      if (k > 0) max_friction = std::max(max_friction, gii(k, k));
    }
    w.r_friction = w.dim > 1 ? alpha / max_friction : 0.0;
  }

  const bool gauss_seidel = options.type == SolverType::kGaussSeidel;
  const double tolerance_rel = options.tolerance_rel;
  bool converged = false;
  bool finite = true;
  int iteration = 0;
  while (iteration < options.max_iterations && !converged && finite) {
    ++iteration;
    converged = true;
    for (std::size_t i = 0; i < m; ++i) {
      Vector6d xi = c_hat_[i];
      for (std::size_t j = 0; j < m; ++j) {
        xi.noalias() +=
            g_hat_[i * m + j] * ((gauss_seidel && j < i) ? lambda_next_[j] : lambda_hat_[j]);
      }
      Work& w = work_[i];
      lambda_next_[i] = Update(&w, lambda_hat_[i], xi);
      w.previous_change = w.change;
      w.change = (lambda_next_[i] - lambda_hat_[i]).cwiseAbs();
      const Eigen::Array<double, 6, 1> bound =
          tolerance_rel * lambda_next_[i].array().abs() + w.tolerance_abs_hat.array();
      converged = converged && (w.change.array() <= bound).all() &&
                  (Distance(w, lambda_next_[i]).array() <= bound).all();
    }
    for (std::size_t i = 0; i < m && !converged; ++i) finite = finite && AllFinite(lambda_next_[i]);
    if (finite) std::swap(lambda_hat_, lambda_next_);
  }

  statistics->iterations = iteration;
  statistics->converged = converged && finite;
  double residual = 0.0;
  double max_change = 0.0;
  for (std::size_t i = 0; i < m; ++i) {
    const Work& w = work_[i];
    // Λ_i = A_iΛ̂_i (47); the distances of the last update, in the original coordinates
    (*lambda)[i] = w.scale.cwiseProduct(lambda_hat_[i]);
    const Vector6d distance = w.scale.cwiseProduct(Distance(w, lambda_hat_[i]));
    for (int k = 0; k < 6; ++k) {
      const double bound =
          options.tolerance_abs + options.tolerance_rel * std::abs((*lambda)[i][k]);
      if (distance[k] == 0.0) continue;
      residual = std::max(residual, bound > 0.0 ? distance[k] / bound
                                                : std::numeric_limits<double>::infinity());
    }
    max_change = std::max(max_change, w.scale.cwiseProduct(w.change).maxCoeff());
    statistics->friction_projected[i] = w.friction_projected;
    statistics->normal_projected[i] = w.normal_projected;
    if (rim_hints != nullptr) (*rim_hints)[i] = w.rim_hint;
  }
  if (!finite) {
    residual = std::numeric_limits<double>::infinity();
    max_change = std::numeric_limits<double>::infinity();
  }
  statistics->residual = residual;
  statistics->max_change = max_change;
}

}  // namespace nonsmooth_sim
