// A performance property (not timing): a step does not allocate once its problem sizes have
// been seen, for both integrators.
#include <gtest/gtest.h>

#include "allocation_counter.h"  // the heap allocation count
#include "nonsmooth_sim/core/simulator.h"
#include "nonsmooth_sim/core/tippe_top.h"

namespace nonsmooth_sim {
namespace {

void ExpectNoAllocationOnceWarm(Integrator integrator) {
  // the Tippe-Top's first 2 s meet every problem size it has (none, one and two closed
  // contacts) and both pairs (big_sphere/ground, peg_sphere/ground: the per-pair memory of warm
  // start and tangents allocates when a pair first touches). The run goes on from there (not
  // replayed: SetState() clears that memory, so a replay allocates again when the pairs touch);
  // the next 6 s, which meet the one- and two-contact problems again (measured: peg alone from
  // 2 s, both spheres from 4.55 s), must not touch the heap.
  SimulatorOptions options;
  options.integrator = integrator;
  Simulator sim(MakeTippeTopScene(), options);
  StepStatistics stats;
  bool warm_sizes[3] = {false, false, false};
  bool warm_pairs[2] = {false, false};
  for (int k = 0; k < 20000; ++k) {
    sim.Step(&stats);
    warm_sizes[stats.closed_contacts] = true;
    warm_pairs[0] = warm_pairs[0] || sim.InContact(kBigSphere);
    warm_pairs[1] = warm_pairs[1] || sim.InContact(kPegSphere);
  }
  // (moreau2 keeps the ball's contact closed through the hand-over: no step without one)
  ASSERT_TRUE(warm_sizes[1] && warm_sizes[2]);
  if (integrator == Integrator::kMoreau) {
    ASSERT_TRUE(warm_sizes[0]);
  }
  ASSERT_TRUE(warm_pairs[0] && warm_pairs[1]);
  const long before = test::HeapAllocations();
  bool sizes[3] = {false, false, false};
  for (int k = 0; k < 60000; ++k) {
    sim.Step(&stats);
    sizes[stats.closed_contacts] = true;
  }
  EXPECT_EQ(test::HeapAllocations() - before, 0);
  EXPECT_TRUE(sizes[1]);
  EXPECT_TRUE(sizes[2]);
}

TEST(Step, DoesNotAllocateOnceItsProblemSizesHaveBeenSeen) {
  ExpectNoAllocationOnceWarm(Integrator::kMoreau);
}

TEST(Step, Moreau2DoesNotAllocateOnceItsProblemSizesHaveBeenSeen) {
  // its end gaps (RecordEndGaps) and re-solves reuse the same workspaces
  ExpectNoAllocationOnceWarm(Integrator::kMoreau2);
}

}  // namespace
}  // namespace nonsmooth_sim
