// Coverage measured on the laid bands (planner/winding/coverage.h): synthetic bands with a known
// gap and a known overlap, and a planner bug (one circuit turned by half a band) caught by the
// measure; the same on tubes that are not shapes of revolution (sections normal to the centre
// line: an oval tube and a torus bend).
#include "planner/winding/coverage.h"

#include <gtest/gtest.h>

#include <cmath>

#include "planner/winding/revolution_winding.h"
#include "tests/geometry/region/tube_fixtures.h"
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

// ---- Sections normal to a tube's centre line ----

Spine exact_spine(const test::BentTube& tube) {
  std::vector<Vec3> pts;
  for (int k = 0; k <= 2000; ++k) pts.push_back(tube.centre(tube.length() * k / 2000));
  return spine_from_polyline(pts);
}

// An axial band centre line along vertex i of every ring of the tube's mesh, out and back.
Circuit ring_vertex_circuit(const test::BentTube& tube, const Mesh& m, int index, int i) {
  Circuit c;
  c.index = index;
  const int rings = static_cast<int>(tube.stations().size());
  for (int dir = 0; dir < 2; ++dir) {
    const int first = static_cast<int>(c.points.size());
    for (int j = 0; j < rings; ++j) {
      FibrePoint p;
      p.position = m.position((dir == 0 ? j : rings - 1 - j) * tube.around + i);
      c.points.push_back(p);
    }
    c.segments.push_back(
        {CircuitSegment::Kind::Pass, first, static_cast<int>(c.points.size()) - 1});
  }
  return c;
}

// The bare length of bands of width B centred at arc lengths u on a loop of length L, swept at
// 200000 points (independent of the measure's interval sweep).
double bare_by_sampling(const std::vector<double>& u, double B, double L) {
  const int n = 200000;
  int bare = 0;
  for (int k = 0; k < n; ++k) {
    const double x = L * (k + 0.5) / n;
    bool covered = false;
    for (double c : u) {
      double d = std::fmod(std::fabs(x - c), L);
      covered |= std::min(d, L - d) <= 0.5 * B;
    }
    bare += !covered;
  }
  return L * bare / n;
}

TEST(TubeCoverage, OvalSectionBandsMeasuredAlongTheLoop) {
  test::BentTube tube;
  tube.a = 35;  // in the bend plane
  tube.b = 20;
  tube.bend = 120;
  const Mesh m = tube.mesh();
  const Spine sp = exact_spine(tube);
  // 8 bands at equal steps of the ellipse's parameter: unequal steps of arc length (wider on the
  // flat sides), so the gaps differ around the loop.
  std::vector<Circuit> cs;
  std::vector<int> at;
  for (int q = 0; q < 8; ++q) at.push_back(q * tube.around / 8);
  for (int q = 0; q < 8; ++q) cs.push_back(ring_vertex_circuit(tube, m, q, at[q]));
  // The 96-gon of the ellipse: its length and the vertices' arc lengths.
  std::vector<double> cum{0.0};
  for (int i = 0; i < tube.around; ++i) {
    const double t0 = 2 * M_PI * i / tube.around, t1 = 2 * M_PI * (i + 1) / tube.around;
    cum.push_back(cum.back() + std::hypot(tube.a * (std::cos(t1) - std::cos(t0)),
                                          tube.b * (std::sin(t1) - std::sin(t0))));
  }
  const double L = cum.back();
  const double B = 14.0;
  std::vector<double> u;
  for (int i : at) u.push_back(cum[i]);
  const double bare = bare_by_sampling(u, B, L);
  ASSERT_GT(bare, 0.1 * L);  // (the fixture leaves gaps)
  CoverageOptions o;
  o.band_width = B;
  o.spine = &sp;
  const CoverageReport r = measure_coverage(m, SpindleAxis{}, cs, o);
  ASSERT_TRUE(r.centre_line);
  ASSERT_EQ(r.stations.size(), 12u);
  for (const StationCoverage& st : r.stations) {
    // On the legs the normal section is the 96-gon itself; on the bend within the chords' sag.
    const bool leg = st.station < tube.leg || st.station > tube.leg + tube.bend * tube.angle;
    const double tol = leg ? 1e-6 : 2e-3;
    EXPECT_NEAR(st.loop_length, L, tol * L) << st.station;
    EXPECT_NEAR(st.bare_fraction, bare / L, tol + 2e-4) << st.station;
    EXPECT_EQ(st.bands[0], 8);
    EXPECT_EQ(st.bands[1], 8);
  }
  // The widest gap is on the flat side (parameter step pi/4 at the b = 20 ends of the ellipse
  // gives the longest arc).
  double widest = 0;
  for (int q = 0; q < 8; ++q) {
    const double next = q == 7 ? L : u[q + 1];
    widest = std::max(widest, next - u[q] - B);
  }
  EXPECT_NEAR(r.widest_gap, widest, 0.05);
}

