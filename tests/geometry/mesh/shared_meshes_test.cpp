// Every mesh in ../shared/data/meshes loads, and its health report matches its row in
// ../shared/data/meshes/SOURCES.md (V, F, closed, manifold, genus, boundary edges), including
// the "bad" ones. Skips with a message when ../shared is absent.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/mesh/mesh_io.h"
#include "geometry/mesh/mesh_validation.h"
#include "tests/test_data.h"

namespace windplan {
namespace {

constexpr int kNoGenus = -2;  // SOURCES.md gives no genus (open or non-manifold)

struct Row {
  const char* file;
  int vertices;  // referenced vertices (SOURCES counts after dropping unreferenced ones)
  int faces;     // triangles after fan-splitting
  bool closed;
  bool manifold;
  int genus;  // kNoGenus when not given
  int boundary_edges;
  double weld;  // STL weld tolerance (relative); SOURCES welded exactly equal corners
};

void PrintTo(const Row& r, std::ostream* os) { *os << r.file; }

// Straight from SOURCES.md.
const Row kRows[] = {
    {"stanford-bunny.obj", 34834, 69451, false, true, kNoGenus, 223, 1e-9},
    {"bunny-closed-28k.obj", 14290, 28576, true, true, 0, 0, 1e-9},
    {"kitten-106k.obj", 53123, 106246, true, true, 1, 0, 1e-9},
    {"horse.ply", 48485, 96966, true, true, 0, 0, 1e-9},
    {"rocker-arm.obj", 10044, 20088, true, true, 1, 0, 1e-9},
    {"armadillo.obj", 43243, 86482, true, true, 0, 0, 1e-9},
    {"fertility.off", 4494, 9000, true, true, 4, 0, 1e-9},
    {"3holes.off", 3596, 7200, true, true, 3, 0, 1e-9},
    {"bumpy-cube.obj", 19970, 39936, true, true, 0, 0, 1e-9},
    {"spot.obj", 2930, 5856, true, true, 0, 0, 1e-9},
    {"cheburashka.obj", 6669, 13334, true, true, 0, 0, 1e-9},
    {"fandisk.obj", 6475, 12946, true, true, 0, 0, 1e-9},
    {"torus.off", 800, 1600, true, true, 1, 0, 1e-9},
    {"aerobar-brake-mandrel.stl", 2393, 4786, true, true, 1, 0, 1e-9},
    // Exact weld: at the default tolerance 10 vertex pairs 4.4e-17 apart also merge (see below).
    {"bent-pipe.stl", 352, 700, true, true, 0, 0, 0.0},
    {"cylinder.obj", 220, 436, true, true, 0, 0, 1e-9},
    {"camelhead.off", 11381, 22704, false, true, kNoGenus, 56, 1e-9},
    {"face.obj", 25905, 51712, false, true, kNoGenus, 96, 1e-9},
    {"teapot.obj", 3644, 6320, false, false, kNoGenus, 1036, 1e-9},
    {"beast.obj", 32311, 64618, true, false, kNoGenus, 0, 1e-9},
    {"derived/bunny-remesh-20k.obj", 9742, 19480, true, true, 0, 0, 1e-9},
    {"derived/bunny-remesh-100k.obj", 51580, 103156, true, true, 0, 0, 1e-9},
    {"derived/bunny-remesh-300k.obj", 151782, 303560, true, true, 0, 0, 1e-9},
};

TriangleSoup load(const std::filesystem::path& p, double weld) {
  MeshReadOptions o;
  o.weld_tolerance = weld;
  return read_mesh(p, o);
}

class SharedMesh : public ::testing::TestWithParam<Row> {};

TEST_P(SharedMesh, HealthMatchesSources) {
  const Row& row = GetParam();
  WINDPLAN_REQUIRE_SHARED_MESH(path, row.file);
  const MeshHealth h = check_mesh(load(path, row.weld));
  EXPECT_EQ(h.num_referenced_vertices, row.vertices);
  EXPECT_EQ(h.num_faces, row.faces);
  EXPECT_EQ(h.closed, row.closed);
  EXPECT_EQ(h.manifold, row.manifold);
  EXPECT_EQ(h.num_boundary_edges, row.boundary_edges);
  if (row.genus != kNoGenus) {
    EXPECT_EQ(h.genus, row.genus);
    EXPECT_EQ(h.num_components, 1);
  }
  if (!row.manifold) {
    EXPECT_EQ(h.genus, -1);
  }
}

TEST_P(SharedMesh, BuildMeshKeepsTheTopologyOrRefusesNonManifolds) {
  const Row& row = GetParam();
  WINDPLAN_REQUIRE_SHARED_MESH(path, row.file);
  if (!row.manifold) {
    EXPECT_THROW(build_mesh(load(path, row.weld), true), TopologyError);
    return;
  }
  MeshHealth before;
  std::vector<std::string> changes;
  const Mesh m = build_mesh(load(path, row.weld), true, &before, &changes);
  EXPECT_EQ(m.num_faces() + before.num_degenerate_triangles, row.faces);
  EXPECT_EQ(m.num_vertices(), row.vertices);
  EXPECT_EQ(m.is_closed(), row.closed);
  EXPECT_EQ(m.num_unreferenced_vertices(), 0);
  EXPECT_EQ(static_cast<int>(m.boundary_loops().size()), before.num_boundary_loops);
  if (row.genus != kNoGenus) {
    EXPECT_EQ(m.genus(), row.genus);
  }
}

INSTANTIATE_TEST_SUITE_P(Sources, SharedMesh, ::testing::ValuesIn(kRows),
                         [](const ::testing::TestParamInfo<Row>& i) {
                           std::string n = i.param.file;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

TEST(SharedMeshes, TeapotHas38NonManifoldVerticesIn19Components) {
  WINDPLAN_REQUIRE_SHARED_MESH(path, "teapot.obj");
  const TriangleSoup s = read_mesh(path);
  const MeshHealth h = check_mesh(s);
  EXPECT_EQ(h.num_nonmanifold_vertices, 38);
  EXPECT_EQ(h.num_nonmanifold_edges, 0);
  EXPECT_EQ(h.num_components, 19);
  try {
    repair_mesh(s);
    FAIL() << "no TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("non-manifold vert"), std::string::npos) << e.what();
  }
  EXPECT_THROW(build_mesh(s, false), TopologyError);
  RepairOptions split;
  split.split_nonmanifold_vertices = true;
  const RepairResult r = repair_mesh(s, split);
  EXPECT_TRUE(r.after.is_valid_mesh());
  EXPECT_GT(r.split_vertices, 0);
  EXPECT_NO_THROW(Mesh(r.soup));
}

TEST(SharedMeshes, BeastHasTwoNonManifoldEdgesAndRepairNamesThem) {
  WINDPLAN_REQUIRE_SHARED_MESH(path, "beast.obj");
  const TriangleSoup s = read_mesh(path);
  const MeshHealth h = check_mesh(s);
  EXPECT_EQ(h.num_nonmanifold_edges, 2);
  ASSERT_EQ(h.nonmanifold_edges.size(), 2u);
  const std::string first = "(" + std::to_string(h.nonmanifold_edges[0][0]) + ", " +
                            std::to_string(h.nonmanifold_edges[0][1]) + ")";
  try {
    build_mesh(s, true);
    FAIL() << "no TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("non-manifold edge"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(first), std::string::npos) << e.what();
  }
}

TEST(SharedMeshes, BentPipeIsInconsistentlyOrientedAndRepairOrientsIt) {
  WINDPLAN_REQUIRE_SHARED_MESH(path, "bent-pipe.stl");
  // As counted in SOURCES.md (exact weld): 70 edges traversed twice the same way.
  const MeshHealth exact = check_mesh(load(path, 0.0));
  EXPECT_EQ(exact.num_inconsistent_edges, 70);
  EXPECT_FALSE(exact.oriented);
  // At the default relative tolerance 1e-9 the 10 pairs of corners at x = -4.4e-17 and x = 0
  // weld too, and the 20 sliver triangles between them become degenerate.
  const TriangleSoup s = read_mesh(path);
  const MeshHealth h = check_mesh(s);
  EXPECT_EQ(h.num_vertices, 342);
  EXPECT_EQ(h.num_degenerate_triangles, 20);
  EXPECT_FALSE(h.oriented);
  const RepairResult r = repair_mesh(s);
  EXPECT_TRUE(r.after.oriented);
  EXPECT_TRUE(r.after.closed);
  EXPECT_TRUE(r.after.manifold);
  EXPECT_EQ(r.after.genus, 0);
  EXPECT_EQ(r.after.num_faces, 680);
  const Mesh m(r.soup);
  EXPECT_EQ(m.genus(), 0);
  double volume = 0.0;
  for (const Tri& t : m.triangles()) {
    volume += m.position(t[0]).dot(m.position(t[1]).cross(m.position(t[2]))) / 6.0;
  }
  EXPECT_GT(volume, 0.0);
}

TEST(SharedMeshes, StanfordBunnyHasFiveHolesAndUnreferencedVertices) {
  WINDPLAN_REQUIRE_SHARED_MESH(path, "stanford-bunny.obj");
  const TriangleSoup s = read_mesh(path);
  const MeshHealth h = check_mesh(s);
  EXPECT_EQ(h.num_unreferenced_vertices, 1113);
  EXPECT_EQ(h.num_boundary_loops, 5);
  EXPECT_EQ(h.num_boundary_edges, 223);
  const RepairResult r = repair_mesh(s);
  EXPECT_EQ(r.removed_unreferenced, 1113);
  EXPECT_EQ(r.after.num_vertices, 34834);
}

TEST(SharedMeshes, AerobarZeroAreaTriangleIsFlippedAway) {
  WINDPLAN_REQUIRE_SHARED_MESH(path, "aerobar-brake-mandrel.stl");
  const TriangleSoup s = read_mesh(path);
  const MeshHealth h = check_mesh(s);
  EXPECT_EQ(h.num_zero_area_triangles, 1);
  EXPECT_EQ(h.num_degenerate_triangles, 0);
  const RepairResult r = repair_mesh(s);
  EXPECT_EQ(r.removed_zero_area, 1);
  EXPECT_EQ(r.after.num_zero_area_triangles, 0);
  EXPECT_EQ(r.after.genus, 1);
  EXPECT_TRUE(r.after.closed);
  const Mesh a(Mesh(r.soup));
  double area_before = 0.0;
  for (const Tri& t : s.triangles) {
    area_before +=
        0.5 * (s.points[t[1]] - s.points[t[0]]).cross(s.points[t[2]] - s.points[t[0]]).norm();
  }
  EXPECT_NEAR(a.total_area(), area_before, 1e-9 * area_before);
}

}  // namespace
}  // namespace windplan
