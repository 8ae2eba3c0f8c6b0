#include "geometry/mesh/mesh.h"

#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

void expect_connectivity_invariants(const Mesh& m) {
  for (int h = 0; h < m.num_halfedges(); ++h) {
    ASSERT_EQ(m.twin(m.twin(h)), h);
    ASSERT_NE(m.twin(h), h);
    EXPECT_EQ(m.from(m.twin(h)), m.to(h));
    EXPECT_EQ(m.to(m.twin(h)), m.from(h));
    EXPECT_EQ(m.next(m.prev(h)), h);
    EXPECT_EQ(m.from(m.next(h)), m.to(h));
    EXPECT_EQ(m.edge(h), m.edge(m.twin(h)));
    EXPECT_FALSE(m.is_boundary_halfedge(h) && m.is_boundary_halfedge(m.twin(h)));
  }
  for (int e = 0; e < m.num_edges(); ++e) {
    EXPECT_EQ(m.edge(m.edge_halfedge(e)), e);
    EXPECT_GE(m.face(m.edge_halfedge(e)), 0);
  }
  for (int v = 0; v < m.num_vertices(); ++v) {
    const int h = m.vertex_halfedge(v);
    if (h < 0) continue;
    EXPECT_EQ(m.from(h), v);
    for (int g : m.outgoing_halfedges(v)) EXPECT_EQ(m.from(g), v);
  }
}

TEST(Mesh, OctahedronCountsAndGeometry) {
  const Mesh m(test::octahedron());
  expect_connectivity_invariants(m);
  EXPECT_EQ(m.num_vertices(), 6);
  EXPECT_EQ(m.num_faces(), 8);
  EXPECT_EQ(m.num_edges(), 12);
  EXPECT_TRUE(m.is_closed());
  EXPECT_EQ(m.euler_characteristic(), 2);
  EXPECT_EQ(m.genus(), 0);
  EXPECT_EQ(m.num_components(), 1);
  EXPECT_TRUE(m.boundary_loops().empty());
  // Equilateral faces of side sqrt(2): area sqrt(3)/2, every corner pi/3, cone angle 4 pi/3.
  for (int f = 0; f < 8; ++f) {
    EXPECT_NEAR(m.face_area(f), std::sqrt(3.0) / 2.0, 1e-14);
    EXPECT_NEAR(m.face_normal(f).dot(m.face_centroid(f).normalized()), 1.0, 1e-14);
  }
  for (int h = 0; h < 24; ++h) EXPECT_NEAR(m.corner_angle(h), M_PI / 3.0, 1e-14);
  for (int v = 0; v < 6; ++v) {
    EXPECT_NEAR(m.cone_angle(v), 4.0 * M_PI / 3.0, 1e-13);
    EXPECT_EQ(m.vertex_type(v), VertexType::Spherical);
    EXPECT_EQ(m.valence(v), 4);
    EXPECT_NEAR(m.vertex_normal(v).dot(m.position(v)), 1.0, 1e-13);
  }
  const auto stats = m.edge_length_stats();
  EXPECT_NEAR(stats[0], std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(stats[2], std::sqrt(2.0), 1e-14);
  const BoundingBox box = m.bounding_box();
  EXPECT_EQ(box.min, Vec3(-1, -1, -1));
  EXPECT_EQ(box.max, Vec3(1, 1, 1));
}

TEST(Mesh, GridHasOneBoundaryLoopAndEuclideanInterior) {
  const Mesh m(test::grid(4, 3));
  expect_connectivity_invariants(m);
  EXPECT_EQ(m.num_vertices(), 20);
  EXPECT_EQ(m.num_faces(), 24);
  EXPECT_EQ(m.num_edges(), 4 * 4 + 5 * 3 + 12);
  EXPECT_EQ(m.euler_characteristic(), 1);
  const auto loops = m.boundary_loops();
  ASSERT_EQ(loops.size(), 1u);
  EXPECT_EQ(loops[0].size(), 14u);
  EXPECT_EQ(m.genus(), 0);
  EXPECT_NEAR(m.total_area(), 12.0, 1e-12);
  int interior = 0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    if (m.is_boundary_vertex(v)) {
      EXPECT_EQ(m.vertex_type(v), VertexType::Boundary);
    } else {
      ++interior;
      EXPECT_EQ(m.vertex_type(v), VertexType::Euclidean);
      EXPECT_NEAR(m.cone_angle(v), 2 * M_PI, 1e-12);
    }
  }
  EXPECT_EQ(interior, 6);
  // The boundary loop runs with the interior on its left when seen from +z... i.e. the
  // boundary halfedges are opposite to the face halfedges: clockwise seen from +z.
  double signed_area = 0.0;
  for (int h : loops[0]) {
    const Vec3& a = m.position(m.from(h));
    const Vec3& b = m.position(m.to(h));
    signed_area += 0.5 * (a.x() * b.y() - b.x() * a.y());
  }
  EXPECT_NEAR(signed_area, -12.0, 1e-12);
}

