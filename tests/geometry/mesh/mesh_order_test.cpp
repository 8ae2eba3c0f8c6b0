#include "geometry/mesh/mesh_order.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

// Median over the faces' corner pairs of the distance between their indices.
double median_index_gap(const Mesh& m) {
  std::vector<int> gap;
  for (int f = 0; f < m.num_faces(); ++f) {
    const Tri& t = m.triangle(f);
    for (int k = 0; k < 3; ++k) gap.push_back(std::abs(t[k] - t[(k + 1) % 3]));
  }
  std::nth_element(gap.begin(), gap.begin() + gap.size() / 2, gap.end());
  return gap[gap.size() / 2];
}

void expect_same_surface(const Mesh& original, const MeshOrder& o) {
  const Mesh& local = o.mesh;
  ASSERT_EQ(local.num_vertices(), original.num_vertices());
  ASSERT_EQ(local.num_faces(), original.num_faces());
  ASSERT_EQ(local.num_halfedges(), original.num_halfedges());
  for (int v = 0; v < local.num_vertices(); ++v) {
    ASSERT_EQ(o.vertex_to_local[o.vertex_from_local[v]], v);
    EXPECT_EQ(local.position(v), original.position(o.vertex_from_local[v])) << "vertex " << v;
  }
  std::vector<int> seen(original.num_halfedges(), 0);
  for (int h = 0; h < local.num_halfedges(); ++h) {
    const int g = o.halfedge_from_local(original, h);
    ASSERT_GE(g, 0);
    ++seen[g];
    EXPECT_EQ(original.from(g), o.vertex_from_local[local.from(h)]) << "halfedge " << h;
    EXPECT_EQ(original.to(g), o.vertex_from_local[local.to(h)]) << "halfedge " << h;
    EXPECT_EQ(original.is_boundary_halfedge(g), local.is_boundary_halfedge(h));
    if (!local.is_boundary_halfedge(h)) {
      EXPECT_EQ(original.face(g), o.face_from_local[local.face(h)]);
      // Every length and angle is the original's, bit for bit.
      EXPECT_EQ(local.corner_angle(h), original.corner_angle(g));
      EXPECT_EQ(local.halfedge_length(h), original.halfedge_length(g));
    }
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
}

TEST(MeshOrder, AShuffledGridWithAHoleIsTheSameSurfaceWithNeighboursNearInMemory) {
  // A 60 x 60 grid with its middle faces removed: boundary halfedges inside and outside.
  TriangleSoup soup = test::grid(60, 60, 0.5);
  TriangleSoup holed;
  holed.points = soup.points;
  for (const Tri& t : soup.triangles) {
    const Vec3 c = (soup.points[t[0]] + soup.points[t[1]] + soup.points[t[2]]) / 3.0;
    if ((c - Vec3(15, 15, 0)).norm() > 5.0) holed.triangles.push_back(t);
  }
  const Mesh original(test::renumbered_at_random(holed, 7));
  const MeshOrder o = order_for_locality(original);
  expect_same_surface(original, o);
  // At random the corners of a face lie about a third of the mesh apart; in Morton order a
  // few rows at most.
  const double before = median_index_gap(original), after = median_index_gap(o.mesh);
  EXPECT_GT(before, 500.0);
  EXPECT_LT(after, 0.05 * before) << "median index gap " << before << " -> " << after;
}

TEST(MeshOrder, ClosedTorusAndPathsMapBack) {
  const Mesh original(test::renumbered_at_random(test::torus(3.0, 1.0, 40, 20), 11));
  const MeshOrder o = order_for_locality(original);
  expect_same_surface(original, o);
  // A path on the copy (a straight walk of crossings around the local vertex 0's first face)
  // and its image on the original: the same polyline.
  SurfacePath p;
  p.start = SurfacePoint::at_vertex(o.mesh.from(0));
  p.start_face = 0;
  int h = 1;  // the edge of face 0 opposite its first corner
  for (int i = 0; i < 6; ++i) {
    p.halfedges.push_back(h);
    p.lambdas.push_back(0.3 + 0.05 * i);
    h = o.mesh.next(o.mesh.twin(h));
  }
  p.end = SurfacePoint::in_face(o.mesh.face(o.mesh.twin(p.halfedges.back())), Vec3(0.2, 0.3, 0.5));
  const SurfacePath q = o.path_from_local(original, p);
  const std::vector<Vec3> a = polyline(o.mesh, p), b = polyline(original, q);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << "point " << i;
  EXPECT_EQ(strip_face(original, q, 0), o.face_from_local[strip_face(o.mesh, p, 0)]);
  const SurfacePoint e = o.point_from_local(original, SurfacePoint::on_edge(5, 0.25));
  EXPECT_EQ(position(original, e), position(o.mesh, SurfacePoint::on_edge(5, 0.25)));
}

}  // namespace
}  // namespace windplan
