// The checks every world call makes on its inputs: one std::invalid_argument line naming the field,
// what was wrong and what is allowed.
#ifndef NONSMOOTH_SIM_WORLD_CHECKS_H_
#define NONSMOOTH_SIM_WORLD_CHECKS_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

namespace nonsmooth_sim::world {

/// Throws std::invalid_argument(message) unless `ok`.
inline void Check(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

/// `v` if it is finite with |v| ≤ bound; else throws naming `field`.
inline Eigen::Vector3d FiniteVector(const char* field, const Eigen::Vector3d& v, double bound) {
  Check(v.allFinite(), std::string(field) + ": must be finite");
  Check(v.norm() <= bound, std::string(field) + ": |" + field + "| = " + std::to_string(v.norm()) +
                               " is above " + std::to_string(bound));
  return v;
}

/// A pose's quaternion, normalised; a zero or non-finite one is an error naming `field`.
inline Eigen::Quaterniond Orientation(const char* field, const Eigen::Quaterniond& p) {
  Check(p.coeffs().allFinite(), std::string(field) + ": must be finite");
  const double norm = p.norm();
  Check(norm > 1e-6 && std::isfinite(norm),
        std::string(field) + ": |q| = " + std::to_string(norm) +
            " cannot be normalised (x y z w all about 0, or too large)");
  return p.normalized();
}

}  // namespace nonsmooth_sim::world

#endif  // NONSMOOTH_SIM_WORLD_CHECKS_H_
