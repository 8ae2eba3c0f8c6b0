#include "geometry/geodesic/edge_path_steiner.h"

#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/geodesic/edge_path.h"
#include "geometry/geodesic/geodesic.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

// On a plane the geodesic is the straight segment: the Steiner path is a polyline between the
// straight distance and the vertex-graph path, closer with more points, and its strip refines
// to the straight distance.
TEST(SteinerPath, PlaneBoundsAndStripRefinesToTheStraightLine) {
  const Mesh mesh(test::grid(12, 9, 1.0));
  const int a = 0, b = 9 * 13 + 12;  // (0, 0) and (12, 9): no grid diagonal joins them
  const Vec3 pa = mesh.position(a), pb = mesh.position(b);
  const double straight = (pb - pa).norm();
  const EdgePath edge = shortest_edge_path(mesh, build_edge_graph(mesh), SurfacePoint::at_vertex(a),
                                           SurfacePoint::at_vertex(b));
  double previous = edge.length;
  for (int k : {1, 2, 4}) {
    const SteinerGraph graph(mesh, PathMetric{}, k);
    EXPECT_EQ(graph.num_nodes(), mesh.num_vertices() + k * mesh.num_edges());
    const SteinerPath sp =
        shortest_steiner_path(graph, SurfacePoint::at_vertex(a), SurfacePoint::at_vertex(b));
    ASSERT_TRUE(sp.found);
    EXPECT_EQ(sp.faces.size(), sp.nodes.size() + 1);
    EXPECT_GE(sp.length, straight * (1 - 1e-12));
    EXPECT_LE(sp.length, previous * (1 + 1e-12)) << "k = " << k;
    previous = sp.length;
    // The polyline through the nodes has the reported length.
    double polyline_length = 0.0;
    for (std::size_t i = 1; i < sp.nodes.size(); ++i)
      polyline_length += (graph.position(sp.nodes[i]) - graph.position(sp.nodes[i - 1])).norm();
    EXPECT_NEAR(polyline_length, sp.length, 1e-12 * straight);

    const SurfacePath strip =
        strip_from_steiner_path(graph, SurfacePoint::at_vertex(a), sp, SurfacePoint::at_vertex(b));
    std::string why;
    ASSERT_TRUE(is_valid_path(mesh, strip, &why)) << why;
    // (The strip's initial crossings sit off the vertices it turns around, so its polyline is
    // not the graph path's.)
    const GeodesicResult r = refine_path(mesh, strip);
    EXPECT_NEAR(r.summary.final_length, straight, 1e-10 * straight) << "k = " << k;
  }
  EXPECT_LT(previous, edge.length);
}

// Points inside faces and on edges as endpoints; a shared face gives no nodes.
TEST(SteinerPath, FaceAndEdgeEndpoints) {
  const Mesh mesh(test::grid(6, 6, 1.0));
  const SteinerGraph graph(mesh, PathMetric{}, 3);
  const SurfacePoint a = SurfacePoint::in_face(0, Vec3(0.2, 0.3, 0.5));
  const SurfacePoint b = SurfacePoint::on_edge(3 * (mesh.num_faces() - 1), 0.4);
  const SteinerPath sp = shortest_steiner_path(graph, a, b);
  ASSERT_TRUE(sp.found);
  const double straight = (position(mesh, b) - position(mesh, a)).norm();
  EXPECT_GE(sp.length, straight * (1 - 1e-12));
  const SurfacePath strip = strip_from_steiner_path(graph, a, sp, b);
  std::string why;
  ASSERT_TRUE(is_valid_path(mesh, strip, &why)) << why;
  EXPECT_NEAR(refine_path(mesh, strip).summary.final_length, straight, 1e-10 * straight);

  const SurfacePoint c = SurfacePoint::in_face(0, Vec3(0.6, 0.2, 0.2));
  const SteinerPath same = shortest_steiner_path(graph, a, c);
  EXPECT_TRUE(same.found);
  EXPECT_TRUE(same.nodes.empty());
  EXPECT_NEAR(same.length, (position(mesh, c) - position(mesh, a)).norm(), 1e-15);
}

// Around a cone vertex of an octahedron the path and its strip stay consistent, and a vertex
// passed by the Steiner path is turned around.
TEST(SteinerPath, OctahedronOppositeVertices) {
  const Mesh mesh(test::octahedron());
  const SteinerGraph graph(mesh, PathMetric{}, 2);
  const SteinerPath sp =
      shortest_steiner_path(graph, SurfacePoint::at_vertex(0), SurfacePoint::at_vertex(1));
  ASSERT_TRUE(sp.found);
  const SurfacePath strip =
      strip_from_steiner_path(graph, SurfacePoint::at_vertex(0), sp, SurfacePoint::at_vertex(1));
  std::string why;
  ASSERT_TRUE(is_valid_path(mesh, strip, &why)) << why;
  // Exact: unfold two faces around the middle: 2 * sqrt(2) * sin(60 deg) * ... = sqrt(6).
  EXPECT_NEAR(refine_path(mesh, strip).summary.final_length, std::sqrt(6.0), 1e-9);
}

TEST(SteinerPath, BadOptions) {
  const Mesh mesh(test::grid(2, 2, 1.0));
  EXPECT_THROW(SteinerGraph(mesh, PathMetric{}, 0), InputError);
  const PathMetric aniso = PathMetric::anisotropic(
      mesh, std::vector<std::array<double, 3>>(mesh.num_faces(), {1, 0, 1}));
  EXPECT_THROW(SteinerGraph(mesh, aniso, 2), InputError);
}

}  // namespace
}  // namespace windplan
