// Sharp edges of a wound surface (geometry/region/sharp_edges.h): a box's 12 edges turn by
// exactly 90 deg (total length 4 (a + b + c)) and its face diagonals by 0; a bent tube of 96-gon
// sections turns by 360 / 96 = 3.75 deg across its ring edges at most (plus the bend's share)
// and has no sharp edge at 60 deg.
#include "geometry/region/sharp_edges.h"

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "tests/geometry/region/tube_fixtures.h"

namespace windplan {
namespace {

TEST(SharpEdges, ABoxHasTwelveRightAngledEdges) {
  TriangleSoup s;
  const double a = 1, b = 2, c = 3;
  for (int i = 0; i < 8; ++i) {
    s.points.push_back(Vec3(a * (i & 1), b * ((i >> 1) & 1), c * ((i >> 2) & 1)));
  }
  const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                       {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : q) {
    s.triangles.push_back({f[0], f[1], f[2]});
    s.triangles.push_back({f[0], f[2], f[3]});
  }
  const SharpEdges e = sharp_edges(Mesh(std::move(s)), 60.0);
  EXPECT_EQ(e.count, 12);
  EXPECT_NEAR(e.length, 4 * (a + b + c), 1e-12);
  EXPECT_NEAR(e.max_angle_deg, 90.0, 1e-9);
  EXPECT_NEAR(e.area, 2 * (a * b + b * c + c * a), 1e-12);
  EXPECT_NEAR(e.flat_area, 0.0, 1e-12);  // every face touches a corner edge
  EXPECT_THROW(sharp_edges(Mesh(), 0.0), InputError);
}

TEST(SharpEdges, ATessellatedBentTubeHasNone) {
  test::BentTube tube;
  const SharpEdges e = sharp_edges(tube.mesh(), 60.0);
  EXPECT_EQ(e.count, 0);
  EXPECT_GT(e.max_angle_deg, 3.7);  // around the section: 3.75 deg between ring faces' normals
  EXPECT_LT(e.max_angle_deg, 6.0);
}

}  // namespace
}  // namespace windplan
