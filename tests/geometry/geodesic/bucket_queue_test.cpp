// The bucket queue (geometry/geodesic/bucket_queue.h): every item out once, bucket by bucket,
// low keys taken into the current bucket, far keys into the ring's last, peek, and a reset after
// a search that stopped early.
#include "geometry/geodesic/bucket_queue.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace windplan {
namespace {

struct Item {
  double key;
  int index;
};

TEST(BucketQueue, PopsBucketByBucketWhileKeysGrow) {
  // Dijkstra-like use: every push is at least the key just popped, in steps smaller and larger
  // than a bucket.
  const double width = 0.25;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> step(0.0, 2.0);
  BucketQueue<Item> q;
  q.reset(width);
  std::vector<double> pushed, popped;
  for (int i = 0; i < 50; ++i) {
    const double k = step(rng) * 10.0;
    q.push({k, i});
    pushed.push_back(k);
  }
  double last_bucket = 0.0;
  while (!q.empty()) {
    const Item it = q.pop();
    const double bucket = std::floor(it.key / width);
    EXPECT_GE(bucket, last_bucket) << it.key;  // never from a bucket before the last one
    last_bucket = bucket;
    popped.push_back(it.key);
    if (pushed.size() < 5000) {
      for (const double d : {0.0, 1e-12 * it.key, 0.1 * width, step(rng)}) {
        q.push({it.key + d, 0});
        pushed.push_back(it.key + d);
      }
    }
  }
  std::sort(pushed.begin(), pushed.end());
  std::sort(popped.begin(), popped.end());
  EXPECT_EQ(popped, pushed);  // each once
}

TEST(BucketQueue, LastInFirstOutWithinABucketAndLowKeysInTheCurrentOne) {
  BucketQueue<Item> q;
  q.reset(1.0);
  q.push({2.1, 0});
  q.push({2.9, 1});
  q.push({5.0, 2});
  EXPECT_EQ(q.pop().index, 1);  // same bucket as 2.1, pushed later: out first
  q.push({0.5, 3});             // below the current bucket (2): taken into it
  EXPECT_EQ(q.pop().index, 3);
  EXPECT_EQ(q.pop().index, 0);
  EXPECT_EQ(q.pop().index, 2);
  EXPECT_TRUE(q.empty());
}

TEST(BucketQueue, PeekShowsTheNextPopWithinTheCurrentBucket) {
  BucketQueue<Item> q;
  q.reset(1.0);
  EXPECT_EQ(q.peek(), nullptr);  // empty
  q.push({0.2, 0});
  q.push({0.7, 1});
  q.push({3.5, 2});
  ASSERT_NE(q.peek(), nullptr);
  EXPECT_EQ(q.peek()->index, 1);  // what pop returns next
  EXPECT_EQ(q.pop().index, 1);
  ASSERT_NE(q.peek(), nullptr);
  EXPECT_EQ(q.peek()->index, 0);
  EXPECT_EQ(q.pop().index, 0);
  EXPECT_EQ(q.peek(), nullptr);  // the next item lies beyond the current bucket
  EXPECT_EQ(q.size(), 1u);       // and peek did not move to it
  EXPECT_EQ(q.pop().index, 2);
  q.push({3.9, 3});
  ASSERT_NE(q.peek(), nullptr);  // now in the current bucket
  EXPECT_EQ(q.peek()->index, 3);
  EXPECT_EQ(q.pop().index, 3);
  EXPECT_TRUE(q.empty());
  EXPECT_EQ(q.peek(), nullptr);
}

TEST(BucketQueue, KeysBeyondTheRingWaitInItsLastBucket) {
  BucketQueue<Item> q;
  q.reset(1.0);
  const double last = static_cast<double>(BucketQueue<Item>::kBuckets - 1);
  q.push({1e9, 0});                             // beyond the ring: its last bucket
  q.push({last - 0.5, 1});                      // the bucket before it
  q.push({std::numeric_limits<double>::infinity(), 2});
  EXPECT_EQ(q.pop().index, 1);
  const Item a = q.pop(), b = q.pop();
  EXPECT_EQ(a.index + b.index, 2);  // the two far ones, in either order
  EXPECT_TRUE(q.empty());
  // The ring has turned: buckets are reused past its end.
  q.push({last + 10.0, 3});
  q.push({last + 2.0, 4});
  EXPECT_EQ(q.pop().index, 4);
  EXPECT_EQ(q.pop().index, 3);
}

TEST(BucketQueue, ResetAfterAnEarlyStopStartsAgainEmpty) {
  BucketQueue<Item> q;
  q.reset(0.5);
  for (int i = 0; i < 20; ++i) q.push({1.0 + i * 7.5, i});
  EXPECT_EQ(q.pop().index, 0);
  EXPECT_EQ(q.size(), 19u);
  q.reset(2.0);
  EXPECT_TRUE(q.empty());
  q.push({300.0, 102});
  q.push({0.5, 100});
  q.push({40.0, 101});
  for (const int expected : {100, 101, 102}) {
    ASSERT_FALSE(q.empty());
    EXPECT_EQ(q.pop().index, expected);
  }
  EXPECT_TRUE(q.empty());
}

}  // namespace
}  // namespace windplan
