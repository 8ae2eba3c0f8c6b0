// Equal-distance points of two windows (see geometry/geodesic/window_distance.h).
#include "geometry/geodesic/window_distance.h"

#include <algorithm>
#include <cmath>

namespace windplan {

int equal_distance_points(const EdgeDistance& a, const EdgeDistance& b, double lo, double hi,
                          double out[2]) {
  const double k = b.sigma - a.sigma;
  // r_a^2 - r_b^2 - k^2 = alpha x + beta = 2 k r_b.
  const double alpha = 2.0 * (b.sx - a.sx);
  const double beta = a.sx * a.sx - b.sx * b.sx + a.sy * a.sy - b.sy * b.sy - k * k;
  const double qa = alpha * alpha - 4.0 * k * k;
  const double qb = 2.0 * alpha * beta + 8.0 * k * k * b.sx;
  const double qc = beta * beta - 4.0 * k * k * (b.sx * b.sx + b.sy * b.sy);
  double roots[2];
  int n = 0;
  if (k == 0.0) {
    // r_a = r_b: one root of the linear alpha x + beta (the quadratic's double root).
    if (alpha != 0.0) roots[n++] = -beta / alpha;
  } else if (std::abs(qa) <= 1e-14 * (alpha * alpha + 4.0 * k * k)) {
    if (qb != 0.0) roots[n++] = -qc / qb;
  } else {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc > 0.0) {
      const double r = std::sqrt(disc);
      // The stable pair of roots.
      const double q = -0.5 * (qb + (qb >= 0.0 ? r : -r));
      if (q != 0.0) roots[n++] = qc / q;
      roots[n++] = q / qa;
    } else {
      // A double root, or none: round-off can take a tangency either way, so the parabola's
      // vertex is a candidate (a point where f does not change sign only splits a piece).
      roots[n++] = -qb / (2.0 * qa);
    }
  }
  int m = 0;
  for (int i = 0; i < n; ++i)
    if (roots[i] > lo && roots[i] < hi) out[m++] = roots[i];
  if (m == 2 && out[0] > out[1]) std::swap(out[0], out[1]);
  return m;
}

}  // namespace windplan
