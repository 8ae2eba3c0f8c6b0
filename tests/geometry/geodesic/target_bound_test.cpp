// The A* lower bound of geometry/geodesic/target_bound.h against CGAL's exact distances (an
// independent implementation): below the distance to the target at every vertex a shortest
// path may pass, much tighter than the straight distance where the geodesic bends, and the
// window search's distances unchanged by it.
#include "geometry/geodesic/target_bound.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/geodesic/exact_geodesic.h"
#include "geometry/geodesic/geodesic_windows.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

std::vector<double> exact_field(ExactGeodesic& cgal, const Mesh& mesh, int source) {
  std::vector<SurfacePoint> all;
  for (int v = 0; v < mesh.num_vertices(); ++v) all.push_back(SurfacePoint::at_vertex(v));
  return cgal.distances(SurfacePoint::at_vertex(source), all);
}

struct Checked {
  int pairs = 0;     // pairs whose bound was built
  int vertices = 0;  // vertices on or near a shortest path checked
  double least_gain = 1e300;  // least h(s) / |s t| over the pairs with a bound
  double least_share = 1e300;  // least h(s) / D
  double median_share = 0.0;   // median h(s) / D
  int with_radius = 0;         // pairs whose bound leaves out {psi <= r}, r > 0
  int with_faces_out = 0;      // pairs whose bound left steep faces out (step 5)
  int with_levels = 0;         // pairs whose E near the target is below the whole E (step 6)
};

// For `count` random pairs of `mesh`: the bound at every vertex v with d(s, v) + d(v, t) <= U
// (exactly, by CGAL) is at most d(v, t). (It holds on the shortest paths from s to t; and every
// point y of a shortest path from such a v to t has |y s| + |y t| <= d(s, v) + d(v, t) <= U, so
// the path crosses only faces whose slopes entered the bound: the same proof.) `straighten`:
// U is step 1's straightened path (within a hair of D: few vertices to check), or the graph
// path's length (about 1 % longer: the bound over a wider ellipsoid). `clamp`: step 2's clamp
// (0: none).
Checked check_bound(const Mesh& mesh, int count, unsigned seed, double min_detour,
                    bool straighten, double clamp = TargetBoundOptions{}.clamp_slope) {
  const WindowMesh wm = prepare_window_mesh(mesh);
  ExactGeodesic cgal(mesh);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, mesh.num_vertices() - 1);
  TargetBoundOptions options;
  options.min_detour = min_detour;
  options.straighten_upper = straighten;
  options.clamp_slope = clamp;
  TargetBound bound;
  Checked c;
  std::vector<double> shares;
  for (int i = 0; i < count; ++i) {
    const int s = pick(rng), t = pick(rng);
    if (s == t) continue;
    const std::vector<int>& local = wm.order.vertex_to_local;
    build_target_bound(wm, local[s], local[t], std::numeric_limits<double>::infinity(), options,
                       &bound);
    if (!bound.active) continue;
    ++c.pairs;
    if (bound.radius > 0.0) ++c.with_radius;
    if (bound.faces_out > 0) ++c.with_faces_out;
    const std::vector<double> from_s = exact_field(cgal, mesh, s), from_t = exact_field(cgal, mesh, t);
    const double D = from_s[t];
    EXPECT_GE(bound.upper, D * (1.0 - 1e-12)) << s << " -> " << t;
    EXPECT_GE(bound.slope, 1.0);
    EXPECT_GE(bound.excess, 0.0);
    const std::vector<double>& levels = bound.excess_by_level();
    for (std::size_t i = 0; i < levels.size(); ++i) {
      EXPECT_GE(levels[i], i > 0 ? levels[i - 1] : 0.0) << s << " -> " << t << ": level " << i;
      EXPECT_LE(levels[i], bound.excess) << s << " -> " << t << ": level " << i;
    }
    if (!levels.empty() && levels[0] < bound.excess) ++c.with_levels;
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      if (!(from_s[v] + from_t[v] <= bound.upper)) continue;
      ++c.vertices;
      const double h = bound.at(local[v]);
      EXPECT_LE(h, from_t[v] * (1.0 + 1e-12) + 1e-12)
          << s << " -> " << t << ": vertex " << v << " on a shortest path";
    }
    const double hs = bound.at(local[s]);
    c.least_gain = std::min(c.least_gain, hs / (mesh.position(s) - mesh.position(t)).norm());
    c.least_share = std::min(c.least_share, hs / D);
    shares.push_back(hs / D);
  }
  if (!shares.empty()) {
    std::sort(shares.begin(), shares.end());
    c.median_share = shares[(shares.size() - 1) / 2];
  }
  std::printf("%d pairs, %d with E by level; h(s) / D least %.3f, median %.3f (clamp %g)\n",
              c.pairs, c.with_levels, c.least_share, c.median_share, clamp);
  return c;
}

