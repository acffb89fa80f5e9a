// The islands stage on its own (core/step/islands.h): constructed contact lists against a
// brute-force connected-components reference (breadth-first search over the bodies), and the
// orders the island solve relies on (islands by first contact, contacts in their list order,
// bodies ascending).
#include <gtest/gtest.h>

#include <algorithm>
#include <queue>
#include <random>
#include <vector>

#include "nonsmooth_sim/core/step/islands.h"

namespace nonsmooth_sim {
namespace {

ClosedContact Contact(int body_a, int body_b) {
  ClosedContact c;
  c.report.body_a = body_a;
  c.report.body_b = body_b;
  return c;
}

// Per body its connected component (numbered by BFS from the lowest body), -1 if no contact
// touches it: the reference, independent of union-find.
std::vector<int> Components(const std::vector<ClosedContact>& contacts, int bodies) {
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(bodies));
  std::vector<char> touched(static_cast<std::size_t>(bodies), 0);
  for (const ClosedContact& c : contacts) {
    touched[static_cast<std::size_t>(c.report.body_b)] = 1;
    if (c.report.body_a < 0) continue;
    touched[static_cast<std::size_t>(c.report.body_a)] = 1;
    neighbours[static_cast<std::size_t>(c.report.body_a)].push_back(c.report.body_b);
    neighbours[static_cast<std::size_t>(c.report.body_b)].push_back(c.report.body_a);
  }
  std::vector<int> component(static_cast<std::size_t>(bodies), -1);
  int next = 0;
  for (int start = 0; start < bodies; ++start) {
    if (!touched[static_cast<std::size_t>(start)]) continue;
    if (component[static_cast<std::size_t>(start)] >= 0) continue;
    std::queue<int> queue;
    queue.push(start);
    component[static_cast<std::size_t>(start)] = next;
    while (!queue.empty()) {
      const int b = queue.front();
      queue.pop();
      for (int n : neighbours[static_cast<std::size_t>(b)]) {
        if (component[static_cast<std::size_t>(n)] >= 0) continue;
        component[static_cast<std::size_t>(n)] = next;
        queue.push(n);
      }
    }
    ++next;
  }
  return component;
}

// Checks `islands` built on `contacts` against the reference; every failure names the case.
void ExpectMatchesReference(const Islands& islands, const std::vector<ClosedContact>& contacts,
                            int bodies) {
  const std::vector<int> component = Components(contacts, bodies);
  const std::vector<Island>& list = islands.islands();
  // one island per component, numbered in the order of its first contact in the list
  std::vector<int> island_of_component;
  for (const ClosedContact& c : contacts) {
    const int comp = component[static_cast<std::size_t>(c.report.body_b)];
    if (std::find(island_of_component.begin(), island_of_component.end(), comp) ==
        island_of_component.end()) {
      island_of_component.push_back(comp);
    }
  }
  ASSERT_EQ(list.size(), island_of_component.size());
  std::vector<int> seen(contacts.size(), 0);
  int total = 0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const int comp = island_of_component[i];
    // its contacts: exactly those of the component, in list order, each once
    std::vector<int> expected;
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      if (component[static_cast<std::size_t>(contacts[k].report.body_b)] == comp) {
        expected.push_back(static_cast<int>(k));
      }
    }
    std::vector<int> got;
    for (int k = 0; k < list[i].contact_count; ++k) got.push_back(islands.contact(list[i], k));
    EXPECT_EQ(got, expected) << "island " << i;
    for (int k : got) ++seen[static_cast<std::size_t>(k)];
    total += list[i].contact_count;
    // its bodies: exactly those of the component, ascending
    std::vector<int> expected_bodies;
    for (int b = 0; b < bodies; ++b) {
      if (component[static_cast<std::size_t>(b)] == comp) expected_bodies.push_back(b);
    }
    std::vector<int> got_bodies;
    for (int k = islands.body_begin(i); k < islands.body_end(i); ++k) {
      got_bodies.push_back(islands.body(k));
    }
    EXPECT_EQ(got_bodies, expected_bodies) << "island " << i;
    for (int b : got_bodies) EXPECT_EQ(islands.island_of(static_cast<std::size_t>(b)), int(i));
  }
  EXPECT_EQ(total, static_cast<int>(contacts.size()));
  for (int s : seen) EXPECT_EQ(s, 1);
  for (int b = 0; b < bodies; ++b) {
    if (component[static_cast<std::size_t>(b)] < 0) {
      EXPECT_EQ(islands.island_of(static_cast<std::size_t>(b)), -1) << "body " << b;
    }
  }
}

