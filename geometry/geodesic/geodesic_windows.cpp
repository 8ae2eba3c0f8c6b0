// Bounded exact window propagation (see geometry/geodesic/geodesic_windows.h): the options,
// the per-mesh data, full runs and searches to one target. The search itself is
// geometry/geodesic/window_search.h.
#include "geometry/geodesic/geodesic_windows.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "geometry/base/errors.h"
#include "geometry/geodesic/window_search.h"

namespace windplan {

bool WindowSearchOptions::is_valid(std::string* why) const {
  if (!(upper_bound > 0.0)) {
    if (why) *why = "upper_bound must be > 0 (mesh units)";
    return false;
  }
  if (max_windows < 0) {
    if (why) *why = "max_windows must be >= 0 (0: no limit)";
    return false;
  }
  if (resume_limit < 0) {
    if (why) *why = "resume_limit must be >= 0 (windows)";
    return false;
  }
  return target_bound.is_valid(why);
}

WindowMesh prepare_window_mesh(const Mesh& original) {
  WindowMesh w;
  w.order = order_for_locality(original);
  const Mesh& mesh = w.order.mesh;
  w.pseudo_source.assign(mesh.num_vertices(), 0);
  constexpr double kTwoPi = 6.283185307179586;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (mesh.vertex_halfedge(v) < 0) continue;
    w.pseudo_source[v] = mesh.is_boundary_vertex(v) || mesh.cone_angle(v) >= kTwoPi - 1e-9;
  }
  const int nh = mesh.num_interior_halfedges();
  w.frame.resize(nh);
  w.corner_angle.resize(nh);
  const auto inside = [&](int h) { return mesh.is_boundary_halfedge(h) ? -1 : h; };
  for (int h = 0; h < nh; ++h) {
    HalfedgeFrame& f = w.frame[h];
    f.from = mesh.from(h);
    f.to = mesh.to(h);
    f.opposite = mesh.opposite_vertex(h);
    const Vec3& a = mesh.position(f.from);
    const Vec3& b = mesh.position(f.to);
    const Vec3& c = mesh.position(f.opposite);
    f.len = mesh.halfedge_length(h);
    f.cx = f.len > 0.0 ? (c - a).dot(b - a) / f.len : 0.0;
    f.cy = std::sqrt(std::max(0.0, (c - a).squaredNorm() - f.cx * f.cx));
    f.len_prev = mesh.halfedge_length(mesh.prev(h));
    f.len_next = mesh.halfedge_length(mesh.next(h));
    f.twin = mesh.twin(h);
    f.out_prev = inside(mesh.twin(mesh.prev(h)));
    f.out_next = inside(mesh.twin(mesh.next(h)));
    w.corner_angle[h] = mesh.corner_angle(h);
    w.max_edge = std::max(w.max_edge, f.len);
  }
  w.ring_start.assign(mesh.num_vertices() + 1, 0);
  w.ring.reserve(nh);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    w.ring_start[v] = static_cast<int>(w.ring.size());
    const int first = mesh.vertex_halfedge(v);
    for (int o = first; o >= 0;) {
      const HalfedgeFrame& f = w.frame[o];
      w.ring.push_back({f.to, f.opposite, f.len, f.len_prev, f.cx, f.cy, f.len_next});
      o = mesh.ccw_rotate(o);
      if (o == first) break;
    }
  }
  w.ring_start[mesh.num_vertices()] = static_cast<int>(w.ring.size());
  w.graph = build_edge_graph(mesh, {}, true);
  return w;
}

namespace window_search {

Scratch& thread_scratch() {
  static thread_local Scratch scratch;
  return scratch;
}

void check_inputs(const Mesh& mesh, const WindowMesh& window_mesh,
                  std::initializer_list<int> vertices) {
  for (const int v : vertices) {
    if (v < 0 || v >= mesh.num_vertices()) {
      throw InputError("vertex " + std::to_string(v) + " out of range (the mesh has " +
                       std::to_string(mesh.num_vertices()) + " vertices)");
    }
  }
  const Mesh& local = window_mesh.order.mesh;
  if (local.num_vertices() != mesh.num_vertices() || local.num_faces() != mesh.num_faces() ||
      local.num_halfedges() != mesh.num_halfedges() ||
      static_cast<int>(window_mesh.pseudo_source.size()) != mesh.num_vertices() ||
      window_mesh.frame.size() != static_cast<std::size_t>(mesh.num_interior_halfedges())) {
    throw ConfigError("window search: the window mesh (prepare_window_mesh) is not this mesh's");
  }
}

void check_query(const Mesh& mesh, const WindowMesh& window_mesh,
                 std::initializer_list<int> vertices, const WindowSearchOptions& options,
                 const Landmarks* landmarks) {
  check_inputs(mesh, window_mesh, vertices);
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError("window search: " + why);
  if (landmarks != nullptr &&
      landmarks->dist.size() != static_cast<std::size_t>(mesh.num_vertices()) * landmarks->count)
    throw ConfigError("window search: landmark fields do not match the mesh");
}

void path_in_original(const Mesh& mesh, const MeshOrder& order, WindowSearchResult* result) {
  if (!result->found) return;
  result->path = order.path_from_local(mesh, result->path);
  for (int& v : result->vertices_passed) v = order.vertex_from_local[v];
}

}  // namespace window_search

using window_search::check_query;
using window_search::Clock;
using window_search::path_in_original;
using window_search::Search;

std::vector<double> geodesic_distances_by_windows(const Mesh& mesh, const WindowMesh& window_mesh,
                                                  int source, const WindowSearchOptions& options,
                                                  WindowSearchResult* stats) {
  check_query(mesh, window_mesh, {source}, options, nullptr);
  // A bound or a cap would leave some distances too long or missing without a word.
  if (options.max_windows != 0 || std::isfinite(options.upper_bound))
    throw ConfigError("window search: a full run takes neither max_windows nor upper_bound");
  const auto full_run = [&](auto&& search) {
    const WindowSearchResult r = search.run();
    if (stats != nullptr) *stats = r;
    return search.distances();
  };
  const int s = window_mesh.order.vertex_to_local[source];
  if (options.reuse_windows) return full_run(Search<true>(window_mesh, s, -1, options));
  return full_run(Search<false>(window_mesh, s, -1, options));
}

WindowSearchResult shortest_path_by_windows(const Mesh& mesh, const WindowMesh& window_mesh,
                                            int source, int target,
                                            const WindowSearchOptions& options,
                                            const Landmarks* landmarks) {
  const auto t0 = Clock::now();
  check_query(mesh, window_mesh, {source, target}, options, landmarks);
  WindowSearchResult result;
  if (source != target) {
    const MeshOrder& order = window_mesh.order;
    result = Search<false>(window_mesh, order.vertex_to_local[source],
                           order.vertex_to_local[target], options, landmarks)
                 .run();
    path_in_original(mesh, order, &result);
  }
  result.time_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  return result;
}

}  // namespace windplan