TEST(Mesh, OpenCylinderIsAnAnnulus) {
  const Mesh m(test::open_cylinder(1.0, 2.0, 16, 4));
  expect_connectivity_invariants(m);
  EXPECT_EQ(m.boundary_loops().size(), 2u);
  EXPECT_EQ(m.euler_characteristic(), 0);
  EXPECT_EQ(m.genus(), 0);
  for (const auto& loop : m.boundary_loops()) EXPECT_EQ(loop.size(), 16u);
}

TEST(Mesh, TorusHasGenusOne) {
  const Mesh m(test::torus(3.0, 1.0, 24, 12));
  expect_connectivity_invariants(m);
  EXPECT_TRUE(m.is_closed());
  EXPECT_EQ(m.euler_characteristic(), 0);
  EXPECT_EQ(m.genus(), 1);
  // Outer equator vertices are spherical (positive curvature), inner ones are saddles.
  EXPECT_EQ(m.vertex_type(0), VertexType::Spherical);    // j = 0: outer equator
  EXPECT_EQ(m.vertex_type(6 * 24), VertexType::Saddle);  // j = 6: inner equator
}

TEST(Mesh, TwoComponentsAndUnreferencedVertex) {
  TriangleSoup s = test::octahedron();
  TriangleSoup t = test::octahedron();
  const int off = static_cast<int>(s.points.size());
  for (auto& p : t.points) s.points.push_back(p + Vec3(5, 0, 0));
  for (auto tri : t.triangles) s.triangles.push_back({tri[0] + off, tri[1] + off, tri[2] + off});
  s.points.emplace_back(100, 100, 100);
  const Mesh m(std::move(s));
  EXPECT_EQ(m.num_components(), 2);
  EXPECT_EQ(m.genus(), -1);
  EXPECT_EQ(m.num_unreferenced_vertices(), 1);
  EXPECT_EQ(m.euler_characteristic(), 4);
  EXPECT_EQ(m.vertex_type(12), VertexType::Isolated);
}

TEST(Mesh, RejectsNonManifoldEdge) {
  TriangleSoup s;
  s.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)};
  s.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  try {
    Mesh m(std::move(s));
    FAIL() << "expected TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("(0"), std::string::npos) << e.what();
  }
}

TEST(Mesh, RejectsFlippedTriangle) {
  TriangleSoup s = test::octahedron();
  std::swap(s.triangles[3][0], s.triangles[3][1]);
  EXPECT_THROW(Mesh m(std::move(s)), TopologyError);
}

TEST(Mesh, RejectsNonManifoldVertex) {
  // Two triangles touching at one vertex (a bow tie).
  TriangleSoup s;
  s.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0)};
  s.triangles = {{0, 1, 2}, {0, 3, 4}};
  try {
    Mesh m(std::move(s));
    FAIL() << "expected TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 0"), std::string::npos) << e.what();
  }
}

TEST(Mesh, RejectsOutOfRangeAndRepeatedIndices) {
  TriangleSoup s = test::octahedron();
  s.triangles[2][1] = 17;
  EXPECT_THROW(Mesh m(s), TopologyError);
  s = test::octahedron();
  s.triangles[2][1] = s.triangles[2][0];
  EXPECT_THROW(Mesh m(s), TopologyError);
}

TEST(Mesh, UvSphereAreaConvergesToSphere) {
  const Mesh m(test::uv_sphere(2.0, 128, 64));
  EXPECT_TRUE(m.is_closed());
  EXPECT_EQ(m.genus(), 0);
  EXPECT_NEAR(m.total_area() / (4.0 * M_PI * 4.0), 1.0, 2e-3);
}

}  // namespace
}  // namespace windplan
