#pragma once
// windplan::Mesh <-> CGAL::Surface_mesh<Epick::Point_3>, behind an opaque handle so that this
// header stays cheap: it includes no CGAL header. CGAL translation units that need the CGAL type
// itself include geometry/mesh/cgal_mesh_types.h instead (to_surface_mesh / from_surface_mesh).
//
// Index convention (both directions): vertex i of the Mesh is Surface_mesh vertex i, face f is
// Surface_mesh face f, and face f keeps its orientation (its vertices in the same cyclic order).
// Unreferenced Mesh vertices become isolated Surface_mesh vertices, so the indices stay equal.
#include <memory>

#include "geometry/mesh/mesh.h"

namespace windplan {

class CgalMesh {
 public:
  /// An empty Surface_mesh.
  CgalMesh();
  /// Converts a Mesh (O(V + F)).
  explicit CgalMesh(const Mesh& mesh);
  ~CgalMesh();
  CgalMesh(CgalMesh&&) noexcept;
  CgalMesh& operator=(CgalMesh&&) noexcept;
  CgalMesh(const CgalMesh&);
  CgalMesh& operator=(const CgalMesh&);

  int num_vertices() const;
  int num_faces() const;
  int num_edges() const;
  /// CGAL's own consistency check of the halfedge structure (Surface_mesh::is_valid).
  bool is_valid() const;
  /// No border halfedge (CGAL::is_closed).
  bool is_closed() const;
  /// Total area computed by CGAL::Polygon_mesh_processing::area (mesh units squared).
  double area() const;
  /// Enclosed volume by CGAL::Polygon_mesh_processing::volume; closed meshes only.
  /// \throw TopologyError if the mesh is not closed.
  double volume() const;
  /// Converts back to a Mesh (same vertex and face indices).
  /// \throw TopologyError if a face is not a triangle or the result is not a valid Mesh.
  Mesh to_mesh() const;

  /// The CGAL object, reachable only through geometry/mesh/cgal_mesh_types.h.
  struct Impl;
  Impl& impl() { return *impl_; }
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace windplan
