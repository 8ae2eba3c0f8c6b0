// The only translation unit that instantiates Surface_mesh for the Mesh conversion; keep CGAL out
// of everything else that is compiled often.
#include "geometry/mesh/cgal_mesh_types.h"

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/boost/graph/helpers.h>

#include "geometry/base/errors.h"

namespace windplan {

SurfaceMesh to_surface_mesh(const Mesh& mesh) {
  SurfaceMesh sm;
  sm.reserve(mesh.num_vertices(), mesh.num_edges(), mesh.num_faces());
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Vec3& p = mesh.position(v);
    sm.add_vertex(CgalPoint(p.x(), p.y(), p.z()));
  }
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Tri& t = mesh.triangle(f);
    const SurfaceMesh::Face_index fi =
        sm.add_face(SurfaceMesh::Vertex_index(t[0]), SurfaceMesh::Vertex_index(t[1]),
                    SurfaceMesh::Vertex_index(t[2]));
    if (fi == SurfaceMesh::null_face() || static_cast<int>(fi) != f) {
      throw InvariantError("to_surface_mesh: CGAL rejected triangle " + std::to_string(f));
    }
  }
  return sm;
}

Mesh from_surface_mesh(const SurfaceMesh& sm) {
  TriangleSoup soup;
  std::vector<int> index(sm.num_vertices() + sm.number_of_removed_vertices(), -1);
  soup.points.reserve(sm.number_of_vertices());
  for (SurfaceMesh::Vertex_index v : sm.vertices()) {
    index[static_cast<std::size_t>(v)] = static_cast<int>(soup.points.size());
    const CgalPoint& p = sm.point(v);
    soup.points.emplace_back(p.x(), p.y(), p.z());
  }
  soup.triangles.reserve(sm.number_of_faces());
  for (SurfaceMesh::Face_index f : sm.faces()) {
    // The cyclic order is kept; the starting corner is whichever halfedge CGAL stores.
    std::vector<int> vs;
    for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      vs.push_back(index[static_cast<std::size_t>(v)]);
    }
    if (vs.size() != 3) {
      throw TopologyError("from_surface_mesh: face " + std::to_string(static_cast<int>(f)) +
                          " has " + std::to_string(vs.size()) + " vertices, not 3");
    }
    soup.triangles.push_back({vs[0], vs[1], vs[2]});
  }
  return Mesh(std::move(soup));
}

CgalMesh::CgalMesh() : impl_(std::make_unique<Impl>()) {}
CgalMesh::CgalMesh(const Mesh& mesh) : impl_(std::make_unique<Impl>(Impl{to_surface_mesh(mesh)})) {}
CgalMesh::~CgalMesh() = default;
CgalMesh::CgalMesh(CgalMesh&&) noexcept = default;
CgalMesh& CgalMesh::operator=(CgalMesh&&) noexcept = default;
CgalMesh::CgalMesh(const CgalMesh& o) : impl_(std::make_unique<Impl>(*o.impl_)) {}
CgalMesh& CgalMesh::operator=(const CgalMesh& o) {
  if (this != &o) impl_ = std::make_unique<Impl>(*o.impl_);
  return *this;
}

int CgalMesh::num_vertices() const { return static_cast<int>(impl_->mesh.number_of_vertices()); }
int CgalMesh::num_faces() const { return static_cast<int>(impl_->mesh.number_of_faces()); }
int CgalMesh::num_edges() const { return static_cast<int>(impl_->mesh.number_of_edges()); }
bool CgalMesh::is_valid() const { return impl_->mesh.is_valid(false); }
bool CgalMesh::is_closed() const { return CGAL::is_closed(impl_->mesh); }
double CgalMesh::area() const { return CGAL::Polygon_mesh_processing::area(impl_->mesh); }
double CgalMesh::volume() const {
  if (!is_closed()) throw TopologyError("CgalMesh::volume: the mesh is not closed");
  return CGAL::Polygon_mesh_processing::volume(impl_->mesh);
}
Mesh CgalMesh::to_mesh() const { return from_surface_mesh(impl_->mesh); }

}  // namespace windplan
