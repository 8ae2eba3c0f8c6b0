#pragma once
// Surface points and the canonical surface path of windplan.
//
// After Liu, Chen, Xin, He, Liu, Zhao, "An Optimization-Driven Approach for Computing Geodesic
// Paths on Triangle Meshes": a path is the ordered sequence of mesh edges it crosses, each
// crossing a point p_i = (1 - l_i) a_i + l_i b_i on its edge.
//
// SurfacePoint convention:
//  - Vertex: `element` is the vertex index.
//  - Edge:   `element` is a halfedge h; the point is (1 - t) from(h) + t to(h), t in [0, 1].
//  - Face:   `element` is a face f; the point is b0 v0 + b1 v1 + b2 v2 with the face's corners in
//            Mesh::triangle(f) order, b0 + b1 + b2 = 1, all >= 0.
//
// SurfacePath convention:
//  - halfedges[i] is the i-th crossed edge, given by the halfedge that lies in the face the path
//    LEAVES: the path runs from face(halfedges[i]) into face(twin(halfedges[i])). It is always
//    an interior halfedge and never a boundary edge.
//  - lambdas[i] in [0, 1] places the crossing at (1 - l) from(h) + l to(h). l == 0 or l == 1
//    means the path touches a mesh vertex there; several consecutive crossings at one vertex
//    mean the path passes through that vertex on the side of the faces of the strip.
//  - The strip faces are f_0 = face(halfedges[0]), f_{i+1} = face(twin(halfedges[i])).
//  - Open path (closed == false): `start` lies in the closure of `start_face`, `end` in the
//    closure of the last strip face. With no crossings, start_face holds both endpoints. The
//    polyline is start, p_0, ..., p_{k-1}, end; segment i lies in strip face f_i.
//  - Closed loop (closed == true): start/end are unused; the strip is cyclic,
//    face(twin(halfedges[k-1])) == face(halfedges[0]); the polyline is p_0, ..., p_{k-1} and
//    the closing segment p_{k-1} -> p_0 lies in face(halfedges[0]).
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

/// A surface point whose edge parameter or barycentric coordinate is within this of a corner is
/// taken to be at that vertex (closest-point queries return corners with round-off).
constexpr double kOnVertex = 1e-12;

struct SurfacePoint {
  enum class Kind { Vertex, Edge, Face };
  Kind kind = Kind::Vertex;
  int element = -1;
  double t = 0.0;             ///< Edge: parameter along the halfedge
  Vec3 bary = Vec3(1, 0, 0);  ///< Face: barycentric coordinates

  static SurfacePoint at_vertex(int v) { return {Kind::Vertex, v, 0.0, Vec3(1, 0, 0)}; }
  static SurfacePoint on_edge(int h, double t) { return {Kind::Edge, h, t, Vec3(1, 0, 0)}; }
  static SurfacePoint in_face(int f, const Vec3& b) { return {Kind::Face, f, 0.0, b}; }
};

/// 3D position of a surface point.
Vec3 position(const Mesh& mesh, const SurfacePoint& p);
/// A face whose closure contains p (for a boundary-free choice, any one).
int containing_face(const Mesh& mesh, const SurfacePoint& p);
/// Whether face f's closure contains p.
bool face_contains(const Mesh& mesh, int f, const SurfacePoint& p);
/// The point as barycentric coordinates in face f (which must contain it).
Vec3 barycentric_in_face(const Mesh& mesh, int f, const SurfacePoint& p);
/// Human-readable form for messages: "vertex 12", "edge 3->7 at t=0.25", "face 9 (0.2,0.3,0.5)".
std::string to_string(const Mesh& mesh, const SurfacePoint& p);

struct SurfacePath {
  bool closed = false;
  SurfacePoint start, end;  ///< open paths only
  int start_face = -1;      ///< open paths only: f_0 when there are no crossings
  std::vector<int> halfedges;
  std::vector<double> lambdas;

  int num_crossings() const { return static_cast<int>(halfedges.size()); }
};

/// Position of crossing i.
inline Vec3 crossing_position(const Mesh& mesh, const SurfacePath& path, int i) {
  const int h = path.halfedges[i];
  const double l = path.lambdas[i];
  return (1.0 - l) * mesh.position(mesh.from(h)) + l * mesh.position(mesh.to(h));
}
/// Strip face before crossing i (i in [0, k]; i == k is the face after the last crossing).
int strip_face(const Mesh& mesh, const SurfacePath& path, int i);
/// The polyline: start, crossings, end (open) or the crossings (closed; not repeated).
std::vector<Vec3> polyline(const Mesh& mesh, const SurfacePath& path);
/// The strip face of each polyline segment (same order as the segments of polyline()).
std::vector<int> segment_faces(const Mesh& mesh, const SurfacePath& path);
/// Euclidean length (mm) including the closing segment of a loop.
double euclidean_length(const Mesh& mesh, const SurfacePath& path);
/// Checks the convention above; returns false with a reason when the path is inconsistent.
bool is_valid_path(const Mesh& mesh, const SurfacePath& path, std::string* why);

}  // namespace windplan
