// A CGAL translation unit: never include OCCT here (its Handle macro breaks CGAL headers).
#include "geometry/remesh.h"

#include <chrono>
#include <cmath>

#include <CGAL/Polygon_mesh_processing/remesh.h>

#include "geometry/cgal_mesh_types.h"
#include "geometry/errors.h"

namespace windplan {

namespace PMP = CGAL::Polygon_mesh_processing;

bool RemeshOptions::is_valid(std::string* why) const {
  if (!(target_edge_length > 0.0) || !std::isfinite(target_edge_length)) {
    if (why) *why = "remesh target edge length must be > 0 mm";
    return false;
  }
  if (iterations < 1) {
    if (why) *why = "remesh iterations must be >= 1";
    return false;
  }
  return true;
}

RemeshResult remesh_isotropic(const Mesh& mesh, const std::vector<int>& face_patch,
                              const RemeshOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError(why);
  if (!face_patch.empty() && static_cast<int>(face_patch.size()) != mesh.num_faces()) {
    throw InputError("remesh: " + std::to_string(face_patch.size()) + " patch ids for " +
                     std::to_string(mesh.num_faces()) + " faces");
  }
  const auto t0 = std::chrono::steady_clock::now();
  SurfaceMesh sm = to_surface_mesh(mesh);
  using face_descriptor = SurfaceMesh::Face_index;
  using edge_descriptor = SurfaceMesh::Edge_index;
  auto patch = sm.add_property_map<face_descriptor, int>("f:windplan_patch", 0).first;
  for (face_descriptor f : sm.faces()) {
    patch[f] = face_patch.empty() ? 0 : face_patch[static_cast<std::size_t>(f.idx())];
  }
  auto constrained = sm.add_property_map<edge_descriptor, bool>("e:windplan_constrained", false).first;
  std::vector<edge_descriptor> borders;
  for (edge_descriptor e : sm.edges()) {
    const auto h = sm.halfedge(e);
    const bool border = sm.is_border(e) || patch[sm.face(h)] != patch[sm.face(sm.opposite(h))];
    constrained[e] = border;
    if (border) borders.push_back(e);
  }
  // Constrained edges much longer than the target make the remesher cascade: split them first
  // (the new edges inherit the constraint).
  PMP::split_long_edges(borders, options.target_edge_length, sm,
                        CGAL::parameters::edge_is_constrained_map(constrained)
                            .face_patch_map(patch));
  PMP::isotropic_remeshing(faces(sm), options.target_edge_length, sm,
                           CGAL::parameters::number_of_iterations(options.iterations)
                               .edge_is_constrained_map(constrained)
                               .protect_constraints(true)
                               .face_patch_map(patch));
  sm.collect_garbage();
  RemeshResult out;
  out.faces_before = mesh.num_faces();
  out.face_patch.reserve(sm.number_of_faces());
  for (face_descriptor f : sm.faces()) out.face_patch.push_back(patch[f]);
  out.mesh = from_surface_mesh(sm);
  out.faces_after = out.mesh.num_faces();
  out.time_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace windplan
