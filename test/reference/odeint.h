// Boost.Odeint, with GCC 12's -W[maybe-]uninitialized silenced for its header only: its steppers'
// scratch arrays are filled on first use, and copying them warns (a false positive in the header).
#ifndef NONSMOOTH_SIM_TEST_REFERENCE_ODEINT_H_
#define NONSMOOTH_SIM_TEST_REFERENCE_ODEINT_H_

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <boost/numeric/odeint.hpp>
#pragma GCC diagnostic pop

#endif  // NONSMOOTH_SIM_TEST_REFERENCE_ODEINT_H_
