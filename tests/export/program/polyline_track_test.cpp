// The replay's deviation track (export/program/polyline_track.h) against a scan of every segment
// of its window: the same distance and the same segment (the first on a tie), bit for bit, on
// helices walked point by point as the replay walks them, on a polyline that doubles back on
// itself, with repeated points and exact ties, and from points far off the polyline.
#include "export/program/polyline_track.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "export/machine/resample.h"

namespace windplan {
namespace {

// The window of track_polyline, every segment in it tried.
double scan(const std::vector<Vec3>& q, const std::vector<double>& sq, const Vec3& p, double back,
            double ahead, int first, int limit, int* ptr) {
  limit = std::min(limit, static_cast<int>(q.size()) - 1);
  if (limit <= first) {
    *ptr = first;
    return (p - q[first]).norm();
  }
  int lo = std::clamp(*ptr, first, limit - 1), hi = lo;
  while (lo > first && sq[*ptr] - sq[lo] < back) --lo;
  while (hi < limit - 1 && sq[hi] - sq[*ptr] < ahead) ++hi;
  double best = std::numeric_limits<double>::infinity();
  int at = *ptr;
  for (int j = lo; j <= hi; ++j) {
    const double d = distance_to_segment(p, q[j], q[j + 1]);
    if (d < best) {
      best = d;
      at = j;
    }
  }
  *ptr = at;
  return best;
}

std::vector<double> arc_lengths(const std::vector<Vec3>& q) {
  std::vector<double> sq(q.size(), 0.0);
  for (std::size_t i = 1; i < q.size(); ++i) sq[i] = sq[i - 1] + (q[i] - q[i - 1]).norm();
  return sq;
}

void expect_same(const std::vector<Vec3>& q, const std::vector<Vec3>& points, int first, int limit,
                 unsigned seed) {
  const std::vector<double> sq = arc_lengths(q);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> jump(first, std::max(first, limit - 1));
  int a = first, b = first;
  for (std::size_t i = 0; i < points.size(); ++i) {
    // Now and then the last match is anywhere (a tie-on, a lost track).
    if (i % 97 == 0) a = b = jump(rng);
    const double da = track_polyline(q, sq, points[i], 10.0, 40.0, first, limit, &a);
    const double db = scan(q, sq, points[i], 10.0, 40.0, first, limit, &b);
    ASSERT_EQ(da, db) << "point " << i;
    ASSERT_EQ(a, b) << "point " << i;
  }
}

// A helix of radius 50 and pitch 30 mm, a point every 0.4 mm.
std::vector<Vec3> helix(int n) {
  std::vector<Vec3> q;
  for (int i = 0; i < n; ++i) {
    const double t = 0.4 * i / 50.0;
    q.emplace_back(50.0 * std::cos(t), 50.0 * std::sin(t), 30.0 * t / (2.0 * M_PI));
  }
  return q;
}

TEST(PolylineTrack, WalkingAlongAHelixFindsWhatEveryWindowSegmentTriedFinds) {
  const std::vector<Vec3> q = helix(4000);
  std::mt19937 rng(3);
  std::normal_distribution<double> off(0.0, 0.3);
  std::vector<Vec3> walk;
  for (int i = 0; i < 3990; ++i) {
    walk.push_back(0.5 * (q[i] + q[i + 1]) + Vec3(off(rng), off(rng), off(rng)));
  }
  expect_same(q, walk, 0, static_cast<int>(q.size()) - 1, 1);
  // Only a stretch (a layer), and points far off (an eye 40 mm out).
  std::vector<Vec3> far;
  for (const Vec3& p : walk) far.push_back(1.8 * p);
  expect_same(q, far, 500, 2500, 2);
}

TEST(PolylineTrack, DoublingBackRepeatedPointsAndTiesGoToTheFirstSegment) {
  // Out along x and back along the same line, 0.5 mm apart, with repeated points: every point
  // off the line is equally near an outgoing and a returning segment.
  std::vector<Vec3> q;
  for (int i = 0; i <= 100; ++i) q.emplace_back(0.5 * i, 0.0, 0.0);
  q.emplace_back(50.0, 0.0, 0.0);
  for (int i = 100; i >= 0; --i) q.emplace_back(0.5 * i, 0.0, 0.0);
  std::vector<Vec3> points;
  for (int i = 0; i < 400; ++i) points.emplace_back(0.13 * i, 1.0, (i % 3) - 1.0);
  expect_same(q, points, 0, static_cast<int>(q.size()) - 1, 4);
  const std::vector<double> sq = arc_lengths(q);
  int at = 150;
  track_polyline(q, sq, Vec3(49.9, 1.0, 0.0), 100.0, 100.0, 0, static_cast<int>(q.size()) - 1,
                 &at);
  EXPECT_EQ(at, 99);  // the outgoing segment [49.5, 50], not the returning one
}

TEST(PolylineTrack, APolylineOfOnePointGivesTheDistanceToIt) {
  const std::vector<Vec3> q = {Vec3(1, 2, 3), Vec3(4, 5, 6)};
  const std::vector<double> sq = arc_lengths(q);
  int at = 0;
  EXPECT_DOUBLE_EQ(track_polyline(q, sq, Vec3(1, 2, 7), 10, 40, 0, 0, &at), 4.0);
  EXPECT_EQ(at, 0);
}

}  // namespace
}  // namespace windplan
