#include "geometry/mesh/mesh_validation.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

double signed_volume(const TriangleSoup& s) {
  double v = 0.0;
  for (const Tri& t : s.triangles) {
    v += s.points[t[0]].dot(s.points[t[1]].cross(s.points[t[2]])) / 6.0;
  }
  return v;
}

double total_area(const TriangleSoup& s) {
  double a = 0.0;
  for (const Tri& t : s.triangles) {
    a += 0.5 * (s.points[t[1]] - s.points[t[0]]).cross(s.points[t[2]] - s.points[t[0]]).norm();
  }
  return a;
}

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

std::string topology_error(const TriangleSoup& s, const RepairOptions& o = {}) {
  try {
    repair_mesh(s, o);
  } catch (const TopologyError& e) {
    return e.what();
  }
  return "(no TopologyError)";
}

// Two octahedra touching at one vertex (the second shifted by 2 along x so that its vertex 1
// lands on the first's vertex 0): the shared vertex has two fans.
TriangleSoup bowtie() {
  TriangleSoup a = test::octahedron();
  const TriangleSoup b = test::octahedron();
  std::vector<int> map(6);
  for (int v = 0; v < 6; ++v) {
    if (v == 1) {
      map[v] = 0;
      continue;
    }
    map[v] = static_cast<int>(a.points.size());
    a.points.push_back(b.points[v] + Vec3(2, 0, 0));
  }
  for (const Tri& t : b.triangles) a.triangles.push_back({map[t[0]], map[t[1]], map[t[2]]});
  return a;
}

// A Moebius strip: n quads between two rails whose last quad joins the rails swapped.
TriangleSoup moebius(int n) {
  TriangleSoup s;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    const Vec3 c(std::cos(t), std::sin(t), 0.0);
    const Vec3 w = 0.3 * (std::cos(t / 2) * c + std::sin(t / 2) * Vec3(0, 0, 1));
    s.points.push_back(c + w);  // top rail: 2i
    s.points.push_back(c - w);  // bottom rail: 2i + 1
  }
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * i + 1;
    int c = 2 * (i + 1) + 1, d = 2 * (i + 1);
    if (i == n - 1) {
      c = 0;  // the twist: bottom meets top
      d = 1;
    }
    s.triangles.push_back({a, b, c});
    s.triangles.push_back({a, c, d});
  }
  return s;
}

