// A CGAL translation unit: never include OCCT here (its Handle macro breaks CGAL headers).
#include "geometry/mesh/remesh.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <vector>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>

#include "geometry/base/errors.h"
#include "geometry/base/parallel.h"
#include "geometry/mesh/cgal_mesh_types.h"

namespace windplan {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

using face_descriptor = SurfaceMesh::Face_index;
using vertex_descriptor = SurfaceMesh::Vertex_index;
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
      // Built here, not lazily at the first query: the patches are remeshed in parallel (each
      // queries only its own tree, but nothing is left to build under a lock).
      tree->build();
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

// A convex planar polygon (a triangle whose sides were cut into pieces) triangulated by clipping,
// again and again, the ear whose new edge is the shortest, at a corner (never at a point on a
// straight side): a sliver with points along its long sides becomes a zigzag strip. The
// triangles keep the face's patch.
void triangulate_cut_face(face_descriptor f, SurfaceMesh& sm, PatchMap& patch) {
  const int id = patch[f];
  std::vector<SurfaceMesh::Halfedge_index> hs;
  for (;;) {
    hs.clear();
    for (auto h : CGAL::halfedges_around_face(sm.halfedge(f), sm)) hs.push_back(h);
    const std::size_t n = hs.size();
    if (n <= 3) return;
    std::size_t best = n;
    double best_length = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      // The ear at v = target(hs[i]), between u = source(hs[i]) and w = target(hs[i + 1]).
      const CgalPoint& u = sm.point(sm.source(hs[i]));
      const CgalPoint& v = sm.point(sm.target(hs[i]));
      const CgalPoint& w = sm.point(sm.target(hs[(i + 1) % n]));
      const auto uv = v - u, vw = w - v;
      const double sine2 = CGAL::cross_product(uv, vw).squared_length() /
                           (uv.squared_length() * vw.squared_length());
      if (!(sine2 > 1e-18)) continue;  // v lies on a straight side: no corner
      const double length = CGAL::squared_distance(u, w);
      if (best != n && length >= best_length) continue;
      // In a convex polygon only a vertex on the new edge u-w itself (a straight side running
      // from u or w) can spoil the ear: it would leave a polygon with no area.
      bool spoiled = false;
      const auto uw = w - u;
      for (std::size_t j = 0; j < n && !spoiled; ++j) {
        const CgalPoint& x = sm.point(sm.target(hs[j]));
        if (x == u || x == v || x == w) continue;
        const auto ux = x - u;
        const double along = ux * uw;
        spoiled = along > 0.0 && along < uw.squared_length() &&
                  CGAL::cross_product(uw, ux).squared_length() <=
                      1e-18 * uw.squared_length() * ux.squared_length();
      }
      if (spoiled) continue;
      best = i;
      best_length = length;
    }
    if (best == n) {
      throw InvariantError("remesh: a face cut along its long edges has no corner left (" +
                           std::to_string(n) + " sides)");
    }
    const auto into_u = hs[(best + n - 1) % n], into_w = hs[(best + 1) % n];
    const auto u_to_w = CGAL::Euler::split_face(into_u, into_w, sm);  // the ear is on w -> u's side
    f = sm.face(u_to_w);
    patch[f] = id;
    patch[sm.face(sm.opposite(u_to_w))] = id;
  }
}

