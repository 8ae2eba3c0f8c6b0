#pragma once
// The windplan triangle mesh: compact indexed arrays with halfedge connectivity.
//
// This is the structure the geodesic optimizer walks millions of times, so every element is an
// int index into flat arrays; there are no per-element heap objects.
//
// Conventions (all indices are 0-based ints; -1 means "none"):
//  - Faces f in [0, F) are triangles (v0, v1, v2), counter-clockwise seen from the outside; the
//    face normal is (p1 - p0) x (p2 - p0) normalised.
//  - Interior halfedges are implicit: h in [0, 3F) belongs to face h / 3 and runs from corner
//    h % 3 to corner (h % 3 + 1) % 3, i.e. from(h) = tri[f][k], to(h) = tri[f][(k + 1) % 3].
//    next(h) and prev(h) stay in the face. corner_angle(h) is the angle at from(h) in face(h).
//  - Boundary halfedges h in [3F, 3F + B) have face(h) == -1; they run along the boundary so that
//    the interior lies on their right (opposite to their twin); next(h) follows the boundary loop.
//  - twin(h) is never -1: every interior halfedge without a neighbour face is paired with a
//    boundary halfedge. edge(h) == edge(twin(h)); edge_halfedge(e) is the interior one of the
//    pair (the lower index), so face(edge_halfedge(e)) is always valid.
//  - vertex_halfedge(v) is an interior halfedge going out of v; for a boundary vertex it is the
//    most clockwise one (its twin is a boundary halfedge), so that rotating counter-clockwise with
//    ccw_rotate(h) = twin(prev(h)) visits every face around v once. Unreferenced vertices have -1.
//
// A Mesh is built from a TriangleSoup that must already be an oriented 2-manifold (with or
// without boundary); geometry/mesh/mesh_validation.h checks and repairs soups before that.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace windplan {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;
using Tri = std::array<int, 3>;

/// Points and triangles as read from a file, before any connectivity is built.
struct TriangleSoup {
  std::vector<Vec3> points;
  std::vector<Tri> triangles;
};

/// Axis-aligned bounding box.
struct BoundingBox {
  Vec3 min = Vec3::Constant(0.0);
  Vec3 max = Vec3::Constant(0.0);
  Vec3 diagonal() const { return max - min; }
  double diagonal_length() const { return (max - min).norm(); }
};

/// Classification of a vertex by its cone angle (sum of corner angles) against 2*pi.
enum class VertexType { Spherical, Euclidean, Saddle, Boundary, Isolated };

class Mesh {
 public:
  Mesh() = default;

  /// Builds the halfedge connectivity in O(V + F) (bounded vertex degree).
  /// \param soup points and triangles; indices must be in range and the triangles must form an
  ///        oriented 2-manifold: no repeated index in a triangle, every undirected edge in at most
  ///        two triangles with opposite directions, every vertex a single fan.
  /// \throw TopologyError naming the first offending triangle, edge or vertex otherwise.
  explicit Mesh(TriangleSoup soup);

  // ---- sizes ----
  int num_vertices() const { return static_cast<int>(points_.size()); }
  int num_faces() const { return static_cast<int>(tris_.size()); }
  int num_edges() const { return static_cast<int>(edge_halfedge_.size()); }
  int num_halfedges() const { return static_cast<int>(twin_.size()); }
  int num_interior_halfedges() const { return 3 * num_faces(); }
  int num_boundary_halfedges() const { return num_halfedges() - num_interior_halfedges(); }

  // ---- raw arrays ----
  const std::vector<Vec3>& points() const { return points_; }
  const std::vector<Tri>& triangles() const { return tris_; }
  const Vec3& position(int v) const { return points_[v]; }
  const Tri& triangle(int f) const { return tris_[f]; }
  /// Moves every vertex (connectivity unchanged), e.g. for unit scaling.
  void set_points(std::vector<Vec3> points);