TEST(CheckMesh, OctahedronIsAClosedGenusZeroSurface) {
  const MeshHealth h = check_mesh(test::octahedron());
  EXPECT_EQ(h.num_vertices, 6);
  EXPECT_EQ(h.num_faces, 8);
  EXPECT_EQ(h.num_edges, 12);
  EXPECT_EQ(h.euler_characteristic, 2);
  EXPECT_EQ(h.genus, 0);
  EXPECT_EQ(h.num_components, 1);
  EXPECT_EQ(h.num_boundary_loops, 0);
  EXPECT_TRUE(h.closed);
  EXPECT_TRUE(h.manifold);
  EXPECT_TRUE(h.oriented);
  EXPECT_TRUE(h.is_valid_mesh());
  EXPECT_TRUE(h.problems().empty());
  EXPECT_DOUBLE_EQ(h.min_edge_length, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(h.max_edge_length, std::sqrt(2.0));
  EXPECT_EQ(h.bbox.min, Vec3(-1, -1, -1));
  EXPECT_EQ(h.bbox.max, Vec3(1, 1, 1));
}

TEST(CheckMesh, TorusHasGenusOne) {
  const MeshHealth h = check_mesh(test::torus(3, 1, 16, 8));
  EXPECT_EQ(h.euler_characteristic, 0);
  EXPECT_EQ(h.genus, 1);
  EXPECT_TRUE(h.closed);
}

TEST(CheckMesh, OpenCylinderHasTwoBoundaryLoops) {
  const int n = 24, m = 5;
  const MeshHealth h = check_mesh(test::open_cylinder(2.0, 3.0, n, m));
  EXPECT_EQ(h.num_boundary_edges, 2 * n);
  EXPECT_EQ(h.num_boundary_loops, 2);
  EXPECT_EQ(h.euler_characteristic, 0);
  EXPECT_EQ(h.genus, 0);
  EXPECT_FALSE(h.closed);
  EXPECT_TRUE(h.is_valid_mesh());
  // Edges: around 2*pi*r/n, along len/m, diagonals sqrt of both squared.
  const double around = 2 * 2.0 * std::sin(M_PI / n), along = 3.0 / m;
  EXPECT_NEAR(h.min_edge_length, std::min(around, along), 1e-12);
  EXPECT_NEAR(h.max_edge_length, std::hypot(around, along), 1e-12);
}

TEST(CheckMesh, GridHasOneBoundaryLoop) {
  const MeshHealth h = check_mesh(test::grid(4, 3));
  EXPECT_EQ(h.num_boundary_edges, 2 * (4 + 3));
  EXPECT_EQ(h.num_boundary_loops, 1);
  EXPECT_EQ(h.genus, 0);
  EXPECT_EQ(h.euler_characteristic, 1);
}

TEST(CheckMesh, CountsEachKindOfProblem) {
  TriangleSoup s = test::octahedron();
  s.points.push_back(Vec3(7, 7, 7));      // 6: unreferenced
  s.points.push_back(s.points[0]);        // 7: duplicate position of 0, unreferenced
  s.triangles.push_back({0, 2, 0});       // degenerate
  s.triangles.push_back(s.triangles[3]);  // duplicate
  const MeshHealth h = check_mesh(s);
  EXPECT_EQ(h.num_vertices, 8);
  EXPECT_EQ(h.num_faces, 10);
  EXPECT_EQ(h.num_unreferenced_vertices, 2);
  EXPECT_EQ(h.num_referenced_vertices, 6);
  EXPECT_EQ(h.num_duplicate_vertices, 1);
  EXPECT_EQ(h.num_degenerate_triangles, 1);
  ASSERT_EQ(h.degenerate_triangles.size(), 1u);
  EXPECT_EQ(h.degenerate_triangles[0], 8);
  EXPECT_EQ(h.num_duplicate_triangles, 1);
  // The duplicate puts its three edges into three triangles each.
  EXPECT_EQ(h.num_nonmanifold_edges, 3);
  EXPECT_FALSE(h.manifold);
  EXPECT_EQ(h.genus, -1);
  EXPECT_EQ(h.bbox.max, Vec3(1, 1, 1));  // unreferenced (7,7,7) is not in the box
  // Blocking: the non-manifold edges and the degenerate triangle; not the unreferenced vertices.
  EXPECT_EQ(h.blocking_problems().size(), 2u);
  EXPECT_EQ(h.problems().size(), 5u);
}

TEST(CheckMesh, InconsistentOrientationCountsEdges) {
  TriangleSoup s = test::octahedron();
  std::swap(s.triangles[2][1], s.triangles[2][2]);
  const MeshHealth h = check_mesh(s);
  EXPECT_EQ(h.num_inconsistent_edges, 3);
  EXPECT_FALSE(h.oriented);
  EXPECT_TRUE(h.manifold);
  EXPECT_EQ(h.genus, 0);
}

TEST(CheckMesh, NonManifoldEdgeListsItsVertexPair) {
  TriangleSoup s = test::grid(1, 1);      // (0,1,3), (0,3,2)
  s.points.push_back(Vec3(0.5, 0.5, 1));  // 4
  s.triangles.push_back({0, 3, 4});       // a fin on the diagonal (0, 3)
  const MeshHealth h = check_mesh(s);
  EXPECT_EQ(h.num_nonmanifold_edges, 1);
  ASSERT_EQ(h.nonmanifold_edges.size(), 1u);
  EXPECT_EQ(h.nonmanifold_edges[0], (std::array<int, 2>{0, 3}));
  EXPECT_NE(topology_error(s).find("(0, 3)"), std::string::npos) << topology_error(s);
}

TEST(CheckMesh, NonManifoldVertexHasTwoFans) {
  const MeshHealth h = check_mesh(bowtie());
  EXPECT_EQ(h.num_nonmanifold_vertices, 1);
  ASSERT_EQ(h.nonmanifold_vertices.size(), 1u);
  EXPECT_EQ(h.nonmanifold_vertices[0], 0);
  EXPECT_EQ(h.num_nonmanifold_edges, 0);
  EXPECT_EQ(h.num_components, 2);
  EXPECT_FALSE(h.manifold);
}

TEST(CheckMesh, HighValenceFanApex) {
  // A closed cone-like surface: a fan of n triangles around an apex, closed by a fan around the
  // base centre; two vertices of valence n.
  const int n = 500;
  TriangleSoup s;
  s.points.push_back(Vec3(0, 0, 1));   // apex
  s.points.push_back(Vec3(0, 0, -1));  // base centre
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    s.points.push_back(Vec3(std::cos(t), std::sin(t), 0));
  }
  for (int i = 0; i < n; ++i) {
    const int a = 2 + i, b = 2 + (i + 1) % n;
    s.triangles.push_back({0, a, b});
    s.triangles.push_back({1, b, a});
  }
  const MeshHealth h = check_mesh(s);
  EXPECT_EQ(h.num_edges, 3 * n);
  EXPECT_TRUE(h.closed && h.manifold && h.oriented);
  EXPECT_EQ(h.genus, 0);
  EXPECT_EQ(h.num_nonmanifold_vertices, 0);
}

