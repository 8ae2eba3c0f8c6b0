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

void cut_overlap(const EdgeDistance& a, const EdgeDistance& b, double lo, double hi, double eps,
                 double tol, double* a0, double* a1, double* b0, double* b1) {
  // Pieces of [lo, hi] split where a - b crosses +eps or -eps (the points where a shifted by
  // -+eps equals b): on each, a - b stays above eps, below -eps, or between (a tie), whichever
  // its midpoint shows.
  double x[6];
  int n = 0;
  x[n++] = lo;
  const EdgeDistance above{a.sigma - eps, a.sx, a.sy}, below{a.sigma + eps, a.sx, a.sy};
  n += equal_distance_points(above, b, lo, hi, x + n);
  n += equal_distance_points(below, b, lo, hi, x + n);
  for (int i = 2; i < n; ++i)  // the (at most 4) candidates in order
    for (int j = i; j > 1 && x[j] < x[j - 1]; --j) std::swap(x[j], x[j - 1]);
  x[n] = hi;
  // The same pseudo-source unfolded the same way (a window made twice): its rays are a's, so a
  // tie is no reason to keep both.
  const bool twin_rays = std::abs(a.sigma - b.sigma) <= eps && std::abs(a.sx - b.sx) <= tol &&
                         std::abs(a.sy - b.sy) <= tol;
  // Per piece: -1 a strictly shorter, +1 b strictly shorter, 0 a tie. (Only a strictly shorter
  // window cuts: found in review, a flat grid's vertex reached only along edges, 10 % long, when
  // windows from different sources within round-off of each other cut each other.)
  int sign[5];
  for (int i = 0; i < n; ++i) {
    const double m = 0.5 * (x[i] + x[i + 1]);
    const double f = a.at(m) - b.at(m);
    sign[i] = f < -eps ? -1 : (f > eps || twin_rays ? 1 : 0);
  }
  // [c0, c1] loses the pieces at its ends that the overlap covers and where the other window is
  // strictly shorter (sign `beaten`).
  const auto cut = [&](double* c0, double* c1, int beaten) {
    if (lo <= *c0 + tol) {
      int i = 0;
      while (i < n && sign[i] == beaten) ++i;
      if (i > 0) *c0 = x[i];
    }
    if (hi >= *c1 - tol) {
      int i = n;
      while (i > 0 && sign[i - 1] == beaten) --i;
      if (i < n) *c1 = x[i];
    }
  };
  cut(a0, a1, 1);
  cut(b0, b1, -1);
}

}  // namespace windplan
