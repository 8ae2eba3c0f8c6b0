// The girth loop is the shortest loop through p, not a locally shortest one
// (planner/girth/girth_loops.h): checked against the exact geodesic distance on the surface's
// cyclic cover, an independent reference (CGAL, geometry/geodesic/exact_geodesic.h).
#include "planner/girth/girth_loops.h"

#include <cmath>
#include <functional>
#include <iostream>

#include <gtest/gtest.h>

#include "geometry/geodesic/exact_geodesic.h"
#include "planner/girth/girth.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

double polygon_perimeter(double r, int n) { return n * 2.0 * r * std::sin(M_PI / n); }

// Three turns of test::revolution(r, z0, z1, n, m) unrolled: columns i = 0..3n at angles
// 2 pi i / n, vertex (i, j) = j (3n + 1) + i, the same triangles as the closed mesh. A loop
// through vertex (i, j) of the closed mesh winding once lifts to a path from (n + i, j) to
// (2n + i, j) on this cover, so the girth is the exact geodesic distance between them (the
// path stays within the three turns: it is shorter than a turn's circumference at every ring).
TriangleSoup unrolled_cover(const std::function<double(double)>& r, double z0, double z1, int n,
                            int m) {
  TriangleSoup s;
  const int cols = 3 * n + 1;
  for (int j = 0; j <= m; ++j) {
    const double z = z0 + (z1 - z0) * j / m;
    for (int i = 0; i < cols; ++i) {
      const double t = 2.0 * M_PI * i / n;
      s.points.emplace_back(r(z) * std::cos(t), r(z) * std::sin(t), z);
    }
  }
  auto id = [cols](int i, int j) { return j * cols + i; };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i + 1 < cols; ++i) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

double exact_girth(const std::function<double(double)>& r, double z0, double z1, int n, int m,
                   int i, int j) {
  const Mesh cover(unrolled_cover(r, z0, z1, n, m));
  const int cols = 3 * n + 1;
  return exact_geodesic_distance(cover, SurfacePoint::at_vertex(j * cols + n + i),
                                 SurfacePoint::at_vertex(j * cols + 2 * n + i));
}

std::array<std::vector<int>, 2> ring_loops(int n, int m) { return test::revolution_loops(n, m); }

// A neck (r = 3 at z = 10) next to a bulge (r = 8.3 at z = 30). Through p on the bulge's widest
// ring, that ring is a locally shortest loop (a geodesic parallel, 2 pi 8.3 = 52 mm), but the
// loop that runs down to the neck, around it and back is shorter; its edge loop (down a
// meridian, around the neck ring, back) is longer than the ring, so the shortest edge loop lies
// in the ring's corridor.
TEST(GirthLoops, NeckNextToABulgeGivesTheShortestLoopNotTheLocalOne) {
  const auto r = [](double z) { return 5.65 - 2.65 * std::cos(M_PI * (z - 10.0) / 20.0); };
  const int n = 64, m = 40;
  const double z0 = 0.0, z1 = 40.0;
  const Mesh mesh(test::revolution(r, z0, z1, n, m));
  const auto loops = ring_loops(n, m);
  const GirthContext context(mesh, loops);
  const int j = 30, i = 5;  // z = 30, the bulge's widest ring
  const int p = j * n + i;
  const double ring = polygon_perimeter(8.3, n);
  const double exact = exact_girth(r, z0, z1, n, m, i, j);
  const GirthContext::Loop loop = context.girth(p);
  std::cout << "[ girth    ] ring " << ring << " mm, edge loop " << loop.edge_length
            << " mm, girth " << loop.girth << " mm, exact (cover) " << exact << " mm\n";
  // The setting: the exact girth is clearly below the ring, the shortest edge loop is not.
  ASSERT_LT(exact, ring * 0.98);
  EXPECT_GE(loop.edge_length, ring * (1.0 - 1e-9));
  EXPECT_NEAR(loop.girth, exact, 1e-7 * exact);
  EXPECT_EQ(std::abs(loop.winding), 1);
  EXPECT_TRUE(loop.converged);
}

// Exhaustive on a small mesh: at every vertex of a coarse neck-and-bulge mandrel, the girth
// equals the exact distance on the cover.
TEST(GirthLoops, EveryVertexOfASmallMandrelMatchesTheCover) {
  const auto r = [](double z) { return 5.65 - 2.65 * std::cos(M_PI * (z - 10.0) / 20.0); };
  const int n = 16, m = 10;
  const double z0 = 0.0, z1 = 40.0;
  const Mesh mesh(test::revolution(r, z0, z1, n, m));
  const GirthContext context(mesh, ring_loops(n, m));
  const int cols = 3 * n + 1;
  const Mesh cover(unrolled_cover(r, z0, z1, n, m));
  ExactGeodesic exact(cover);
  double worst = 0.0;
  for (int j = 0; j <= m; ++j) {
    // Rotational symmetry: one vertex per ring has the girth of the whole ring.
    const double reference = exact.distances(SurfacePoint::at_vertex(j * cols + n),
                                             {SurfacePoint::at_vertex(j * cols + 2 * n)})[0];
    for (int i = 0; i < n; i += 5) {
      const GirthContext::Loop loop = context.girth(j * n + i);
      worst = std::max(worst, std::abs(loop.girth - reference) / reference);
      EXPECT_NEAR(loop.girth, reference, 1e-7 * reference) << "ring " << j << ", vertex " << i;
      EXPECT_EQ(std::abs(loop.winding), 1) << "ring " << j << ", vertex " << i;
    }
  }
  std::cout << "[ girth    ] " << (m + 1) << " rings: worst relative difference " << worst << "\n";
}

}  // namespace
}  // namespace windplan