TEST(CheckMesh, ZeroAreaTrianglesAreFoundByTolerance) {
  TriangleSoup s = test::grid(1, 1);
  s.points.push_back(Vec3(2, 0, 0));
  s.triangles.push_back({1, 4, 0});  // collinear: zero area
  const MeshHealth h = check_mesh(s);
  EXPECT_EQ(h.num_zero_area_triangles, 1);
  ASSERT_EQ(h.zero_area_triangles.size(), 1u);
  EXPECT_EQ(h.zero_area_triangles[0], 2);
  MeshCheckOptions o;
  o.zero_area_tolerance = 0.2;  // a unit-square half has area 0.5 < 0.2 * diag^2 = 0.2 * 5
  EXPECT_EQ(check_mesh(s, o).num_zero_area_triangles, 3);
}

TEST(RepairMesh, CleanMeshIsUnchanged) {
  const TriangleSoup s = test::torus(3, 1, 10, 6);
  const RepairResult r = repair_mesh(s);
  EXPECT_TRUE(r.changes.empty());
  EXPECT_EQ(r.soup.points, s.points);
  EXPECT_EQ(r.soup.triangles, s.triangles);
}

TEST(RepairMesh, ReorientsAFlippedTriangle) {
  TriangleSoup s = test::octahedron();
  std::swap(s.triangles[5][0], s.triangles[5][1]);
  const RepairResult r = repair_mesh(s);
  EXPECT_EQ(r.flipped_triangles, 1);
  EXPECT_TRUE(r.after.oriented);
  EXPECT_EQ(r.soup.points, test::octahedron().points);
  // The flipped face now has the orientation of the original (as a cyclic order).
  const Tri t = r.soup.triangles[5], o = test::octahedron().triangles[5];
  bool same = false;
  for (int k = 0; k < 3; ++k)
    same = same || (t[k] == o[0] && t[(k + 1) % 3] == o[1] && t[(k + 2) % 3] == o[2]);
  EXPECT_TRUE(same);
  EXPECT_NO_THROW(Mesh(r.soup));
}

TEST(RepairMesh, TurnsAnInsideOutClosedMeshOutward) {
  TriangleSoup s = test::uv_sphere(2.0, 12, 8);
  for (Tri& t : s.triangles) std::swap(t[1], t[2]);
  ASSERT_LT(signed_volume(s), 0.0);
  const RepairResult r = repair_mesh(s);
  EXPECT_GT(signed_volume(r.soup), 0.0);
  EXPECT_EQ(r.flipped_triangles, static_cast<int>(s.triangles.size()));
  ASSERT_EQ(r.changes.size(), 1u);
  EXPECT_TRUE(contains(r.changes[0], "outward")) << r.changes[0];
  RepairOptions keep;
  keep.orient_outward = false;
  EXPECT_LT(signed_volume(repair_mesh(s, keep).soup), 0.0);
}

TEST(RepairMesh, OpenComponentKeepsTheMajorityOrientation) {
  TriangleSoup s = test::grid(3, 3);
  std::swap(s.triangles[4][1], s.triangles[4][2]);
  const RepairResult r = repair_mesh(s);
  EXPECT_EQ(r.flipped_triangles, 1);
  EXPECT_EQ(r.soup.triangles, test::grid(3, 3).triangles);
}

