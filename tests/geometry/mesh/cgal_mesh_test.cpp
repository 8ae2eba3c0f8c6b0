#include "geometry/mesh/cgal_mesh.h"

#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/mesh/mesh_io.h"
#include "geometry/mesh/mesh_validation.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_data.h"

namespace windplan {
namespace {

// Triangles equal as cyclic orders (the starting corner is CGAL's choice).
bool same_cycle(const Tri& a, const Tri& b) {
  for (int k = 0; k < 3; ++k) {
    if (a[0] == b[k] && a[1] == b[(k + 1) % 3] && a[2] == b[(k + 2) % 3]) return true;
  }
  return false;
}

void expect_round_trip(const Mesh& m) {
  const CgalMesh c(m);
  EXPECT_EQ(c.num_vertices(), m.num_vertices());
  EXPECT_EQ(c.num_faces(), m.num_faces());
  EXPECT_EQ(c.num_edges(), m.num_edges());
  EXPECT_TRUE(c.is_valid());
  EXPECT_EQ(c.is_closed(), m.is_closed());
  EXPECT_NEAR(c.area(), m.total_area(), 1e-12 * m.total_area());
  const Mesh back = c.to_mesh();
  ASSERT_EQ(back.num_vertices(), m.num_vertices());
  ASSERT_EQ(back.num_faces(), m.num_faces());
  EXPECT_EQ(back.points(), m.points());
  for (int f = 0; f < m.num_faces(); ++f) {
    EXPECT_TRUE(same_cycle(back.triangle(f), m.triangle(f))) << "face " << f;
  }
  EXPECT_EQ(back.genus(), m.genus());
  EXPECT_EQ(back.boundary_loops().size(), m.boundary_loops().size());
}

TEST(CgalMesh, OctahedronRoundTripAndClosedFormMeasures) {
  const Mesh m(test::octahedron());
  expect_round_trip(m);
  const CgalMesh c(m);
  EXPECT_NEAR(c.area(), 4.0 * std::sqrt(3.0), 1e-12);  // 8 equilateral triangles of side sqrt 2
  EXPECT_NEAR(c.volume(), 4.0 / 3.0, 1e-12);           // |x| + |y| + |z| <= 1
}

TEST(CgalMesh, TorusRoundTrip) { expect_round_trip(Mesh(test::torus(3.0, 1.0, 24, 12))); }

TEST(CgalMesh, OpenCylinderRoundTripAndVolumeNeedsAClosedMesh) {
  const Mesh m(test::open_cylinder(50.0, 200.0, 32, 8));
  expect_round_trip(m);
  const CgalMesh c(m);
  EXPECT_FALSE(c.is_closed());
  EXPECT_THROW(c.volume(), TopologyError);
}

TEST(CgalMesh, UnreferencedVerticesKeepTheIndices) {
  TriangleSoup s = test::octahedron();
  s.points.insert(s.points.begin(), Vec3(5, 5, 5));
  for (Tri& t : s.triangles)
    for (int& v : t) ++v;
  const Mesh m(s);
  const CgalMesh c(m);
  EXPECT_EQ(c.num_vertices(), 7);
  const Mesh back = c.to_mesh();
  EXPECT_EQ(back.points(), m.points());
  EXPECT_EQ(back.num_unreferenced_vertices(), 1);
}

TEST(CgalMesh, SharedMeshesRoundTripAndCgalAgreesOnAreaAndVolume) {
  for (const char* name : {"fertility.off", "torus.off", "camelhead.off"}) {
    WINDPLAN_REQUIRE_SHARED_MESH(path, name);
    const Mesh m = build_mesh(read_mesh(path), true);
    SCOPED_TRACE(name);
    expect_round_trip(m);
    if (!m.is_closed()) continue;
    double volume = 0.0;  // divergence theorem, independent of CGAL
    for (const Tri& t : m.triangles()) {
      volume += m.position(t[0]).dot(m.position(t[1]).cross(m.position(t[2]))) / 6.0;
    }
    EXPECT_NEAR(CgalMesh(m).volume(), volume, 1e-9 * std::abs(volume));
  }
}

TEST(CgalMesh, CopyAndMove) {
  CgalMesh a{Mesh(test::octahedron())};  // (braces: clang reads the parentheses as a declaration)
  CgalMesh b = a;
  CgalMesh c = std::move(a);
  EXPECT_EQ(b.num_faces(), 8);
  EXPECT_EQ(c.num_faces(), 8);
  CgalMesh empty;
  EXPECT_EQ(empty.num_vertices(), 0);
}

}  // namespace
}  // namespace windplan
