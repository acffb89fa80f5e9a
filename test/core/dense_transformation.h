// The maps of section 4 for a general non-singular A (n × n), and the solver's diagonal maps
// stacked over a whole problem: the references the tests check (20)-(31), (41), (47) and (56)
// with (transformation.h holds what the solver itself uses).
//
//   ξ̂ = Aᵀξ, Λ̂ = A⁻¹Λ, Ĝ = AᵀGA (41);  Λ = AΛ̂ (47);  R = A⁻ᵀR̂A⁻¹ (29);  AᵀRA (23), (38)
//
// The dense functions take a general A (cost O(n³) where an inverse is needed), the *Diagonal
// functions the diagonal of a diagonal A. All throw std::invalid_argument naming the argument for
// mismatched sizes, for a singular A where A⁻¹ is needed, and for a diagonal with a zero or
// non-finite entry.
#ifndef NONSMOOTH_SIM_TEST_CORE_DENSE_TRANSFORMATION_H_
#define NONSMOOTH_SIM_TEST_CORE_DENSE_TRANSFORMATION_H_

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nonsmooth_sim/core/contact_solver.h"
#include "nonsmooth_sim/core/transformation.h"

namespace nonsmooth_sim {
namespace dense_detail {

inline void RequireSquare(const Eigen::MatrixXd& m, const char* name) {
  if (m.rows() != m.cols() || m.rows() == 0) {
    throw std::invalid_argument(std::string(name) + ": must be a non-empty square matrix, got " +
                                std::to_string(m.rows()) + " x " + std::to_string(m.cols()));
  }
}

inline void RequireSize(Eigen::Index size, Eigen::Index expected, const char* name) {
  if (size != expected) {
    throw std::invalid_argument(std::string(name) + ": size must be " + std::to_string(expected) +
                                " (that of A), got " + std::to_string(size));
  }
}

// LU of a square, non-singular A (the inverse is needed by (29) and (41))
inline Eigen::FullPivLU<Eigen::MatrixXd> NonSingularLu(const Eigen::MatrixXd& a) {
  dense_detail::RequireSquare(a, "A");
  if (!a.allFinite()) throw std::invalid_argument("A: entries must be finite");
  Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
  if (!lu.isInvertible()) throw std::invalid_argument("A: must be non-singular (det(A) != 0)");
  return lu;
}

inline void RequireDiagonal(const Eigen::VectorXd& a) {
  if (a.size() == 0) throw std::invalid_argument("a (diagonal of A): must not be empty");
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    if (!std::isfinite(a[k]) || a[k] == 0.0) {
      throw std::invalid_argument("a (diagonal of A): entries must be finite and non-zero, entry " +
                                  std::to_string(k) + " is " + std::to_string(a[k]));
    }
  }
}

}  // namespace dense_detail

/// A of (56) on (Λ_T1, Λ_T2, Λ_τ): diag(1, 1, R̄), with A⁻¹E_F = S_F (57).
/// Throws std::invalid_argument unless rbar is finite and > 0 [m].
inline Eigen::Matrix3d ContensouMap(double rbar) {
  if (!(std::isfinite(rbar) && rbar > 0.0)) {
    throw std::invalid_argument("rbar: must be finite and > 0 [m], got " + std::to_string(rbar));
  }
  // (56)
  return Eigen::Vector3d(1.0, 1.0, rbar).asDiagonal();
}

/// The paper's choice, section 6: only the `sphere` law is mapped, every other law is iterated on
/// its original set (ContactMapDiagonal without map_drilling_sets); NOT what the solver does with
/// the default SolverOptions.
inline Eigen::Vector4d ContactMapDiagonal(const ContactLaw& law) {
  return ContactMapDiagonal(law, /*map_drilling_sets=*/false);
}

/// Stacked diagonal (size n) of the block-diagonal A = diag(A_1, ..., A_m) of a problem, each
/// block from ContactMapDiagonal(law, options.map_drilling_sets). Throws std::invalid_argument
/// for an invalid problem.
inline Eigen::VectorXd ProblemMapDiagonal(const ContactProblem& problem,
                                          const SolverOptions& options) {
  ValidateContactProblem(problem);
  Eigen::VectorXd a(problem.c.size());
  for (const ContactBlock& contact : problem.contacts) {
    const int dim = ContactDimension(contact.law);
    a.segment(contact.offset, dim) =
        ContactMapDiagonal(contact.law, options.map_drilling_sets).head(dim);
  }
  return a;
}

