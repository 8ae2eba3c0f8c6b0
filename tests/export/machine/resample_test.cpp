#include "export/machine/resample.h"

#include <cmath>

#include <gtest/gtest.h>

namespace windplan {
namespace {

TEST(Resample, StraightLineKeepsTheEnds) {
  std::vector<Vec3> p;
  for (int i = 0; i < 100; ++i) p.emplace_back(i * 0.5, 2 * i * 0.5, 0);
  const ResampleResult r = resample_by_chord({&p}, 1e-6);
  EXPECT_EQ(r.kept, (std::vector<int>{0, 99}));
  const ResampleResult f = resample_by_chord({&p}, 1e-6, {40, 7});
  EXPECT_EQ(f.kept, (std::vector<int>{0, 7, 40, 99}));
}

TEST(Resample, CircleChordsMatchTheSagittaBound) {
  // Circle of radius R sampled every d radians: a chord over m steps has sagitta
  // R (1 - cos(m d / 2)); the greedy keeps every m-th point with m the largest such that the
  // farthest dropped point (the one nearest the chord's middle) is within tolerance.
  const double R = 100, d = 0.001, tol = 0.05;
  std::vector<Vec3> p;
  for (int i = 0; i <= 3000; ++i) p.emplace_back(R * std::cos(i * d), R * std::sin(i * d), 0);
  const ResampleResult r = resample_by_chord({&p}, tol);
  auto dev = [&](int m) {  // max distance of interior points of an m-step chord
    double best = 0;
    for (int k = 1; k < m; ++k) {
      const double mid = R * std::cos(m * d / 2);
      best = std::max(best, R * std::cos((k - m / 2.0) * d) - mid);
    }
    return best;
  };
  int m = 1;
  while (dev(m + 1) <= tol) ++m;
  ASSERT_GT(r.kept.size(), 2u);
  for (std::size_t i = 1; i + 1 < r.kept.size(); ++i) EXPECT_EQ(r.kept[i] - r.kept[i - 1], m);
  EXPECT_LE(r.max_deviation, tol);
  EXPECT_NEAR(r.max_deviation, dev(m), 1e-9);
  // Every dropped point is within tolerance of its chord (independent check).
  for (std::size_t i = 1; i < r.kept.size(); ++i) {
    for (int k = r.kept[i - 1] + 1; k < r.kept[i]; ++k) {
      EXPECT_LE(distance_to_segment(p[k], p[r.kept[i - 1]], p[r.kept[i]]), tol);
    }
  }
}

TEST(Resample, SecondPolylineAlsoBoundsTheChords) {
  std::vector<Vec3> line, wave;
  for (int i = 0; i <= 200; ++i) {
    line.emplace_back(i, 0, 0);
    wave.emplace_back(i, std::sin(i * 0.05) * 10, 0);
  }
  const ResampleResult a = resample_by_chord({&line}, 0.01);
  const ResampleResult b = resample_by_chord({&line, &wave}, 0.01);
  EXPECT_EQ(a.kept.size(), 2u);
  EXPECT_GT(b.kept.size(), 10u);
}

}  // namespace
}  // namespace windplan