TEST(RepairMesh, MergesDropsAndReportsEachChange) {
  TriangleSoup s = test::octahedron();
  // Vertex 6 duplicates vertex 4 and takes over two of its triangles: the seam is open until
  // the merge closes it.
  s.points.push_back(s.points[4]);
  for (Tri& t : s.triangles) {
    if (&t == &s.triangles[0] || &t == &s.triangles[1])
      for (int& v : t) v = v == 4 ? 6 : v;
  }
  s.points.push_back(Vec3(9, 9, 9));      // unreferenced
  s.triangles.push_back({1, 1, 3});       // degenerate
  s.triangles.push_back(s.triangles[6]);  // duplicate
  const MeshHealth before = check_mesh(s);
  EXPECT_FALSE(before.closed);
  const RepairResult r = repair_mesh(s);
  EXPECT_EQ(r.merged_vertices, 1);
  EXPECT_EQ(r.removed_degenerate, 1);
  EXPECT_EQ(r.removed_duplicates, 1);
  EXPECT_EQ(r.removed_unreferenced, 1);
  EXPECT_EQ(r.changes.size(), 4u);
  EXPECT_TRUE(r.after.closed);
  EXPECT_TRUE(r.after.is_valid_mesh());
  EXPECT_EQ(r.after.num_vertices, 6);
  EXPECT_EQ(r.after.num_faces, 8);
  EXPECT_EQ(r.after.genus, 0);
  EXPECT_NEAR(signed_volume(r.soup), 4.0 / 3.0, 1e-12);
}

TEST(RepairMesh, RefusesAMergeThatWouldMakeANonManifoldVertex) {
  // Two separate octahedra whose vertices coincide at one point, as two distinct vertices:
  // merging them would create the bowtie.
  TriangleSoup s = test::octahedron();
  const TriangleSoup b = test::octahedron();
  for (const Vec3& p : b.points) s.points.push_back(p + Vec3(2, 0, 0));
  for (const Tri& t : b.triangles) s.triangles.push_back({t[0] + 6, t[1] + 6, t[2] + 6});
  ASSERT_EQ(check_mesh(s).num_duplicate_vertices, 1);
  const RepairResult r = repair_mesh(s);
  EXPECT_EQ(r.merged_vertices, 0);
  ASSERT_EQ(r.kept.size(), 1u);
  EXPECT_TRUE(contains(r.kept[0], "non-manifold")) << r.kept[0];
  EXPECT_TRUE(r.after.is_valid_mesh());
  EXPECT_EQ(r.after.num_components, 2);
}

