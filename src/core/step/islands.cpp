// Islands: union-find over the bodies that closed contacts link, see islands.h.
#include "nonsmooth_sim/core/step/islands.h"

#include <algorithm>

namespace nonsmooth_sim {
namespace {

// Union-find root with path halving.
int Root(std::vector<int>* parent, int b) {
  std::vector<int>& p = *parent;
  while (p[static_cast<std::size_t>(b)] != b) {
    p[static_cast<std::size_t>(b)] = p[static_cast<std::size_t>(p[static_cast<std::size_t>(b)])];
    b = p[static_cast<std::size_t>(b)];
  }
  return b;
}

}  // namespace

void Islands::Resize(std::size_t bodies) {
  union_find_.assign(bodies, 0);
  island_of_.assign(bodies, -1);
  last_bodies_ = 0;
}

void Islands::Build(const ClosedContact* contacts, std::size_t count) {
  islands_.clear();
  // body_[0, last_bodies_): the bodies of the last islands, the only ones with one to forget
  for (std::size_t k = 0; k < last_bodies_; ++k) {
    island_of_[static_cast<std::size_t>(body_[k])] = -1;
  }
  last_bodies_ = 0;
  if (count == 0) return;
  // one body against the static world (a top on the ground): one island, contacts in order
  bool single = true;
  for (std::size_t i = 0; i < count; ++i) {
    single = single && contacts[i].report.body_a < 0 &&
             contacts[i].report.body_b == contacts[0].report.body_b;
  }
  if (single) {
    islands_.push_back(Island{0, static_cast<int>(count)});
    contact_.resize(count);
    for (std::size_t i = 0; i < count; ++i) contact_[i] = static_cast<int>(i);
    island_of_[static_cast<std::size_t>(contacts[0].report.body_b)] = 0;
    body_.resize(1);
    body_[0] = contacts[0].report.body_b;
    body_start_.resize(2);
    body_start_[0] = 0;
    body_start_[1] = 1;
    last_bodies_ = 1;
    return;
  }
  // union-find over the bodies that closed contacts link
  for (std::size_t b = 0; b < union_find_.size(); ++b) union_find_[b] = static_cast<int>(b);
  for (std::size_t i = 0; i < count; ++i) {
    const ContactState& c = contacts[i].report;
    if (c.body_a < 0) continue;
    const int ra = Root(&union_find_, c.body_a);
    const int rb = Root(&union_find_, c.body_b);
    if (ra != rb) union_find_[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
  }
  // islands numbered in the order of their first contact; island_of_[root] holds it
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t root =
        static_cast<std::size_t>(Root(&union_find_, contacts[i].report.body_b));
    if (island_of_[root] < 0) {
      island_of_[root] = static_cast<int>(islands_.size());
      islands_.push_back(Island{});
    }
    ++islands_[static_cast<std::size_t>(island_of_[root])].contact_count;
  }
  // counting sort of the contacts by island, keeping their order within an island
  int start = 0;
  for (Island& island : islands_) {
    island.first_contact = start;
    start += island.contact_count;
    island.contact_count = 0;
  }
  contact_.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t root =
        static_cast<std::size_t>(Root(&union_find_, contacts[i].report.body_b));
    Island& island = islands_[static_cast<std::size_t>(island_of_[root])];
    contact_[static_cast<std::size_t>(island.first_contact + island.contact_count++)] =
        static_cast<int>(i);
  }
  // every body of an island knows it; the bodies grouped by island
  for (std::size_t b = 0; b < island_of_.size(); ++b) {
    const int root = Root(&union_find_, static_cast<int>(b));
    island_of_[b] = island_of_[static_cast<std::size_t>(root)];
  }
  body_start_.assign(islands_.size() + 1, 0);
  for (const int island : island_of_) {
    if (island >= 0) ++body_start_[static_cast<std::size_t>(island) + 1];
  }
  for (std::size_t k = 1; k < body_start_.size(); ++k) body_start_[k] += body_start_[k - 1];
  body_.resize(static_cast<std::size_t>(body_start_.back()));
  last_bodies_ = body_.size();
  std::vector<int>& next = union_find_;  // reused as the fill pointer per island
  for (std::size_t k = 0; k < islands_.size(); ++k) next[k] = body_start_[k];
  for (std::size_t b = 0; b < island_of_.size(); ++b) {
    const int island = island_of_[b];
    if (island < 0) continue;
    body_[static_cast<std::size_t>(next[static_cast<std::size_t>(island)]++)] =
        static_cast<int>(b);
  }
}

}  // namespace nonsmooth_sim
