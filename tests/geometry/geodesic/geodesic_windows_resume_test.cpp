// One exact window search resumed from target to target (geometry/geodesic/
// geodesic_windows_resume.cpp) against CGAL's exact tree from the source, against a search per
// target, and through geodesics_from against geodesic_between pair by pair.
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/geodesic/exact_geodesic.h"
#include "geometry/geodesic/geodesic.h"
#include "geometry/geodesic/geodesic_windows.h"
#include "geometry/geodesic/window_landmarks.h"
#include "geometry/mesh/mesh_io.h"
#include "geometry/mesh/mesh_validation.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_data.h"

namespace windplan {
namespace {

/// shortest_paths_by_windows from each of `sources` to `count` random targets (with a repeat,
/// the source itself and the other sources among them) against CGAL's tree from the source:
/// every distance, corridor and count. Returns the windows made, summed over the sources.
long expect_resumed_equal_to_cgal(const Mesh& mesh, const std::vector<int>& sources, int count,
                                  unsigned seed, const std::string& what,
                                  const WindowSearchOptions& options = {},
                                  const Landmarks* marks = nullptr) {
  const WindowMesh wm = prepare_window_mesh(mesh);
  ExactGeodesic cgal(mesh);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, mesh.num_vertices() - 1);
  long windows = 0;
  for (const int a : sources) {
    std::vector<int> targets;
    for (int k = 0; k < count; ++k) targets.push_back(pick(rng));
    targets.push_back(targets.front());
    targets.push_back(a);
    for (const int b : sources) targets.push_back(b);
    std::vector<SurfacePoint> points;
    for (const int b : targets) points.push_back(SurfacePoint::at_vertex(b));
    const std::vector<double> exact = cgal.distances(SurfacePoint::at_vertex(a), points);
    const std::vector<WindowSearchResult> r =
        shortest_paths_by_windows(mesh, wm, a, targets, options, marks);
    EXPECT_EQ(r.size(), targets.size());
    for (std::size_t i = 0; i < targets.size(); ++i) {
      const int b = targets[i];
      if (b == a) {
        EXPECT_FALSE(r[i].found);
        continue;
      }
      if (!r[i].found) {
        ADD_FAILURE() << what << " " << a << " -> " << b << ": not found";
        continue;
      }
      EXPECT_TRUE(r[i].complete);
      EXPECT_NEAR(r[i].distance, exact[i], 1e-12 * exact[i]) << what << " " << a << " -> " << b;
      std::string why;
      if (!is_valid_path(mesh, r[i].path, &why)) {
        ADD_FAILURE() << what << " " << a << " -> " << b << ": " << why;
        continue;
      }
      EXPECT_EQ(r[i].path.start.element, a);
      EXPECT_EQ(r[i].path.end.element, b);
      const GeodesicResult refined = refine_path(mesh, r[i].path);
      EXPECT_NEAR(refined.summary.final_length, exact[i], 1e-9 * exact[i])
          << what << " " << a << " -> " << b << ": " << refined.summary.brief_report();
      windows += r[i].windows;
    }
  }
  return windows;
}

// One search resumed from target to target gives each target's exact distance and corridor,
// also through vertices an earlier target's search stopped at (a target that is a saddle is
// expanded for the later ones), with landmarks, and when every target starts afresh; and it
// makes fewer windows than a search per target.
TEST(WindowSearch, ResumedSearchEqualsCgalTargetAfterTarget) {
  const Mesh hill(test::hills(30, 6.0));
  const Mesh torus(test::rough_torus(0.03, 11));
  const long resumed = expect_resumed_equal_to_cgal(hill, {5, 400, 811}, 12, 21, "hills");
  expect_resumed_equal_to_cgal(torus, {0, 77, 300}, 12, 22, "rough torus");
  WindowSearchOptions fresh;
  fresh.resume_limit = 0;
  const long separate =
      expect_resumed_equal_to_cgal(hill, {5, 400, 811}, 12, 21, "hills, afresh", fresh);
  EXPECT_LT(resumed, separate);
  const WindowMesh wm = prepare_window_mesh(torus);
  const Landmarks marks = compute_landmarks(torus, wm, 4);
  expect_resumed_equal_to_cgal(torus, {3, 500}, 12, 23, "rough torus, landmarks", {}, &marks);
}

// A target's search stopped by max_windows leaves a state the next target's search goes on
// from: every search that completes is exact.
TEST(WindowSearch, ResumedSearchAfterAWindowLimit) {
  const Mesh mesh(test::hills(30, 6.0));
  const WindowMesh wm = prepare_window_mesh(mesh);
  ExactGeodesic cgal(mesh);
  const int a = 400;
  std::vector<int> targets;
  std::vector<SurfacePoint> points;
  for (int b = 7; b < mesh.num_vertices(); b += 53) {
    targets.push_back(b);
    points.push_back(SurfacePoint::at_vertex(b));
  }
  const std::vector<double> exact = cgal.distances(SurfacePoint::at_vertex(a), points);
  WindowSearchOptions options;
  options.max_windows = 400;
  const std::vector<WindowSearchResult> r =
      shortest_paths_by_windows(mesh, wm, a, targets, options);
  int stopped = 0, complete = 0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (!r[i].complete) {
      ++stopped;
      EXPECT_FALSE(r[i].found);
      continue;
    }
    ++complete;
    ASSERT_TRUE(r[i].found) << a << " -> " << targets[i];
    EXPECT_NEAR(r[i].distance, exact[i], 1e-12 * exact[i]) << a << " -> " << targets[i];
  }
  EXPECT_GT(stopped, 0);
  EXPECT_GT(complete, 0);
  // In the order of the search (nearest in space first), a target completes after one that
  // stopped: a stopped search leaves a state the next one goes on from.
  std::vector<int> turn(targets.size());
  for (std::size_t i = 0; i < turn.size(); ++i) turn[i] = static_cast<int>(i);
  const Vec3& pa = mesh.position(a);
  std::stable_sort(turn.begin(), turn.end(), [&](int i, int j) {
    return (mesh.position(targets[i]) - pa).squaredNorm() <
           (mesh.position(targets[j]) - pa).squaredNorm();
  });
  bool stopped_before = false, completed_after = false;
  for (const int i : turn) {
    if (!r[i].complete) stopped_before = true;
    if (stopped_before && r[i].complete) completed_after = true;
  }
  EXPECT_TRUE(completed_after);
}

