// The CGAL exact reference (geometry/geodesic/exact_geodesic.cpp) against closed forms, and the
// geodesic core (geometry/geodesic/refine_path.h) against the exact reference: two independent
// implementations.
#include "geometry/geodesic/exact_geodesic.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/geodesic/geodesic.h"
#include "geometry/mesh/mesh_io.h"
#include "geometry/mesh/mesh_validation.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_data.h"

namespace windplan {
namespace {

// ---- the reference against closed forms ----

TEST(ExactGeodesic, PlaneGivesTheStraightDistance) {
  const Mesh mesh(test::grid(8, 6, 0.5));
  // Corners (0,0) and (4,3): vertex indices j * 9 + i.
  EXPECT_NEAR(
      exact_geodesic_distance(mesh, SurfacePoint::at_vertex(0), SurfacePoint::at_vertex(6 * 9 + 8)),
      std::hypot(4.0, 3.0), 1e-12);
}

TEST(ExactGeodesic, FaceAndEdgePointsMapToTheRightCoordinates) {
  // Non-symmetric barycentric coordinates in every face catch a wrong corner order.
  const Mesh mesh(test::grid(5, 5));
  ExactGeodesic exact(mesh);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.05, 1.0);
  for (int f = 0; f < mesh.num_faces(); f += 3) {
    Vec3 b(u(rng), u(rng), u(rng));
    b /= b.sum();
    const SurfacePoint p = SurfacePoint::in_face(f, b);
    const int g = (f * 7 + 5) % mesh.num_faces();
    Vec3 c(u(rng), 0.3 * u(rng), u(rng));
    c /= c.sum();
    const SurfacePoint q = SurfacePoint::in_face(g, c);
    const int h = (f * 5 + 1) % mesh.num_interior_halfedges();
    const SurfacePoint e = SurfacePoint::on_edge(h, 0.3);
    const std::vector<double> d = exact.distances(p, {q, e, SurfacePoint::at_vertex(35)});
    EXPECT_NEAR(d[0], (position(mesh, p) - position(mesh, q)).norm(), 1e-12) << "face " << f;
    EXPECT_NEAR(d[1], (position(mesh, p) - position(mesh, e)).norm(), 1e-12) << "face " << f;
    EXPECT_NEAR(d[2], (position(mesh, p) - mesh.position(35)).norm(), 1e-12) << "face " << f;
  }
}

TEST(ExactGeodesic, CylinderUnrollsIntoAStrip) {
  // Every quad of the polyhedral cylinder is a planar rectangle: the surface develops into a flat
  // strip of width n * chord, so the distance is the straight line there, the shorter way round.
  const int n = 24, m = 10;
  const double r = 2.0, len = 5.0;
  const Mesh mesh(test::open_cylinder(r, len, n, m));
  const double chord = 2.0 * r * std::sin(M_PI / n), dz = len / m;
  ExactGeodesic exact(mesh);
  for (const auto& [i1, j1, i2, j2] : std::vector<std::array<int, 4>>{
           {0, 0, 5, 7}, {3, 2, 20, 9}, {1, 10, 1, 0}, {0, 4, 12, 6}, {7, 1, 8, 10}}) {
    const int di = std::min(std::abs(i2 - i1), n - std::abs(i2 - i1));
    const double expected = std::hypot(di * chord, (j2 - j1) * dz);
    const std::vector<double> d = exact.distances(SurfacePoint::at_vertex(j1 * n + i1),
                                                  {SurfacePoint::at_vertex(j2 * n + i2)});
    EXPECT_NEAR(d[0], expected, 1e-11) << i1 << "," << j1 << " -> " << i2 << "," << j2;
    // The path polyline has the same length and runs from the source to the target.
    double length = 0.0;
    const std::vector<Vec3> path = exact.path(SurfacePoint::at_vertex(j1 * n + i1),
                                              SurfacePoint::at_vertex(j2 * n + i2), &length);
    ASSERT_GE(path.size(), 2u);
    EXPECT_NEAR((path.front() - mesh.position(j1 * n + i1)).norm(), 0.0, 1e-12);
    EXPECT_NEAR((path.back() - mesh.position(j2 * n + i2)).norm(), 0.0, 1e-12);
    double sum = 0.0;
    for (std::size_t k = 1; k < path.size(); ++k) sum += (path[k] - path[k - 1]).norm();
    EXPECT_NEAR(sum, expected, 1e-11);
    EXPECT_NEAR(length, expected, 1e-11);
  }
}

TEST(ExactGeodesic, OctahedronAroundTheVertex) {
  // Unit octahedron: from vertex +x to vertex -x, the geodesic crosses two faces through the
  // midpoint of an edge; the two faces unfold into a rhombus of side sqrt(2) with 60-degree
  // angles at the ends, whose long diagonal is sqrt(2) * sqrt(3).
  const Mesh mesh(test::octahedron());
  EXPECT_NEAR(exact_geodesic_distance(mesh, SurfacePoint::at_vertex(0), SurfacePoint::at_vertex(1)),
              std::sqrt(6.0), 1e-12);
  EXPECT_NEAR(exact_geodesic_distance(mesh, SurfacePoint::at_vertex(0), SurfacePoint::at_vertex(2)),
              std::sqrt(2.0), 1e-12);
}

TEST(ExactGeodesic, OtherComponentIsInfinitelyFar) {
  TriangleSoup soup = test::octahedron();
  const TriangleSoup second = test::octahedron();
  for (const Vec3& p : second.points) soup.points.push_back(p + Vec3(5, 0, 0));
  for (const Tri& t : second.triangles) soup.triangles.push_back({t[0] + 6, t[1] + 6, t[2] + 6});
  const Mesh mesh(soup);
  const std::vector<double> d = exact_geodesic_distances(
      mesh, SurfacePoint::at_vertex(0), {SurfacePoint::at_vertex(1), SurfacePoint::at_vertex(7)});
  EXPECT_NEAR(d[0], std::sqrt(6.0), 1e-12);
  EXPECT_TRUE(std::isinf(d[1]));
}

TEST(ExactGeodesic, OutOfRangePointsAreInputErrors) {
  const Mesh mesh(test::octahedron());
  EXPECT_THROW(
      exact_geodesic_distance(mesh, SurfacePoint::at_vertex(6), SurfacePoint::at_vertex(0)),
      InputError);
  EXPECT_THROW(exact_geodesic_distance(mesh, SurfacePoint::at_vertex(0),
                                       SurfacePoint::in_face(8, Vec3(1, 0, 0))),
               InputError);
  EXPECT_THROW(
      exact_geodesic_distance(mesh, SurfacePoint::on_edge(-1, 0.5), SurfacePoint::at_vertex(0)),
      InputError);
}

// ---- the geodesic core against the reference ----

/// Largest distance from the points of `a` to the polyline `b`.
double one_sided_distance(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double worst = 0.0;
  for (const Vec3& p : a) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k < b.size(); ++k) {
      const Vec3 d = b[k] - b[k - 1];
      const double t =
          std::clamp((p - b[k - 1]).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
      best = std::min(best, (p - (b[k - 1] + t * d)).norm());
    }
    worst = std::max(worst, best);
  }
  return worst;
}

