// Sorting what was sorted one step ago: the broad phase's sweep order, the contact pairs and the
// gap-correction records of a step come in nearly the order of the last step's, so an insertion
// sort costs O(n + k) for k displacements where std::sort costs O(n log n) every step (the
// temporal coherence that Bullet's incremental sweep and prune exploits).
#ifndef NONSMOOTH_SIM_CORE_NEARLY_SORTED_H_
#define NONSMOOTH_SIM_CORE_NEARLY_SORTED_H_

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <utility>

namespace nonsmooth_sim {

/// Sorts [first, last) by `less` (a strict weak order), stably while the input is nearly sorted:
/// an insertion sort, which moves each element past the ones it is out of order with. Once the
/// moves exceed 8 n + 64 (input far from sorted: a first step, a scene reloaded) std::sort
/// finishes the job, so the worst case is O(n log n), not O(n²). Allocates nothing.
template <class RandomIt, class Less>
void SortNearlySorted(RandomIt first, RandomIt last, Less less) {
  const std::size_t n = static_cast<std::size_t>(std::distance(first, last));
  if (n < 2) return;
  std::size_t budget = 8 * n + 64;
  for (RandomIt i = std::next(first); i != last; ++i) {
    if (!less(*i, *std::prev(i))) continue;
    auto value = std::move(*i);
    RandomIt j = i;
    do {
      *j = std::move(*std::prev(j));
      --j;
    } while (j != first && less(value, *std::prev(j)) && --budget > 0);
    *j = std::move(value);
    if (budget == 0) {
      std::sort(first, last, less);
      return;
    }
  }
}

/// SortNearlySorted by operator<.
template <class RandomIt>
void SortNearlySorted(RandomIt first, RandomIt last) {
  SortNearlySorted(first, last, [](const auto& a, const auto& b) { return a < b; });
}

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_NEARLY_SORTED_H_