TEST(TubeCoverage, TorusBendWithAKnownGap) {
  test::BentTube tube;  // r 25, bend 100: a quarter torus between two legs
  const Mesh m = tube.mesh();
  const Spine sp = exact_spine(tube);
  const double L = tube.around * 2 * tube.a * std::sin(M_PI / tube.around);
  std::vector<Circuit> cs;
  for (int q = 0; q < 8; ++q) cs.push_back(ring_vertex_circuit(tube, m, q, q * tube.around / 8));
  CoverageOptions o;
  o.band_width = L / 8 - 3.0;  // a 3 mm gap between neighbours
  o.spine = &sp;
  const CoverageReport r = measure_coverage(m, SpindleAxis{}, cs, o);
  EXPECT_NEAR(r.widest_gap, 3.0, 0.01);
  EXPECT_NEAR(r.bare_fraction, 24.0 / L, 1e-4);
  int on_bend = 0;
  for (const StationCoverage& st : r.stations) {
    EXPECT_NEAR(st.loop_length, L, 1e-3 * L) << st.station;  // normal sections: not oblique
    on_bend += st.station > tube.leg && st.station < tube.leg + tube.bend * tube.angle;
  }
  EXPECT_GE(on_bend, 4);
  // The same bands measured on planes normal to one global axis (z) cut the bend obliquely.
  o.spine = nullptr;
  const CoverageReport z = measure_coverage(m, SpindleAxis{}, cs, o);
  double longest = 0;
  for (const StationCoverage& st : z.stations) longest = std::max(longest, st.loop_length);
  EXPECT_GT(longest, 1.1 * L);
}

// Helical bands on the torus bend: K per family, equally spaced around the section.
std::vector<Circuit> torus_helices(const test::BentTube& tube, int K, double turns) {
  const double w = 2 * M_PI * turns / tube.length();
  std::vector<Circuit> cs;
  for (int k = 0; k < K; ++k) {
    Circuit c;
    c.index = k;
    for (int dir = 0; dir < 2; ++dir) {
      const int first = static_cast<int>(c.points.size());
      for (int j = 0; j <= 1000; ++j) {
        const double s = tube.length() * (dir == 0 ? j : 1000 - j) / 1000;
        FibrePoint p;
        p.position = tube.at(s, 2 * M_PI * k / K + (dir == 0 ? w : -w) * s);
        c.points.push_back(p);
      }
      c.segments.push_back(
          {CircuitSegment::Kind::Pass, first, static_cast<int>(c.points.size()) - 1});
    }
    cs.push_back(std::move(c));
  }
  return cs;
}

TEST(TubeCoverage, CatchesAHelixTurnedByHalfABandOnATorus) {
  test::BentTube tube;
  tube.around = 192;
  const Mesh m = tube.mesh();
  const Spine sp = exact_spine(tube);
  const int K = 10;
  const double turns = 3;
  // The band spacing across the fibre, from the parametrisation: along the tube the section
  // point at angle t moves (1 + (r / R) cos t) per mm of centre line on the bend (1 on the legs),
  // around it w r; the fibre's angle to the section loop has sin = along / |(along, w r)|, and
  // neighbouring bands (2 pi r / K apart along the loop) are that times apart across the band.
  const double w = 2 * M_PI * turns / tube.length(), r = tube.a;
  double widest = 0;
  for (int i = 0; i < 360; ++i) {
    const double t = 2 * M_PI * i / 360, along = 1 + r / tube.bend * std::cos(t);
    widest = std::max(widest, along / std::hypot(along, w * r));
  }
  const double B = 1.1 * (2 * M_PI * r / K) * widest;  // 10% spare where bands are farthest apart
  CoverageOptions o;
  o.band_width = B;
  o.spine = &sp;
  std::vector<Circuit> cs = torus_helices(tube, K, turns);
  const CoverageReport good = measure_coverage(m, SpindleAxis{}, cs, o);
  EXPECT_EQ(good.bare_fraction, 0.0) << good.brief_report();
  EXPECT_EQ(good.max_stack, 2) << good.brief_report();
  // The planner bug: circuit 3 turned about the centre line by half a band spacing.
  const double turn = M_PI / K;
  for (FibrePoint& p : cs[3].points) {
    const double s = sp.project(p.position);
    const Vec3 c = tube.centre(s), n = tube.normal(s), y(0, 1, 0);
    const Vec3 d = p.position - c;
    const double t = std::atan2(d.dot(y) / tube.b, d.dot(n) / tube.a) + turn;
    p.position = tube.at(s, t);
  }
  const CoverageReport bad = measure_coverage(m, SpindleAxis{}, cs, o);
  EXPECT_GT(bad.bare_fraction, 0.01) << bad.brief_report();
  EXPECT_GT(bad.widest_gap, 2.0) << bad.brief_report();
}

}  // namespace
}  // namespace windplan