TEST(TargetBound, BelowTheDistanceOnShortestPathsOfHills) {
  const Checked c = check_bound(Mesh(test::hills(40, 6.0)), 30, 5, 1.0, false);
  EXPECT_GE(c.pairs, 20);
  EXPECT_GE(c.with_radius, 5);  // both forms of the bound are checked
  EXPECT_GE(c.with_faces_out, 5);  // and bounds with faces left out
  EXPECT_GE(c.with_levels, 10);    // and with less E near the target than at the source
  EXPECT_GT(c.vertices, 500);
  // Fast marching on a fine mesh: the bound is most of the distance. (Point-source updates
  // raised the median from 0.908 with plane waves to 0.923, and lowered the least, on a short
  // pair across a hill's flank, from 0.736 to 0.647; L and E chosen with step 6's excess
  // halfway, 0.929; step 2's clamp, 0.964, least 0.686.)
  EXPECT_GT(c.least_share, 0.6);
  EXPECT_GT(c.median_share, 0.95);
  // The default, U straightened: the same bound to within what step 5 and the narrower
  // ellipsoid change (median 0.963), checked at the fewer vertices within that U.
  const Checked d = check_bound(Mesh(test::hills(40, 6.0)), 30, 5, 1.0, true);
  EXPECT_GE(d.pairs, 20);
  EXPECT_GT(d.vertices, 250);
  EXPECT_GT(d.median_share, 0.95);
  // Without the clamp: a bound too (median 0.931, least 0.643), and a lower one.
  const Checked e = check_bound(Mesh(test::hills(40, 6.0)), 30, 5, 1.0, true, 0.0);
  EXPECT_GE(e.pairs, 20);
  EXPECT_GT(e.median_share, 0.925);
  EXPECT_GT(d.median_share, e.median_share + 0.02);
}

TEST(TargetBound, BelowTheDistanceOnShortestPathsOfARoughTorus) {
  const Checked c = check_bound(Mesh(test::rough_torus(0.03, 11)), 30, 6, 1.0, false);
  EXPECT_GE(c.pairs, 20);
  EXPECT_GE(c.with_radius, 5);
  EXPECT_GE(c.with_faces_out, 5);
  EXPECT_GE(c.with_levels, 10);
  EXPECT_GT(c.vertices, 500);
  // Least 0.707, median 0.892: L and E are chosen for the bound halfway (where the A* band is
  // widest), not at the source; chosen at the source (commit 164a8a0), 0.754 and 0.877; by the
  // whole E halfway (before step 6), 0.707 and 0.861. Step 2's clamp: least 0.677, median
  // 0.908 (it lowers the bound of a short pair, whose marching it lowered more than it gained
  // in L).
  EXPECT_GT(c.least_share, 0.65);
  EXPECT_GT(c.median_share, 0.9);
  const Checked d = check_bound(Mesh(test::rough_torus(0.03, 11)), 30, 6, 1.0, true);
  EXPECT_GE(d.pairs, 20);
  EXPECT_GT(d.vertices, 200);
  EXPECT_GT(d.median_share, 0.9);
  // Without the clamp: least 0.732, median 0.885.
  const Checked e = check_bound(Mesh(test::rough_torus(0.03, 11)), 30, 6, 1.0, true, 0.0);
  EXPECT_GE(e.pairs, 20);
  EXPECT_GT(e.median_share, 0.875);
  EXPECT_GT(d.median_share, e.median_share + 0.01);
}

