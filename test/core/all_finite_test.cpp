// AllFinite (all_finite.h), the step's finiteness test, against Eigen's allFinite().
#include "nonsmooth_sim/core/all_finite.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>

namespace nonsmooth_sim {
namespace {

// Values that a diverging state or an overflowing G can hold, finite and not.
double Special(int k) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double values[] = {0.0,
                           -0.0,
                           1.0,
                           -3.5e-310,  // subnormal
                           std::numeric_limits<double>::max(),
                           -std::numeric_limits<double>::max(),
                           kInf,
                           -kInf,
                           std::numeric_limits<double>::quiet_NaN(),
                           -std::numeric_limits<double>::quiet_NaN()};
  return values[k % 10];
}

template <class Matrix>
void ExpectAgreesWithEigen(std::mt19937* random) {
  std::uniform_real_distribution<double> uniform(-1e3, 1e3);
  std::uniform_int_distribution<int> index(0, static_cast<int>(Matrix::SizeAtCompileTime) - 1);
  std::uniform_int_distribution<int> special(0, 9);
  std::uniform_int_distribution<int> count(0, 3);
  for (int trial = 0; trial < 2000; ++trial) {
    Matrix m = Matrix::NullaryExpr([&] { return uniform(*random); });
    for (int k = count(*random); k > 0; --k) m(index(*random)) = Special(special(*random));
    EXPECT_EQ(AllFinite(m), m.allFinite()) << m;
  }
}

TEST(AllFinite, AgreesWithEigenOnFiniteInfiniteAndNanCoefficients) {
  std::mt19937 random(20261203);
  ExpectAgreesWithEigen<Eigen::Matrix4d>(&random);
  ExpectAgreesWithEigen<Eigen::Vector4d>(&random);
  ExpectAgreesWithEigen<Eigen::Vector3d>(&random);
  // the largest finite values: their sum overflows, their products with 0 do not
  const Eigen::Matrix4d huge = Eigen::Matrix4d::Constant(std::numeric_limits<double>::max());
  EXPECT_TRUE(AllFinite(huge));
  EXPECT_FALSE(std::isfinite(huge.sum()));
  Eigen::Quaterniond q(1.0, 0.0, 0.0, 0.0);
  EXPECT_TRUE(AllFinite(q.coeffs()));
  q.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(AllFinite(q.coeffs()));
}

}  // namespace
}  // namespace nonsmooth_sim
