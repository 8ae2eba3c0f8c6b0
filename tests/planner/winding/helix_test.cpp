// planner/winding/helix.cpp: level-set helices, their refinement and the continuous circuits.
#include "planner/winding/helix.h"

#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "tests/mesh_fixtures.h"
#include "tests/planner/revolution_fixtures.h"

namespace windplan {
namespace {

using test::loops_by_z;
using test::polyline_length;

SurfacePoint start_point(const Mesh& m, const HarmonicCoordinates& hc,
                         const std::array<std::vector<int>, 2>& loops, double theta) {
  return loop_point_at_theta(m, hc, loops[0], theta);
}

// The N-turn helix on a cylinder: after refinement it is the straight line of the unrolled
// prism, length sqrt(L^2 + (N P)^2) with P the prism's perimeter, and it tends to the smooth
// sqrt(L^2 + (2 pi R N)^2) as the tessellation refines. N need not be whole: half a turn is
// sqrt(L^2 + (pi R)^2).
TEST(Helix, CylinderHelixHasTheClosedFormLength) {
  const double R = 50.0, L = 200.0;
  const int n = 96;
  const Mesh m(test::open_cylinder(R, L, n, 30));
  const auto loops = loops_by_z(m);
  const HarmonicCoordinates hc = compute_harmonic_coordinates(m, loops);
  for (double N : {1.0, 3.0, 0.5, 0.55}) {
    const SurfacePath init = trace_helix(m, hc, start_point(m, hc, loops, 0.3), N, +1);
    std::string why;
    ASSERT_TRUE(is_valid_path(m, init, &why)) << why;
    const GeodesicResult r = refine_path(m, init);
    ASSERT_TRUE(r.summary.converged()) << r.summary.brief_report();
    const double P = n * 2.0 * R * std::sin(M_PI / n);
    const double prism = std::sqrt(L * L + (N * P) * (N * P));
    const double smooth = std::sqrt(L * L + std::pow(2.0 * M_PI * R * N, 2));
    EXPECT_NEAR(r.summary.euclidean_length, prism, 1e-6 * prism) << "N = " << N;
    EXPECT_NEAR(r.summary.euclidean_length, smooth, 1e-3 * smooth) << "N = " << N;
    // The level set itself is already that line (conformal coordinates of a cylinder).
    EXPECT_NEAR(euclidean_length(m, init), prism, 1e-6 * prism);
    // Constant winding angle: tan a = 2 pi R N / L, up to the facets.
    const std::vector<Vec3> pl = polyline(m, r.path);
    const double a_exact = std::atan2(N * P, L) * 180.0 / M_PI;
    for (std::size_t i = 0; i + 1 < pl.size(); ++i) {
      if ((pl[i + 1] - pl[i]).norm() < 1e-6) continue;
      ASSERT_NEAR(test::segment_angle(pl[i], pl[i + 1], 0.0), a_exact, 0.5 + 180.0 / n)
          << "segment " << i;
    }
    // The pass turns by 2 pi N about the axis: theta runs clockwise seen from +z (n x grad h,
    // harmonic_test.cpp), so the end's polar angle is the start's - 2 pi N modulo 2 pi, up to the
    // chords' bulge (the polar angle is not linear along an edge: < 1e-4 rad for 96 sides).
    const Vec3 a = pl.front(), b = pl.back();
    EXPECT_NEAR(a.z(), 0.0, 1e-9);
    EXPECT_NEAR(b.z(), L, 1e-9);
    const double turned = std::atan2(a.y(), a.x()) - std::atan2(b.y(), b.x());
    EXPECT_NEAR(std::remainder(turned - 2.0 * M_PI * N, 2.0 * M_PI), 0.0, 1e-4) << "N = " << N;
  }
}

// rho = 1 / (2 pi r) on a cone: the density geodesics are loxodromes (constant winding angle),
// while plain geodesics (Clairaut: r sin a = const) are not.
TEST(Helix, ConeUnderInverseGirthDensityIsALoxodrome) {
  const double r0 = 60.0, slope = -0.2, len = 150.0;
  auto r = [&](double z) { return r0 + slope * z; };
  const Mesh m(test::revolution(r, 0.0, len, 128, 60));
  const auto loops = loops_by_z(m);
  const HarmonicCoordinates hc = compute_harmonic_coordinates(m, loops);
  std::vector<double> rho(m.num_faces());
  for (int f = 0; f < m.num_faces(); ++f) {
    rho[f] = 1.0 / (2.0 * M_PI * r(m.face_centroid(f).z()));
  }
  const SurfacePath init = trace_helix(m, hc, start_point(m, hc, loops, 0.1), 2, +1);
  // (funnel_start off: the planner's workaround for the core under density metrics.)
  GeodesicOptions go;
  go.funnel_start = false;
  const GeodesicResult lox = refine_path(m, init, PathMetric::density(m, rho), go);
  const GeodesicResult geo = refine_path(m, init);
  ASSERT_TRUE(lox.summary.converged()) << lox.summary.brief_report();
  ASSERT_TRUE(geo.summary.converged()) << geo.summary.brief_report();
  auto angle_range = [&](const SurfacePath& p) {
    const std::vector<Vec3> pl = polyline(m, p);
    double lo = 90.0, hi = 0.0;
    // Average over ~10 mm windows to filter the facets.
    std::size_t i = 0;
    while (i + 1 < pl.size()) {
      std::size_t j = i + 1;
      while (j + 1 < pl.size() && (pl[j] - pl[i]).norm() < 10.0) ++j;
      const double a = test::segment_angle(pl[i], pl[j], slope);
      lo = std::min(lo, a);
      hi = std::max(hi, a);
      i = j;
    }
    return hi - lo;
  };
  EXPECT_LT(angle_range(lox.path), 1.5) << "loxodrome angle spread (deg)";
  EXPECT_GT(angle_range(geo.path), 5.0) << "a plain geodesic on a cone changes its angle";
}

// beta = 0 on a vessel-like bulge: Clairaut's relation r sin a = const along the refined path.
TEST(Helix, PlainGeodesicObeysClairaut) {
  auto r = [](double z) { return 40.0 + 25.0 * std::sin(M_PI * z / 200.0); };
  auto drdz = [](double z) { return 25.0 * M_PI / 200.0 * std::cos(M_PI * z / 200.0); };
  const Mesh m(test::revolution(r, 0.0, 200.0, 160, 100));
  const auto loops = loops_by_z(m);
  const HarmonicCoordinates hc = compute_harmonic_coordinates(m, loops);
  const SurfacePath init = trace_helix(m, hc, start_point(m, hc, loops, 0.0), 1, +1);
  const GeodesicResult g = refine_path(m, init);
  ASSERT_TRUE(g.summary.converged()) << g.summary.brief_report();
  const std::vector<Vec3> pl = polyline(m, g.path);
  std::vector<double> c;
  std::size_t i = 0;
  while (i + 1 < pl.size()) {
    std::size_t j = i + 1;
    while (j + 1 < pl.size() && (pl[j] - pl[i]).norm() < 8.0) ++j;
    const Vec3 mid = 0.5 * (pl[i] + pl[j]);
    const double a = test::segment_angle(pl[i], pl[j], drdz(mid.z())) * M_PI / 180.0;
    c.push_back(std::hypot(mid.x(), mid.y()) * std::sin(a));
    i = j;
  }
  ASSERT_GT(c.size(), 10u);
  const double c0 = c[c.size() / 2];
  for (double x : c) EXPECT_NEAR(x, c0, 0.02 * c0);
}

void expect_closed_pattern_on_cylinder(double turns, double dwell) {
  const Mesh m(test::open_cylinder(40.0, 150.0, 64, 20));
  const auto loops = loops_by_z(m);
  WindingOptions o;
  o.turns = turns;
  o.circuits = 5;
  const HelixPlan plan = plan_helices(m, loops, {}, SpindleAxis{}, o);
  ASSERT_EQ(plan.summary.circuits, 5);
  ASSERT_EQ(plan.passes.size(), 10u);
  ASSERT_EQ(plan.turnarounds.size(), 10u);
  for (int k = 0; k < 5; ++k) {
    const HelixPass& out = plan.passes[2 * k];
    const HelixPass& back = plan.passes[2 * k + 1];
    const Turnaround& top = plan.turnarounds[2 * k];
    const Turnaround& bottom = plan.turnarounds[2 * k + 1];
    EXPECT_EQ(out.hand, 1);
    EXPECT_EQ(back.hand, -1);
    // Each piece starts where the previous one ends.
    EXPECT_LT((top.arc.points.front() - position(m, out.path.end)).norm(), 1e-9);
    EXPECT_LT((position(m, back.path.start) - top.arc.points.back()).norm(), 1e-9);
    EXPECT_LT((bottom.arc.points.front() - position(m, back.path.end)).norm(), 1e-9);
    const HelixPass& next = plan.passes[(2 * k + 2) % 10];
    EXPECT_NEAR((position(m, next.path.start) - bottom.arc.points.back()).norm(), 0.0,
                k == 4 ? 1e-3 : 1e-9);
    // Ends on the right loops.
    EXPECT_NEAR(position(m, out.path.start).z(), 0.0, 1e-9);
    EXPECT_NEAR(position(m, out.path.end).z(), 150.0, 1e-9);
    // The dwell of the loop (R = 40): arc length ~ R dwell.
    EXPECT_NEAR(top.dwell, dwell, 1e-12);
    EXPECT_NEAR(bottom.dwell, dwell, 1e-12);
    EXPECT_NEAR(top.arc.length, 40.0 * dwell, 0.02 * 40.0 * M_PI);
    EXPECT_NEAR(bottom.arc.length, 40.0 * dwell, 0.02 * 40.0 * M_PI);
    // Each pass turns by 2 pi N about the axis (clockwise seen from +z, as theta).
    for (const HelixPass* p : {&out, &back}) {
      const Vec3 a = position(m, p->path.start), b = position(m, p->path.end);
      const double turned = std::atan2(a.y(), a.x()) - std::atan2(b.y(), b.x());
      EXPECT_NEAR(std::remainder(turned - 2.0 * M_PI * turns, 2.0 * M_PI), 0.0, 1e-3);
    }
  }
  // Circuit starts advance by 1/K turn (clockwise seen from +z).
  for (int k = 0; k + 1 < 5; ++k) {
    const Vec3 a = position(m, plan.passes[2 * k].path.start);
    const Vec3 b = position(m, plan.passes[2 * k + 2].path.start);
    const double d = std::atan2(a.y(), a.x()) - std::atan2(b.y(), b.x());
    EXPECT_NEAR(std::remainder(d - 2.0 * M_PI / 5, 2.0 * M_PI), 0.0, 1e-3);
  }
}

// K = 5 circuits on a cylinder close into one fibre: each piece starts where the previous one
// ends, the last turnaround ends where circuit 0 starts, and circuit k starts 2 pi k / K after
// circuit 0. With N = 0.55 each pass advances 1.1 pi, so both dwells are pi + pi / K - 0.1 pi
// (the circuit then advances 2.2 pi + 2 pi - 0.2 pi + 2 pi / K, i.e. 2 pi / K modulo 2 pi).
TEST(Helix, CircuitsAreContinuousAndClosePattern) {
  for (double N : {2.0, 0.55}) {
    SCOPED_TRACE("N = " + format_turns(N));
    const double dwell = N == 2.0 ? M_PI + M_PI / 5 : M_PI + M_PI / 5 - 0.1 * M_PI;
    expect_closed_pattern_on_cylinder(N, dwell);
  }
}

TEST(Helix, TurnaroundDwellClosesThePatternForAnyN) {
  // Whole and half turns: exactly the dwell of whole turns, pi + pi p / K.
  for (double N : {1.0, 2.0, 5.0, 0.5, 1.5}) {
    EXPECT_EQ(turnaround_dwell(N, 5, 1), M_PI + M_PI / 5) << N;
  }
  EXPECT_NEAR(turnaround_dwell(0.55, 5, 1), M_PI + M_PI / 5 - 0.1 * M_PI, 1e-12);
  EXPECT_NEAR(turnaround_dwell(0.25, 7, 1), M_PI / 2 + M_PI / 7, 1e-12);
  EXPECT_NEAR(turnaround_dwell(0.8, 7, 1), 1.4 * M_PI + M_PI / 7, 1e-12);
  EXPECT_NEAR(turnaround_dwell(2.3, 12, 5), 1.4 * M_PI + 5 * M_PI / 12, 1e-12);
  // A circuit (two passes of 2 pi N, two dwells) advances 2 pi p / K modulo 2 pi; the dwell stays
  // within a quarter turn of half a turn (plus pi p / K).
  for (int K : {1, 5, 38}) {
    for (int i = 1; i <= 400; ++i) {
      const double N = 0.0137 * i;
      const double d = turnaround_dwell(N, K, 1);
      const double circuit = 4.0 * M_PI * N + 2.0 * d;
      EXPECT_NEAR(std::remainder(circuit - 2.0 * M_PI / K, 2.0 * M_PI), 0.0, 1e-9)
          << "N = " << N << ", K = " << K;
      EXPECT_GE(d - M_PI / K, 0.5 * M_PI - 1e-12) << N;
      EXPECT_LE(d - M_PI / K, 1.5 * M_PI + 1e-12) << N;
    }
  }
}

TEST(Helix, AutoCircuitsFromTheBandWidth) {
  const double R = 40.0, L = 150.0;
  const Mesh m(test::open_cylinder(R, L, 64, 20));
  WindingOptions o;
  o.turns = 1;
  o.circuits = 0;
  o.band_width = 12.0;
  const HelixPlan plan = plan_helices(m, loops_by_z(m), {}, SpindleAxis{}, o);
  const double a = std::atan2(2.0 * M_PI * R, L);
  EXPECT_TRUE(plan.summary.circuits_auto);
  EXPECT_NEAR(plan.summary.auto_angle_deg, a * 180.0 / M_PI, 0.5);
  EXPECT_EQ(plan.summary.circuits,
            static_cast<int>(std::ceil(2.0 * M_PI * R * std::cos(a) / 12.0)));
}

TEST(Helix, BadOptionsAreRejected) {
  const Mesh m(test::open_cylinder(40.0, 150.0, 32, 10));
  const auto loops = loops_by_z(m);
  auto expect_config = [&](WindingOptions o, const std::string& word) {
    try {
      plan_helices(m, loops, {}, SpindleAxis{}, o);
      FAIL() << "accepted: " << word;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  WindingOptions o;
  for (double bad : {0.0, -1.0, -0.5, std::nan(""), HUGE_VAL}) {
    o.turns = bad;
    expect_config(o, "turns must be > 0");
  }
  o = {};
  o.circuits = -1;
  expect_config(o, "circuits");
  o = {};
  o.beta = 1.5;
  expect_config(o, "beta");
  o = {};
  o.beta = -0.1;
  expect_config(o, "beta");
  o = {};
  o.band_width = 0.0;
  expect_config(o, "band_width");
  // A disk is not an annulus.
  const Mesh disk(test::grid(3, 3));
  EXPECT_THROW(plan_helices(disk, loops, {}, SpindleAxis{}, WindingOptions{}), TopologyError);
  // A start that is not on the boundary.
  const HarmonicCoordinates hc = compute_harmonic_coordinates(m, loops);
  EXPECT_THROW(trace_helix(m, hc, SurfacePoint::at_vertex(0), 1, 1), InputError);
  const SurfacePoint on_loop = start_point(m, hc, loops, 0.3);
  for (double bad : {0.0, -1.0, std::nan("")}) {
    EXPECT_THROW(trace_helix(m, hc, on_loop, bad, 1), InputError) << bad;
  }
}

// Axial stations on a cylinder: every pass runs from one station plane to the other with N turns
// between them, so after refinement it is the straight line of the unrolled prism between the
// stations, sqrt(L'^2 + (N P)^2) (L' the station distance), and tends to the smooth
// sqrt(L'^2 + (2 pi R N)^2); the turnarounds are dwell arcs on the station circles. Fractional N
// too: half a turn keeps the dwell pi + pi / K, N = 0.55 takes 0.1 pi off it.
TEST(HelixStations, PassesRunBetweenTheStationPlanes) {
  const double R = 50.0, L = 200.0;
  const int n = 96;
  const Mesh m(test::open_cylinder(R, L, n, 30));
  const auto loops = loops_by_z(m);
  const double z0 = 0.25 * L, z1 = 0.75 * L, Lp = z1 - z0;
  const double P = n * 2.0 * R * std::sin(M_PI / n);
  for (double N : {1.0, 2.0, 0.5, 0.55}) {
    WindingOptions o;
    o.turns = N;
    o.circuits = 3;
    o.start_station = z0;
    o.end_station = z1;
    const HelixPlan plan = plan_helices(m, loops, {}, SpindleAxis{}, o);
    ASSERT_EQ(plan.passes.size(), 6u);
    ASSERT_EQ(plan.turnarounds.size(), 6u);
    EXPECT_NEAR(plan.summary.heights[0], 0.25, 1e-9);
    EXPECT_NEAR(plan.summary.heights[1], 0.75, 1e-9);
    const double prism = std::sqrt(Lp * Lp + (N * P) * (N * P));
    const double smooth = std::sqrt(Lp * Lp + std::pow(2.0 * M_PI * R * N, 2));
    for (const HelixPass& p : plan.passes) {
      std::string why;
      ASSERT_TRUE(is_valid_path(m, p.initial, &why)) << why;
      ASSERT_TRUE(is_valid_path(m, p.path, &why)) << why;
      ASSERT_TRUE(p.summary.converged()) << p.summary.brief_report();
      const double za = p.hand > 0 ? z0 : z1, zb = p.hand > 0 ? z1 : z0;
      EXPECT_NEAR(position(m, p.path.start).z(), za, 1e-6);
      EXPECT_NEAR(position(m, p.path.end).z(), zb, 1e-6);
      const double len = euclidean_length(m, p.path);
      EXPECT_NEAR(len, prism, 1e-6 * prism) << "N = " << N << " circuit " << p.circuit;
      EXPECT_NEAR(len, smooth, 1e-3 * smooth) << "N = " << N << " circuit " << p.circuit;
      // The level set between the stations is already that line.
      EXPECT_NEAR(euclidean_length(m, p.initial), prism, 1e-6 * prism);
    }
    for (int k = 0; k < 3; ++k) {
      const HelixPass& out = plan.passes[2 * k];
      const HelixPass& back = plan.passes[2 * k + 1];
      const Turnaround& top = plan.turnarounds[2 * k];
      const Turnaround& bottom = plan.turnarounds[2 * k + 1];
      ASSERT_TRUE(top.at_station());
      ASSERT_TRUE(bottom.at_station());
      EXPECT_EQ(top.station, z1);
      EXPECT_EQ(bottom.station, z0);
      for (const Vec3& q : top.arc.points) EXPECT_NEAR(q.z(), z1, 1e-6);
      for (const Vec3& q : bottom.arc.points) EXPECT_NEAR(q.z(), z0, 1e-6);
      ASSERT_EQ(top.arc.faces.size() + 1, top.arc.points.size());
      // The arcs run on the station circle (radius R up to the facets).
      for (const Vec3& q : top.arc.points) {
        EXPECT_NEAR(std::hypot(q.x(), q.y()), R, R * (1.0 - std::cos(M_PI / n)) + 1e-9);
      }
      // Continuous: each piece starts where the previous one ends.
      EXPECT_LT((top.arc.points.front() - position(m, out.path.end)).norm(), 1e-9);
      EXPECT_LT((position(m, back.path.start) - top.arc.points.back()).norm(), 1e-9);
      EXPECT_LT((bottom.arc.points.front() - position(m, back.path.end)).norm(), 1e-9);
      const HelixPass& next = plan.passes[(2 * k + 2) % 6];
      EXPECT_NEAR((position(m, next.path.start) - bottom.arc.points.back()).norm(), 0.0,
                  k == 2 ? 1e-3 : 1e-9);
      // Dwell pi + pi / K (- 0.1 pi for N = 0.55) of theta, which is linear along the prism's
      // perimeter P.
      const double theta = M_PI + M_PI / 3 - (N == 0.55 ? 0.1 * M_PI : 0.0);
      const double dwell = theta / (2.0 * M_PI) * P;
      EXPECT_NEAR(top.arc.length, dwell, 1e-6 * P) << "N = " << N;
      EXPECT_NEAR(bottom.arc.length, dwell, 1e-6 * P) << "N = " << N;
      // The pass turns by 2 pi N about the axis (clockwise seen from +z, as theta).
      for (const HelixPass* p : {&out, &back}) {
        const Vec3 a = position(m, p->path.start), b = position(m, p->path.end);
        const double turned = std::atan2(a.y(), a.x()) - std::atan2(b.y(), b.x());
        EXPECT_NEAR(std::remainder(turned - 2.0 * M_PI * N, 2.0 * M_PI), 0.0, 1e-4);
      }
    }
  }
}

// One station: the other end of the passes stays the boundary loop.
TEST(HelixStations, OneStationKeepsTheOtherLoop) {
  const double R = 40.0, L = 150.0;
  const int n = 64;
  const Mesh m(test::open_cylinder(R, L, n, 20));
  const auto loops = loops_by_z(m);
  const double P = n * 2.0 * R * std::sin(M_PI / n);
  for (int which : {0, 1}) {
    WindingOptions o;
    o.turns = 2;
    o.circuits = 2;
    const double z = which == 0 ? 40.0 : 100.0;
    (which == 0 ? o.start_station : o.end_station) = z;
    const double za = which == 0 ? z : 0.0, zb = which == 0 ? L : z;
    const HelixPlan plan = plan_helices(m, loops, {}, SpindleAxis{}, o);
    const double prism = std::sqrt((zb - za) * (zb - za) + std::pow(2 * P, 2));
    for (const HelixPass& p : plan.passes) {
      EXPECT_NEAR(position(m, p.path.start).z(), p.hand > 0 ? za : zb, 1e-6);
      EXPECT_NEAR(position(m, p.path.end).z(), p.hand > 0 ? zb : za, 1e-6);
      EXPECT_NEAR(euclidean_length(m, p.path), prism, 1e-6 * prism) << "station " << which;
    }
    for (const Turnaround& t : plan.turnarounds) {
      const bool station_end = t.loop == which;
      EXPECT_EQ(t.at_station(), station_end);
      const double zt = t.loop == 0 ? za : zb;
      for (const Vec3& q : t.arc.points) EXPECT_NEAR(q.z(), zt, 1e-6);
    }
  }
}

// On an irregular tessellation of a curved surface h is not constant on a station circle, so the
// passes advance theta by 2 pi N only nearly; the start dwell takes up the difference and the K
// circuits still close: the last turnaround ends where circuit 0 starts, each circuit starting
// 1/K turn after the previous one. The same with N = 0.55 (nominal dwell pi + pi / K - 0.1 pi).
TEST(HelixStations, PatternClosesOnAnIrregularTessellation) {
  auto r = [](double z) { return 40.0 + 15.0 * std::sin(M_PI * z / 160.0); };
  const double L = 160.0;
  const int n = 48, rings = 16;
  TriangleSoup soup = test::revolution(r, 0.0, L, n, rings);
  for (int j = 1; j < rings; ++j) {
    for (int i = 0; i < n; ++i) {  // move the inner rings' vertices along the surface
      Vec3& p = soup.points[j * n + i];
      const double z = p.z() + 0.35 * (L / rings) * std::sin(12.9898 * i + 78.233 * j);
      const double t = std::atan2(p.y(), p.x());
      p = Vec3(r(z) * std::cos(t), r(z) * std::sin(t), z);
    }
  }
  const Mesh m(soup);
  const auto loops = loops_by_z(m);
  for (double N : {2.0, 0.55}) {
    SCOPED_TRACE("N = " + format_turns(N));
    WindingOptions o;
    o.turns = N;
    o.circuits = 5;
    o.start_station = 45.0;
    o.end_station = 115.0;
    const HelixPlan plan = plan_helices(m, loops, {}, SpindleAxis{}, o);
    ASSERT_EQ(plan.passes.size(), 10u);
    const double nominal = M_PI + M_PI / 5 - (N == 2.0 ? 0.0 : 0.1 * M_PI);
    double spread = 0.0;
    for (int k = 0; k < 5; ++k) {
      const Turnaround& top = plan.turnarounds[2 * k];
      const Turnaround& bottom = plan.turnarounds[2 * k + 1];
      EXPECT_NEAR(top.dwell, nominal, N == 2.0 ? 0.0 : 1e-12);  // whole N: exactly pi + pi / K
      EXPECT_NEAR(bottom.dwell, nominal, 0.1);
      spread = std::max(spread, std::fabs(bottom.dwell - nominal));
      for (const Vec3& q : bottom.arc.points) EXPECT_NEAR(q.z(), 45.0, 1e-6);
      for (const Vec3& q : top.arc.points) EXPECT_NEAR(q.z(), 115.0, 1e-6);
      const HelixPass& next = plan.passes[(2 * k + 2) % 10];
      EXPECT_LT((position(m, next.path.start) - bottom.arc.points.back()).norm(), 1e-4);
      // Theta is close to the polar angle here (up to the jitter).
      const Vec3 a = position(m, plan.passes[2 * k].path.start);
      const Vec3 b = bottom.arc.points.back();
      const double d = std::atan2(a.y(), a.x()) - std::atan2(b.y(), b.x());  // clockwise from +z
      EXPECT_NEAR(std::remainder(d - 2.0 * M_PI / 5, 2.0 * M_PI), 0.0, 0.05) << "circuit " << k;
    }
    EXPECT_GT(spread, 1e-4) << "the tessellation should make h vary along the station circles";
    for (const HelixPass& p : plan.passes) {
      EXPECT_NEAR(position(m, p.path.start).z(), p.hand > 0 ? 45.0 : 115.0, 1e-6);
      EXPECT_NEAR(position(m, p.path.end).z(), p.hand > 0 ? 115.0 : 45.0, 1e-6);
    }
  }
}

TEST(HelixStations, StationOutsideTheWoundRegionNamesTheKeyAndRange) {
  const Mesh m(test::open_cylinder(40.0, 150.0, 32, 10));
  const auto loops = loops_by_z(m);
  auto expect_config = [&](double start, double end, const std::string& key) {
    WindingOptions o;
    o.start_station = start;
    o.end_station = end;
    try {
      plan_helices(m, loops, {}, SpindleAxis{}, o);
      FAIL() << "accepted: " << key;
    } catch (const ConfigError& e) {
      const std::string w = e.what();
      EXPECT_NE(w.find(key), std::string::npos) << w;
      EXPECT_NE(w.find("(0, 150) mm"), std::string::npos) << w;
    }
  };
  const double none = std::nan("");
  expect_config(-10.0, none, "winding.start_station");
  expect_config(0.0, none, "winding.start_station");  // on the loop itself
  expect_config(none, 150.0, "winding.end_station");
  expect_config(none, 400.0, "winding.end_station");
  expect_config(20.0, 160.0, "winding.end_station");
  // Stations are measured from the axis origin: shifted origin, shifted range.
  WindingOptions o;
  o.start_station = -60.0;
  SpindleAxis shifted;
  shifted.origin = Vec3(0, 0, 50);
  try {
    plan_helices(m, loops, {}, shifted, o);
    FAIL() << "accepted a station below the loop of a shifted axis";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("(-50, 100) mm"), std::string::npos) << e.what();
  }
}

TEST(Helix, DensityFromGirthIsNormalised) {
  const Mesh m(test::open_cylinder(40.0, 150.0, 32, 10));
  std::vector<double> g(m.num_faces(), 251.0);
  for (double x : density_from_girth(m, g, 1.0)) EXPECT_NEAR(x, 1.0, 1e-12);
  g[3] = 0.0;
  EXPECT_THROW(density_from_girth(m, g, 1.0), InputError);
}

}  // namespace
}  // namespace windplan