// Half a turn round the torus' hole the geodesic (6.90 by CGAL) bends far from the straight
// line (5.40): the bound beats the straight distance by a wide margin there (the reason it
// exists), even on this coarse mesh of long thin triangles (its slopes are the steepest of
// these tests: L 1.04, E 0.21 without step 2's clamp). The clamp lowers the marching's values
// here more than elsewhere (506 vertices): h(s) 6.44 -> 5.94, yet the search makes fewer
// windows (88,249 -> 78,135): the bound is higher where the band of windows is widest.
TEST(TargetBound, FarTighterThanTheStraightDistanceRoundATorus) {
  const Mesh mesh(test::torus(2.0, 0.7, 96, 40));
  const WindowMesh wm = prepare_window_mesh(mesh);
  ExactGeodesic cgal(mesh);
  // Vertices 0 and 48: the outer equator's (radius 2.7) opposite points.
  const int s = 0, t = 48;
  ASSERT_NEAR(mesh.position(t).norm(), 2.7, 1e-9);
  const double D = exact_field(cgal, mesh, s)[t];
  const double chord = (mesh.position(s) - mesh.position(t)).norm();
  long windows[2] = {0, 0};
  for (const double clamp : {0.0, TargetBoundOptions{}.clamp_slope}) {
    TargetBoundOptions options;
    options.clamp_slope = clamp;
    TargetBound bound;
    build_target_bound(wm, wm.order.vertex_to_local[s], wm.order.vertex_to_local[t],
                       std::numeric_limits<double>::infinity(), options, &bound);
    ASSERT_TRUE(bound.active);
    EXPECT_EQ(bound.clamped > 0, clamp > 0.0);
    const double hs = bound.at(wm.order.vertex_to_local[s]);
    EXPECT_LE(hs, D);
    EXPECT_GE(bound.upper, D);
    EXPECT_GT(hs, (clamp > 0.0 ? 0.85 : 0.9) * D)
        << "slope " << bound.slope << ", excess " << bound.excess;
    EXPECT_GT(hs, (clamp > 0.0 ? 1.08 : 1.15) * chord);
    WindowSearchOptions search;
    search.target_bound = options;
    const WindowSearchResult r = shortest_path_by_windows(mesh, wm, s, t, search);
    ASSERT_TRUE(r.found);
    EXPECT_NEAR(r.distance, D, 1e-9 * D);
    windows[clamp > 0.0] = r.windows;
  }
  EXPECT_LT(windows[1], windows[0]);
}

// A plane with a wall: the geodesics bend round the wall's end, a vertex from which the
// distance spreads as a cone, and point-source fast marching follows that cone exactly where the
// plane wave of Kimmel and Sethian did not (h(s) / D 0.944-0.954 on these pairs, against
// 0.925-0.953 with plane waves). What remains below 1 is L and E: the linear pieces' slopes
// round the target and round the wall's end (L 1.05).
TEST(TargetBound, PointSourceFastMarchingRoundAWall) {
  const TriangleSoup grid = test::grid(40, 40, 1.0);
  TriangleSoup cut;
  cut.points = grid.points;
  for (const Tri& t : grid.triangles) {
    const Vec3 c = (grid.points[t[0]] + grid.points[t[1]] + grid.points[t[2]]) / 3.0;
    if (!(c.x() > 19.0 && c.x() < 21.0 && c.y() < 30.0)) cut.triangles.push_back(t);
  }
  const Mesh mesh(cut);
  const WindowMesh wm = prepare_window_mesh(mesh);
  ExactGeodesic cgal(mesh);
  TargetBound bound;
  const std::vector<int>& local = wm.order.vertex_to_local;
  const auto id = [](int i, int j) { return 41 * j + i; };
  for (const auto& [s, t] : {std::pair{id(10, 5), id(30, 5)}, std::pair{id(5, 20), id(35, 10)},
                             std::pair{id(12, 2), id(28, 25)}, std::pair{id(0, 0), id(40, 0)}}) {
    build_target_bound(wm, local[s], local[t], std::numeric_limits<double>::infinity(), {},
                       &bound);
    ASSERT_TRUE(bound.active);
    // (The wall's middle vertices belong to no face: CGAL is asked for the target only.)
    const double D =
        cgal.distances(SurfacePoint::at_vertex(s), {SurfacePoint::at_vertex(t)}).front();
    const double hs = bound.at(local[s]);
    EXPECT_LE(hs, D) << s << " -> " << t;
    EXPECT_GT(hs, 0.94 * D) << s << " -> " << t << ": slope " << bound.slope << ", excess "
                            << bound.excess;
  }
}

