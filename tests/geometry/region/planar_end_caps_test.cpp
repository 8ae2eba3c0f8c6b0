// The flat end caps of a closed bent tube (geometry/region/planar_end_caps.h): found on a
// synthetic 90 degree bent tube closed by two polygon fans whose planes are normal to the legs
// (one along z, one along x), each of the polygon's area n/2 r^2 sin(2 pi / n); the rest is the
// open tube. A closed box (six planar faces) has no such pair.
#include "geometry/region/planar_end_caps.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/region/mandrel_region.h"
#include "tests/geometry/region/tube_fixtures.h"

namespace windplan {
namespace {

Mesh closed_bent_tube(const test::BentTube& tube) {
  const Mesh open = tube.mesh();
  TriangleSoup s{open.points(), open.triangles()};
  const auto loops = tube.loops();
  const int n = tube.around;
  for (int e = 0; e < 2; ++e) {
    const int c = static_cast<int>(s.points.size());
    s.points.push_back(tube.centre(e == 0 ? 0.0 : tube.length()));
    for (int i = 0; i < n; ++i) {
      const int a = loops[e][i], b = loops[e][(i + 1) % n];
      // The tube's faces run a -> b on loop 0 ({i, i+1, ...}): the cap runs b -> a there.
      if (e == 0)
        s.triangles.push_back({c, b, a});
      else
        s.triangles.push_back({c, a, b});
    }
  }
  return Mesh(std::move(s));
}

TEST(PlanarEndCaps, TheTwoEndsOfAClosedBentTube) {
  test::BentTube tube;
  const Mesh m = closed_bent_tube(tube);
  ASSERT_TRUE(m.is_closed());
  const PlanarEndCaps caps = planar_end_caps(m, {});
  ASSERT_TRUE(caps.found) << caps.brief();
  const double polygon = 0.5 * tube.around * 25.0 * 25.0 * std::sin(2 * M_PI / tube.around);
  for (int e = 0; e < 2; ++e) {
    EXPECT_EQ(caps.cap_faces[e], tube.around);
    EXPECT_NEAR(caps.cap_area[e], polygon, 1e-9 * polygon);
  }
  // What remains is the open tube: every face of it, none of the caps.
  int kept = 0;
  for (char k : caps.keep) kept += k;
  EXPECT_EQ(kept, tube.mesh().num_faces());
}

TEST(PlanarEndCaps, AClosedBoxIsASquareTubeAndATetrahedronHasNone) {
  // A box without two opposite faces is a square tube (an annulus): its largest pair are caps.
  TriangleSoup s;
  for (int i = 0; i < 8; ++i)
    s.points.push_back(Vec3(i & 1, 2.0 * ((i >> 1) & 1), 3.0 * ((i >> 2) & 1)));
  const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                       {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : q) {
    s.triangles.push_back({f[0], f[1], f[2]});
    s.triangles.push_back({f[0], f[2], f[3]});
  }
  const Mesh box(std::move(s));
  ASSERT_TRUE(box.is_closed());
  // A 1 x 2 x 3 box: its two largest faces (2 x 3, at x = 0 and x = 1) are opposite, and the
  // four others are a band around x.
  const PlanarEndCaps caps = planar_end_caps(box, {});
  ASSERT_TRUE(caps.found) << caps.brief();
  EXPECT_NEAR(caps.cap_area[0], 6.0, 1e-12);
  EXPECT_NEAR(caps.cap_area[1], 6.0, 1e-12);
  // A tetrahedron: any two faces removed leave two faces sharing an edge (one loop).
  TriangleSoup t;
  t.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  t.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const Mesh tet(std::move(t));
  ASSERT_TRUE(tet.is_closed());
  EXPECT_FALSE(planar_end_caps(tet, {}).found);
}

}  // namespace
}  // namespace windplan