// Every unconstrained edge longer than `length` cut into equal pieces no longer than it, and the
// polygons this makes of its faces triangulated into strips (triangulate_cut_face): splitting
// edge by edge (PMP::split_long_edges, or the remesher's own splits) makes fans at a sliver's
// short side instead, which the remesher then spends most of its time collapsing. The new
// vertices lie on the input edges, the new faces inside their input face, with its patch. A mesh
// with a face of no area (its corners on a line) is left as it is: cut next to such a face,
// CGAL's tangential relaxation crashed (remesh_test.cpp), where it remeshes the uncut mesh.
void cut_long_edges(SurfaceMesh& sm, const ConstraintMap& constrained, PatchMap& patch,
                    double length) {
  for (face_descriptor f : sm.faces()) {
    const auto g = sm.halfedge(f);
    const CgalPoint& a = sm.point(sm.source(g));
    const auto ab = sm.point(sm.target(g)) - a, ac = sm.point(sm.target(sm.next(g))) - a;
    if (!(CGAL::cross_product(ab, ac).squared_length() >
          1e-12 * ab.squared_length() * ac.squared_length()))
      return;
  }
  std::vector<edge_descriptor> long_edges;
  for (edge_descriptor e : sm.edges()) {
    const auto h = sm.halfedge(e);
    if (!constrained[e] &&
        CGAL::squared_distance(sm.point(sm.source(h)), sm.point(sm.target(h))) > length * length)
      long_edges.push_back(e);
  }
  std::vector<face_descriptor> cut_faces;
  for (edge_descriptor e : long_edges) {
    const auto h = sm.halfedge(e);
    for (auto g : {h, sm.opposite(h)})
      if (!sm.is_border(g)) cut_faces.push_back(sm.face(g));
    const CgalPoint a = sm.point(sm.source(h)), b = sm.point(sm.target(h));
    const int n = static_cast<int>(std::ceil(std::sqrt(CGAL::squared_distance(a, b)) / length));
    for (int k = 1; k < n; ++k) {
      const auto piece = CGAL::Euler::split_edge(h, sm);  // source(h) -> new vertex; then h
      sm.point(sm.target(piece)) = a + (b - a) * (static_cast<double>(k) / n);
    }
  }
  std::sort(cut_faces.begin(), cut_faces.end());
  cut_faces.erase(std::unique(cut_faces.begin(), cut_faces.end()), cut_faces.end());
  for (face_descriptor f : cut_faces) triangulate_cut_face(f, sm, patch);
}

