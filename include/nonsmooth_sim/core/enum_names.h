// Names of enumerated choices (command line, ROS, JSON): the lookups each enum's own file builds
// from the array of all its values and its name function.
#ifndef NONSMOOTH_SIM_CORE_ENUM_NAMES_H_
#define NONSMOOTH_SIM_CORE_ENUM_NAMES_H_

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace nonsmooth_sim {

/// Whether `value` is one of `all` (an enum holds any value of its underlying type).
template <typename Enum, std::size_t N>
constexpr bool IsOneOf(Enum value, const std::array<Enum, N>& all) {
  for (Enum candidate : all) {
    if (candidate == value) return true;
  }
  return false;
}

/// The value of `all` whose name is `name`; std::nullopt for none.
template <typename Enum, std::size_t N, typename ToName>
std::optional<Enum> EnumFromName(std::string_view name, const std::array<Enum, N>& all,
                                 ToName to_name) {
  for (Enum value : all) {
    if (to_name(value) == name) return value;
  }
  return std::nullopt;
}

/// "a, b, c": the names of `all` in order (for error messages and help texts).
template <typename Enum, std::size_t N, typename ToName>
std::string EnumNameList(const std::array<Enum, N>& all, ToName to_name) {
  std::string list;
  for (Enum value : all) {
    if (!list.empty()) list += ", ";
    list += to_name(value);
  }
  return list;
}

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_ENUM_NAMES_H_
