// Coverage on sections normal to a tube's centre line (planner/winding/tube_coverage.h) on
// synthetic bands: K helices per family on a straight tube whose traces B / cos(a) just close
// the circle (cover factor 1.02) leave nothing bare; one circuit turned by half a band opens a
// gap of (1/2 - 0.02) of a trace in its family, which the figures must show.
#include "planner/winding/tube_coverage.h"

#include <gtest/gtest.h>

#include <cmath>

namespace windplan {
namespace {

std::vector<Circuit> helices(const TubeCentreLine& line, int K, double a, double shift_one) {
  const double r = line.tube_radius(), L = line.length();
  std::vector<Circuit> cs;
  for (int k = 0; k < K; ++k) {
    Circuit c;
    c.index = k;
    const double th0 = 2 * M_PI * k / K + (k == 3 ? shift_one : 0.0);
    const double turn = L * std::tan(a) / r;
    auto add = [&](double s, double th, int dir) {
      FibrePoint q;
      q.position = line.point(s, th);
      q.normal = line.normal(s, th);
      const TubeFrame f = line.frame(s);
      const Vec3 e_th = -std::sin(th) * f.u + std::cos(th) * f.v;
      q.tangent = dir * std::cos(a) * f.t + std::sin(a) * e_th;
      c.points.push_back(q);
    };
    for (int i = 0; i <= 200; ++i) add(L * i / 200, th0 + turn * i / 200, 1);
    for (int i = 1; i <= 200; ++i) add(L - L * i / 200, th0 + turn + turn * i / 200, -1);
    cs.push_back(c);
  }
  return cs;
}

TEST(TubeCoverage, SyntheticBandsAndAHalfBandShift) {
  const TubeCentreLine line(50, {400}, {});
  const int K = 10;
  const double a = M_PI / 4, r = 50;
  const double B = 1.02 * 2 * M_PI * r * std::cos(a) / K;  // cover factor 1.02 per family
  const CoverageReport ok = measure_tube_coverage(line, helices(line, K, a, 0.0), B, 50, 350, 8);
  ASSERT_EQ(ok.stations.size(), 8u);
  EXPECT_EQ(ok.bare_fraction, 0.0);
  for (const StationCoverage& st : ok.stations) {
    EXPECT_EQ(st.bands[0], K);
    EXPECT_EQ(st.bands[1], K);
    EXPECT_NEAR(st.cover_factor, 1.02, 1e-6);
    EXPECT_NEAR(st.mean_plies, 2.04, 1e-6);
  }
  const double trace = B / std::cos(a);  // mm on the section circle
  const CoverageReport bad =
      measure_tube_coverage(line, helices(line, K, a, 0.5 * trace / r), B, 50, 350, 8);
  const double gap = (0.5 - 0.02 * 1.0 / 1.02 * 1.0) * trace;  // the neighbours overlapped by 2%
  EXPECT_NEAR(bad.bare_fraction, gap / (2 * M_PI * r), 0.002);
  EXPECT_NEAR(bad.widest_gap, gap, 0.2);
}

// The same bands through the loop-length measure of any tube surface (the overload for fitted
// mesh tubes: bins along the loop, traces B / |T . nu|): the same figures on the circle.
TEST(TubeCoverage, LoopLengthMeasureAgreesOnTheCircle) {
  const TubeCentreLine line(50, {400}, {});
  const TubeSurface& surface = line;
  const int K = 10;
  const double a = M_PI / 4, r = 50;
  const double B = 1.02 * 2 * M_PI * r * std::cos(a) / K;
  const CoverageReport ok = measure_tube_coverage(surface, helices(line, K, a, 0.0), B, 50, 350, 8);
  ASSERT_EQ(ok.stations.size(), 8u);
  EXPECT_EQ(ok.bare_fraction, 0.0);
  for (const StationCoverage& st : ok.stations) {
    EXPECT_NEAR(st.loop_length, 2 * M_PI * r, 0.01);
    EXPECT_NEAR(st.cover_factor, 1.02, 1e-3);
  }
  const double trace = B / std::cos(a);
  const CoverageReport bad =
      measure_tube_coverage(surface, helices(line, K, a, 0.5 * trace / r), B, 50, 350, 8);
  const double gap = (0.5 - 0.02 * 1.0 / 1.02 * 1.0) * trace;
  EXPECT_NEAR(bad.bare_fraction, gap / (2 * M_PI * r), 0.002);
  EXPECT_NEAR(bad.widest_gap, gap, 0.3);
}

}  // namespace
}  // namespace windplan
