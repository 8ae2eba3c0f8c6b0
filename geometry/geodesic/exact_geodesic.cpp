// The only translation unit that instantiates CGAL::Surface_mesh_shortest_path (expensive to
// compile); everything else reaches it through the CGAL-free geometry/geodesic/exact_geodesic.h.
#include "geometry/geodesic/exact_geodesic.h"

#include <algorithm>
#include <iterator>
#include <limits>
#include <string>

#include <CGAL/Surface_mesh_shortest_path.h>

#include "geometry/base/errors.h"
#include "geometry/mesh/cgal_mesh_types.h"

namespace windplan {

namespace {

using Traits = CGAL::Surface_mesh_shortest_path_traits<CgalKernel, SurfaceMesh>;
using ShortestPath = CGAL::Surface_mesh_shortest_path<Traits>;
using FaceLocation = ShortestPath::Face_location;

void check_point(const Mesh& mesh, const SurfacePoint& p, const char* role) {
  bool ok = p.element >= 0;
  switch (p.kind) {
    case SurfacePoint::Kind::Vertex:
      ok = ok && p.element < mesh.num_vertices() && mesh.vertex_halfedge(p.element) >= 0;
      break;
    case SurfacePoint::Kind::Edge:
      ok = ok && p.element < mesh.num_halfedges() && p.t >= 0.0 && p.t <= 1.0;
      break;
    case SurfacePoint::Kind::Face:
      ok = ok && p.element < mesh.num_faces() && p.bary.allFinite();
      break;
  }
  if (!ok) {
    throw InputError(std::string("exact geodesic: ") + role + " point (element " +
                     std::to_string(p.element) + ") is not a valid surface point of a mesh with " +
                     std::to_string(mesh.num_vertices()) + " vertices and " +
                     std::to_string(mesh.num_faces()) + " faces");
  }
}

}  // namespace

struct ExactGeodesic::Impl {
  SurfaceMesh sm;
  ShortestPath shortest;
  explicit Impl(const Mesh& mesh) : sm(to_surface_mesh(mesh)), shortest(sm) {}

  // Our barycentric coordinates follow Mesh::triangle(f); CGAL's follow the halfedge cycle that
  // starts at halfedge(f). Both keep the same cyclic order (to_surface_mesh keeps orientation),
  // so the map is a rotation by the corner index of CGAL's first source vertex.
  FaceLocation location(const Mesh& mesh, const SurfacePoint& p) const {
    const int f = containing_face(mesh, p);
    const Vec3 b = barycentric_in_face(mesh, f, p);
    const SurfaceMesh::Face_index cf(static_cast<SurfaceMesh::size_type>(f));
    const int first = static_cast<int>(sm.source(sm.halfedge(cf)));
    const Tri& t = mesh.triangle(f);
    const int k = t[0] == first ? 0 : t[1] == first ? 1 : 2;
    return FaceLocation(cf, {{b[k], b[(k + 1) % 3], b[(k + 2) % 3]}});
  }

  // The sequence tree of the last source is kept: consecutive queries from one source reuse it.
  bool has_source = false;
  SurfacePoint last_source;

  void set_source(const Mesh& mesh, const SurfacePoint& source) {
    if (has_source && source.kind == last_source.kind && source.element == last_source.element &&
        source.t == last_source.t && source.bary == last_source.bary) {
      return;
    }
    has_source = false;
    shortest.remove_all_source_points();
    if (source.kind == SurfacePoint::Kind::Vertex) {
      shortest.add_source_point(SurfaceMesh::Vertex_index(source.element));
    } else {
      shortest.add_source_point(location(mesh, source));
    }
    shortest.build_sequence_tree();
    last_source = source;
    has_source = true;
  }

  double distance_to(const Mesh& mesh, const SurfacePoint& target) {
    const double d =
        target.kind == SurfacePoint::Kind::Vertex
            ? shortest.shortest_distance_to_source_points(SurfaceMesh::Vertex_index(target.element))
                  .first
            : [&] {
                const FaceLocation l = location(mesh, target);
                return shortest.shortest_distance_to_source_points(l.first, l.second).first;
              }();
    // CGAL reports an unreachable point (another component) with a negative distance.
    return d < 0.0 ? std::numeric_limits<double>::infinity() : d;
  }
};

ExactGeodesic::ExactGeodesic(const Mesh& mesh) : mesh_(mesh), impl_(std::make_unique<Impl>(mesh)) {}

ExactGeodesic::~ExactGeodesic() = default;

std::vector<double> ExactGeodesic::distances(const SurfacePoint& source,
                                             const std::vector<SurfacePoint>& targets) {
  check_point(mesh_, source, "source");
  for (const SurfacePoint& t : targets) check_point(mesh_, t, "target");
  impl_->set_source(mesh_, source);
  std::vector<double> out;
  out.reserve(targets.size());
  for (const SurfacePoint& t : targets) out.push_back(impl_->distance_to(mesh_, t));
  return out;
}

std::vector<Vec3> ExactGeodesic::path(const SurfacePoint& source, const SurfacePoint& target,
                                      double* distance) {
  check_point(mesh_, source, "source");
  check_point(mesh_, target, "target");
  impl_->set_source(mesh_, source);
  std::vector<CgalPoint> points;
  double d = 0.0;
  if (target.kind == SurfacePoint::Kind::Vertex) {
    d = impl_->shortest
            .shortest_path_points_to_source_points(SurfaceMesh::Vertex_index(target.element),
                                                   std::back_inserter(points))
            .first;
  } else {
    const FaceLocation l = impl_->location(mesh_, target);
    d = impl_->shortest
            .shortest_path_points_to_source_points(l.first, l.second, std::back_inserter(points))
            .first;
  }
  if (distance) *distance = d < 0.0 ? std::numeric_limits<double>::infinity() : d;
  std::vector<Vec3> out;
  if (d < 0.0) return out;
  // CGAL lists the points from the query back to the source.
  for (auto it = points.rbegin(); it != points.rend(); ++it)
    out.emplace_back(it->x(), it->y(), it->z());
  return out;
}

double exact_geodesic_distance(const Mesh& mesh, const SurfacePoint& source,
                               const SurfacePoint& target) {
  return exact_geodesic_distances(mesh, source, {target}).front();
}

std::vector<double> exact_geodesic_distances(const Mesh& mesh, const SurfacePoint& source,
                                             const std::vector<SurfacePoint>& targets) {
  ExactGeodesic exact(mesh);
  return exact.distances(source, targets);
}

}  // namespace windplan