struct Agreement {
  int pairs = 0;
  int same_geodesic = 0;   ///< the refined path lies on the exact one
  int within_1e4 = 0;      ///< relative excess <= 1e-4
  int other_geodesic = 0;  ///< a different, locally shortest geodesic (excess > 1e-4)
  double median = 0.0;     ///< median relative excess
  double min_excess = 0.0;
  double max_same_excess = 0.0;  ///< worst |excess| among the same-geodesic pairs
  int not_converged = 0;         ///< pairs whose summary is not converged()
};

/// `sources` random vertex sources with `per_source` random vertex targets each (fixed seed).
Agreement compare_with_exact(const Mesh& mesh, int sources, int per_source, unsigned seed,
                             GeodesicSolver solver) {
  const GeodesicContext ctx(mesh);
  ExactGeodesic exact(mesh);
  GeodesicOptions options;
  options.solver = solver;
  const double same_tol = 1e-6 * mesh.bounding_box().diagonal_length();
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> pick(0, mesh.num_vertices() - 1);
  Agreement a;
  std::vector<double> excess;
  for (int s = 0; s < sources; ++s) {
    const int v = pick(rng);
    for (int t = 0; t < per_source; ++t) {
      int w = pick(rng);
      while (w == v) w = pick(rng);
      const SurfacePoint pa = SurfacePoint::at_vertex(v), pb = SurfacePoint::at_vertex(w);
      double exact_length = 0.0;
      const std::vector<Vec3> exact_path = exact.path(pa, pb, &exact_length);
      const OpenGeodesicResult r = geodesic_between(ctx, pa, pb, options);
      std::string why;
      EXPECT_TRUE(is_valid_path(mesh, r.path, &why)) << why;
      const double length = euclidean_length(mesh, r.path);
      EXPECT_NEAR(length, r.summary.final_length, 1e-9 * length);
      const double e = (length - exact_length) / exact_length;
      excess.push_back(e);
      // A solver that stops without its convergence test (e.g. a failed line search) must at
      // least have stopped on the exact geodesic.
      if (!r.summary.converged()) ++a.not_converged;
      EXPECT_TRUE(r.summary.converged() || std::abs(e) < 1e-9)
          << v << " -> " << w << ": excess " << e << ", " << r.summary.brief_report();
      const std::vector<Vec3> ours = polyline(mesh, r.path);
      const bool same = one_sided_distance(ours, exact_path) < same_tol &&
                        one_sided_distance(exact_path, ours) < same_tol;
      ++a.pairs;
      if (same) {
        ++a.same_geodesic;
        a.max_same_excess = std::max(a.max_same_excess, std::abs(e));
        EXPECT_LT(std::abs(e), 1e-9) << "same geodesic, different length: vertex " << v << " -> "
                                     << w << ", ours " << length << ", exact " << exact_length;
      }
      if (e <= 1e-4) ++a.within_1e4;
      if (e > 1e-4) ++a.other_geodesic;
      EXPECT_GT(e, -1e-9) << "shorter than the exact geodesic: vertex " << v << " -> " << w
                          << ", ours " << length << ", exact " << exact_length;
    }
  }
  std::sort(excess.begin(), excess.end());
  a.median = excess[excess.size() / 2];
  a.min_excess = excess.front();
  return a;
}

