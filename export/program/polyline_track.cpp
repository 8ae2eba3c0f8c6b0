#include "export/program/polyline_track.h"

#include <algorithm>

#include "export/machine/resample.h"

namespace windplan {

double track_polyline(const std::vector<Vec3>& q, const std::vector<double>& sq, const Vec3& p,
                      double back, double ahead, int first, int limit, int* ptr) {
  const int m = static_cast<int>(q.size());
  limit = std::min(limit, m - 1);
  if (limit <= first) {
    *ptr = first;
    return (p - q[first]).norm();
  }
  const int hi_max = limit - 1;
  int lo = std::clamp(*ptr, first, hi_max), hi = lo;
  while (lo > first && sq[*ptr] - sq[lo] < back) --lo;
  while (hi < hi_max && sq[hi] - sq[*ptr] < ahead) ++hi;
  // The least distance over the window and the first segment at it, as a scan of every segment
  // would find them, found sooner: started at the last match (usually the nearest), the scan
  // skips every run of segments that the triangle inequality puts farther than the best so far
  // (no point of the polyline within arc length a of q[j] is nearer p than |p q[j]| - a; a
  // margin of 1e-9 covers the rounding of the arc lengths), and a tie goes to the first.
  const int start = std::clamp(*ptr, lo, hi);
  const double d_start = distance_to_segment(p, q[start], q[start + 1]);
  double best = d_start;
  int at = start;
  for (int j = lo; j <= hi;) {
    const double dq = (p - q[j]).norm();
    const double slack = dq - best - 1e-9 * (1.0 + dq + sq[hi + 1] - sq[lo]);
    if (slack > 0.0) {
      // Segments j .. k-1 end within arc length `slack` of q[j]: all farther than best.
      const int k = static_cast<int>(
                        std::upper_bound(sq.begin() + j + 1, sq.begin() + hi + 2, sq[j] + slack) -
                        sq.begin()) -
                    1;
      if (k > j) {
        j = k;
        continue;
      }
    }
    const double dd = j == start ? d_start : distance_to_segment(p, q[j], q[j + 1]);
    if (dd < best || (dd == best && j < at)) {
      best = dd;
      at = j;
    }
    ++j;
  }
  *ptr = at;
  return best;
}

}  // namespace windplan
