// Isotropic remeshing: edge lengths near the target, boundary and patch borders kept in place,
// patch ids carried over (also onto the faces cut off when long borders are split), closed
// meshes stay closed, patches remeshed apart (in parallel) and sewn back the same at any thread
// count, bad options refused.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/base/parallel.h"
#include "geometry/mesh/remesh.h"
#include "geometry/region/winding_surface.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

TEST(Remesh, LongThinCylinderTrianglesBecomeIsotropic) {
  const double r = 20, len = 200;
  const Mesh in(test::open_cylinder(r, len, 48, 4));  // 50 mm long slivers
  ASSERT_GT(in.edge_length_stats()[2], 50.0);
  // Two patches, the lower and upper halves: their border is the vertex ring at mid-length.
  std::vector<int> patch(in.num_faces());
  for (int f = 0; f < in.num_faces(); ++f) patch[f] = in.face_centroid(f).z() < len / 2 ? 0 : 1;
  RemeshOptions o;
  o.target_edge_length = 4.0;
  const RemeshResult res = remesh_isotropic(in, patch, o);
  const Mesh& m = res.mesh;
  ASSERT_EQ(res.face_patch.size(), static_cast<std::size_t>(m.num_faces()));
  EXPECT_EQ(res.faces_before, in.num_faces());
  // About area / (sqrt(3) / 4 * 4^2) = 3600 near-equilateral triangles.
  EXPECT_GT(res.faces_after, 3000);
  EXPECT_LT(res.faces_after, 5000);
  const auto el = m.edge_length_stats();
  EXPECT_NEAR(el[1], 4.0, 1.2);
  EXPECT_LT(el[2], 8.0);
  // Still an open tube with two loops at z = 0 and z = len, every vertex on the original
  // (faceted) surface: between r cos(pi / 48) and r from the axis.
  EXPECT_EQ(m.boundary_loops().size(), 2u);
  EXPECT_EQ(m.genus(), 0);
  for (const auto& loop : m.boundary_loops()) {
    const double z0 = m.position(m.from(loop[0])).z();
    EXPECT_TRUE(std::abs(z0) < 1e-9 || std::abs(z0 - len) < 1e-9);
    for (int h : loop) EXPECT_NEAR(m.position(m.from(h)).z(), z0, 1e-9);
  }
  for (const Vec3& p : m.points()) {
    const double rad = std::hypot(p.x(), p.y());
    EXPECT_LE(rad, r + 1e-6);
    EXPECT_GE(rad, r * std::cos(M_PI / 48) - 1e-6);
  }
  // New vertices lie on the 48 facets; triangles spanning a fold between facets cut the corner,
  // losing at most the facet sagitta ratio 1 - cos(pi / 48) of the area.
  const double loss = 1 - std::cos(M_PI / 48);
  EXPECT_LE(m.total_area(), in.total_area() + 1e-6);
  EXPECT_GE(m.total_area(), (1 - loss) * in.total_area());
  // Patch ids were carried over: the faces of the two patches have the same total area as before.
  double a0 = 0, a1 = 0;
  for (int f = 0; f < m.num_faces(); ++f) (res.face_patch[f] == 0 ? a0 : a1) += m.face_area(f);
  double b0 = 0, b1 = 0;
  for (int f = 0; f < in.num_faces(); ++f) (patch[f] == 0 ? b0 : b1) += in.face_area(f);
  EXPECT_NEAR(a0, b0, loss * b0);
  EXPECT_NEAR(a1, b1, loss * b1);
  EXPECT_NEAR(a0, a1, 0.02 * a1) << "the patch border stayed at mid-length";
  for (int f = 0; f < m.num_faces(); ++f) {
    const double z = m.face_centroid(f).z();
    EXPECT_EQ(res.face_patch[f], z < len / 2 ? 0 : 1) << "face " << f << " at z " << z;
  }
}

