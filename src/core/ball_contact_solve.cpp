// One contact's inclusion (17) with a ball friction set, solved directly; see ball_contact_solve.h.
#include "nonsmooth_sim/core/ball_contact_solve.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace nonsmooth_sim {
namespace {

// Newton's method on the secular equation converges quadratically from the left; it stops when a
// step no longer increases λ (round-off), long before this cap.
constexpr int kMaxNewtonSteps = 100;
// Bisection halves the bracket: ~60 halvings reach the spacing of doubles at n_hi.
constexpr int kMaxBisections = 200;
constexpr int kMaxBracketDoublings = 64;

// min ½xᵀHx + bᵀx over ||x|| ≤ ρ with H = Q diag(d) Qᵀ, d > 0 (a trust-region subproblem)
class BallQuadratic {
 public:
  BallQuadratic(const Eigen::Matrix3d& q, const Eigen::Vector3d& d) : q_(q), d_(d) {}

  Eigen::Vector3d Minimize(const Eigen::Vector3d& b, double rho) const {
    if (!(rho > 0.0)) return Eigen::Vector3d::Zero();
    const Eigen::Array3d beta = (q_.transpose() * b).array();
    // x(λ) = -(H + λI)⁻¹b in the eigenbasis
    Eigen::Array3d y = -beta / d_.array();
    double norm = y.matrix().norm();
    if (norm <= rho) return q_ * y.matrix();  // the unconstrained minimiser is inside: stick
    // φ(λ) = 1/||y(λ)|| - 1/ρ, φ'(λ) = Σ y_i²/(d_i + λ) / ||y||³; concave and increasing, so
    // Newton's steps from λ = 0 < λ* increase monotonically to λ*
    double lambda = 0.0;
    for (int k = 0; k < kMaxNewtonSteps; ++k) {
      const double phi = 1.0 / norm - 1.0 / rho;
      const double slope = (y.square() / (d_.array() + lambda)).sum() / (norm * norm * norm);
      const double next = lambda - phi / slope;
      if (!(next > lambda)) break;
      lambda = next;
      y = -beta / (d_.array() + lambda);
      norm = y.matrix().norm();
    }
    // onto the sphere ||x|| = ρ (a round-off correction)
    return q_ * (y.matrix() * (rho / norm));
  }

 private:
  Eigen::Matrix3d q_;
  Eigen::Vector3d d_;
};

}  // namespace

bool SolveBallContact(const Eigen::Matrix4d& G, const Eigen::Vector4d& c, int dim, double mu,
                      const Eigen::Vector3d& friction_metric, Eigen::Vector4d* lambda) {
  const double g_nn = G(0, 0);
  if (!(g_nn > 0.0)) return false;
  // the frictionless normal percussion; 0: the contact separates (and Λ_F = 0 on the set {0})
  const double n_free = std::fmax(0.0, -c[0] / g_nn);
  if (dim == 1 || n_free == 0.0) {
    *lambda = Eigen::Vector4d(n_free, 0.0, 0.0, 0.0);
    return true;
  }
  // x = D⁻¹Λ_F over k = dim - 1 components, padded to three (H = I, b = 0 beyond: x = 0 there)
  const int k = dim - 1;
  Eigen::Vector3d metric = Eigen::Vector3d::Ones();
  metric.head(k) = friction_metric.head(k);
  if (!(metric.minCoeff() > 0.0)) return false;
  Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
  h.topLeftCorner(k, k) =
      metric.head(k).asDiagonal() * G.block(1, 1, k, k) * metric.head(k).asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(h);
  if (eigen.info() != Eigen::Success || !(eigen.eigenvalues().minCoeff() > 0.0)) return false;
  const BallQuadratic ball(eigen.eigenvectors(), eigen.eigenvalues());
  Eigen::Vector3d g_fn = Eigen::Vector3d::Zero();
  Eigen::Vector3d c_f = Eigen::Vector3d::Zero();
  g_fn.head(k) = G.block(1, 0, k, 1);
  c_f.head(k) = c.segment(1, k);

  // Λ_F(n) of (a), and n minus the right side of (b)
  const auto friction = [&](double n) -> Eigen::Vector3d {
    return metric.cwiseProduct(ball.Minimize(metric.cwiseProduct(c_f + g_fn * n), mu * n));
  };
  const auto excess = [&](double n, const Eigen::Vector3d& f) {
    return n - std::fmax(0.0, -(c[0] + g_fn.dot(f)) / g_nn);
  };
  // bracket: excess(0) = -n_free < 0; double the right end until the excess is ≥ 0
  double lo = 0.0;
  double hi = n_free;
  Eigen::Vector3d f_hi = friction(hi);
  int doublings = 0;
  while (!(excess(hi, f_hi) >= 0.0)) {
    if (++doublings > kMaxBracketDoublings || !std::isfinite(hi)) return false;
    lo = hi;
    hi *= 2.0;
    f_hi = friction(hi);
  }
  for (int k_bisect = 0; k_bisect < kMaxBisections; ++k_bisect) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    const Eigen::Vector3d f_mid = friction(mid);
    if (excess(mid, f_mid) >= 0.0) {
      hi = mid;
      f_hi = f_mid;
    } else {
      lo = mid;
    }
  }
  Eigen::Vector4d result = Eigen::Vector4d::Zero();
  result[0] = hi;
  result.segment(1, k) = f_hi.head(k);
  if (!result.allFinite()) return false;
  *lambda = result;
  return true;
}

}  // namespace nonsmooth_sim
