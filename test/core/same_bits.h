// Bit-for-bit equality of body states, for tests that hold two runs to the same trajectory.
#ifndef NONSMOOTH_SIM_TEST_CORE_SAME_BITS_H_
#define NONSMOOTH_SIM_TEST_CORE_SAME_BITS_H_

#include <cstring>
#include <vector>

#include "nonsmooth_sim/core/scene.h"

namespace nonsmooth_sim::test {

/// Every position, quaternion and velocity of `a` and `b` has the same bits.
inline bool SameBits(const std::vector<BodyState>& a, const std::vector<BodyState>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::memcmp(a[i].position.data(), b[i].position.data(), 3 * sizeof(double)) != 0 ||
        std::memcmp(a[i].orientation.coeffs().data(), b[i].orientation.coeffs().data(),
                    4 * sizeof(double)) != 0 ||
        std::memcmp(a[i].linear_velocity.data(), b[i].linear_velocity.data(),
                    3 * sizeof(double)) != 0 ||
        std::memcmp(a[i].angular_velocity.data(), b[i].angular_velocity.data(),
                    3 * sizeof(double)) != 0) {
      return false;
    }
  }
  return true;
}

}  // namespace nonsmooth_sim::test

#endif  // NONSMOOTH_SIM_TEST_CORE_SAME_BITS_H_
