#pragma once
// The start corridor of the geodesic core: shortest paths in a Steiner-point graph.
//
// After Lanthier, Maheshwari, Sack, "Approximating shortest paths on weighted polyhedral
// surfaces" (Algorithmica 30, 2001) and Aleksandrov, Maheshwari, Sack, "Determining approximate
// shortest paths on weighted polyhedral surfaces" (JACM 52, 2005): every edge carries k Steiner
// points, and any two points on the boundary of a common face (vertices included) are joined by
// the straight segment inside that face. A path in this graph is a polyline on the surface, so
// the graph distance is >= the geodesic distance, and it approaches it as k grows (for k evenly
// spaced points the excess per face crossed is O(edge length / k^2) where the geodesic crosses
// an edge at a small angle and less elsewhere). Unlike the vertex graph of
// geometry/geodesic/edge_path.h, whose paths must bend at vertices (a few per cent longer than the
// geodesic), these paths cross edges where the geodesic does, so the graph's shortest path lies in
// the corridor of the globally shortest geodesic whenever the next locally shortest one is longer
// by more than the graph's excess; the geodesic core (geometry/geodesic/geodesic.h) then refines
// that corridor exactly.
//
// Node numbering: vertex v is node v; Steiner point i (0 <= i < k) of edge e is node
// #V + k e + i, at t = (i + 1) / (k + 1) along the edge's halfedge Mesh::edge_halfedge(e)
// (t = 0 at from(h)). Segments are weighted by the Euclidean length times the face's density
// (density metric); anisotropic metrics are not supported (the caller falls back to edge paths).
#include <vector>

#include "geometry/geodesic/path_metric.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/surface_path.h"

namespace windplan {

/// The Steiner-point graph of a mesh (precompute once per mesh and metric; query many times,
/// also from several threads at once: queries keep their scratch space per thread).
class SteinerGraph {
 public:
  /// \param points_per_edge k >= 1 Steiner points per edge.
  /// \throw InputError for an anisotropic metric or k < 1.
  SteinerGraph(const Mesh& mesh, const PathMetric& metric, int points_per_edge);

  const Mesh& mesh() const { return mesh_; }
  int points_per_edge() const { return k_; }
  int num_nodes() const { return static_cast<int>(position_.size()); }
  const Vec3& position(int node) const { return position_[node]; }
  bool is_vertex(int node) const { return node < mesh_.num_vertices(); }
  /// Edge of a Steiner node (not a vertex) and its parameter along Mesh::edge_halfedge(edge).
  int edge_of(int node) const { return (node - mesh_.num_vertices()) / k_; }
  double t_of(int node) const { return ((node - mesh_.num_vertices()) % k_ + 1.0) / (k_ + 1.0); }
  /// The 3 + 3k nodes on the boundary of face f.
  const int* face_nodes(int f) const {
    return &face_nodes_[static_cast<std::size_t>(f) * per_face_];
  }
  int nodes_per_face() const { return per_face_; }
  /// Faces around vertex v.
  const int* vertex_faces_begin(int v) const { return &vertex_faces_[vertex_face_offsets_[v]]; }
  const int* vertex_faces_end(int v) const { return &vertex_faces_[vertex_face_offsets_[v + 1]]; }
  /// Segment weight factor in face f (1 under the Euclidean metric).
  double density(int f) const { return density_.empty() ? 1.0 : density_[f]; }
  double min_density() const { return min_density_; }

 private:
  const Mesh& mesh_;
  int k_ = 1, per_face_ = 6;
  std::vector<Vec3> position_;
  std::vector<int> face_nodes_;
  std::vector<int> vertex_face_offsets_, vertex_faces_;
  std::vector<double> density_;
  double min_density_ = 1.0;
};

/// A shortest path in the Steiner graph from surface point a to surface point b.
struct SteinerPath {
  /// Nodes from the first to the last: a's node first when a is a vertex, b's last when b is.
  std::vector<int> nodes;
  /// faces[i]: the face holding the segment that arrives at nodes[i] (-1 for a vertex a, which
  /// is reached by no segment); faces.back() holds the last segment (to b, or the one arriving
  /// at b's node), so faces.size() == nodes.size() + 1.
  std::vector<int> faces;
  double length = 0.0;  ///< weighted length incl. the legs to the points (mm)
  int settled = 0;      ///< nodes settled by the search (diagnostics)
  bool found = false;
};

/// A* over the Steiner graph (straight-line heuristic times the smallest density). When a and b
/// share a face the result has no nodes (found, length of the straight segment).
SteinerPath shortest_steiner_path(const SteinerGraph& graph, const SurfacePoint& a,
                                  const SurfacePoint& b);

/// The face strip of a Steiner path (a SurfacePath from a to b with crossings at the path's
/// Steiner points; at a vertex the strip turns on the side of the smaller angle, crossings a
/// quarter of the spoke away from the vertex).
/// \throw InvariantError when the path is not a chain of segments in adjacent faces.
SurfacePath strip_from_steiner_path(const SteinerGraph& graph, const SurfacePoint& a,
                                    const SteinerPath& path, const SurfacePoint& b);

}  // namespace windplan
