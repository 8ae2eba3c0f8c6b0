// Equal-distance points of two windows (geometry/geodesic/window_distance.h) against a dense scan
// of the sign of their difference: every sign change lies within round-off of a candidate,
// including equal pseudo-source distances (a double root of the squared equation) and tangencies.
#include "geometry/geodesic/window_distance.h"

#include <algorithm>
#include <random>

#include <gtest/gtest.h>

namespace windplan {
namespace {

// The sign changes of a - b over a scan of n steps of [lo, hi] that are clear of round-off.
std::vector<double> sign_changes(const EdgeDistance& a, const EdgeDistance& b, double lo, double hi,
                                 int n) {
  std::vector<double> changes;
  const double eps = 1e-12 * (a.sigma + b.sigma + hi - lo + 1.0);
  int last = 0;
  double last_x = lo;
  for (int i = 0; i <= n; ++i) {
    const double x = lo + (hi - lo) * i / n;
    const double f = a.at(x) - b.at(x);
    const int s = f > eps ? 1 : (f < -eps ? -1 : 0);
    if (s != 0 && last != 0 && s != last) changes.push_back(0.5 * (x + last_x));
    if (s != 0) {
      last = s;
      last_x = x;
    }
  }
  return changes;
}

void expect_candidates_cover(const EdgeDistance& a, const EdgeDistance& b, double lo, double hi,
                             const char* what) {
  double out[2];
  const int n = equal_distance_points(a, b, lo, hi, out);
  ASSERT_LE(n, 2);
  for (int i = 0; i < n; ++i) {
    EXPECT_GT(out[i], lo);
    EXPECT_LT(out[i], hi);
    if (i > 0) {
      EXPECT_LE(out[i - 1], out[i]);
    }
  }
  const int steps = 4000;
  for (const double x : sign_changes(a, b, lo, hi, steps)) {
    double nearest = 1e300;
    for (int i = 0; i < n; ++i) nearest = std::min(nearest, std::abs(out[i] - x));
    EXPECT_LE(nearest, 2.0 * (hi - lo) / steps)
        << what << ": a - b changes sign near " << x << " with no candidate (" << n << ")";
  }
}

TEST(WindowDistance, ClosedFormOfTwoSourcesAtEqualDistance) {
  // sigma equal: the points equidistant from (0, -1) and (2, -1) are x = 1 (the bisector).
  double out[2];
  const EdgeDistance a{0.5, 0.0, -1.0}, b{0.5, 2.0, -1.0};
  ASSERT_EQ(equal_distance_points(a, b, -5.0, 5.0, out), 1);
  EXPECT_NEAR(out[0], 1.0, 1e-15);
  // Unequal sigma: a hyperbola branch; its point on the edge solves the equation exactly.
  const EdgeDistance c{0.3, 0.0, -1.0}, d{0.0, 2.0, -1.5};
  const int n = equal_distance_points(c, d, -10.0, 10.0, out);
  ASSERT_GE(n, 1);
  bool exact = false;
  for (int i = 0; i < n; ++i) exact = exact || std::abs(c.at(out[i]) - d.at(out[i])) < 1e-12;
  EXPECT_TRUE(exact);
}

TEST(WindowDistance, EverySignChangeHasACandidate) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  for (int trial = 0; trial < 3000; ++trial) {
    EdgeDistance a{pos(rng), 2.0 * u(rng), -pos(rng)};
    EdgeDistance b{pos(rng), 2.0 * u(rng), -pos(rng)};
    if (trial % 3 == 0) b.sigma = a.sigma;  // one pseudo-source reached two ways
    if (trial % 7 == 0) b.sy = 0.0;         // a source on the edge's line
    expect_candidates_cover(a, b, -1.0, 1.5, "random");
    if (HasFailure()) return;
  }
}

TEST(WindowDistance, TangencyAndEqualSigmaSurviveRoundOff) {
  // Equal sigma and mirror-image sources at the scale of a real mesh edge (the case whose
  // discriminant round-off drops below zero): the bisector must be a candidate.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const double sigma = u(rng);
    const double x0 = 0.2 + 0.1 * u(rng), y = -0.2 - 0.1 * u(rng);
    const double dx = 1e-3 * (0.5 + u(rng)), dy = 1e-3 * (u(rng) - 0.5);
    const EdgeDistance a{sigma, x0, y}, b{sigma, x0 + dx, y + dy};
    expect_candidates_cover(a, b, x0 - 0.01, x0 + 0.01, "equal sigma");
    if (HasFailure()) return;
  }
}

