#pragma once
// A monotone priority queue on keys >= 0: a radix heap (Ahuja, Mehlhorn, Orlin and Tarjan,
// "Faster algorithms for the shortest path problem", J. ACM 1990) on the bits of the key.
// Pushes are O(1); each item moves down at most 64 buckets over its life, in practice a few.
//
// Monotone: a key pushed below the last key popped is taken as that key. It serves searches
// whose keys never fall below the one being expanded except by round-off (Dijkstra's order,
// or A* with a consistent bound: geometry/geodesic/window_search.h), where keys order the work
// and never decide it.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

namespace windplan {

/// Item: any type with a `double key` member (>= 0, not NaN).
template <class Item>
class RadixQueue {
 public:
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }

  void clear() {
    for (auto& b : buckets_) b.clear();
    size_ = 0;
    last_ = 0;
    occupied_ = 0;
  }

  /// Adds `item`; its key is raised to the last key popped when it is below.
  void push(Item item) {
    std::uint64_t k = bits(item.key);
    if (k < last_) {
      k = last_;
      item.key = value(k);
    }
    put(k, item);
    ++size_;
  }

  /// Removes and returns an item with the smallest key (the queue must not be empty).
  Item pop() {
    if (buckets_[0].empty()) {
      // The first non-empty bucket: its items all go to lower buckets around its least key.
      const int i = __builtin_ctzll(occupied_) + 1;
      occupied_ &= occupied_ - 1;
      std::vector<Item>& from = buckets_[i];
      std::uint64_t least = bits(from[0].key);
      for (const Item& e : from) least = std::min(least, bits(e.key));
      last_ = least;
      for (const Item& e : from) put(bits(e.key), e);
      from.clear();
    }
    const Item item = buckets_[0].back();
    buckets_[0].pop_back();
    --size_;
    return item;
  }

  /// Empties the queue and gives the buckets' memory back.
  void release() {
    for (auto& b : buckets_) std::vector<Item>().swap(b);
    size_ = 0;
    last_ = 0;
    occupied_ = 0;
  }

 private:
  // The bits of a double >= 0 order as the double does.
  static std::uint64_t bits(double key) {
    std::uint64_t k;
    std::memcpy(&k, &key, sizeof k);
    return k;
  }
  static double value(std::uint64_t k) {
    double key;
    std::memcpy(&key, &k, sizeof key);
    return key;
  }
  // Bucket 0 holds the keys equal to last_, bucket i those whose highest bit differing from
  // last_ is bit i - 1 (all of them larger than last_, smaller than those of bucket i + 1).
  int bucket(std::uint64_t k) const { return k == last_ ? 0 : 64 - __builtin_clzll(k ^ last_); }

  void put(std::uint64_t k, const Item& item) {
    const int b = bucket(k);
    buckets_[b].push_back(item);
    if (b > 0) occupied_ |= std::uint64_t{1} << (b - 1);
  }

  std::vector<Item> buckets_[65];
  // Bit i - 1 set: bucket i (1..64) holds items.
  std::uint64_t occupied_ = 0;
  std::size_t size_ = 0;
  std::uint64_t last_ = 0;
};

}  // namespace windplan
