// The wound region between two sections normal to a tube's centre line
// (geometry/region/centre_line_region.h), on synthetic bent tubes whose centre line is exact: the
// region's loops lie on the planes normal to the legs (not to one axis), its area is the torus
// and cylinder closed form 2 pi r (to - from), a plane that also crosses the other leg of a
// U-bend does not cut that leg out, and the bad stations are refused naming the key.
#include "geometry/region/centre_line_region.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"
#include "tests/geometry/region/tube_fixtures.h"

namespace windplan {
namespace {

Spine exact_spine(const test::BentTube& tube) {
  std::vector<Vec3> pts;
  for (int k = 0; k <= 2000; ++k) pts.push_back(tube.centre(tube.length() * k / 2000));
  return spine_from_polyline(pts);
}

// The kept faces' area, and the loops of the kept part as point lists.
struct Kept {
  double area = 0.0;
  std::vector<std::vector<Vec3>> loops;
};

Kept kept(const RegionSelection& sel) {
  Kept k;
  TriangleSoup soup;
  soup.points = sel.mesh.points();
  for (int f = 0; f < sel.mesh.num_faces(); ++f) {
    if (!sel.keep[f]) continue;
    k.area += sel.mesh.face_area(f);
    soup.triangles.push_back(sel.mesh.triangle(f));
  }
  // Unreferenced vertices are allowed by Mesh; boundary loops of the kept faces only.
  const Mesh part(std::move(soup));
  for (const auto& L : part.boundary_loops()) {
    std::vector<Vec3> pts;
    for (int v : part.loop_vertices(L)) pts.push_back(part.position(v));
    k.loops.push_back(pts);
  }
  return k;
}

// Area of the 96-gon tube between two stations: 2 pi r (to - from) times the polygon's
// perimeter ratio n sin(pi / n) / pi (flat facets between rings; on the bend the facets' area is
// that of the polygon swept along the centre line to within the ring spacing's second order).
double polygon_tube_area(const test::BentTube& t, double length) {
  const double n = t.around;
  return 2.0 * n * std::sin(M_PI / n) * t.a * length;
}

TEST(CentreLineRegion, EndsOnTheSectionsNormalToEachLeg) {
  test::BentTube tube;  // legs 100 mm along z and then along x, r 25, bend 100 (90 deg)
  const Mesh m = tube.mesh();
  const Spine sp = exact_spine(tube);
  CentreLineEnds ends;
  ends.from = 41.0;  // between rings (every 2 mm): the plane splits edges
  ends.to = tube.length() - 31.0;
  const RegionSelection sel = select_centre_line_region(m, sp, ends, SpindleAxis{});
  const Kept k = kept(sel);
  ASSERT_EQ(k.loops.size(), 2u);
  EXPECT_GT(sel.split_edges, 0);
  // Each loop lies on one end's plane, at the tube radius from that end's centre: one on the
  // plane z = 41 (the first leg), the other on x = 100 + 69 (the second leg, along +x; the
  // polyline's chords on the bend make its arc length 2e-5 mm short of the exact one).
  const Vec3 c0 = sp.point(ends.from), c1 = sp.point(ends.to);
  EXPECT_NEAR(c1.x(), 169.0, 1e-4);
  for (const auto& loop : k.loops) {
    const bool first = std::abs(loop[0].z() - 41.0) < 1e-6;
    const Vec3 c = first ? c0 : c1, t = first ? Vec3(0, 0, 1) : Vec3(1, 0, 0);
    for (const Vec3& p : loop) {
      EXPECT_NEAR((p - c).dot(t), 0.0, 1e-6);
      EXPECT_NEAR((p - c).norm(), 25.0, 25.0 * (1.0 - std::cos(M_PI / 96)) + 1e-9);
    }
  }
  EXPECT_NEAR(k.area, polygon_tube_area(tube, ends.to - ends.from), 2e-3 * k.area);
}

TEST(CentreLineRegion, EndsInsideTheBendAreNormalToItThere) {
  test::BentTube tube;
  tube.per_mm = 1.0;
  const Mesh m = tube.mesh();
  const Spine sp = exact_spine(tube);
  CentreLineEnds ends;
  ends.from = tube.leg + 100.0 * M_PI / 8;    // 22.5 deg into the bend
  ends.to = tube.leg + 100.0 * 3 * M_PI / 8;  // 67.5 deg
  const RegionSelection sel = select_centre_line_region(m, sp, ends, SpindleAxis{});
  const Kept k = kept(sel);
  ASSERT_EQ(k.loops.size(), 2u);
  for (const auto& loop : k.loops) {
    // Each loop is on the plane through the bend's centre (100, 0, 100) at its angle: the
    // torus' meridian planes.
    const double s = (loop[0] - tube.centre(ends.from)).norm() < 30 ? ends.from : ends.to;
    for (const Vec3& p : loop) EXPECT_NEAR((p - tube.centre(s)).dot(tube.tangent(s)), 0.0, 1e-3);
  }
  // The torus piece: 2 pi r R phi (Pappus), R phi = to - from.
  EXPECT_NEAR(k.area, polygon_tube_area(tube, ends.to - ends.from), 3e-3 * k.area);
}

TEST(CentreLineRegion, APlaneThatAlsoCrossesTheOtherLegOfAUBendLeavesItWhole) {
  test::BentTube tube;
  tube.angle = M_PI;  // a U: the second leg runs back down along -z at x = 200
  const Mesh m = tube.mesh();
  const Spine sp = exact_spine(tube);
  CentreLineEnds ends;
  ends.from = 50.0;                // z = 50 on the first leg
  ends.to = tube.length() - 50.0;  // z = 50 on the second: the same plane
  const RegionSelection sel = select_centre_line_region(m, sp, ends, SpindleAxis{});
  const Kept k = kept(sel);
  EXPECT_EQ(k.loops.size(), 2u);
  EXPECT_NEAR(k.area, polygon_tube_area(tube, ends.to - ends.from), 2e-3 * k.area);
  // Only one station on the second leg: from = 50 and to = L - 20 (z = 20 there).
  ends.to = tube.length() - 20.0;
  const Kept k2 = kept(select_centre_line_region(m, sp, ends, SpindleAxis{}));
  EXPECT_NEAR(k2.area, polygon_tube_area(tube, ends.to - ends.from), 2e-3 * k2.area);
}

TEST(CentreLineRegion, BadStationsAreRefusedNamingTheKey) {
  test::BentTube tube;
  const Mesh m = tube.mesh();
  const Spine sp = exact_spine(tube);
  auto message = [&](double from, double to, const Spine& spine) {
    CentreLineEnds e;
    e.from = from;
    e.to = to;
    try {
      select_centre_line_region(m, spine, e, SpindleAxis{});
    } catch (const ConfigError& err) {
      return std::string(err.what());
    }
    return std::string("no error");
  };
  const double L = tube.length();
  EXPECT_NE(message(-5, 100, sp).find("mandrel.region.centre_line.from: -5.00 mm is outside"),
            std::string::npos);
  EXPECT_NE(message(10, L + 1, sp).find("mandrel.region.centre_line.to"), std::string::npos);
  EXPECT_NE(message(10, L, sp).find("its ends excluded"), std::string::npos);
  EXPECT_NE(message(100, 50, sp).find("must lie after"), std::string::npos);
  // A centre line that runs past the tube's start: the plane there misses the tube.
  const Spine longer = spine_from_polyline({Vec3(0, 0, -100), Vec3(0, 0, 90)});
  const std::string miss = message(50, 150, longer);
  EXPECT_NE(miss.find("mandrel.region.centre_line.from: the plane normal to the centre line at "
                      "50.00 mm does not cut a closed section of the tube"),
            std::string::npos)
      << miss;
}

}  // namespace
}  // namespace windplan
