#include "geometry/base/parallel.h"

#include <exception>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

namespace windplan {

void parallel_for_index(int n, const std::function<void(int)>& body) {
  if (n <= 0) return;
  std::vector<std::exception_ptr> errors(n);
  // Grain 1: items (geodesics, girth loops, passes) take 0.1 ms to seconds each, so the
  // scheduling overhead is small and the load balances item by item.
  tbb::parallel_for(tbb::blocked_range<int>(0, n, 1), [&](const tbb::blocked_range<int>& r) {
    for (int i = r.begin(); i != r.end(); ++i) {
      try {
        body(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  });
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

int max_threads() {
  return static_cast<int>(
      tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

struct ThreadLimit::Impl {
  tbb::global_control control;
  explicit Impl(int threads)
      : control(tbb::global_control::max_allowed_parallelism,
                static_cast<std::size_t>(threads < 1 ? 1 : threads)) {}
};

ThreadLimit::ThreadLimit(int threads) : impl_(std::make_unique<Impl>(threads)) {}
ThreadLimit::~ThreadLimit() = default;

}  // namespace windplan
