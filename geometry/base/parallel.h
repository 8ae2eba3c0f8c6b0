#pragma once
// Parallel loops over independent items (TBB), with results that do not depend on the number
// of threads: every item writes only its own output slot, and when items throw, the exception
// of the lowest index is rethrown (the one a serial loop would have met first).
//
// The thread count is process-wide: the windplan CLI's --threads N limits it with a
// tbb::global_control (ThreadLimit below); by default TBB uses every core.
#include <functional>
#include <memory>

namespace windplan {

/// Calls body(i) for every i in [0, n), in parallel, each index exactly once.
/// \throw the exception thrown by body for the lowest index, after all items have run.
void parallel_for_index(int n, const std::function<void(int)>& body);

/// The number of threads parallel_for_index may use now (>= 1).
int max_threads();

/// Limits the threads of parallel_for_index (and every other TBB loop) while it is alive.
class ThreadLimit {
 public:
  /// \param threads >= 1
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace windplan
