// A CGAL translation unit: never include OCCT here (its Handle macro breaks CGAL headers).
#include "geometry/mesh/remesh.h"

#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>

#include "geometry/base/errors.h"
#include "geometry/mesh/cgal_mesh_types.h"

namespace windplan {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

using face_descriptor = SurfaceMesh::Face_index;
using edge_descriptor = SurfaceMesh::Edge_index;
using PatchMap = SurfaceMesh::Property_map<face_descriptor, int>;
using ConstraintMap = SurfaceMesh::Property_map<edge_descriptor, bool>;

constexpr int kNoPatch = -1;

// PMP::split_long_edges(edges, ...) takes no face patch map: the faces it creates by splitting a
// face in two get the property map's default. Each new face lies inside the input face it was cut
// from, and is joined to that face's other pieces by the new, unconstrained diagonals; input
// faces of other patches are only ever behind constrained edges (every patch border is
// constrained). So a flood across unconstrained edges gives every new face its input face's patch.
void fill_new_face_patches(const SurfaceMesh& sm, const ConstraintMap& constrained,
                           PatchMap& patch) {
  std::vector<face_descriptor> stack;
  for (face_descriptor f : sm.faces()) {
    if (patch[f] != kNoPatch) stack.push_back(f);
  }
  while (!stack.empty()) {
    const face_descriptor f = stack.back();
    stack.pop_back();
    for (auto h : CGAL::halfedges_around_face(sm.halfedge(f), sm)) {
      if (constrained[sm.edge(h)]) continue;
      const face_descriptor g = sm.face(sm.opposite(h));
      if (g == SurfaceMesh::null_face() || patch[g] != kNoPatch) continue;
      patch[g] = patch[f];
      stack.push_back(g);
    }
  }
}

// The input surface, one AABB tree per patch: remeshed vertices are projected onto the input
// faces of their own patch (as CGAL does by default, but onto the input of the whole remesh, so
// that a coarse first pass does not become the surface of the second).
class InputSurface {
 public:
  InputSurface(const Mesh& mesh, const std::vector<int>& face_patch) {
    for (int f = 0; f < mesh.num_faces(); ++f) {
      const Tri& t = mesh.triangle(f);
      auto point = [&](int v) {
        const Vec3& p = mesh.position(v);
        return CgalPoint(p.x(), p.y(), p.z());
      };
      triangles_[face_patch.empty() ? 0 : face_patch[static_cast<std::size_t>(f)]].emplace_back(
          point(t[0]), point(t[1]), point(t[2]));
    }
    for (const auto& [id, tris] : triangles_) {
      auto tree = std::make_unique<Tree>(tris.begin(), tris.end());
      tree->accelerate_distance_queries();
      trees_.emplace(id, std::move(tree));
    }
  }
  CgalPoint closest_point(int patch, const CgalPoint& p) const {
    return trees_.at(patch)->closest_point(p);
  }

 private:
  using Triangles = std::vector<CgalKernel::Triangle_3>;
  using Primitive = CGAL::AABB_triangle_primitive<CgalKernel, Triangles::const_iterator>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<CgalKernel, Primitive>>;
  std::map<int, Triangles> triangles_;  // node-based: the trees' iterators stay valid
  std::map<int, std::unique_ptr<Tree>> trees_;
};

// The invariant the planner relies on (the wound region is a union of patches, cut out along
// its borders): every face has a patch and every edge between two patches is constrained, so no
// patch touches another anywhere but along the protected borders.
void check_patches(const SurfaceMesh& sm, const ConstraintMap& constrained, const PatchMap& patch,
                   const char* stage) {
  for (face_descriptor f : sm.faces()) {
    if (patch[f] == kNoPatch) {
      throw InvariantError(std::string("remesh: face ") + std::to_string(f.idx()) +
                           " has no patch after " + stage);
    }
  }
  for (edge_descriptor e : sm.edges()) {
    if (sm.is_border(e) || constrained[e]) continue;
    const auto h = sm.halfedge(e);
    if (patch[sm.face(h)] != patch[sm.face(sm.opposite(h))]) {
      throw InvariantError(std::string("remesh: an unconstrained edge separates patches ") +
                           std::to_string(patch[sm.face(h)]) + " and " +
                           std::to_string(patch[sm.face(sm.opposite(h))]) + " after " + stage);
    }
  }
}

}  // namespace

