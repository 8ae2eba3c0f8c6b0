// Circuits on shapes of revolution (planner/winding/revolution_winding.h): copies of circuit 0, one
// continuous fibre, geodesic turnarounds tangent to r = c, Clairaut on the placed points.
#include "planner/winding/revolution_winding.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "geometry/base/errors.h"
#include "tests/planner/winding_fixtures.h"

namespace windplan {
namespace {

constexpr double kR = 100, kL = 300, kOpen = 30, kB = 16;

double angle_of(const Vec3& p) { return std::atan2(p.y(), p.x()); }

// The out pass's crossing of the plane z = zc, as an angle about z.
double crossing_angle(const Circuit& c, double zc) {
  const CircuitSegment& s = c.segments.front();
  for (int i = s.first + 1; i <= s.last; ++i) {
    const Vec3 &a = c.points[i - 1].position, &b = c.points[i].position;
    if ((a.z() - zc) * (b.z() - zc) <= 0.0 && a.z() != b.z()) {
      return angle_of(a + (zc - a.z()) / (b.z() - a.z()) * (b - a));
    }
  }
  return std::nan("");
}

struct Capsule {
  Mesh mesh;
  RevolutionWinding w;
};

const Capsule& capsule(double k) {
  static std::map<double, Capsule> cache;
  auto it = cache.find(k);
  if (it != cache.end()) return it->second;
  Capsule c;
  c.mesh = test::revolve(test::capsule_meridian(kR, kL, kOpen, 120, 30, k), 128);
  WindingOptions o;
  o.band_width = kB;
  c.w = plan_revolution_winding(c.mesh, {}, SpindleAxis{}, o);
  return cache.emplace(k, std::move(c)).first->second;
}

class Domes : public ::testing::TestWithParam<double> {};

TEST_P(Domes, CircuitsAreCopiesThatCloseIntoOneFibre) {
  const Capsule& cap = capsule(GetParam());
  const RevolutionWinding& w = cap.w;
  ASSERT_TRUE(w.planned);
  const int K = w.pattern.circuits;
  ASSERT_EQ(static_cast<int>(w.circuits.size()), K);
  EXPECT_TRUE(w.geodesic_end[0] && w.geodesic_end[1]);
  // Each circuit: two passes, no dwell arc.
  for (const Circuit& c : w.circuits) {
    ASSERT_EQ(c.segments.size(), 2u);
    EXPECT_EQ(c.segments[0].kind, CircuitSegment::Kind::Pass);
    EXPECT_EQ(c.segments[1].kind, CircuitSegment::Kind::Pass);
  }
  // One continuous fibre: each circuit starts where the last one ended, the last ends where the
  // first started (the pattern closes after K circuits and not before).
  for (int k = 0; k < K; ++k) {
    const Vec3 end = w.circuits[k].points.back().position;
    const Vec3 next = w.circuits[(k + 1) % K].points.front().position;
    EXPECT_LT((end - next).norm(), 1e-6) << "circuit " << k;
  }
  std::vector<double> starts;
  for (const Circuit& c : w.circuits) starts.push_back(angle_of(c.points.front().position));
  std::sort(starts.begin(), starts.end());
  for (int k = 0; k < K; ++k) {
    const double next = k + 1 < K ? starts[k + 1] : starts[0] + 2 * M_PI;
    EXPECT_NEAR(next - starts[k], 2 * M_PI / K, 1e-6);
  }
  // Copies: the mid-cylinder crossing relative to the circuit's start is the same for all.
  const double ref =
      crossing_angle(w.circuits[0], kL / 2) - angle_of(w.circuits[0].points.front().position);
  double spread = 0.0;
  for (const Circuit& c : w.circuits) {
    const double rel = crossing_angle(c, kL / 2) - angle_of(c.points.front().position);
    spread = std::max(spread, kR * std::abs(std::remainder(rel - ref, 2 * M_PI)));
  }
  EXPECT_LT(spread, 0.1);  // mm
}

TEST_P(Domes, TurnaroundsAreTangentToTheParallelAndGeodesic) {
  const Capsule& cap = capsule(GetParam());
  const RevolutionWinding& w = cap.w;
  const double c = w.pattern.c;
  for (const Circuit& cir : w.circuits) {
    double rmin = 1e9;
    for (const FibrePoint& p : cir.points)
      rmin = std::min(rmin, std::hypot(p.position.x(), p.position.y()));
    EXPECT_NEAR(rmin, c, 0.5);
    EXPECT_GT(rmin, c - 0.2);  // the projection onto the facets moves it by their sagitta only
  }
  // Clairaut on the placed, annotated points of the cylinder: r sin(a) = c; and the passes
  // stay where friction is not needed.
  double worst = 0.0, slip = 0.0;
  for (const Circuit& cir : w.circuits) {
    for (const FibrePoint& p : cir.points) {
      slip = std::max(slip, p.slippage);
      if (p.position.z() < 20 || p.position.z() > kL - 20) continue;
      const double r = std::hypot(p.position.x(), p.position.y());
      worst = std::max(worst, std::abs(r * std::sin(p.winding_angle * M_PI / 180) - c));
    }
  }
  EXPECT_LT(worst, 0.3);  // mm
  EXPECT_LT(slip, 0.2);
}

INSTANTIATE_TEST_SUITE_P(HemisphericalAndElliptical, Domes, ::testing::Values(1.0, 0.6));

TEST(RevolutionWinding, PipeDwellsAtBothEndsAndCloses) {
  const Mesh pipe =
      test::revolve({{0, 50}, {100, 50}, {200, 50}, {300, 50}, {400, 50}, {500, 50}}, 128);
  WindingOptions o;
  o.band_width = 12;
  o.turns = 3;
  const RevolutionWinding w = plan_revolution_winding(pipe, {}, SpindleAxis{}, o);
  ASSERT_TRUE(w.planned);
  EXPECT_FALSE(w.geodesic_end[0] || w.geodesic_end[1]);
  const int K = w.pattern.circuits;
  EXPECT_EQ(
      K, static_cast<int>(std::ceil(2 * M_PI * 50 * std::cos(std::asin(w.pattern.c / 50)) / 12)));
  for (const Circuit& c : w.circuits) {
    ASSERT_EQ(c.segments.size(), 4u);
    EXPECT_EQ(c.segments[1].kind, CircuitSegment::Kind::Turnaround);
    EXPECT_EQ(c.segments[3].kind, CircuitSegment::Kind::Turnaround);
  }
  for (int k = 0; k < K; ++k) {
    EXPECT_LT(
        (w.circuits[k].points.back().position - w.circuits[(k + 1) % K].points.front().position)
            .norm(),
        1e-6);
  }
  // The pass makes the 3 turns: the helix angle tan(a) = 2 pi R N / L.
  const FibrePoint& mid = w.circuits[0].points[w.circuits[0].segments[0].last / 2];
  EXPECT_NEAR(std::tan(mid.winding_angle * M_PI / 180), 2 * M_PI * 50 * 3 / 500, 5e-3);
}

TEST(RevolutionWinding, StationsClipTheMeridian) {
  const std::vector<Vec2> m{{0, 50}, {100, 50}, {200, 60}};
  const std::vector<Vec2> c = clip_meridian(m, 25, 150);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c.front(), Vec2(25, 50));
  EXPECT_EQ(c[1], Vec2(100, 50));
  EXPECT_NEAR(c.back().y(), 55, 1e-12);
}

}  // namespace
}  // namespace windplan