TEST(Remesh, PatchBordersLongerThanTheTargetAreSplitAndKeepTheirPatches) {
  // Issue #4: border edges longer than the target are split before remeshing, and the faces that
  // this split cuts off must keep their patch (CGAL's split_long_edges gives them none).
  const double r = 20, len = 60;
  const int n = 48;  // rings of 2 r sin(pi / 48) = 2.6 mm chords, split at a 2 mm target
  const Mesh in(test::open_cylinder(r, len, n, 2));
  std::vector<int> patch(in.num_faces());
  for (int f = 0; f < in.num_faces(); ++f) patch[f] = in.face_centroid(f).z() < len / 2 ? 0 : 1;
  RemeshOptions o;
  o.target_edge_length = 2.0;
  const RemeshResult res = remesh_isotropic(in, patch, o);
  const Mesh& m = res.mesh;
  ASSERT_EQ(res.face_patch.size(), static_cast<std::size_t>(m.num_faces()));
  int wrong = 0;
  for (int f = 0; f < m.num_faces(); ++f) {
    wrong += res.face_patch[f] != (m.face_centroid(f).z() < len / 2 ? 0 : 1);
  }
  EXPECT_EQ(wrong, 0) << "faces whose patch is not the half they lie in";
  // The border ring and both boundary loops were split: twice their vertices, still on the rings.
  const auto loops = m.boundary_loops();
  ASSERT_EQ(loops.size(), 2u);
  for (const auto& loop : loops) EXPECT_EQ(loop.size(), 2u * n);
  int ring = 0;
  for (const Vec3& p : m.points()) ring += std::abs(p.z() - len / 2) < 1e-9;
  EXPECT_EQ(ring, 2 * n);
  // Every edge between the two patches lies on the ring z = len / 2: the patches meet only
  // there, and each one cut out on its own is an annulus (no vertex where two fans meet).
  for (int e = 0; e < m.num_edges(); ++e) {
    const int h = m.edge_halfedge(e);
    const int f = m.face(h), g = m.face(m.twin(h));
    if (f < 0 || g < 0 || res.face_patch[f] == res.face_patch[g]) continue;
    EXPECT_NEAR(m.position(m.from(h)).z(), len / 2, 1e-9);
    EXPECT_NEAR(m.position(m.to(h)).z(), len / 2, 1e-9);
  }
  for (int p = 0; p < 2; ++p) {
    std::vector<char> keep(m.num_faces());
    for (int f = 0; f < m.num_faces(); ++f) keep[f] = res.face_patch[f] == p;
    const WindingSurface ws = extract_winding_surface(m, keep, SpindleAxis{});
    EXPECT_NEAR(ws.loops[0].axial, p == 0 ? 0.0 : len / 2, 1e-9);
    EXPECT_NEAR(ws.loops[1].axial, p == 0 ? len / 2 : len, 1e-9);
  }
}

TEST(Remesh, CoarseFirstPassGivesTheSameMeshQuality) {
  // 100 mm slivers remeshed to 2.5 mm, with and without the coarse first pass: the same density
  // and edge lengths, every vertex on the input facets (projected onto the input, not onto the
  // coarse intermediate mesh).
  const double r = 20, len = 100;
  const int n = 48;
  const Mesh in(test::open_cylinder(r, len, n, 1));
  RemeshOptions o;
  o.target_edge_length = 2.5;
  o.coarse_factor = 0.0;
  const RemeshResult direct = remesh_isotropic(in, {}, o);
  o.coarse_factor = 4.0;
  const RemeshResult coarse = remesh_isotropic(in, {}, o);
  EXPECT_NEAR(coarse.faces_after, direct.faces_after, 0.1 * direct.faces_after);
  const auto ed = direct.mesh.edge_length_stats(), ec = coarse.mesh.edge_length_stats();
  EXPECT_NEAR(ec[1], ed[1], 0.1 * ed[1]);
  EXPECT_LT(ec[2], 2.0 * o.target_edge_length);
  for (const Vec3& p : coarse.mesh.points()) {
    const double rad = std::hypot(p.x(), p.y());
    EXPECT_LE(rad, r + 1e-6);
    EXPECT_GE(rad, r * std::cos(M_PI / n) - 1e-6);
    // On the facet of its angle: the facet's plane is at r cos(pi / n) from the axis.
    const double a = std::atan2(p.y(), p.x());
    const double mid = (std::floor(a / (2 * M_PI / n)) + 0.5) * (2 * M_PI / n);
    EXPECT_NEAR(p.x() * std::cos(mid) + p.y() * std::sin(mid), r * std::cos(M_PI / n), 1e-6);
  }
  EXPECT_EQ(coarse.mesh.boundary_loops().size(), 2u);
}

