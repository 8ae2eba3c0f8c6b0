#pragma once
// An approximate monotone priority queue on keys >= 0: buckets of a fixed width w on a ring
// (Dial's queue, "untidy" as in Yatziv, Bartesaghi and Sapiro, "O(N) implementation of the fast
// marching algorithm", J. Comput. Phys. 2006). Pushes and pops are O(1), plus one step per empty
// bucket passed. Items come out bucket by bucket, last in first out within one, so an item may
// come out before another whose key is up to w smaller.
//
// It serves searches whose order need only be close to Dijkstra's: the target bound's two passes
// (geometry/geodesic/target_bound.cpp), where any function is a valid psi and any path's length
// a valid upper bound. There it takes a quarter of the bound's instructions off the radix heap's
// (geometry/geodesic/radix_queue.h) with the same windows to within 2e-5 of their number
// (bench/README.md, session 21). Exact orders use the radix heap.
#include <cstddef>
#include <vector>

namespace windplan {

/// Item: any type with a `double key` member (>= 0, not NaN).
template <class Item>
class BucketQueue {
 public:
  /// The ring's buckets (a power of 2): keys up to this many widths beyond the current bucket
  /// keep their order.
  static constexpr long kBuckets = 4096;

  /// Empties the queue and sets the bucket width (> 0, the keys' units). Items left from a search
  /// that stopped early lie in the buckets from the current one on: only those are cleared.
  void reset(double width) {
    for (long b = current_; size_ > 0; ++b) {
      std::vector<Item>& v = buckets_[b & (kBuckets - 1)];
      size_ -= v.size();
      v.clear();
    }
    current_ = 0;
    per_width_ = 1.0 / width;
  }

  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }

  /// Adds `item`: to the current bucket when its key is below it, to the ring's last bucket when
  /// its key lies beyond the ring.
  void push(const Item& item) {
    const double at = item.key * per_width_;
    const long b = at < static_cast<double>(current_) ? current_
                   : at >= static_cast<double>(current_ + kBuckets - 1)
                       ? current_ + kBuckets - 1
                       : static_cast<long>(at);
    buckets_[b & (kBuckets - 1)].push_back(item);
    ++size_;
  }

  /// The item the next pop returns, when it lies in the current bucket; nullptr otherwise (the
  /// current bucket is empty: finding the next item would pass the empty buckets). For a
  /// prefetch of what the next item reads while this one is processed. Valid until the next
  /// push or pop.
  const Item* peek() const {
    const std::vector<Item>& b = buckets_[current_ & (kBuckets - 1)];
    return b.empty() ? nullptr : &b.back();
  }

  /// Removes and returns an item of the first non-empty bucket (the queue must not be empty).
  Item pop() {
    while (buckets_[current_ & (kBuckets - 1)].empty()) ++current_;
    std::vector<Item>& b = buckets_[current_ & (kBuckets - 1)];
    const Item item = b.back();
    b.pop_back();
    --size_;
    return item;
  }

 private:
  std::vector<Item> buckets_[kBuckets];
  std::size_t size_ = 0;
  long current_ = 0;        // the current bucket's number (on the ring: modulo kBuckets)
  double per_width_ = 1.0;  // 1 / the bucket width
};

}  // namespace windplan
