// The broad phase (broad_phase.h) against brute force over all pairs, and SortNearlySorted
// (nearly_sorted.h) against std::stable_sort / std::sort. Fixed seeds.
#include "nonsmooth_sim/core/collision/broad_phase.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "nonsmooth_sim/core/nearly_sorted.h"

namespace nonsmooth_sim {
namespace {

using PairSet = std::set<std::pair<int, int>>;

// every pair of spheres that overlap, not of one body, not both static: O(n²)
PairSet BruteForce(const std::vector<BoundingSphere>& spheres) {
  PairSet pairs;
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    for (std::size_t j = i + 1; j < spheres.size(); ++j) {
      const BoundingSphere& a = spheres[i];
      const BoundingSphere& b = spheres[j];
      if (a.body == b.body) continue;
      const double reach = a.radius + b.radius;
      if ((a.center - b.center).squaredNorm() > reach * reach) continue;
      pairs.emplace(std::min(a.collider, b.collider), std::max(a.collider, b.collider));
    }
  }
  return pairs;
}

// SweepAndPrune's pairs as a set; fails on a pair reported twice or in the wrong orientation
PairSet Swept(std::vector<BoundingSphere>* spheres) {
  std::vector<std::pair<int, int>> list;
  SweepAndPrune(spheres, &list);
  PairSet pairs;
  for (const auto& p : list) {
    EXPECT_LT(p.first, p.second);
    EXPECT_TRUE(pairs.insert(p).second) << "pair (" << p.first << ", " << p.second << ") twice";
  }
  return pairs;
}

// n spheres in a box of side `extent`, two per body (body -1 static for some)
std::vector<BoundingSphere> RandomSpheres(int n, double extent, std::mt19937* rng) {
  std::uniform_real_distribution<double> position(-0.5 * extent, 0.5 * extent);
  std::uniform_real_distribution<double> radius(0.01, 0.3);
  std::vector<BoundingSphere> spheres;
  for (int i = 0; i < n; ++i) {
    BoundingSphere s;
    s.center = Eigen::Vector3d(position(*rng), position(*rng), position(*rng));
    s.radius = radius(*rng);
    s.collider = i;
    s.body = i % 7 == 0 ? -1 : i / 2;
    spheres.push_back(s);
  }
  return spheres;
}

TEST(SweepAndPrune, FindsEveryOverlappingPairOfRandomSpheres) {
  std::mt19937 rng(20261203);
  for (int round = 0; round < 50; ++round) {
    const int n = 2 + round * 4;
    std::vector<BoundingSphere> spheres = RandomSpheres(n, 1.0 + 0.05 * round, &rng);
    const PairSet expected = BruteForce(spheres);
    EXPECT_EQ(Swept(&spheres), expected) << "round " << round << ", n = " << n;
  }
}

TEST(SweepAndPrune, KeepsFindingThemAsTheSpheresMoveInTheOrderOfTheLastCall) {
  // the caller's use: the spheres stay in the order the last call left them, their centres move;
  // small moves (a few swaps a step), then large ones (the order far from sorted)
  std::mt19937 rng(7);
  std::vector<BoundingSphere> spheres = RandomSpheres(300, 4.0, &rng);
  std::vector<std::pair<int, int>> unused;
  SweepAndPrune(&spheres, &unused);
  for (const double step : {1e-3, 1e-2, 0.1, 2.0}) {
    std::normal_distribution<double> move(0.0, step);
    for (int k = 0; k < 20; ++k) {
      for (BoundingSphere& s : spheres)
        s.center += Eigen::Vector3d(move(rng), move(rng), move(rng));
      const PairSet expected = BruteForce(spheres);
      EXPECT_EQ(Swept(&spheres), expected) << "moves of " << step << ", call " << k;
      for (std::size_t i = 1; i < spheres.size(); ++i) {
        ASSERT_LE(spheres[i - 1].interval_start, spheres[i].interval_start);
      }
    }
  }
}

TEST(SweepAndPrune, FindsTouchingAndCoincidentSpheresOnAGrid) {
  // a 12 × 12 grid in x, y whose neighbours touch exactly (spacing = 2 r, the overlap test is ≤)
  // plus coincident spheres of other bodies: ties in the interval starts
  std::vector<BoundingSphere> spheres;
  const double r = 0.25;
  for (int i = 0; i < 12; ++i) {
    for (int j = 0; j < 12; ++j) {
      BoundingSphere s;
      s.center = Eigen::Vector3d(0.5 * i, 0.5 * j, 0.0);
      s.radius = r;
      s.collider = static_cast<int>(spheres.size());
      s.body = s.collider;
      spheres.push_back(s);
    }
  }
  for (int k = 0; k < 10; ++k) {
    BoundingSphere s = spheres[static_cast<std::size_t>(13 * k)];
    s.collider = static_cast<int>(spheres.size());
    s.body = s.collider;
    spheres.push_back(s);
  }
  const PairSet expected = BruteForce(spheres);
  EXPECT_GT(expected.size(), 2u * 11u * 12u);  // the grid's 264 neighbours touch, and more
  EXPECT_EQ(Swept(&spheres), expected);
}

TEST(SweepAndPrune, TheDirectionSeparatesTheColumnsOfAGrid) {
  // broad_phase.h: the points of an n × n grid of spacing s in x and y (or x and z) project at
  // least 0.073 s (n = 8), 0.017 s (n = 32) apart onto the sweep direction; in y and z 0.045 s,
  // 0.011 s
  const Eigen::Vector3d a = SweepDirection();
  EXPECT_NEAR(a.norm(), 1.0, 1e-15);
  struct Case {
    int n, u, v;
    double bound;
  };
  for (const Case& c : {Case{8, 0, 1, 0.072}, Case{8, 0, 2, 0.072}, Case{8, 1, 2, 0.045},
                        Case{32, 0, 1, 0.017}, Case{32, 0, 2, 0.017}, Case{32, 1, 2, 0.0106}}) {
    std::vector<double> projection;
    for (int i = 0; i < c.n; ++i) {
      for (int j = 0; j < c.n; ++j) projection.push_back(a[c.u] * i + a[c.v] * j);
    }
    std::sort(projection.begin(), projection.end());
    double closest = INFINITY;
    for (std::size_t k = 1; k < projection.size(); ++k) {
      closest = std::min(closest, projection[k] - projection[k - 1]);
    }
    EXPECT_GT(closest, c.bound) << "n = " << c.n << ", axes " << c.u << ", " << c.v;
  }
}

TEST(SortNearlySorted, IsAStableSortWhileTheInputIsNearlySorted) {
  // pairs (key, original index): a stable sort keeps the index order among equal keys
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> key(0, 50);
  for (int round = 0; round < 100; ++round) {
    std::vector<std::pair<int, int>> v;
    for (int i = 0; i < 200; ++i) v.emplace_back(key(rng), i);
    std::stable_sort(v.begin(), v.end());
    for (auto& e : v) e.second = static_cast<int>(&e - v.data());
    // a few neighbours swapped: far below the move budget
    std::uniform_int_distribution<std::size_t> at(0, v.size() - 2);
    for (int s = 0; s < round % 10; ++s) std::swap(v[at(rng)], v[at(rng) + 1]);
    std::vector<std::pair<int, int>> expected = v;
    const auto by_key = [](const auto& x, const auto& y) { return x.first < y.first; };
    std::stable_sort(expected.begin(), expected.end(), by_key);
    SortNearlySorted(v.begin(), v.end(), by_key);
    EXPECT_EQ(v, expected) << "round " << round;
  }
}

TEST(SortNearlySorted, SortsAnyInputIncludingReversedAndShuffledOnes) {
  // beyond its move budget it hands over to std::sort: still sorted, still a permutation
  std::mt19937 rng(11);
  for (const int n : {0, 1, 2, 3, 10, 100, 1000}) {
    std::vector<int> shuffled(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) shuffled[static_cast<std::size_t>(i)] = (i * 37) % 101;
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    std::vector<int> reversed = shuffled;
    std::sort(reversed.rbegin(), reversed.rend());
    for (std::vector<int> v : {shuffled, reversed}) {
      std::vector<int> expected = v;
      std::sort(expected.begin(), expected.end());
      SortNearlySorted(v.begin(), v.end());
      EXPECT_EQ(v, expected) << "n = " << n;
    }
  }
}

}  // namespace
}  // namespace nonsmooth_sim
