// The key of a contact's memory across steps (warm start, tangent frame): (first collider, second
// collider, feature) packed in 24 + 24 + 16 bits, first < second. One place for the layout: the
// contact pipeline (step/contact_pipeline.cpp) builds keys, RemoveBodies (simulator_world.cpp)
// re-keys them when collider indices change.
#ifndef NONSMOOTH_SIM_CORE_CONTACT_CONTACT_KEY_H_
#define NONSMOOTH_SIM_CORE_CONTACT_CONTACT_KEY_H_

#include <cstdint>

namespace nonsmooth_sim {

inline constexpr int kContactKeyFirstShift = 40;
inline constexpr int kContactKeySecondShift = 16;
inline constexpr std::uint64_t kContactKeyColliderMask = 0xffffff;
inline constexpr std::uint64_t kContactKeyFeatureMask = 0xffff;

inline std::uint64_t ContactKey(int first, int second, int feature) {
  return (static_cast<std::uint64_t>(first) << kContactKeyFirstShift) |
         (static_cast<std::uint64_t>(second) << kContactKeySecondShift) |
         (static_cast<std::uint64_t>(feature) & kContactKeyFeatureMask);
}
inline int ContactKeyFirst(std::uint64_t key) {
  return static_cast<int>(key >> kContactKeyFirstShift);
}
inline int ContactKeySecond(std::uint64_t key) {
  return static_cast<int>((key >> kContactKeySecondShift) & kContactKeyColliderMask);
}
inline int ContactKeyFeature(std::uint64_t key) {
  return static_cast<int>(key & kContactKeyFeatureMask);
}

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_CONTACT_CONTACT_KEY_H_