TEST(Remesh, ClosedMeshStaysClosed) {
  const Mesh in(test::uv_sphere(50, 24, 12));
  RemeshOptions o;
  o.target_edge_length = 5.0;
  const RemeshResult res = remesh_isotropic(in, {}, o);
  EXPECT_TRUE(res.mesh.is_closed());
  EXPECT_EQ(res.mesh.genus(), 0);
  EXPECT_EQ(res.mesh.num_components(), 1);
  for (int p : res.face_patch) EXPECT_EQ(p, 0);
}

// The smallest angle of each face (degrees), sorted.
std::vector<double> smallest_angles(const Mesh& m) {
  std::vector<double> out;
  for (int f = 0; f < m.num_faces(); ++f) {
    const Tri& t = m.triangle(f);
    double least = 180.0;
    for (int k = 0; k < 3; ++k) {
      const Vec3 a = m.position(t[(k + 1) % 3]) - m.position(t[k]);
      const Vec3 b = m.position(t[(k + 2) % 3]) - m.position(t[k]);
      least = std::min(least, std::atan2(a.cross(b).norm(), a.dot(b)) * 180.0 / M_PI);
    }
    out.push_back(least);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Remesh, SliversAsLongAsTheTubeBecomeWellShapedTriangles) {
  // One row of 300 mm slivers, 2.6 mm wide (a CAD cylinder's tessellation), cut into strips
  // before the remeshing (for speed: bench/README.md, session 18): the triangles come out well
  // shaped, as without the cut.
  const double r = 50, len = 300;
  const Mesh in(test::open_cylinder(r, len, 120, 1));
  RemeshOptions o;
  o.target_edge_length = 3.0;
  const RemeshResult res = remesh_isotropic(in, {}, o);
  const std::vector<double> a = smallest_angles(res.mesh);
  EXPECT_GT(a.front(), 20.0);
  EXPECT_GT(a[a.size() / 20], 38.0) << "the 5th percentile of the faces' smallest angles";
  EXPECT_GT(a[a.size() / 2], 48.0) << "the median";
  const auto el = res.mesh.edge_length_stats();
  EXPECT_NEAR(el[1], 3.0, 0.5);
  EXPECT_LT(el[2], 5.0);
  EXPECT_EQ(res.mesh.boundary_loops().size(), 2u);
}

// A closed sphere cut into the four quadrants of its x-y plane (patches 0-3).
std::vector<int> quadrant_patches(const Mesh& in) {
  std::vector<int> patch(in.num_faces());
  for (int f = 0; f < in.num_faces(); ++f) {
    const Vec3 c = in.face_centroid(f);
    patch[f] = (c.x() < 0 ? 1 : 0) + (c.y() < 0 ? 2 : 0);
  }
  return patch;
}

TEST(Remesh, PatchesRemeshedApartAreSewnAlongTheirBorders) {
  const Mesh in(test::uv_sphere(50, 48, 24));
  const std::vector<int> patch = quadrant_patches(in);
  RemeshOptions o;
  o.target_edge_length = 4.0;
  const RemeshResult res = remesh_isotropic(in, patch, o);
  const Mesh& m = res.mesh;
  EXPECT_TRUE(m.is_closed());
  EXPECT_EQ(m.genus(), 0);
  EXPECT_EQ(m.num_components(), 1);
  ASSERT_EQ(res.face_patch.size(), static_cast<std::size_t>(m.num_faces()));
  // Every face in its quadrant; every edge between two quadrants on the meridian planes x = 0
  // or y = 0, where the input's borders were.
  int wrong = 0, borders = 0;
  for (int f = 0; f < m.num_faces(); ++f) {
    const Vec3 c = m.face_centroid(f);
    wrong += res.face_patch[f] != (c.x() < 0 ? 1 : 0) + (c.y() < 0 ? 2 : 0);
  }
  EXPECT_EQ(wrong, 0);
  for (int h = 0; h < m.num_halfedges(); ++h) {
    const int g = m.twin(h);
    if (m.face(h) < 0 || m.face(g) < 0 ||
        res.face_patch[m.face(h)] == res.face_patch[m.face(g)])
      continue;
    ++borders;
    const Vec3 a = m.position(m.from(h)), b = m.position(m.to(h));
    EXPECT_TRUE((std::abs(a.x()) < 1e-9 && std::abs(b.x()) < 1e-9) ||
                (std::abs(a.y()) < 1e-9 && std::abs(b.y()) < 1e-9))
        << a.transpose() << " - " << b.transpose();
  }
  EXPECT_GT(borders, 0);
  const auto el = m.edge_length_stats();
  EXPECT_NEAR(el[1], 4.0, 1.0);
  EXPECT_GT(smallest_angles(m)[m.num_faces() / 2], 45.0);
}

TEST(Remesh, TheSameMeshAtAnyThreadCount) {
  const Mesh in(test::uv_sphere(50, 48, 24));
  const std::vector<int> patch = quadrant_patches(in);
  RemeshOptions o;
  o.target_edge_length = 4.0;
  RemeshResult one, two;
  {
    const ThreadLimit limit(1);
    one = remesh_isotropic(in, patch, o);
  }
  {
    const ThreadLimit limit(2);
    two = remesh_isotropic(in, patch, o);
  }
  EXPECT_EQ(one.mesh.points(), two.mesh.points());
  EXPECT_EQ(one.mesh.triangles(), two.mesh.triangles());
  EXPECT_EQ(one.face_patch, two.face_patch);
}

TEST(Remesh, PatchesThatTouchThemselvesAtAVertexAreRemeshedWhole) {
  // A checkerboard of patches by octant: each touches itself at the poles and along the
  // equator's corners, so it is no manifold on its own; the mesh is remeshed as one.
  const Mesh in(test::uv_sphere(50, 48, 24));
  std::vector<int> patch(in.num_faces());
  for (int f = 0; f < in.num_faces(); ++f) {
    const Vec3 c = in.face_centroid(f);
    patch[f] = ((c.x() < 0) + (c.y() < 0) + (c.z() < 0)) % 2;
  }
  RemeshOptions o;
  o.target_edge_length = 4.0;
  const RemeshResult res = remesh_isotropic(in, patch, o);
  EXPECT_TRUE(res.mesh.is_closed());
  EXPECT_EQ(res.mesh.genus(), 0);
  int wrong = 0;
  for (int f = 0; f < res.mesh.num_faces(); ++f) {
    const Vec3 c = res.mesh.face_centroid(f);
    wrong += res.face_patch[f] != ((c.x() < 0) + (c.y() < 0) + (c.z() < 0)) % 2;
  }
  EXPECT_EQ(wrong, 0);
}

TEST(Remesh, AMeshWithAFaceOfNoAreaIsRemeshedUncut) {
  // A 300 mm strip (two triangles) with a face of no area below its long edge A-B (its third
  // corner M on the edge). Cut into strips, it crashed in CGAL's tangential relaxation; uncut,
  // CGAL remeshes it.
  TriangleSoup soup;
  soup.points = {Vec3(0, 0, 0), Vec3(150, 0, 0), Vec3(300, 0, 0), Vec3(0, 2.6, 0),
                 Vec3(300, 2.6, 0)};  // A, M, B, C, D
  soup.triangles = {{0, 2, 4}, {0, 4, 3}, {0, 1, 2}};
  const Mesh in(soup);
  RemeshOptions o;
  o.target_edge_length = 10.0;
  RemeshResult res;
  ASSERT_NO_THROW(res = remesh_isotropic(in, {}, o));
  EXPECT_GT(res.mesh.num_faces(), 3);
  EXPECT_NEAR(res.mesh.total_area(), in.total_area(), 1e-6 * in.total_area());
}

TEST(Remesh, BadOptionsAndSizesAreRefused) {
  const Mesh in(test::open_cylinder(20, 100, 16, 2));
  RemeshOptions o;
  o.target_edge_length = 0.0;
  EXPECT_THROW(remesh_isotropic(in, {}, o), ConfigError);
  o.target_edge_length = 5.0;
  o.iterations = 0;
  EXPECT_THROW(remesh_isotropic(in, {}, o), ConfigError);
  o.iterations = 3;
  EXPECT_THROW(remesh_isotropic(in, std::vector<int>(3, 0), o), InputError);
  EXPECT_THROW(remesh_isotropic(in, std::vector<int>(in.num_faces(), -1), o), InputError);
  o.coarse_factor = 1.0;
  EXPECT_THROW(remesh_isotropic(in, {}, o), ConfigError);
}

}  // namespace
}  // namespace windplan
