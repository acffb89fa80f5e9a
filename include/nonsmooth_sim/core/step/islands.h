// Islands of a step: bodies linked by closed contacts, each one contact problem (17) of the paper
// (the G_ij of contacts on different islands are zero, (16)). Union-find over the bodies that the
// contacts of the index set (12) link; a contact with the static world (body A = kWorld) links
// nothing. Islands are numbered in the order of their first contact; within an island the
// contacts keep their order (the Gauss-Seidel order of the solve) and the bodies are ascending.
#ifndef NONSMOOTH_SIM_CORE_STEP_ISLANDS_H_
#define NONSMOOTH_SIM_CORE_STEP_ISLANDS_H_

#include <cstddef>
#include <vector>

#include "nonsmooth_sim/core/step/step_data.h"

namespace nonsmooth_sim {

/// Bodies linked by closed contacts: one contact problem (17).
struct Island {
  int first_contact = 0;  ///< into Islands::contact
  int contact_count = 0;
};

class Islands {
 public:
  /// Sizes the per-body arrays for `bodies` bodies (after every change of the scene).
  void Resize(std::size_t bodies);
  /// The islands of contacts[0, count) (their report.body_a, report.body_b: body_b a body, body_a
  /// a body or kWorld) over the bodies of Resize.
  void Build(const ClosedContact* contacts, std::size_t count);

  const std::vector<Island>& islands() const { return islands_; }
  /// The index (into Build's contacts) of contact k of `island`, k < island.contact_count.
  int contact(const Island& island, int k) const {
    return contact_[static_cast<std::size_t>(island.first_contact + k)];
  }
  /// The bodies of island i are body(k) for k in [body_begin(i), body_end(i)).
  int body_begin(std::size_t i) const { return body_start_[i]; }
  int body_end(std::size_t i) const { return body_start_[i + 1]; }
  int body(int k) const { return body_[static_cast<std::size_t>(k)]; }
  /// The island of body b, -1 if it has no closed contact.
  int island_of(std::size_t b) const { return island_of_[b]; }

 private:
  std::vector<Island> islands_;
  std::vector<int> contact_;     // contact indices grouped by island
  std::vector<int> body_;        // body indices grouped by island
  std::vector<int> body_start_;  // island i's bodies: body_[body_start_[i], body_start_[i + 1])
  std::vector<int> island_of_;   // per body
  std::vector<int> union_find_;  // per body
  std::size_t last_bodies_ = 0;  // body_'s entries of the last Build
};

}  // namespace nonsmooth_sim

#endif  // NONSMOOTH_SIM_CORE_STEP_ISLANDS_H_
