// A measured value as the text RecordProperty writes into the test XML (the worst errors a test
// saw, next to its pass/fail bound).
#ifndef NONSMOOTH_SIM_TEST_MEASURED_VALUE_H_
#define NONSMOOTH_SIM_TEST_MEASURED_VALUE_H_

#include <iomanip>
#include <sstream>
#include <string>

namespace nonsmooth_sim::test {

/// "1.23e-10": three significant digits in scientific notation.
inline std::string Scientific(double value) {
  std::ostringstream out;
  out << std::scientific << std::setprecision(2) << value;
  return out.str();
}

}  // namespace nonsmooth_sim::test

#endif  // NONSMOOTH_SIM_TEST_MEASURED_VALUE_H_