TEST(Islands, NoContactNoIsland) {
  Islands islands;
  islands.Resize(3);
  islands.Build(nullptr, 0);
  EXPECT_TRUE(islands.islands().empty());
  for (std::size_t b = 0; b < 3; ++b) EXPECT_EQ(islands.island_of(b), -1);
}

TEST(Islands, OneBodyOnTheWorldIsOneIslandInContactOrder) {
  // the fast path: every contact against the static world, one body
  const std::vector<ClosedContact> contacts = {Contact(kWorld, 1), Contact(kWorld, 1),
                                               Contact(kWorld, 1)};
  Islands islands;
  islands.Resize(3);
  islands.Build(contacts.data(), contacts.size());
  ASSERT_EQ(islands.islands().size(), 1u);
  ExpectMatchesReference(islands, contacts, 3);
  EXPECT_EQ(islands.island_of(0), -1);
  EXPECT_EQ(islands.island_of(2), -1);
}

TEST(Islands, TheWorldLinksNothing) {
  // two bodies each on the ground, and a stack 2-3-4 of which 4 touches the ground: three
  // islands, although every one of them touches the world
  const std::vector<ClosedContact> contacts = {Contact(kWorld, 0), Contact(kWorld, 1),
                                               Contact(3, 4),      Contact(kWorld, 4),
                                               Contact(2, 3),      Contact(kWorld, 0)};
  Islands islands;
  islands.Resize(6);
  islands.Build(contacts.data(), contacts.size());
  ASSERT_EQ(islands.islands().size(), 3u);
  EXPECT_EQ(islands.islands()[0].contact_count, 2);  // body 0: contacts 0 and 5
  EXPECT_EQ(islands.islands()[2].contact_count, 3);  // the stack
  EXPECT_EQ(islands.island_of(5), -1);
  ExpectMatchesReference(islands, contacts, 6);
}

TEST(Islands, ChainsJoinedByALaterContactAreOneIsland) {
  // 0-1 and 2-3 first look like two islands; the last contact 1-2 joins them, after a
  // contact of body 5 came in between: two islands, the joined one first
  const std::vector<ClosedContact> contacts = {Contact(0, 1), Contact(kWorld, 5), Contact(2, 3),
                                               Contact(1, 2)};
  Islands islands;
  islands.Resize(6);
  islands.Build(contacts.data(), contacts.size());
  ASSERT_EQ(islands.islands().size(), 2u);
  EXPECT_EQ(islands.islands()[0].contact_count, 3);
  EXPECT_EQ(islands.islands()[1].contact_count, 1);
  ExpectMatchesReference(islands, contacts, 6);
}

TEST(Islands, RandomContactListsMatchConnectedComponents) {
  // 2 000 random lists over up to 40 bodies, sparse to dense, some against the world; the same
  // Islands reused (as a simulator reuses it step after step)
  std::mt19937 rng(20261206);
  Islands islands;
  for (int trial = 0; trial < 2000; ++trial) {
    const int bodies = 1 + static_cast<int>(rng() % 40);
    const int count = static_cast<int>(rng() % static_cast<unsigned>(2 * bodies + 1));
    std::uniform_int_distribution<int> body(0, bodies - 1);
    std::vector<ClosedContact> contacts;
    for (int k = 0; k < count; ++k) {
      const int b = body(rng);
      int a = rng() % 3 == 0 ? kWorld : body(rng);
      if (a == b) a = kWorld;
      contacts.push_back(Contact(a, b));
    }
    islands.Resize(static_cast<std::size_t>(bodies));
    islands.Build(contacts.data(), contacts.size());
    ExpectMatchesReference(islands, contacts, bodies);
    if (::testing::Test::HasFailure()) {
      ADD_FAILURE() << "trial " << trial << ": " << bodies << " bodies, " << count << " contacts";
      return;
    }
  }
}

}  // namespace
}  // namespace nonsmooth_sim