// Every target keyed afresh: on a flat grid (where the Euclidean bound is the distance) with
// landmark bounds and searches started afresh once they hold `resume_limit` windows' worth of
// memory (slots and a quarter of the path records; a limit the grid's searches pass, so that
// they restart: more windows than one search resumed throughout), and under an upper
// bound, which a resumed search keeps for every target (a target beyond it in space costs no
// propagation; found in review: retarget had dropped the bound).
TEST(WindowSearch, ResumedSearchOnAFlatGridWithLandmarks) {
  const Mesh grid(test::grid(20, 20));
  const WindowMesh wm = prepare_window_mesh(grid);
  const Landmarks marks = compute_landmarks(grid, wm, 4);
  WindowSearchOptions options;
  options.resume_limit = 120;
  const long restarted = expect_resumed_equal_to_cgal(grid, {17, 212, 398}, 30, 31,
                                                      "grid, landmarks", options, &marks);
  const long resumed =
      expect_resumed_equal_to_cgal(grid, {17, 212, 398}, 30, 31, "grid, landmarks", {}, &marks);
  EXPECT_GT(restarted, resumed);
  expect_resumed_equal_to_cgal(grid, {0, 220}, 30, 32, "grid", options);
}

TEST(WindowSearch, ResumedSearchUnderAnUpperBound) {
  const Mesh mesh(test::hills(30, 6.0));
  const WindowMesh wm = prepare_window_mesh(mesh);
  ExactGeodesic cgal(mesh);
  std::mt19937 rng(71);
  std::uniform_int_distribution<int> pick(0, mesh.num_vertices() - 1);
  int found = 0, beyond = 0;
  for (const double bound : {0.8, 1.5, 3.0}) {
    WindowSearchOptions options;
    options.upper_bound = bound;
    for (const int a : {5, 400, 811}) {
      std::vector<int> targets;
      std::vector<SurfacePoint> points;
      for (int k = 0; k < 20; ++k) {
        targets.push_back(pick(rng));
        points.push_back(SurfacePoint::at_vertex(targets.back()));
      }
      const std::vector<double> exact = cgal.distances(SurfacePoint::at_vertex(a), points);
      const std::vector<WindowSearchResult> r =
          shortest_paths_by_windows(mesh, wm, a, targets, options);
      for (std::size_t i = 0; i < targets.size(); ++i) {
        if (targets[i] == a) continue;
        EXPECT_TRUE(r[i].complete);
        EXPECT_EQ(r[i].found, exact[i] < bound) << a << " -> " << targets[i];
        if (r[i].found) {
          ++found;
          EXPECT_NEAR(r[i].distance, exact[i], 1e-12 * exact[i]) << a << " -> " << targets[i];
        }
        if ((mesh.position(targets[i]) - mesh.position(a)).norm() >= bound) {
          ++beyond;
          // (The search's first target lights the edges around the source.)
          EXPECT_LE(r[i].windows, mesh.valence(a))
              << a << " -> " << targets[i] << " beyond " << bound;
        }
      }
    }
  }
  EXPECT_GT(found, 10);
  EXPECT_GT(beyond, 10);
}