TEST(RepairMesh, RemovesAZeroAreaCapByAnEdgeFlipWithoutChangingTheSurface) {
  // Octahedron with the midpoint m of edge (0, 2) inserted on one side only: face (0, 2, 4)
  // becomes (0, m, 4) + (m, 2, 4), and the cap (2, m, 0) closes the surface with zero area.
  TriangleSoup s = test::octahedron();
  const int m = 6;
  s.points.push_back(0.5 * (s.points[0] + s.points[2]));
  s.triangles[0] = {0, m, 4};
  s.triangles.push_back({m, 2, 4});
  s.triangles.push_back({2, m, 0});
  const MeshHealth h = check_mesh(s);
  ASSERT_EQ(h.num_zero_area_triangles, 1);
  ASSERT_TRUE(h.closed && h.manifold && h.oriented);
  const RepairResult r = repair_mesh(s);
  EXPECT_EQ(r.removed_zero_area, 1);
  EXPECT_EQ(r.after.num_zero_area_triangles, 0);
  EXPECT_TRUE(r.after.closed && r.after.manifold && r.after.oriented);
  EXPECT_EQ(r.after.genus, 0);
  EXPECT_EQ(r.after.num_faces, 10);
  // Same surface: the octahedron's area 4 sqrt(3) and volume 4/3.
  EXPECT_NEAR(total_area(r.soup), 4.0 * std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(signed_volume(r.soup), 4.0 / 3.0, 1e-12);
  EXPECT_NO_THROW(Mesh(r.soup));
}

TEST(RepairMesh, DropsAZeroAreaTriangleOnTheBoundaryThatCannotBeFlipped) {
  // A cap hanging off the open grid: its long edge (0, 4) is a boundary edge, so there is no
  // neighbour to flip with; dropping it opens no hole and loses no area.
  TriangleSoup s = test::grid(1, 1);
  s.points.push_back(Vec3(2, 0, 0));
  s.triangles.push_back({0, 4, 1});  // 1 lies on the segment (0, 4)
  const RepairResult r = repair_mesh(s);
  EXPECT_EQ(r.removed_zero_area, 1);
  EXPECT_EQ(r.removed_unreferenced, 1);  // vertex 4 was used by the cap only
  EXPECT_TRUE(r.kept.empty());
  ASSERT_EQ(r.changes.size(), 1u);
  EXPECT_TRUE(contains(r.changes[0], "on the open boundary")) << r.changes[0];
  EXPECT_EQ(r.soup.points, test::grid(1, 1).points);
  EXPECT_EQ(r.soup.triangles, test::grid(1, 1).triangles);
}

TEST(RepairMesh, KeepsAZeroAreaTriangleItCannotFlipOrDropAndSaysSo) {
  // The octahedron's top vertex 4 split into 4 (faces 0, 1) and 6 = 4 + 1e-13 x (faces 2, 3);
  // two needles (0, 4, 6) and (4, 1, 6) close the seam. Each needle's flip would make another
  // zero-area triangle, and the surface is closed, so both are kept.
  TriangleSoup s = test::octahedron();
  s.points.push_back(s.points[4] + Vec3(1e-13, 0, 0));
  s.triangles[2] = {1, 3, 6};
  s.triangles[3] = {3, 0, 6};
  s.triangles.push_back({0, 4, 6});
  s.triangles.push_back({4, 1, 6});
  const MeshHealth h = check_mesh(s);
  ASSERT_TRUE(h.closed && h.manifold && h.oriented) << h.brief_report();
  ASSERT_EQ(h.num_zero_area_triangles, 2);
  const RepairResult r = repair_mesh(s);
  EXPECT_EQ(r.removed_zero_area, 0);
  ASSERT_EQ(r.kept.size(), 1u);
  EXPECT_TRUE(contains(r.kept[0], "2 zero-area triangles")) << r.kept[0];
  EXPECT_TRUE(r.after.closed);
  EXPECT_EQ(r.after.num_zero_area_triangles, 2);
}

TEST(RepairMesh, RefusesNonManifoldVerticesUnlessAskedToSplit) {
  const std::string e = topology_error(bowtie());
  EXPECT_TRUE(contains(e, "non-manifold vertex")) << e;
  EXPECT_TRUE(contains(e, ": 0")) << e;
  RepairOptions o;
  o.split_nonmanifold_vertices = true;
  const RepairResult r = repair_mesh(bowtie(), o);
  EXPECT_EQ(r.split_vertices, 1);
  EXPECT_TRUE(r.after.is_valid_mesh());
  EXPECT_EQ(r.after.num_vertices, 12);
  EXPECT_EQ(r.after.num_components, 2);
  const Mesh mesh(r.soup);
  EXPECT_EQ(mesh.num_components(), 2);
  EXPECT_EQ(mesh.euler_characteristic(), 4);  // two spheres
}

TEST(RepairMesh, RefusesANonOrientableSurface) {
  const TriangleSoup s = moebius(8);
  const MeshHealth h = check_mesh(s);
  ASSERT_TRUE(h.manifold);
  EXPECT_EQ(h.num_boundary_loops, 1);  // a Moebius strip has one boundary curve
  const std::string e = topology_error(s);
  EXPECT_TRUE(contains(e, "non-orientable")) << e;
}

TEST(BuildMesh, WithoutRepairRefusesInconsistentOrientationNamingEdges) {
  TriangleSoup s = test::octahedron();
  std::swap(s.triangles[0][1], s.triangles[0][2]);
  try {
    build_mesh(s, false);
    FAIL() << "no TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_TRUE(contains(e.what(), "inconsistent orientation")) << e.what();
    EXPECT_TRUE(contains(e.what(), "(0, 2)")) << e.what();
  }
  MeshHealth h;
  std::vector<std::string> changes;
  const Mesh m = build_mesh(s, true, &h, &changes);
  EXPECT_EQ(h.num_inconsistent_edges, 3);
  EXPECT_EQ(changes.size(), 1u);
  EXPECT_EQ(m.genus(), 0);
  EXPECT_TRUE(m.is_closed());
}

TEST(BuildMesh, RepairFailureIsATopologyError) {
  EXPECT_THROW(build_mesh(bowtie(), true), TopologyError);
  EXPECT_THROW(build_mesh(bowtie(), false), TopologyError);
}

TEST(MeshHealth, ReportMentionsTheKeyFigures) {
  const std::string r = check_mesh(test::open_cylinder(1, 1, 8, 2)).brief_report();
  EXPECT_TRUE(contains(r, "boundary loops:  2")) << r;
  EXPECT_TRUE(contains(r, "genus:           0")) << r;
}

}  // namespace
}  // namespace windplan
