#pragma once
// Initial paths for the geodesic core: shortest paths along mesh edges (A* with the straight-line
// distance as heuristic, or plain Dijkstra) and their conversion into a face strip with edge
// crossings (a SurfacePath), for open paths between two surface points, for closed vertex cycles
// and for curves given as points near the surface.
#include <functional>
#include <vector>

#include "geometry/geodesic/path_metric.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/surface_path.h"

namespace windplan {

/// The vertex graph of a mesh in compressed rows, with edge weights under a metric
/// (precompute once per mesh and metric; query many times).
struct EdgeGraph {
  std::vector<int> offsets;     ///< #V + 1
  std::vector<int> neighbors;   ///< per entry: the neighbour vertex
  std::vector<double> weights;  ///< per entry: length (mm) times the smaller adjacent density
  /// With diagonals: per entry, -1 for a mesh edge, else the halfedge crossed by the diagonal,
  /// given in the face that contains the entry's source vertex. Empty without diagonals.
  std::vector<int> via;
  double min_density = 1.0;  ///< keeps the A* heuristic admissible under a density metric
  bool anisotropic = false;  ///< A* is disabled (no cheap admissible heuristic)
};

/// Builds the graph. Anisotropic metrics weigh each edge by its metric length in the
/// adjacent face where it is smallest. With `diagonals`, every pair of adjacent triangles whose
/// unfolding is convex also links its two opposite vertices by the straight line across the
/// shared edge (Euclidean and density metrics): shortest paths in that graph are much closer to
/// geodesics (a few per mille instead of a few per cent), so the refinement starts nearer the
/// global geodesic and reroutes less.
EdgeGraph build_edge_graph(const Mesh& mesh, const PathMetric& metric = {}, bool diagonals = false);

struct EdgePathOptions {
  bool use_astar = true;  ///< A* (early exit, straight-line heuristic) or plain Dijkstra
};

struct EdgePath {
  std::vector<int> vertices;  ///< from a vertex of the start's face to one of the end's face
  /// Per vertex: the halfedge crossed by the diagonal that reaches it (graph.via), or -1.
  std::vector<int> via;
  double length = 0.0;  ///< weighted graph length incl. the legs to the points (mm)
  int settled = 0;      ///< vertices settled by the search (diagnostics)
  bool found = false;
};

/// Shortest edge path between two surface points. Sources are the vertices of the faces that
/// contain `a` (weighted by the straight distance to a), targets those of `b`.
EdgePath shortest_edge_path(const Mesh& mesh, const EdgeGraph& graph, const SurfacePoint& a,
                            const SurfacePoint& b, const EdgePathOptions& options = {});

/// Face strip along a vertex path from a to b (a's face contains vertices.front(), b's face
/// contains vertices.back()); at every vertex the strip turns on the side of the smaller angle.
/// The crossings start close to the vertices (lambda 0.25 from them).
/// `via` (optional, as EdgePath::via) marks steps that are diagonals across an edge.
SurfacePath strip_from_vertex_path(const Mesh& mesh, const SurfacePoint& a,
                                   const std::vector<int>& vertices, const SurfacePoint& b,
                                   const std::vector<int>* via = nullptr);

/// Closed face strip along a closed vertex cycle (the first vertex is not repeated at the end).
/// \throw InputError when the cycle has fewer than 3 vertices or is not connected by edges.
SurfacePath strip_from_vertex_cycle(const Mesh& mesh, const std::vector<int>& cycle);

/// Initial open path: shortest edge path, then strip. \throw InputError if b is unreachable
/// from a (different components), naming both points.
SurfacePath initial_open_path(const Mesh& mesh, const EdgeGraph& graph, const SurfacePoint& a,
                              const SurfacePoint& b, const EdgePathOptions& options = {},
                              EdgePath* diagnostics = nullptr);

/// Initial path from a curve given as points on or near the surface: each point is snapped to
/// the closest surface point (error if farther than max_distance), consecutive snapped points
/// are joined by shortest edge paths, and the result is turned into a strip. A closed curve
/// gives a loop; an open one a path from the first to the last point.
/// \throw InputError naming the first point that is too far, or a curve with < 2 points.
SurfacePath path_from_curve(const Mesh& mesh, const EdgeGraph& graph,
                            const std::vector<Vec3>& points, bool closed, double max_distance);

/// The open path `first` (ending at vertex q) continued by `second` (starting at q): a rotation
/// around q from first's last strip face to second's first, on the side of the smaller angle (a
/// boundary vertex has one side only), with the crossings on q (lambda 0 or 1).
/// Returns a path with start_face -1 when neither side reaches second's face.
SurfacePath join_at_vertex(const Mesh& mesh, const SurfacePath& first, const SurfacePath& second,
                           int q);

/// A vertex chain without repeats (u, u) and back-and-forth spurs (u, w, u), which a face strip
/// cannot represent.
std::vector<int> remove_spurs(const std::vector<int>& chain);

/// The vertex a surface point sits on (within kOnVertex of a corner), or -1.
int as_vertex(const Mesh& mesh, const SurfacePoint& p);

/// Faces whose closure contains p (every face around a vertex, both faces of an edge).
std::vector<int> faces_containing(const Mesh& mesh, const SurfacePoint& p);

/// Appends to `path` the crossings of a rotation around vertex u from face *face to the first
/// face for which stop(face) holds, on the side where the angle swept from prev_point to
/// next_point (points on the path before and after u) is smaller; *face becomes that face.
/// Crossings sit a quarter of the spoke away from u. Nothing when stop(*face) already holds.
/// 	hrow InvariantError when neither side reaches such a face.
void turn_at(const Mesh& mesh, int u, int* face, const Vec3& prev_point, const Vec3& next_point,
             const std::function<bool(int)>& stop, SurfacePath* path);

}  // namespace windplan