// Along a grid line the edge path is the straight line: no bound is built (the straight
// distance is already exact), and none between a vertex and itself.
TEST(TargetBound, NoneForStraightPairs) {
  const Mesh mesh(test::grid(20, 20, 1.0));
  const WindowMesh wm = prepare_window_mesh(mesh);
  TargetBound bound;
  const std::vector<int>& local = wm.order.vertex_to_local;
  build_target_bound(wm, local[0], local[20], std::numeric_limits<double>::infinity(), {},
                     &bound);
  EXPECT_FALSE(bound.active);
  EXPECT_NEAR(bound.upper, 20.0, 1e-12);
  EXPECT_EQ(bound.at(local[0]), -std::numeric_limits<double>::infinity());
  build_target_bound(wm, local[5], local[5], std::numeric_limits<double>::infinity(), {}, &bound);
  EXPECT_FALSE(bound.active);
}

// The bound scales with the mesh: on the hills shrunk or grown by 1e30 and 1e37 it is the
// unit mesh's bound times the factor, to 1e-9 of U. At 1e+-30 the faces below the least limit
// take the slope^2 = num / den path, with no root or division; at 1e+-37 (edges beyond 1e-35
// and 1e35) that path would lose den's precision or overflow its cross products, and they take
// the slope as the steep faces do.
TEST(TargetBound, TheSameBoundAtEveryScale) {
  const TriangleSoup unit = test::hills(30, 6.0);
  const Mesh mesh(unit);
  const WindowMesh wm = prepare_window_mesh(mesh);
  const std::vector<int>& local = wm.order.vertex_to_local;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::mt19937 rng(17);
  std::uniform_int_distribution<int> pick(0, mesh.num_vertices() - 1);
  std::vector<std::pair<int, int>> pairs;
  while (pairs.size() < 16) {
    const int s = pick(rng), t = pick(rng);
    if (s != t) pairs.push_back({s, t});
  }
  TargetBound bound, scaled_bound;
  for (const double k : {1e-37, 1e-30, 1e30, 1e37}) {
    TriangleSoup soup = unit;
    for (Vec3& p : soup.points) p *= k;
    const Mesh scaled(soup);
    const WindowMesh swm = prepare_window_mesh(scaled);
    ASSERT_EQ(swm.order.vertex_to_local, local);
    int active = 0;
    for (const auto& [s, t] : pairs) {
      build_target_bound(wm, local[s], local[t], kInf, {}, &bound);
      build_target_bound(swm, local[s], local[t], kInf, {}, &scaled_bound);
      ASSERT_EQ(scaled_bound.active, bound.active) << k << ": " << s << " -> " << t;
      if (!bound.active) continue;
      ++active;
      EXPECT_NEAR(scaled_bound.upper / k, bound.upper, 1e-12 * bound.upper);
      EXPECT_TRUE(std::isfinite(bound.local_length));  // (step 1's straightening, scaled too)
      EXPECT_NEAR(scaled_bound.slope, bound.slope, 1e-12);
      for (int v = 0; v < mesh.num_vertices(); ++v) {
        const double h = bound.at(local[v]), hk = scaled_bound.at(local[v]);
        ASSERT_EQ(std::isfinite(hk), std::isfinite(h)) << k << ": vertex " << v;
        if (std::isfinite(h)) {
          EXPECT_NEAR(hk / k, h, 1e-9 * bound.upper) << k << ": vertex " << v;
        }
      }
    }
    EXPECT_GE(active, 6) << k;
  }
}

// A long, nearly straight pair gets the bound from its length alone (min_edges): on a plane U
// (edges and diagonals) is 1.023 |s t|, below min_detour, but 128 units is more than 60 longest
// edges (sqrt 2 each). Without min_edges, none; a short pair, none.
TEST(TargetBound, LongPairsGetTheBoundByLength) {
  const Mesh mesh(test::grid(120, 60, 1.0));
  const WindowMesh wm = prepare_window_mesh(mesh);
  const std::vector<int>& local = wm.order.vertex_to_local;
  const int s = 0, t = 121 * 40 + 119;  // (0, 0) -> (119, 40)
  const double chord = (mesh.position(s) - mesh.position(t)).norm();
  TargetBound bound;
  build_target_bound(wm, local[s], local[t], std::numeric_limits<double>::infinity(), {},
                     &bound);
  ASSERT_TRUE(bound.active);
  EXPECT_LT(bound.upper, TargetBoundOptions{}.min_detour * chord);
  const double hs = bound.at(local[s]);
  EXPECT_LE(hs, chord);  // the plane's distance
  EXPECT_GT(hs, 0.95 * chord);
  TargetBoundOptions by_detour;
  by_detour.min_edges = std::numeric_limits<double>::infinity();
  build_target_bound(wm, local[s], local[t], std::numeric_limits<double>::infinity(), by_detour,
                     &bound);
  EXPECT_FALSE(bound.active);
  build_target_bound(wm, local[s], local[121 * 10 + 30],
                     std::numeric_limits<double>::infinity(), {}, &bound);
  EXPECT_FALSE(bound.active);
}

