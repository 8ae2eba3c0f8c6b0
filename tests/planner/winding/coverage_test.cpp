// Coverage measured on the laid bands (planner/winding/coverage.h): synthetic bands with a known
// gap and a known overlap, and a planner bug (one circuit turned by half a band) caught by the
// measure.
#include "planner/winding/coverage.h"

#include <gtest/gtest.h>

#include <cmath>

#include "planner/winding/revolution_winding.h"
#include "tests/planner/winding_fixtures.h"

namespace windplan {
namespace {

constexpr int kN = 256;
constexpr double kR = 50, kL = 200;

const Mesh& tube() {
  static const Mesh m = test::revolve({{0, kR}, {50, kR}, {100, kR}, {150, kR}, {200, kR}}, kN);
  return m;
}

// An axial band centre line at the angle of ring vertex i, out (up) and back (down).
Circuit axial_circuit(int index, int i) {
  Circuit c;
  c.index = index;
  const double t = 2 * M_PI * i / kN;
  for (int dir = 0; dir < 2; ++dir) {
    const int first = static_cast<int>(c.points.size());
    for (int j = 0; j <= 20; ++j) {
      const double z = dir == 0 ? kL * j / 20 : kL * (20 - j) / 20;
      FibrePoint p;
      p.position = Vec3(kR * std::cos(t), kR * std::sin(t), z);
      c.points.push_back(p);
    }
    c.segments.push_back(
        {CircuitSegment::Kind::Pass, first, static_cast<int>(c.points.size()) - 1});
  }
  return c;
}

TEST(Coverage, KnownGapsAndOverlap) {
  // The section loop is the 256-gon; its length L and the band positions along it are exact.
  const double L = kN * 2 * kR * std::sin(M_PI / kN);
  const double B = 60;
  std::vector<Circuit> cs;
  for (int q = 0; q < 4; ++q) cs.push_back(axial_circuit(q, q * kN / 4));
  CoverageOptions o;
  o.band_width = B;
  o.stations = 8;
  CoverageReport r = measure_coverage(tube(), SpindleAxis{}, cs, o);
  ASSERT_EQ(r.stations.size(), 8u);
  const double gap = L / 4 - B;
  EXPECT_NEAR(r.bare_fraction, 4 * gap / L, 1e-9);
  EXPECT_NEAR(r.widest_gap, gap, 1e-9);
  EXPECT_NEAR(r.widest_overlap, 0.0, 1e-12);
  EXPECT_EQ(r.max_stack, 1);
  EXPECT_NEAR(r.cover_factor, 4 * B / L, 1e-9);
  EXPECT_NEAR(r.mean_plies, 8 * B / L, 1e-9);
  // One more band 16 vertices on: it overlaps the first by B - 16 L / 256, fills part of a gap.
  cs.push_back(axial_circuit(4, 16));
  r = measure_coverage(tube(), SpindleAxis{}, cs, o);
  EXPECT_NEAR(r.widest_overlap, B - 16 * L / kN, 1e-9);
  EXPECT_EQ(r.max_stack, 2);
  // It reaches past the gap that followed the first band (L / 16 + B / 2 > L / 4 - B / 2), so
  // three gaps are left.
  ASSERT_GT(L / 16 + B / 2, L / 4 - B / 2);
  EXPECT_NEAR(r.bare_fraction, 3 * gap / L, 1e-9);
  EXPECT_NEAR(r.widest_gap, gap, 1e-9);
}

// Off shapes of revolution the stations are level sets of a height field; on the tube with
// h = z / L they are the same loops as the planes normal to the axis, and so are the figures.
TEST(Coverage, LevelSetsOfAHeightFieldAreStationsToo) {
  std::vector<Circuit> cs;
  for (int q = 0; q < 4; ++q) cs.push_back(axial_circuit(q, q * kN / 4));
  cs.push_back(axial_circuit(4, 16));
  std::vector<double> h;
  for (int v = 0; v < tube().num_vertices(); ++v) h.push_back(tube().position(v).z() / kL);
  CoverageOptions o;
  o.band_width = 60;
  o.stations = 8;
  const CoverageReport planes = measure_coverage(tube(), SpindleAxis{}, cs, o);
  o.height = &h;
  const CoverageReport levels = measure_coverage(tube(), SpindleAxis{}, cs, o);
  ASSERT_EQ(levels.stations.size(), 8u);
  EXPECT_NEAR(levels.bare_fraction, planes.bare_fraction, 1e-9);
  EXPECT_NEAR(levels.widest_gap, planes.widest_gap, 1e-9);
  EXPECT_NEAR(levels.widest_overlap, planes.widest_overlap, 1e-9);
  EXPECT_EQ(levels.max_stack, planes.max_stack);
  EXPECT_NEAR(levels.stations[0].loop_length, planes.stations[0].loop_length, 1e-9);
}

TEST(Coverage, FullCoverAndAMissingFamily) {
  const double L = kN * 2 * kR * std::sin(M_PI / kN);
  std::vector<Circuit> cs;
  for (int q = 0; q < 8; ++q) cs.push_back(axial_circuit(q, q * kN / 8));
  CoverageOptions o;
  o.band_width = L / 8 + 1.0;  // 1 mm overlap between neighbours
  CoverageReport r = measure_coverage(tube(), SpindleAxis{}, cs, o);
  EXPECT_EQ(r.bare_fraction, 0.0);
  EXPECT_EQ(r.widest_gap, 0.0);
  EXPECT_NEAR(r.widest_overlap, 1.0, 1e-9);
  // Drop the return passes: that family is bare everywhere.
  for (Circuit& c : cs) c.segments.pop_back();
  r = measure_coverage(tube(), SpindleAxis{}, cs, o);
  EXPECT_EQ(r.bare_fraction, 1.0);
}

TEST(Coverage, CatchesACircuitTurnedByHalfABand) {
  const double R = 100, Lc = 300;
  const Mesh mesh = test::revolve(test::capsule_meridian(R, Lc, 30, 120, 30), 128);
  WindingOptions w;
  w.band_width = 16;
  RevolutionWinding rw = plan_revolution_winding(mesh, {}, SpindleAxis{}, w);
  CoverageOptions o;
  o.band_width = 16;
  const CoverageReport good = measure_coverage(mesh, SpindleAxis{}, rw.circuits, o);
  EXPECT_EQ(good.bare_fraction, 0.0);
  for (const StationCoverage& st : good.stations) {
    if (st.station > 0 && st.station < Lc) {
      EXPECT_LE(st.widest_overlap, 1.0) << st.station;
    }
  }
  // The planner bug: circuit 3 laid half a band (8 mm on the cylinder) off.
  const double turn = 8.0 / (R * std::cos(std::asin(rw.pattern.c / R)));
  for (FibrePoint& p : rw.circuits[3].points) {
    const Vec3 q = p.position;
    p.position = Vec3(q.x() * std::cos(turn) - q.y() * std::sin(turn),
                      q.x() * std::sin(turn) + q.y() * std::cos(turn), q.z());
  }
  const CoverageReport bad = measure_coverage(mesh, SpindleAxis{}, rw.circuits, o);
  EXPECT_GT(bad.bare_fraction, 0.005);
  EXPECT_GT(bad.widest_gap, 5.0);
}

}  // namespace
}  // namespace windplan