TEST(WindowSearch, ResumedSearchBadInputIsNamed) {
  const Mesh mesh(test::octahedron());
  const WindowMesh wm = prepare_window_mesh(mesh);
  EXPECT_THROW(shortest_paths_by_windows(mesh, wm, 0, {2, 6}), InputError);
  EXPECT_THROW(shortest_paths_by_windows(mesh, wm, 7, {2}), InputError);
  const Mesh other(test::grid(2, 2));
  EXPECT_THROW(shortest_paths_by_windows(other, wm, 0, {2}), ConfigError);
  WindowSearchOptions options;
  options.resume_limit = -1;
  EXPECT_THROW(shortest_paths_by_windows(mesh, wm, 0, {2}, options), ConfigError);
}

/// geodesics_from `a` to `targets` against geodesic_between pair by pair: the same lengths
/// (to round-off of the refined corridors) and the same exactness.
void expect_from_equals_between(const Mesh& mesh, int a, const std::vector<SurfacePoint>& targets,
                                const std::string& what) {
  const GeodesicContext ctx(mesh);
  const SurfacePoint pa = SurfacePoint::at_vertex(a);
  const std::vector<OpenGeodesicResult> all = geodesics_from(ctx, pa, targets);
  ASSERT_EQ(all.size(), targets.size());
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const OpenGeodesicResult one = geodesic_between(ctx, pa, targets[i]);
    EXPECT_TRUE(all[i].summary.converged()) << what << " target " << i;
    EXPECT_NEAR(all[i].summary.final_length, one.summary.final_length,
                1e-12 * (1.0 + one.summary.final_length))
        << what << " target " << i;
    EXPECT_EQ(all[i].exact_complete, one.exact_complete) << what << " target " << i;
    EXPECT_EQ(all[i].start, one.start) << what << " target " << i;
  }
}

// Vertex targets share one resumed window search; a face point and the source itself are
// answered as geodesic_between answers them.
TEST(GeodesicBetween, FromOneSourceEqualsOnePairAtATime) {
  const Mesh mesh(test::hills(30, 6.0));
  std::vector<SurfacePoint> targets;
  for (const int b : {900, 17, 511, 950, 17, 263}) targets.push_back(SurfacePoint::at_vertex(b));
  targets.push_back(SurfacePoint::in_face(700, Vec3(0.2, 0.3, 0.5)));
  targets.push_back(SurfacePoint::at_vertex(400));
  expect_from_equals_between(mesh, 400, targets, "hills");
}

TEST(GeodesicBetween, FromOneSourceOnBunny20k) {
  WINDPLAN_REQUIRE_SHARED_MESH(file, "derived/bunny-remesh-20k.obj");
  const Mesh mesh = build_mesh(read_mesh(file), false);
  // bench_geodesic's first sources and targets (seed 20240611).
  std::vector<SurfacePoint> targets;
  for (const int b : {7891, 2099, 8780, 7392, 2097}) targets.push_back(SurfacePoint::at_vertex(b));
  expect_from_equals_between(mesh, 5172, targets, "bunny-20k");
}

}  // namespace
}  // namespace windplan