// The level set's distance from t, against the segment worked out by hand, including a level
// set through a corner (found in review: the first two crossings were then that corner twice,
// and the distance was taken from it and the third crossing only, 1.414 for 1.265).
TEST(TargetBound, LevelSetDistance) {
  const Vec3 corner[3] = {Vec3(1, 1, 0), Vec3(-1, -1, 0), Vec3(1, -3, 0)};
  const Vec3 t(0, 0, 0);
  // Through corner 1: from (-1, -1) to the middle of edge 2 -> 0, (1, -1); nearest (0, -1).
  const double through[3] = {0.5, 1.0, 1.5};
  EXPECT_NEAR(level_set_distance(corner, through, 1.0, t), 1.0, 1e-12);
  // Across edge 0 -> 1 a quarter of the way, (0.5, 0.5), and edge 1 -> 2 three quarters of
  // the way, (0.5, -2.5): the segment x = 0.5, nearest (0.5, 0).
  const double across[3] = {0.0, 4.0, 0.0};
  EXPECT_NEAR(level_set_distance(corner, across, 1.0, t), 0.5, 1e-12);
  // Outside the values' range: no level set.
  EXPECT_EQ(level_set_distance(corner, through, 2.0, t), std::numeric_limits<double>::infinity());
}

TEST(TargetBound, OptionsAreChecked) {
  TargetBoundOptions o;
  std::string why;
  EXPECT_TRUE(o.is_valid(&why));
  o.min_detour = 0.9;
  EXPECT_FALSE(o.is_valid(&why));
  EXPECT_NE(why.find("min_detour"), std::string::npos);
  o = {};
  o.min_edges = -1.0;
  EXPECT_FALSE(o.is_valid(&why));
  EXPECT_NE(why.find("min_edges"), std::string::npos);
  for (const double bad : {0.5, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    o = {};
    o.clamp_slope = bad;
    EXPECT_FALSE(o.is_valid(&why)) << bad;
    EXPECT_NE(why.find("clamp_slope"), std::string::npos);
  }
  o = {};
  o.clamp_slope = 0.0;
  EXPECT_TRUE(o.is_valid(&why));
  const Mesh mesh(test::grid(4, 4, 1.0));
  const WindowMesh wm = prepare_window_mesh(mesh);
  WindowSearchOptions w;
  w.target_bound.min_detour = std::nan("");
  EXPECT_THROW(shortest_path_by_windows(mesh, wm, 0, 24, w), ConfigError);
}

// Step 1's straightened path: a surface path's length, so never below the distance (CGAL), never
// above the graph path's, and on these meshes usually the distance itself; the search below it
// finds the same distances as the A* search without it, with fewer windows.
TEST(TargetBound, StraightenedPathBoundsTheDistanceFromAbove) {
  for (const auto& [mesh, what] :
       {std::pair<Mesh, const char*>{Mesh(test::rough_torus(0.03, 11)), "rough torus"},
        std::pair<Mesh, const char*>{Mesh(test::hills(40, 6.0)), "hills"},
        std::pair<Mesh, const char*>{Mesh(test::torus(2.0, 0.7, 48, 20)), "torus"}}) {
    const WindowMesh wm = prepare_window_mesh(mesh);
    ExactGeodesic cgal(mesh);
    std::mt19937 rng(23);
    std::uniform_int_distribution<int> pick(0, mesh.num_vertices() - 1);
    TargetBoundOptions graph_only;
    graph_only.straighten_upper = false;
    WindowSearchOptions a_star;
    a_star.target_bound = graph_only;
    TargetBound straightened, graph;
    int pairs = 0, finite = 0, exact = 0;
    long with_windows = 0, without_windows = 0;
    for (int i = 0; i < 30; ++i) {
      const int s = pick(rng), t = pick(rng);
      if (s == t) continue;
      ++pairs;
      const std::vector<int>& local = wm.order.vertex_to_local;
      const double kInf = std::numeric_limits<double>::infinity();
      build_target_bound(wm, local[s], local[t], kInf, {}, &straightened);
      build_target_bound(wm, local[s], local[t], kInf, graph_only, &graph);
      EXPECT_FALSE(std::isfinite(graph.local_length)) << what;
      const double D =
          cgal.distances(SurfacePoint::at_vertex(s), {SurfacePoint::at_vertex(t)}).front();
      const double l = straightened.local_length;
      if (std::isfinite(l)) {
        ++finite;
        EXPECT_GE(l, D * (1.0 - 1e-12)) << what << " " << s << " -> " << t;
        EXPECT_LT(l, graph.upper) << what << " " << s << " -> " << t;
        EXPECT_EQ(straightened.upper, std::min(graph.upper, l * (1.0 + 1e-9))) << what;
        exact += l <= D * (1.0 + 1e-9);
      } else {
        EXPECT_EQ(straightened.upper, graph.upper) << what;
      }
      const WindowSearchResult below = shortest_path_by_windows(mesh, wm, s, t);
      const WindowSearchResult plain = shortest_path_by_windows(mesh, wm, s, t, a_star);
      ASSERT_TRUE(below.found && plain.found) << what << " " << s << " -> " << t;
      EXPECT_NEAR(below.distance, D, 1e-9 * D) << what << " " << s << " -> " << t;
      EXPECT_NEAR(plain.distance, D, 1e-9 * D) << what << " " << s << " -> " << t;
      with_windows += below.windows;
      without_windows += plain.windows;
    }
    std::printf("%s: %d pairs, %d straightened, %d of them to the distance; windows %ld, A* %ld\n",
                what, pairs, finite, exact, with_windows, without_windows);
    EXPECT_GE(finite, pairs * 9 / 10) << what;
    EXPECT_GE(exact, finite / 2) << what;
    EXPECT_LT(with_windows, without_windows) << what;
  }
}

// The bound changes the work, never the answer: the same distances with and without it, and
// fewer windows where pairs bend.
TEST(TargetBound, TheSearchFindsTheSameDistancesWithFewerWindows) {
  for (const auto& [mesh, what] :
       {std::pair<Mesh, const char*>{Mesh(test::rough_torus(0.03, 11)), "rough torus"},
        std::pair<Mesh, const char*>{Mesh(test::hills(40, 6.0)), "hills"}}) {
    const WindowMesh wm = prepare_window_mesh(mesh);
    std::mt19937 rng(17);
    std::uniform_int_distribution<int> pick(0, mesh.num_vertices() - 1);
    WindowSearchOptions without;
    without.use_target_bound = false;
    long with_windows = 0, without_windows = 0;
    std::pair<int, int> helped{-1, -1};  // the first pair the bound helped
    for (int i = 0; i < 40; ++i) {
      const int a = pick(rng), b = pick(rng);
      if (a == b) continue;
      const WindowSearchResult r1 = shortest_path_by_windows(mesh, wm, a, b);
      const WindowSearchResult r0 = shortest_path_by_windows(mesh, wm, a, b, without);
      ASSERT_TRUE(r1.found && r0.found) << what;
      EXPECT_NEAR(r1.distance, r0.distance, 1e-12 * r0.distance) << what << " " << a << " -> " << b;
      with_windows += r1.windows;
      without_windows += r0.windows;
      if (r1.windows < r0.windows && helped.first < 0) helped = {a, b};
    }
    EXPECT_LT(with_windows, without_windows) << what;
    // One search resumed from target to target builds a bound per target: from that pair's
    // source, to its target and to others.
    ASSERT_GE(helped.first, 0) << what;
    std::vector<int> targets = {helped.second};
    for (int k = 1; k <= 5; ++k) targets.push_back(k * mesh.num_vertices() / 6);
    const std::vector<WindowSearchResult> r1 =
        shortest_paths_by_windows(mesh, wm, helped.first, targets);
    const std::vector<WindowSearchResult> r0 =
        shortest_paths_by_windows(mesh, wm, helped.first, targets, without);
    long resumed_with = 0, resumed_without = 0;
    for (std::size_t i = 0; i < targets.size(); ++i) {
      if (targets[i] == helped.first) continue;
      ASSERT_TRUE(r1[i].found && r0[i].found) << what;
      EXPECT_NEAR(r1[i].distance, r0[i].distance, 1e-12 * r0[i].distance) << what;
      resumed_with += r1[i].windows;
      resumed_without += r0[i].windows;
    }
    EXPECT_LT(resumed_with, resumed_without) << what;
  }
}

}  // namespace
}  // namespace windplan
