#pragma once
// The exact polyhedral geodesic distance, as a reference for the geodesic core
// (geometry/geodesic/geodesic.h): CGAL::Surface_mesh_shortest_path (Xin and Wang, "Improving Chen
// and Han's algorithm on the discrete geodesic problem", ACM TOG 2009), Epick kernel.
//
// This header includes no CGAL header; the single translation unit exact_geodesic.cpp does.
// Cost: one sequence tree per source point, O(V^2) worst case in time and memory; about 1 s at
// 20K faces and several seconds and GBs at 100K+ faces. Use it in tests on small meshes and for a
// few sources on large meshes (several targets per source amortise the tree).
//
// Surface points follow geometry/mesh/surface_path.h (vertex / edge halfedge + t / face +
// barycentric in Mesh::triangle(f) order); they are mapped to CGAL face locations, whose
// barycentric coordinates are in the order source(h), target(h), target(next(h)) for h =
// halfedge(f) of the CGAL face (not necessarily our corner 0).
#include <memory>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/mesh/surface_path.h"

namespace windplan {

/// Reusable exact-geodesic state for one mesh: the CGAL mesh is built once and a sequence tree is
/// built per source (precompute / query split). The mesh must outlive this object.
class ExactGeodesic {
 public:
  /// Converts the mesh (O(V + F)).
  explicit ExactGeodesic(const Mesh& mesh);
  ~ExactGeodesic();
  ExactGeodesic(const ExactGeodesic&) = delete;
  ExactGeodesic& operator=(const ExactGeodesic&) = delete;

  /// Exact geodesic distances (mesh units) from `source` to every target, in order. A target on a
  /// different connected component than the source gets +infinity.
  /// \throw InputError naming the point when a surface point refers to an element out of range.
  std::vector<double> distances(const SurfacePoint& source,
                                const std::vector<SurfacePoint>& targets);

  /// The exact shortest path from `source` to `target` as a polyline (source first), and its
  /// length in `distance` (+infinity and an empty polyline when unreachable). The tree of the
  /// last source is kept, so that paths from one source to many targets cost one tree.
  std::vector<Vec3> path(const SurfacePoint& source, const SurfacePoint& target,
                         double* distance = nullptr);

 private:
  struct Impl;
  const Mesh& mesh_;
  std::unique_ptr<Impl> impl_;
};

/// Exact geodesic distance between two surface points (mesh units); +infinity when they lie on
/// different components. Builds a CGAL mesh and one sequence tree.
/// \throw InputError naming the point when it refers to an element out of range.
double exact_geodesic_distance(const Mesh& mesh, const SurfacePoint& source,
                               const SurfacePoint& target);

/// Exact geodesic distances from one source to many targets (one sequence tree).
/// \throw InputError as exact_geodesic_distance.
std::vector<double> exact_geodesic_distances(const Mesh& mesh, const SurfacePoint& source,
                                             const std::vector<SurfacePoint>& targets);

}  // namespace windplan