// Both passes on one mesh (the coarse one if asked, then the fine one), borders and patch
// borders protected. CGAL keeps the patch of every face it creates (face_patch_map). It projects
// only vertices inside a patch (border vertices are constrained), so a face next to each has
// its patch.
void remesh_passes(SurfaceMesh& sm, ConstraintMap& constrained, PatchMap& patch,
                   const InputSurface& surface, const RemeshOptions& options) {
  auto project = [&](vertex_descriptor v) {
    auto h = sm.halfedge(v);
    if (sm.is_border(h)) h = sm.opposite(h);
    return surface.closest_point(patch[sm.face(h)], sm.point(v));
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
}

// One patch as a mesh of its own: its borders (the whole mesh's boundary and the patch borders)
// are its boundary, protected; every vertex remembers its vertex in the whole mesh.
struct Part {
  int id = 0;
  double work = 0.0;  // its share of the remeshing (input faces + output faces, estimated)
  SurfaceMesh sm;
  PatchMap patch;
  ConstraintMap constrained;
  SurfaceMesh::Property_map<vertex_descriptor, int> whole;
};

// The patches of `sm`, each as a Part (in increasing patch id), or none when a patch is not a
// manifold of its own (it touches itself at a vertex) or when there is only one.
std::vector<std::unique_ptr<Part>> cut_into_patches(const SurfaceMesh& sm, const PatchMap& patch,
                                                    double target_edge_length) {
  std::map<int, std::vector<face_descriptor>> faces_of;
  for (face_descriptor f : sm.faces()) faces_of[patch[f]].push_back(f);
  std::vector<std::unique_ptr<Part>> parts;  // (the property maps point into each Part's mesh)
  if (faces_of.size() < 2) return parts;
  std::vector<vertex_descriptor> local(sm.num_vertices(), SurfaceMesh::null_vertex());
  for (const auto& [id, fs] : faces_of) {
    parts.push_back(std::make_unique<Part>());
    Part& p = *parts.back();
    p.id = id;
    p.patch = p.sm.add_property_map<face_descriptor, int>("f:windplan_patch", id).first;
    p.constrained = p.sm.add_property_map<edge_descriptor, bool>("e:windplan_constrained").first;
    p.whole = p.sm.add_property_map<vertex_descriptor, int>("v:windplan_whole", -1).first;
    std::vector<vertex_descriptor> touched;
    double area = 0.0;
    for (face_descriptor f : fs) {
      std::array<vertex_descriptor, 3> t;
      int k = 0;
      for (vertex_descriptor v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
        if (local[v.idx()] == SurfaceMesh::null_vertex()) {
          local[v.idx()] = p.sm.add_vertex(sm.point(v));
          p.whole[local[v.idx()]] = static_cast<int>(v.idx());
          touched.push_back(v);
        }
        t[k++] = local[v.idx()];
      }
      if (p.sm.add_face(t[0], t[1], t[2]) == SurfaceMesh::null_face()) return {};
      area += PMP::face_area(f, sm);
    }
    for (vertex_descriptor v : touched) local[v.idx()] = SurfaceMesh::null_vertex();
    // A vertex where the patch touches itself has more halfedges into it than its umbrella.
    std::vector<int> into(p.sm.num_vertices(), 0);
    for (auto h : p.sm.halfedges()) ++into[p.sm.target(h).idx()];
    for (vertex_descriptor v : p.sm.vertices()) {
      if (static_cast<int>(p.sm.degree(v)) != into[v.idx()]) return {};  // (degree: its umbrella)
    }
    for (edge_descriptor e : p.sm.edges()) p.constrained[e] = p.sm.is_border(e);
    p.work = static_cast<double>(fs.size()) +
             area / (std::sqrt(3.0) / 4.0 * target_edge_length * target_edge_length);
  }
  return parts;
}

// The remeshed parts sewn into one mesh along their borders, which the remeshing kept in place
// (protected: never split, collapsed or moved): a part's border vertex is its whole-mesh vertex,
// shared with the parts on the other side. Faces and vertices in part order. False when two
// parts made the same edge, a chord between two border vertices on both sides (on meshes coarse
// for their patches), which the whole mesh could not have.
bool sew_patches(const SurfaceMesh& sm, const std::vector<std::unique_ptr<Part>>& parts, Mesh* mesh,
                 std::vector<int>* face_patch) {
  std::vector<int> sewn(sm.num_vertices(), -1);  // whole-mesh vertex -> output vertex
  std::vector<char> on_border;                   // per output vertex
  std::vector<Vec3> points;
  std::vector<Tri> triangles;
  for (const auto& part : parts) {
    const Part& p = *part;
    std::vector<int> index(p.sm.num_vertices(), -1);
    for (vertex_descriptor v : p.sm.vertices()) {
      const CgalPoint& q = p.sm.point(v);
      if (p.sm.is_border(v)) {
        const int w = p.whole[v];
        if (w < 0 || sm.point(vertex_descriptor(w)) != q) {
          throw InvariantError("remesh: patch " + std::to_string(p.id) +
                               " moved or made a vertex on its border");
        }
        if (sewn[w] < 0) {
          sewn[w] = static_cast<int>(points.size());
          points.emplace_back(q.x(), q.y(), q.z());
          on_border.push_back(1);
        }
        index[v.idx()] = sewn[w];
      } else {
        index[v.idx()] = static_cast<int>(points.size());
        points.emplace_back(q.x(), q.y(), q.z());
        on_border.push_back(0);
      }
    }
    for (face_descriptor f : p.sm.faces()) {
      Tri t;
      int k = 0;
      for (vertex_descriptor v : CGAL::vertices_around_face(p.sm.halfedge(f), p.sm))
        t[k++] = index[v.idx()];
      triangles.push_back(t);
      face_patch->push_back(p.id);
    }
  }
  // Every edge between two border vertices: at most two triangles.
  std::map<std::pair<int, int>, int> chords;
  for (const Tri& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (on_border[a] && on_border[b] && ++chords[std::minmax(a, b)] > 2) {
        face_patch->clear();
        return false;
      }
    }
  }
  *mesh = Mesh(TriangleSoup{std::move(points), std::move(triangles)});
  return true;
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
  // Sides longer than the first pass's target cut into strips (cut_long_edges), not fans.
  cut_long_edges(sm, constrained, patch,
                 std::max(options.coarse_factor, 4.0 / 3.0) * options.target_edge_length);
  const InputSurface surface(mesh, face_patch);
  RemeshResult out;
  out.faces_before = mesh.num_faces();
  std::vector<std::unique_ptr<Part>> parts =
      cut_into_patches(sm, patch, options.target_edge_length);
  bool sewn = false;
  if (parts.size() >= 2) {
    // The patches meet only along protected borders, so each is remeshed on its own, in
    // parallel (the largest first), and the pieces are sewn together along those borders.
    std::vector<int> order(parts.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return parts[a]->work > parts[b]->work; });
    parallel_for_index(static_cast<int>(parts.size()), [&](int i) {
      Part& part = *parts[order[i]];
      remesh_passes(part.sm, part.constrained, part.patch, surface, options);
    });
    sewn = sew_patches(sm, parts, &out.mesh, &out.face_patch);
  }
  if (!sewn) {
    // One patch, a patch that touches itself at a vertex, or a chord made on both sides of a
    // border: the whole mesh at once.
    remesh_passes(sm, constrained, patch, surface, options);
    sm.collect_garbage();
    out.face_patch.reserve(sm.number_of_faces());
    for (face_descriptor f : sm.faces()) out.face_patch.push_back(patch[f]);
    out.mesh = from_surface_mesh(sm);
  }
  out.faces_after = out.mesh.num_faces();
  out.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace windplan