bool RemeshOptions::is_valid(std::string* why) const {
  if (!(target_edge_length > 0.0) || !std::isfinite(target_edge_length)) {
    if (why) *why = "remesh target edge length must be > 0 mm";
    return false;
  }
  if (iterations < 1) {
    if (why) *why = "remesh iterations must be >= 1";
    return false;
  }
  if (!(coarse_factor == 0.0 || (coarse_factor > 1.0 && std::isfinite(coarse_factor)))) {
    if (why) *why = "remesh coarse_factor must be 0 (no coarse pass) or > 1";
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
  for (std::size_t f = 0; f < face_patch.size(); ++f) {
    if (face_patch[f] < 0) {
      throw InputError("remesh: face " + std::to_string(f) + " has patch id " +
                       std::to_string(face_patch[f]) + " (patch ids must be >= 0)");
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  SurfaceMesh sm = to_surface_mesh(mesh);
  // Faces created later start without a patch (kNoPatch) until they are given one.
  PatchMap patch = sm.add_property_map<face_descriptor, int>("f:windplan_patch", kNoPatch).first;
  for (face_descriptor f : sm.faces()) {
    patch[f] = face_patch.empty() ? 0 : face_patch[static_cast<std::size_t>(f.idx())];
  }
  ConstraintMap constrained =
      sm.add_property_map<edge_descriptor, bool>("e:windplan_constrained", false).first;
  std::vector<edge_descriptor> borders;
  for (edge_descriptor e : sm.edges()) {
    const auto h = sm.halfedge(e);
    const bool border = sm.is_border(e) || patch[sm.face(h)] != patch[sm.face(sm.opposite(h))];
    constrained[e] = border;
    if (border) borders.push_back(e);
  }
  // Constrained edges much longer than the target make the remesher cascade: split them first
  // (the new edges inherit the constraint, the new faces get their patch below).
  PMP::split_long_edges(borders, options.target_edge_length, sm,
                        CGAL::parameters::edge_is_constrained_map(constrained));
  fill_new_face_patches(sm, constrained, patch);
  check_patches(sm, constrained, patch, "splitting the borders");
  // From here CGAL keeps the patch of every face it creates (face_patch_map). It projects only
  // vertices inside a patch (border vertices are constrained), so the face of any halfedge into
  // them has their patch.
  const InputSurface surface(mesh, face_patch);
  auto project = [&](SurfaceMesh::Vertex_index v) {
    return surface.closest_point(patch[sm.face(sm.halfedge(v))], sm.point(v));
  };
  if (options.coarse_factor > 0.0) {
    // Splitting long slivers (a CAD cylinder's are its whole length) to the target directly
    // makes ~5 times the final vertices, most of them collapsed again: ~4x the time at 2 mm on
    // the shipped vessel. One pass at a coarser target first turns them into triangles of that
    // size, cheaply.
    PMP::isotropic_remeshing(faces(sm), options.coarse_factor * options.target_edge_length, sm,
                             CGAL::parameters::number_of_iterations(1)
                                 .edge_is_constrained_map(constrained)
                                 .protect_constraints(true)
                                 .face_patch_map(patch)
                                 .projection_functor(project));
    check_patches(sm, constrained, patch, "the coarse pass");
  }
  PMP::isotropic_remeshing(faces(sm), options.target_edge_length, sm,
                           CGAL::parameters::number_of_iterations(options.iterations)
                               .edge_is_constrained_map(constrained)
                               .protect_constraints(true)
                               .face_patch_map(patch)
                               .projection_functor(project));
  check_patches(sm, constrained, patch, "remeshing");
  sm.collect_garbage();
  RemeshResult out;
  out.faces_before = mesh.num_faces();
  out.face_patch.reserve(sm.number_of_faces());
  for (face_descriptor f : sm.faces()) out.face_patch.push_back(patch[f]);
  out.mesh = from_surface_mesh(sm);
  out.faces_after = out.mesh.num_faces();
  out.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace windplan
