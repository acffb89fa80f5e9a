// Mathematical constants of the core, the loader, the world, the programs and the tests: one
// definition each (M_PI is POSIX, not standard C++; std::numbers::pi is C++20).
#ifndef NONSMOOTH_SIM_CORE_CONSTANTS_H_
#define NONSMOOTH_SIM_CORE_CONSTANTS_H_

namespace nonsmooth_sim {

/// π, rounded to the nearest double.
inline constexpr double kPi = 3.14159265358979323846;

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_CONSTANTS_H_