  // ---- halfedge navigation ----
  bool is_boundary_halfedge(int h) const { return h >= 3 * num_faces(); }
  int face(int h) const { return is_boundary_halfedge(h) ? -1 : h / 3; }
  int twin(int h) const { return twin_[h]; }
  int next(int h) const {
    return is_boundary_halfedge(h) ? bnext_[h - 3 * num_faces()] : (h % 3 == 2 ? h - 2 : h + 1);
  }
  int prev(int h) const {
    return is_boundary_halfedge(h) ? bprev_[h - 3 * num_faces()] : (h % 3 == 0 ? h + 2 : h - 1);
  }
  // (Not through each other: a boundary halfedge's twin is interior. Mutual recursion kept the
  // compiler from inlining them in the hot loops of the window search.)
  int from(int h) const {
    return is_boundary_halfedge(h) ? interior_to(twin_[h]) : interior_from(h);
  }
  int to(int h) const { return is_boundary_halfedge(h) ? interior_from(twin_[h]) : interior_to(h); }
  int edge(int h) const { return edge_[h]; }
  int edge_halfedge(int e) const { return edge_halfedge_[e]; }
  int face_halfedge(int f) const { return 3 * f; }
  int vertex_halfedge(int v) const { return vertex_halfedge_[v]; }
  /// Next outgoing interior halfedge counter-clockwise around from(h); -1 past a boundary.
  int ccw_rotate(int h) const {
    const int t = twin_[prev(h)];
    return is_boundary_halfedge(t) ? -1 : t;
  }
  /// Next outgoing interior halfedge clockwise around from(h); -1 past a boundary.
  int cw_rotate(int h) const {
    const int t = twin_[h];
    return is_boundary_halfedge(t) ? -1 : next(t);
  }
  /// The vertex of face(h) opposite to the edge of h (interior h only).
  int opposite_vertex(int h) const { return to(next(h)); }
  bool is_boundary_edge(int e) const { return is_boundary_halfedge(twin_[edge_halfedge_[e]]); }
  bool is_boundary_vertex(int v) const {
    const int h = vertex_halfedge_[v];
    return h >= 0 && is_boundary_halfedge(twin_[h]);
  }
  /// Outgoing interior halfedges of v, counter-clockwise, starting at vertex_halfedge(v).
  std::vector<int> outgoing_halfedges(int v) const;
  /// Number of incident edges (0 for an unreferenced vertex).
  int valence(int v) const;

  // ---- geometry ----
  double edge_length(int e) const;
  double halfedge_length(int h) const { return (position(to(h)) - position(from(h))).norm(); }
  Vec3 face_normal(int f) const;       ///< unit normal, zero vector for a zero-area face
  Vec3 face_area_vector(int f) const;  ///< (p1-p0) x (p2-p0) / 2: normal times area
  double face_area(int f) const;
  Vec3 face_centroid(int f) const;
  /// Interior angle (radians) at from(h) in face(h); h must be interior.
  double corner_angle(int h) const;
  /// Sum of corner angles at v (radians).
  double cone_angle(int v) const;
  /// Spherical / Euclidean / saddle by cone angle against 2*pi within tol (radians).
  VertexType vertex_type(int v, double tol = 1e-9) const;
  /// Angle-weighted unit vertex normal.
  Vec3 vertex_normal(int v) const;
  double total_area() const;
  BoundingBox bounding_box() const;
  /// Min, mean and max edge length, over all edges. Zeros for an empty mesh.
  std::array<double, 3> edge_length_stats() const;

  // ---- topology ----
  /// Connected components of faces: per-face component id in [0, count).
  std::vector<int> face_components(int* count = nullptr) const;
  int num_components() const;
  /// V - E + F (unreferenced vertices excluded).
  int euler_characteristic() const;
  int num_unreferenced_vertices() const;
  /// Genus of a single-component orientable surface with b boundary loops: (2 - chi - b) / 2.
  /// Returns -1 when the mesh has several components.
  int genus() const;
  bool is_closed() const { return num_boundary_halfedges() == 0; }
  /// Boundary loops as sequences of boundary halfedges, each loop in next() order, loops ordered
  /// by their smallest halfedge index.
  std::vector<std::vector<int>> boundary_loops() const;
  /// The vertices of a boundary loop given as halfedges (from(h) of each).
  std::vector<int> loop_vertices(const std::vector<int>& loop) const;

 private:
  int interior_from(int h) const { return corners_[h]; }
  int interior_to(int h) const { return corners_[h % 3 == 2 ? h - 2 : h + 1]; }

  std::vector<Vec3> points_;
  std::vector<Tri> tris_;
  // The faces' corners in one run, from(h) per interior halfedge h (tris_[h / 3][h % 3]): one
  // load where the division by 3 costs a multiply and shifts (about 1 % of the exact geodesic
  // search's instructions, bench/README.md, session 14).
  std::vector<int> corners_;
  std::vector<int> twin_;             // per halfedge (interior, then boundary)
  std::vector<int> edge_;             // per halfedge
  std::vector<int> edge_halfedge_;    // per edge
  std::vector<int> vertex_halfedge_;  // per vertex
  std::vector<int> bnext_, bprev_;    // per boundary halfedge (index h - 3F)
};

}  // namespace windplan
