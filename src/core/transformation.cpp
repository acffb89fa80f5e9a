// Linear maps of normal cone inclusions (19)-(31) and of the contact problem (41), (47), (56).
#include "nonsmooth_sim/core/transformation.h"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>
#include <string>

namespace nonsmooth_sim {
namespace {

void RequireSquare(const Eigen::MatrixXd& m, const char* name) {
  if (m.rows() != m.cols() || m.rows() == 0) {
    throw std::invalid_argument(std::string(name) + ": must be a non-empty square matrix, got " +
                                std::to_string(m.rows()) + " x " + std::to_string(m.cols()));
  }
}

void RequireSize(Eigen::Index size, Eigen::Index expected, const char* name) {
  if (size != expected) {
    throw std::invalid_argument(std::string(name) + ": size must be " + std::to_string(expected) +
                                " (that of A), got " + std::to_string(size));
  }
}

// LU of a square, non-singular A (the inverse is needed by (29) and (41))
Eigen::FullPivLU<Eigen::MatrixXd> NonSingularLu(const Eigen::MatrixXd& a) {
  RequireSquare(a, "A");
  if (!a.allFinite()) throw std::invalid_argument("A: entries must be finite");
  Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
  if (!lu.isInvertible()) throw std::invalid_argument("A: must be non-singular (det(A) != 0)");
  return lu;
}

void RequireDiagonal(const Eigen::VectorXd& a) {
  if (a.size() == 0) throw std::invalid_argument("a (diagonal of A): must not be empty");
  for (Eigen::Index k = 0; k < a.size(); ++k) {
    if (!std::isfinite(a[k]) || a[k] == 0.0) {
      throw std::invalid_argument("a (diagonal of A): entries must be finite and non-zero, entry " +
                                  std::to_string(k) + " is " + std::to_string(a[k]));
    }
  }
}

}  // namespace

Eigen::Matrix3d ContensouMap(double rbar) {
  if (!(std::isfinite(rbar) && rbar > 0.0)) {
    throw std::invalid_argument("rbar: must be finite and > 0 [m], got " + std::to_string(rbar));
  }
  // (56)
  return Eigen::Vector3d(1.0, 1.0, rbar).asDiagonal();
}

Eigen::Vector4d ContactMapDiagonal(const ContactLaw& law) {
  SolverOptions paper;
  paper.map_drilling_sets = false;
  return ContactMapDiagonal(law, paper);
}

Eigen::VectorXd ProblemMapDiagonal(const ContactProblem& problem, const SolverOptions& options) {
  ValidateContactProblem(problem);
  Eigen::VectorXd a(problem.c.size());
  for (const ContactBlock& contact : problem.contacts) {
    const int dim = ContactDimension(contact.law);
    a.segment(contact.offset, dim) = ContactMapDiagonal(contact.law, options).head(dim);
  }
  return a;
}

Eigen::VectorXd ProblemMapDiagonal(const ContactProblem& problem) {
  SolverOptions paper;
  paper.map_drilling_sets = false;
  return ProblemMapDiagonal(problem, paper);
}

Eigen::MatrixXd TransformDelassus(const Eigen::MatrixXd& g, const Eigen::MatrixXd& a) {
  RequireSquare(a, "A");
  RequireSquare(g, "G");
  RequireSize(g.rows(), a.rows(), "G");
  // Ĝ = AᵀGA (41)
  return a.transpose() * g * a;
}

Eigen::VectorXd TransformVelocity(const Eigen::MatrixXd& a, const Eigen::VectorXd& xi) {
  RequireSquare(a, "A");
  RequireSize(xi.size(), a.rows(), "xi");
  // ξ̂ = Aᵀξ (41), (25)
  return a.transpose() * xi;
}

Eigen::VectorXd TransformPercussion(const Eigen::MatrixXd& a, const Eigen::VectorXd& lambda) {
  const Eigen::FullPivLU<Eigen::MatrixXd> lu = NonSingularLu(a);
  RequireSize(lambda.size(), a.rows(), "lambda");
  // Λ̂ = A⁻¹Λ (41)
  return lu.solve(lambda);
}

Eigen::VectorXd RestorePercussion(const Eigen::MatrixXd& a, const Eigen::VectorXd& lambda_hat) {
  RequireSquare(a, "A");
  RequireSize(lambda_hat.size(), a.rows(), "lambda_hat");
  // Λ = AΛ̂ (47)
  return a * lambda_hat;
}

Eigen::MatrixXd MetricOnOriginal(const Eigen::MatrixXd& a, const Eigen::MatrixXd& r_hat) {
  const Eigen::FullPivLU<Eigen::MatrixXd> lu = NonSingularLu(a);
  RequireSquare(r_hat, "R_hat");
  RequireSize(r_hat.rows(), a.rows(), "R_hat");
  const Eigen::MatrixXd a_inverse = lu.inverse();
  // R = A⁻ᵀR̂A⁻¹ (29)
  return a_inverse.transpose() * r_hat * a_inverse;
}

Eigen::MatrixXd MetricOnTransformed(const Eigen::MatrixXd& a, const Eigen::MatrixXd& r) {
  RequireSquare(a, "A");
  RequireSquare(r, "R");
  RequireSize(r.rows(), a.rows(), "R");
  // AᵀRA (23)
  return a.transpose() * r * a;
}

Eigen::MatrixXd TransformDelassusDiagonal(const Eigen::MatrixXd& g, const Eigen::VectorXd& a) {
  RequireDiagonal(a);
  RequireSquare(g, "G");
  RequireSize(g.rows(), a.size(), "G");
  // Ĝ_kl = a_k G_kl a_l (41)
  return a.asDiagonal() * g * a.asDiagonal();
}

Eigen::VectorXd TransformVelocityDiagonal(const Eigen::VectorXd& a, const Eigen::VectorXd& xi) {
  RequireDiagonal(a);
  RequireSize(xi.size(), a.size(), "xi");
  // ξ̂_k = a_k ξ_k (41)
  return a.cwiseProduct(xi);
}

Eigen::VectorXd TransformPercussionDiagonal(const Eigen::VectorXd& a,
                                            const Eigen::VectorXd& lambda) {
  RequireDiagonal(a);
  RequireSize(lambda.size(), a.size(), "lambda");
  // Λ̂_k = Λ_k / a_k (41)
  return lambda.cwiseQuotient(a);
}

Eigen::VectorXd RestorePercussionDiagonal(const Eigen::VectorXd& a,
                                          const Eigen::VectorXd& lambda_hat) {
  RequireDiagonal(a);
  RequireSize(lambda_hat.size(), a.size(), "lambda_hat");
  // Λ_k = a_k Λ̂_k (47)
  return a.cwiseProduct(lambda_hat);
}

}  // namespace nonsmooth_sim
