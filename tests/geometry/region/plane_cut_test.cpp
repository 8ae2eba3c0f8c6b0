// cut_at_stations: the cut lies on the planes to rounding, no face straddles a plane, the mesh
// stays a closed oriented manifold with its area and volume, and no sliver is created.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/cad/cad_shape.h"
#include "geometry/cad/parametric_mandrel.h"
#include "geometry/cad/tessellate.h"
#include "geometry/region/plane_cut.h"

namespace windplan {
namespace {

Mesh tessellated(const CadShape& s) { return Mesh(tessellate(s).soup); }

double volume(const Mesh& m) {
  double v = 0.0;
  for (const Tri& t : m.triangles()) {
    v += m.position(t[0]).dot(m.position(t[1]).cross(m.position(t[2])));
  }
  return v / 6.0;
}

TEST(PlaneCut, CutsAVesselExactlyOnTwoStations) {
  VesselParams vp;  // R 100, L 300, hemispherical domes to r = 30
  const Mesh in = tessellated(make_vessel(vp));
  SpindleAxis axis;
  const std::vector<double> st{37.25, 251.5};
  const PlaneCutResult r = cut_at_stations(in, axis, st);
  const Mesh& m = r.mesh;
  EXPECT_TRUE(m.is_closed());
  EXPECT_EQ(m.num_components(), 1);
  EXPECT_EQ(m.genus(), 0);
  EXPECT_GT(r.split_edges, 0);
  EXPECT_NEAR(m.total_area(), in.total_area(), 1e-9 * in.total_area());
  EXPECT_NEAR(volume(m), volume(in), 1e-9 * volume(in));
  // No face straddles a plane; vertices on a plane are on it to 1e-9 mm.
  int on_plane = 0;
  for (const Vec3& p : m.points()) {
    for (double s : st) {
      if (std::abs(p.z() - s) < 1e-6) {
        EXPECT_LT(std::abs(p.z() - s), 1e-9);
        ++on_plane;
      }
    }
  }
  EXPECT_GE(on_plane, r.split_edges);
  for (int f = 0; f < m.num_faces(); ++f) {
    for (double s : st) {
      double lo = 1e300, hi = -1e300;
      for (int v : m.triangle(f)) {
        lo = std::min(lo, m.position(v).z() - s);
        hi = std::max(hi, m.position(v).z() - s);
      }
      EXPECT_FALSE(lo < -1e-9 && hi > 1e-9) << "face " << f << " straddles z = " << s;
    }
  }
  // Parents: every face lies in its input face's plane.
  for (int f = 0; f < m.num_faces(); ++f) {
    const int p = r.face_parent[f];
    const Vec3 n = in.face_normal(p), o = in.position(in.triangle(p)[0]);
    for (int v : m.triangle(f)) EXPECT_NEAR((m.position(v) - o).dot(n), 0.0, 1e-9);
  }
}

TEST(PlaneCut, NoSliverNearAVertexRing) {
  // A plane 1e-3 mm above a ring of vertices of a fine pipe: those vertices move onto it
  // instead of leaving 1e-3 mm triangles behind.
  const Mesh in = tessellated(make_pipe(PipeParams{50.0, 500.0}));
  SpindleAxis axis;
  const double s = 1e-3;
  PlaneCutOptions o;
  o.min_fraction = 0.05;
  const PlaneCutResult r = cut_at_stations(in, axis, {s}, o);
  EXPECT_GT(r.moved_vertices, 0);
  EXPECT_LE(r.max_move, s * (1.0 + 1e-9) + 1e-12);
  const auto in_stats = in.edge_length_stats();
  const auto stats = r.mesh.edge_length_stats();
  EXPECT_GE(stats[0], 0.5 * o.min_fraction * in_stats[0]) << "no new edge is a sliver edge";
  EXPECT_TRUE(r.mesh.is_closed());
  for (int f = 0; f < r.mesh.num_faces(); ++f) EXPECT_GT(r.mesh.face_area(f), 0.0);
  // With min_fraction 0 the same cut splits instead: tiny triangles appear.
  o.min_fraction = 0.0;
  const PlaneCutResult raw = cut_at_stations(in, axis, {s}, o);
  EXPECT_EQ(raw.moved_vertices, 0);
  EXPECT_LT(raw.mesh.edge_length_stats()[0], 0.01);
}

TEST(PlaneCut, PlaneThroughVerticesSplitsNothing) {
  const Mesh in = tessellated(make_pipe(PipeParams{50.0, 500.0}));
  const PlaneCutResult r = cut_at_stations(in, SpindleAxis{}, {0.0, 500.0});
  EXPECT_EQ(r.split_edges, 0);
  EXPECT_EQ(r.mesh.num_faces(), in.num_faces());
}

TEST(PlaneCut, RejectsBadOptions) {
  const Mesh in = tessellated(make_pipe(PipeParams{50.0, 500.0}));
  PlaneCutOptions o;
  o.min_fraction = 0.5;
  EXPECT_THROW(cut_at_stations(in, SpindleAxis{}, {1.0}, o), ConfigError);
}

}  // namespace
}  // namespace windplan