/// The same with the one-argument ContactMapDiagonal (only `sphere` mapped).
inline Eigen::VectorXd ProblemMapDiagonal(const ContactProblem& problem) {
  SolverOptions paper;
  paper.map_drilling_sets = false;
  return ProblemMapDiagonal(problem, paper);
}

inline Eigen::MatrixXd TransformDelassus(const Eigen::MatrixXd& g, const Eigen::MatrixXd& a) {
  dense_detail::RequireSquare(a, "A");
  dense_detail::RequireSquare(g, "G");
  dense_detail::RequireSize(g.rows(), a.rows(), "G");
  // Ĝ = AᵀGA (41)
  return a.transpose() * g * a;
}

inline Eigen::VectorXd TransformVelocity(const Eigen::MatrixXd& a, const Eigen::VectorXd& xi) {
  dense_detail::RequireSquare(a, "A");
  dense_detail::RequireSize(xi.size(), a.rows(), "xi");
  // ξ̂ = Aᵀξ (41), (25)
  return a.transpose() * xi;
}

inline Eigen::VectorXd TransformPercussion(const Eigen::MatrixXd& a,
                                           const Eigen::VectorXd& lambda) {
  const Eigen::FullPivLU<Eigen::MatrixXd> lu = dense_detail::NonSingularLu(a);
  dense_detail::RequireSize(lambda.size(), a.rows(), "lambda");
  // Λ̂ = A⁻¹Λ (41)
  return lu.solve(lambda);
}

inline Eigen::VectorXd RestorePercussion(const Eigen::MatrixXd& a,
                                         const Eigen::VectorXd& lambda_hat) {
  dense_detail::RequireSquare(a, "A");
  dense_detail::RequireSize(lambda_hat.size(), a.rows(), "lambda_hat");
  // Λ = AΛ̂ (47)
  return a * lambda_hat;
}

inline Eigen::MatrixXd MetricOnOriginal(const Eigen::MatrixXd& a, const Eigen::MatrixXd& r_hat) {
  const Eigen::FullPivLU<Eigen::MatrixXd> lu = dense_detail::NonSingularLu(a);
  dense_detail::RequireSquare(r_hat, "R_hat");
  dense_detail::RequireSize(r_hat.rows(), a.rows(), "R_hat");
  const Eigen::MatrixXd a_inverse = lu.inverse();
  // R = A⁻ᵀR̂A⁻¹ (29)
  return a_inverse.transpose() * r_hat * a_inverse;
}

inline Eigen::MatrixXd MetricOnTransformed(const Eigen::MatrixXd& a, const Eigen::MatrixXd& r) {
  dense_detail::RequireSquare(a, "A");
  dense_detail::RequireSquare(r, "R");
  dense_detail::RequireSize(r.rows(), a.rows(), "R");
  // AᵀRA (23)
  return a.transpose() * r * a;
}

inline Eigen::MatrixXd TransformDelassusDiagonal(const Eigen::MatrixXd& g,
                                                 const Eigen::VectorXd& a) {
  dense_detail::RequireDiagonal(a);
  dense_detail::RequireSquare(g, "G");
  dense_detail::RequireSize(g.rows(), a.size(), "G");
  // Ĝ_kl = a_k G_kl a_l (41)
  return a.asDiagonal() * g * a.asDiagonal();
}

inline Eigen::VectorXd TransformVelocityDiagonal(const Eigen::VectorXd& a,
                                                 const Eigen::VectorXd& xi) {
  dense_detail::RequireDiagonal(a);
  dense_detail::RequireSize(xi.size(), a.size(), "xi");
  // ξ̂_k = a_k ξ_k (41)
  return a.cwiseProduct(xi);
}

inline Eigen::VectorXd TransformPercussionDiagonal(const Eigen::VectorXd& a,
                                            const Eigen::VectorXd& lambda) {
  dense_detail::RequireDiagonal(a);
  dense_detail::RequireSize(lambda.size(), a.size(), "lambda");
  // Λ̂_k = Λ_k / a_k (41)
  return lambda.cwiseQuotient(a);
}

inline Eigen::VectorXd RestorePercussionDiagonal(const Eigen::VectorXd& a,
                                          const Eigen::VectorXd& lambda_hat) {
  dense_detail::RequireDiagonal(a);
  dense_detail::RequireSize(lambda_hat.size(), a.size(), "lambda_hat");
  // Λ_k = a_k Λ̂_k (47)
  return a.cwiseProduct(lambda_hat);
}

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_TEST_CORE_DENSE_TRANSFORMATION_H_