void expect_agreement(const Agreement& a, const std::string& what) {
  std::cout << "[ " << what << " ] " << a.pairs << " pairs: " << a.same_geodesic
            << " on the exact geodesic (worst |excess| " << a.max_same_excess << "), "
            << a.other_geodesic << " on another geodesic, " << a.not_converged
            << " not converged; median excess " << a.median << ", min " << a.min_excess << "\n";
  EXPECT_GE(a.within_1e4, (9 * a.pairs + 9) / 10) << what;
  EXPECT_LE(a.median, 1e-6) << what;
  EXPECT_GE(a.min_excess, -1e-9) << what;
  // Most pairs find the exact geodesic itself (guards the "same geodesic" test from being vacuous).
  EXPECT_GE(a.same_geodesic, a.pairs / 3) << what;
}

/// A bumpy height field z = amp * sin(x) * sin(y) over a grid (an open disc with saddles and
/// bumps, no symmetric ties between geodesics).
TriangleSoup bumpy(int n, double size, double amp) {
  TriangleSoup s = test::grid(n, n, size / n);
  for (Vec3& p : s.points) p.z() = amp * std::sin(1.3 * p.x()) * std::sin(0.9 * p.y() + 0.4);
  return s;
}

class ExactAgreement : public ::testing::TestWithParam<GeodesicSolver> {};

TEST_P(ExactAgreement, Sphere) {
  const Mesh mesh(test::uv_sphere(1.0, 48, 32));
  expect_agreement(compare_with_exact(mesh, 6, 5, 11, GetParam()), "sphere");
}

TEST_P(ExactAgreement, Torus) {
  const Mesh mesh(test::torus(2.0, 0.7, 64, 24));
  expect_agreement(compare_with_exact(mesh, 6, 5, 12, GetParam()), "torus");
}

TEST_P(ExactAgreement, BumpySurface) {
  const Mesh mesh(bumpy(40, 8.0, 0.8));
  expect_agreement(compare_with_exact(mesh, 6, 5, 13, GetParam()), "bumpy");
}

TEST_P(ExactAgreement, Bunny20k) {
  WINDPLAN_REQUIRE_SHARED_MESH(file, "derived/bunny-remesh-20k.obj");
  const Mesh mesh = build_mesh(read_mesh(file), false);
  expect_agreement(compare_with_exact(mesh, 5, 8, 14, GetParam()), "bunny-20k");
}

INSTANTIATE_TEST_SUITE_P(Solvers, ExactAgreement,
                         ::testing::Values(GeodesicSolver::Newton, GeodesicSolver::Lbfgs),
                         [](const auto& info) {
                           return info.param == GeodesicSolver::Newton ? "Newton" : "Lbfgs";
                         });

}  // namespace
}  // namespace windplan
