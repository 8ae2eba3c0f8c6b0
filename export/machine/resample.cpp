#include "export/machine/resample.h"

#include <algorithm>

#include "geometry/base/errors.h"

namespace windplan {

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = ab.squaredNorm();
  if (l2 <= 0.0) return (p - a).norm();
  const double t = std::clamp((p - a).dot(ab) / l2, 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

ResampleResult resample_by_chord(const std::vector<const std::vector<Vec3>*>& polylines,
                                 double tolerance, const std::vector<int>& forced, int max_span) {
  ResampleResult r;
  if (polylines.empty()) return r;
  const int n = static_cast<int>(polylines[0]->size());
  for (const auto* p : polylines) {
    if (static_cast<int>(p->size()) != n) {
      throw InvariantError("resample_by_chord: polylines of different lengths");
    }
  }
  if (n == 0) return r;
  max_span = std::max(1, max_span);
  std::vector<char> must(n, 0);
  for (int f : forced) {
    if (f >= 0 && f < n) must[f] = 1;
  }
  must[0] = must[n - 1] = 1;

  // Largest deviation of points i+1..j-1 from chord (i, j), over all polylines.
  auto deviation = [&](int i, int j) {
    double d = 0.0;
    for (const auto* p : polylines) {
      const Vec3& a = (*p)[i];
      const Vec3& b = (*p)[j];
      for (int k = i + 1; k < j; ++k) d = std::max(d, distance_to_segment((*p)[k], a, b));
    }
    return d;
  };

  // The next forced index after each position bounds every chord.
  std::vector<int> next_forced(n, n - 1);
  for (int k = n - 2; k >= 0; --k) next_forced[k] = must[k + 1] ? k + 1 : next_forced[k + 1];

  // From each kept point, the farthest valid chord end by doubling then bisection: O(span log
  // span) per kept point instead of O(span^2). Only tested chords are accepted, so every dropped
  // point is within tolerance even where validity is not monotone in the end index.
  int i = 0;
  r.kept.push_back(0);
  while (i < n - 1) {
    const int limit = std::min(next_forced[i], i + max_span);
    int good = i + 1, step = 1;
    double good_dev = 0.0;
    int bad = -1;
    while (good < limit) {
      const int j = std::min(limit, good + step);
      const double d = deviation(i, j);
      if (d > tolerance) {
        bad = j;
        break;
      }
      good = j;
      good_dev = d;
      step *= 2;
    }
    if (bad > 0) {
      while (bad - good > 1) {
        const int mid = good + (bad - good) / 2;
        const double d = deviation(i, mid);
        if (d > tolerance) {
          bad = mid;
        } else {
          good = mid;
          good_dev = d;
        }
      }
    }
    r.max_deviation = std::max(r.max_deviation, good_dev);
    r.kept.push_back(good);
    i = good;
  }
  return r;
}

}  // namespace windplan
