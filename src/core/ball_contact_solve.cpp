// One contact's inclusion (17) with a ball friction set, solved directly; see ball_contact_solve.h.
#include "nonsmooth_sim/core/ball_contact_solve.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

namespace nonsmooth_sim {
namespace {

// Newton's method on the secular equation converges quadratically from the left; it stops when a
// step no longer increases λ (round-off), long before this cap.
constexpr int kMaxNewtonSteps = 100;
// The Illinois iteration converges superlinearly (about ten evaluations here); the cap bounds it
// where the excess is flat.
constexpr int kMaxRootSteps = 200;
constexpr int kMaxBracketDoublings = 64;
constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

// x(λ) = -(H + λI)⁻¹b minimising ½xᵀHx + bᵀx over ||x|| ≤ ρ, in the eigenbasis of H (d > 0):
// β = Qᵀb; returns y = Qᵀx
Eigen::Array3d MinimizeOnBall(const Eigen::Array3d& beta, const Eigen::Array3d& d, double rho) {
  if (!(rho > 0.0)) return Eigen::Array3d::Zero();
  Eigen::Array3d y = -beta / d;
  double norm = y.matrix().norm();
  if (norm <= rho) return y;  // the unconstrained minimiser is inside: stick
  // φ(λ) = 1/||y(λ)|| - 1/ρ, φ'(λ) = Σ y_i²/(d_i + λ) / ||y||³; concave and increasing, so
  // Newton's steps from λ = 0 < λ* increase monotonically to λ*
  double lambda = 0.0;
  for (int k = 0; k < kMaxNewtonSteps; ++k) {
    const double phi = 1.0 / norm - 1.0 / rho;
    const double slope = (y.square() / (d + lambda)).sum() / (norm * norm * norm);
    const double next = lambda - phi / slope;
    if (!(next > lambda)) break;
    lambda = next;
    y = -beta / (d + lambda);
    norm = y.matrix().norm();
  }
  return y * (rho / norm);  // onto the sphere ||x|| = ρ (a round-off correction)
}

}  // namespace

bool BallContactSolver::Reset(const Eigen::Matrix4d& G, int dim, double mu,
                              const Eigen::Vector3d& friction_metric) {
  valid_ = false;
  dim_ = dim;
  mu_ = mu;
  g_nn_ = G(0, 0);
  if (!(g_nn_ > 0.0) || (dim != 1 && dim != 3 && dim != 4)) return false;
  // x = D⁻¹Λ_F over k = dim - 1 components, padded to three (H = I, b = 0 beyond: x = 0 there)
  const int k = dim - 1;
  metric_.setOnes();
  g_fn_.setZero();
  eigenvectors_.setIdentity();
  eigenvalues_.setOnes();
  if (k > 0) {
    metric_.head(k) = friction_metric.head(k);
    if (!(metric_.minCoeff() > 0.0)) return false;
    g_fn_.head(k) = G.block(1, 0, k, 1);
    Eigen::Matrix3d h = Eigen::Matrix3d::Identity();
    h.topLeftCorner(k, k) =
        metric_.head(k).asDiagonal() * G.block(1, 1, k, k) * metric_.head(k).asDiagonal();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(h);
    if (eigen.info() != Eigen::Success || !(eigen.eigenvalues().minCoeff() > 0.0)) return false;
    eigenvectors_ = eigen.eigenvectors();
    eigenvalues_ = eigen.eigenvalues();
  }
  valid_ = true;
  return true;
}

bool BallContactSolver::Solve(const Eigen::Vector4d& c, Eigen::Vector4d* lambda) const {
  if (!valid_) return false;
  // the frictionless normal percussion; 0: the contact separates (and Λ_F = 0 on the set {0})
  const double n_free = std::fmax(0.0, -c[0] / g_nn_);
  if (dim_ == 1 || n_free == 0.0) {
    *lambda = Eigen::Vector4d(n_free, 0.0, 0.0, 0.0);
    return true;
  }
  const int k = dim_ - 1;
  Eigen::Vector3d c_f = Eigen::Vector3d::Zero();
  c_f.head(k) = c.segment(1, k);
  // D Qᵀ: β(n) = QᵀD(c_F + G_FN n) = β_c + n β_g
  const Eigen::Matrix3d qt_d = eigenvectors_.transpose() * metric_.asDiagonal();
  const Eigen::Array3d beta_c = (qt_d * c_f).array();
  const Eigen::Array3d beta_g = (qt_d * g_fn_).array();
  const Eigen::Array3d d = eigenvalues_.array();
  // Λ_F(n) of (a), and n minus the right side of (b)
  const auto friction = [&](double n) -> Eigen::Vector3d {
    const Eigen::Array3d y = MinimizeOnBall(beta_c + n * beta_g, d, mu_ * n);
    return metric_.cwiseProduct(eigenvectors_ * y.matrix());
  };
  const auto excess = [&](double n, const Eigen::Vector3d& f) {
    return n - std::fmax(0.0, -(c[0] + g_fn_.dot(f)) / g_nn_);
  };
  // bracket: excess(0) = -n_free < 0; double the right end until the excess is ≥ 0
  double lo = 0.0;
  double h_lo = -n_free;
  double hi = n_free;
  Eigen::Vector3d f_hi = friction(hi);
  double h_hi = excess(hi, f_hi);
  int doublings = 0;
  while (!(h_hi >= 0.0)) {
    if (++doublings > kMaxBracketDoublings || !std::isfinite(hi)) return false;
    lo = hi;
    h_lo = h_hi;
    hi *= 2.0;
    f_hi = friction(hi);
    h_hi = excess(hi, f_hi);
  }
  // Illinois: regula falsi whose retained end's value is halved when the same end stays twice
  int side = 0;
  for (int step = 0; step < kMaxRootSteps && h_hi > 0.0; ++step) {
    if (!(hi - lo > 2.0 * kEpsilon * hi)) break;
    double n = (lo * h_hi - hi * h_lo) / (h_hi - h_lo);
    if (!(n > lo && n < hi)) n = 0.5 * (lo + hi);
    const Eigen::Vector3d f = friction(n);
    const double h = excess(n, f);
    if (h >= 0.0) {
      hi = n;
      h_hi = h;
      f_hi = f;
      if (side == 1) h_lo *= 0.5;
      side = 1;
    } else {
      lo = n;
      h_lo = h;
      if (side == -1) h_hi *= 0.5;
      side = -1;
    }
    // within round-off of the right side of (b)
    if (std::abs(h) <= 4.0 * kEpsilon * n && h >= 0.0) break;
  }
  Eigen::Vector4d result = Eigen::Vector4d::Zero();
  result[0] = hi;
  result.segment(1, k) = f_hi.head(k);
  if (!result.allFinite()) return false;
  *lambda = result;
  return true;
}

bool SolveBallContact(const Eigen::Matrix4d& G, const Eigen::Vector4d& c, int dim, double mu,
                      const Eigen::Vector3d& friction_metric, Eigen::Vector4d* lambda) {
  BallContactSolver solver;
  return solver.Reset(G, dim, mu, friction_metric) && solver.Solve(c, lambda);
}

}  // namespace nonsmooth_sim