// The cut of two windows over their overlap, against cases whose answer is known in closed
// form: a window longer everywhere loses the overlap at its end; two windows whose distances
// cross once keep their own sides of the crossing; a tie within eps keeps both unless the two
// are one window made twice (then the new one, a, loses); an end the overlap does not reach is
// never cut.
TEST(CutOverlap, ClosedFormCases) {
  const double eps = 1e-12, tol = 1e-12;
  {
    // b: the same pseudo-source 1 closer, so a is longer by 1 everywhere.
    const EdgeDistance a{1.0, 3.0, -1.0}, b{0.0, 3.0, -1.0};
    double a0 = 0.0, a1 = 4.0, b0 = 2.0, b1 = 6.0;
    cut_overlap(a, b, 2.0, 4.0, eps, tol, &a0, &a1, &b0, &b1);
    EXPECT_EQ(a0, 0.0);
    EXPECT_EQ(a1, 2.0);  // its end in the overlap is gone
    EXPECT_EQ(b0, 2.0);  // b keeps all of it
    EXPECT_EQ(b1, 6.0);
  }
  {
    // Sources at x = 1 and x = 5, the same sigma: equal at x = 3.
    const EdgeDistance a{0.5, 1.0, -1.0}, b{0.5, 5.0, -1.0};
    double a0 = 0.0, a1 = 6.0, b0 = 0.0, b1 = 6.0;
    cut_overlap(a, b, 0.0, 6.0, eps, tol, &a0, &a1, &b0, &b1);
    EXPECT_EQ(a0, 0.0);
    EXPECT_NEAR(a1, 3.0, 1e-9);
    EXPECT_NEAR(b0, 3.0, 1e-9);
    EXPECT_EQ(b1, 6.0);
  }
  {
    // Pseudo-sources 1e-11 apart (more than tol) and sigmas equal: within eps everywhere, a tie.
    const EdgeDistance a{2.0, 3.0, -1.0}, b{2.0, 3.0 + 1e-11, -1.0};
    double a0 = 0.0, a1 = 6.0, b0 = 1.0, b1 = 5.0;
    cut_overlap(a, b, 1.0, 5.0, 1e-9, tol, &a0, &a1, &b0, &b1);
    EXPECT_EQ(a0, 0.0);
    EXPECT_EQ(a1, 6.0);
    EXPECT_EQ(b0, 1.0);
    EXPECT_EQ(b1, 5.0);
    // The same window twice: a (the new one) loses the whole overlap it ends in.
    double c0 = 2.0, c1 = 5.0, d0 = 1.0, d1 = 5.0;
    cut_overlap(a, a, 2.0, 5.0, eps, tol, &c0, &c1, &d0, &d1);
    EXPECT_LE(c1 - c0, tol);
    EXPECT_EQ(d0, 1.0);
    EXPECT_EQ(d1, 5.0);
  }
  {
    // b inside a and longer: the overlap reaches both of b's ends and neither of a's.
    const EdgeDistance a{0.0, 3.0, -1.0}, b{0.5, 3.0, -1.0};
    double a0 = 0.0, a1 = 6.0, b0 = 2.0, b1 = 4.0;
    cut_overlap(a, b, 2.0, 4.0, eps, tol, &a0, &a1, &b0, &b1);
    EXPECT_EQ(a0, 0.0);
    EXPECT_EQ(a1, 6.0);
    EXPECT_LE(b1 - b0, tol);  // cut to nothing
    // And shorter: b cuts nothing of a (a's ends lie outside the overlap), a nothing of b.
    const EdgeDistance c{-0.5, 3.0, -1.0};
    double e0 = 0.0, e1 = 6.0, f0 = 2.0, f1 = 4.0;
    cut_overlap(a, c, 2.0, 4.0, eps, tol, &e0, &e1, &f0, &f1);
    EXPECT_EQ(e0, 0.0);
    EXPECT_EQ(e1, 6.0);
    EXPECT_EQ(f0, 2.0);
    EXPECT_EQ(f1, 4.0);
  }
}

}  // namespace
}  // namespace windplan
