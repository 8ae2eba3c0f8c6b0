// The radix heap (geometry/geodesic/radix_queue.h) against sorting: the same keys come out in
// order.
#include "geometry/geodesic/radix_queue.h"

#include <algorithm>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace windplan {
namespace {

struct Item {
  double key;
  int index;
};

TEST(RadixQueue, PopsInKeyOrderWhileKeysGrow) {
  // Dijkstra-like use: every push is at least the key just popped.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> step(0.0, 2.0);
  RadixQueue<Item> q;
  std::vector<double> pushed, popped;
  for (int i = 0; i < 50; ++i) {
    const double k = step(rng) * 10.0;
    q.push({k, i});
    pushed.push_back(k);
  }
  double last = 0.0;
  while (!q.empty()) {
    const Item it = q.pop();
    EXPECT_GE(it.key, last);
    last = it.key;
    popped.push_back(it.key);
    // Children at or beyond the popped key, including equal keys and tiny steps.
    if (pushed.size() < 5000) {
      for (const double d : {0.0, 1e-300, 1e-12 * it.key, step(rng)}) {
        q.push({it.key + d, 0});
        pushed.push_back(it.key + d);
      }
    }
  }
  std::sort(pushed.begin(), pushed.end());
  ASSERT_EQ(popped.size(), pushed.size());
  EXPECT_EQ(popped, pushed);
}

TEST(RadixQueue, KeysBelowTheLastPoppedAreRaisedToIt) {
  RadixQueue<Item> q;
  q.push({2.0, 0});
  q.push({5.0, 1});
  EXPECT_EQ(q.pop().key, 2.0);
  q.push({1.5, 2});  // below 2: taken as 2
  const Item it = q.pop();
  EXPECT_EQ(it.index, 2);
  EXPECT_EQ(it.key, 2.0);
  EXPECT_EQ(q.pop().key, 5.0);
  EXPECT_TRUE(q.empty());
  q.clear();
  q.push({0.0, 3});
  EXPECT_EQ(q.size(), 1u);
  EXPECT_EQ(q.pop().index, 3);
}

// Cleared or released with items in several buckets (bits of the occupied ones set), the
// queue starts again empty: the next items come out in order, none of the old ones.
TEST(RadixQueue, ClearAndReleaseStartAgainEmpty) {
  for (const bool release : {false, true}) {
    RadixQueue<Item> q;
    for (int i = 0; i < 20; ++i) q.push({1.0 + i * 7.5, i});
    EXPECT_EQ(q.pop().index, 0);  // spreads the rest over lower buckets
    if (release) {
      q.release();
    } else {
      q.clear();
    }
    EXPECT_TRUE(q.empty());
    q.push({0.5, 100});
    q.push({300.0, 102});
    q.push({40.0, 101});
    for (const int expected : {100, 101, 102}) {
      ASSERT_FALSE(q.empty());
      EXPECT_EQ(q.pop().index, expected) << (release ? "released" : "cleared");
    }
    EXPECT_TRUE(q.empty());
  }
}

}  // namespace
}  // namespace windplan
