// Landmark fields and their bound over an edge interval (geometry/geodesic/window_landmarks.cpp)
// against CGAL's exact distances. (The window search with landmarks is checked against CGAL in
// geometry/geodesic/geodesic_windows_test.cpp.)
#include "geometry/geodesic/window_landmarks.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "geometry/geodesic/exact_geodesic.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

TEST(WindowSearch, LandmarkEdgeBoundIsALowerBound) {
  const Mesh mesh(test::rough_torus(0.03, 11));
  const WindowMesh wm = prepare_window_mesh(mesh);
  const Landmarks marks = compute_landmarks(mesh, wm, 4);
  ASSERT_EQ(marks.count, 4);
  ExactGeodesic cgal(mesh);
  std::mt19937 rng(31);
  std::uniform_int_distribution<int> pick_h(0, mesh.num_interior_halfedges() - 1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int checked = 0, tight = 0, sharper = 0;
  for (const int t : {5, 400, 901}) {
    const double* td = marks.dist.data() + static_cast<std::size_t>(t) * marks.count;
    std::vector<SurfacePoint> points;
    struct Sample {
      int h;
      double s0, s1;
    };
    std::vector<Sample> samples;
    constexpr int kPerInterval = 9;
    for (int i = 0; i < 60; ++i) {
      const int h = pick_h(rng);
      double t0 = u(rng), t1 = u(rng);
      if (t0 > t1) std::swap(t0, t1);
      if (i % 3 == 0) t0 = 0.0, t1 = 1.0;  // whole edges too
      const double len = mesh.halfedge_length(h);
      samples.push_back({h, t0 * len, t1 * len});
      for (int j = 0; j < kPerInterval; ++j)
        points.push_back(SurfacePoint::on_edge(h, t0 + (t1 - t0) * j / (kPerInterval - 1)));
    }
    const std::vector<double> exact = cgal.distances(SurfacePoint::at_vertex(t), points);
    for (std::size_t i = 0; i < samples.size(); ++i) {
      const Sample& sm = samples[i];
      const int a = mesh.from(sm.h), b = mesh.to(sm.h);
      const double len = mesh.halfedge_length(sm.h);
      const double bound = landmark_edge_bound(marks, td, a, b, len, sm.s0, sm.s1);
      double nearest = std::numeric_limits<double>::infinity();
      for (int j = 0; j < kPerInterval; ++j) {
        const double d = exact[i * kPerInterval + j];
        EXPECT_LE(bound, d * (1.0 + 1e-12) + 1e-12)
            << "target " << t << " halfedge " << sm.h << " [" << sm.s0 << ", " << sm.s1 << "]";
        nearest = std::min(nearest, d);
        ++checked;
      }
      // The per-end bracket the search used before (any x is within s1 of a, length - s0 of b).
      const double* la = marks.dist.data() + static_cast<std::size_t>(a) * marks.count;
      const double* lb = marks.dist.data() + static_cast<std::size_t>(b) * marks.count;
      double plain = 0.0;
      for (int k = 0; k < marks.count; ++k) {
        const double upper = std::min(la[k] + sm.s1, lb[k] + len - sm.s0);
        const double lower = std::max(la[k] - sm.s1, lb[k] - (len - sm.s0));
        plain = std::max({plain, td[k] - upper, lower - td[k]});
      }
      EXPECT_GE(bound, plain - 1e-12);
      if (bound > plain + 1e-9) ++sharper;
      if (bound > 0.5 * nearest) ++tight;
    }
  }
  EXPECT_EQ(checked, 3 * 60 * 9);
  EXPECT_GT(tight, 60);    // 4 landmarks on a torus bound most pairs to within 2x
  EXPECT_GT(sharper, 10);  // and the interval's own bracket beats the per-end one
}

}  // namespace
}  // namespace windplan
