#pragma once
// Where two windows of the exact window search (geometry/geodesic/geodesic_windows.h) give an
// edge's points the same distance, and the cut that follows: the window intersection of Mitchell,
// Mount and Papadimitriou ("The discrete geodesic problem", SIAM J. Comput. 1987), by which
// windows on one edge cut each other down to where each is the shorter.
//
// Inline: the window search's competition (geometry/geodesic/window_search.h) calls them for
// every overlap of two windows, and with their bodies in its (flattened) propagation loop it
// takes 10-14 % less time per path (bench/README.md, session 13).
#include <algorithm>
#include <cmath>
#include <utility>

namespace windplan {

/// The distance function of a window on an edge, in the frame of one of the edge's halfedges
/// (the edge on the x axis): sigma + |(x, 0) - (sx, sy)|, with (sx, sy) the unfolded
/// pseudo-source.
struct EdgeDistance {
  double sigma, sx, sy;
  double at(double x) const { return sigma + std::sqrt((x - sx) * (x - sx) + sy * sy); }
};

/// Candidates for the points of (lo, hi) where a and b are equal, ascending, in out[0..n) with
/// n <= 2 returned: every point where a - b changes sign is among them (squaring
/// r_a - r_b = sigma_b - sigma_a twice leaves a quadratic; a double root that round-off
/// pushes below zero is kept). Some candidates may be points where a - b keeps its sign.
inline int equal_distance_points(const EdgeDistance& a, const EdgeDistance& b, double lo, double hi,
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

/// Two windows of one edge against each other over their overlap [lo, hi] (lo < hi), from the
/// ends only. The overlap is split where a - b crosses +eps or -eps; each window loses the pieces
/// at its ends that the overlap reaches and where the other is strictly shorter, by more than
/// eps. Within eps both keep a piece (one of them may hold the ray to a vertex that the other's
/// rays miss), unless they are the same rays (sigma within eps, pseudo-sources within tol): then
/// a loses the tie, so that a window made twice is dropped and the first one kept.
/// The intervals [*a0, *a1] and [*b0, *b1], in the frame of a's halfedge, are cut in place (a
/// window cut to nothing ends with a1 - a0 <= tol); both cuts come from the same split.
inline void cut_overlap(const EdgeDistance& a, const EdgeDistance& b, double lo, double hi,
                        double eps, double tol, double* a0, double* a1, double* b0, double* b1) {
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
