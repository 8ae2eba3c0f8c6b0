#include "geometry/geodesic/edge_path_steiner.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <string>

#include "geometry/base/errors.h"
#include "geometry/geodesic/edge_path.h"

namespace windplan {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Per-thread scratch of the search, sized to the largest graph seen; entries are valid when
// their stamp equals the current generation, so a query clears nothing.
struct Scratch {
  std::vector<double> dist;
  std::vector<int> parent, parent_face;
  std::vector<std::uint32_t> seen, done;
  std::uint32_t generation = 0;
  std::vector<std::pair<double, int>> heap;

  void begin(int n) {
    if (static_cast<int>(dist.size()) < n) {
      dist.resize(n);
      parent.resize(n);
      parent_face.resize(n);
      seen.assign(n, 0);
      done.assign(n, 0);
      generation = 0;
    }
    if (++generation == 0) {  // wrapped: clear the stamps once
      std::fill(seen.begin(), seen.end(), 0);
      std::fill(done.begin(), done.end(), 0);
      generation = 1;
    }
    heap.clear();
  }
};

Scratch& scratch() {
  thread_local Scratch s;
  return s;
}

}  // namespace

SteinerGraph::SteinerGraph(const Mesh& mesh, const PathMetric& metric, int points_per_edge)
    : mesh_(mesh), k_(points_per_edge), per_face_(3 + 3 * points_per_edge) {
  if (points_per_edge < 1) {
    throw InputError("Steiner graph: points per edge must be >= 1, got " +
                     std::to_string(points_per_edge));
  }
  if (metric.kind() == PathMetric::Kind::Anisotropic) {
    throw InputError("Steiner graph: anisotropic metrics are not supported");
  }
  if (metric.kind() == PathMetric::Kind::Density) {
    density_ = metric.densities();
    min_density_ = *std::min_element(density_.begin(), density_.end());
  }
  const int nv = mesh.num_vertices(), ne = mesh.num_edges(), nf = mesh.num_faces();
  position_.resize(nv + static_cast<std::size_t>(k_) * ne);
  for (int v = 0; v < nv; ++v) position_[v] = mesh.position(v);
  for (int e = 0; e < ne; ++e) {
    const int h = mesh.edge_halfedge(e);
    const Vec3& p = mesh.position(mesh.from(h));
    const Vec3 d = mesh.position(mesh.to(h)) - p;
    for (int i = 0; i < k_; ++i) {
      position_[nv + static_cast<std::size_t>(k_) * e + i] = p + ((i + 1.0) / (k_ + 1.0)) * d;
    }
  }
  face_nodes_.resize(static_cast<std::size_t>(nf) * per_face_);
  for (int f = 0; f < nf; ++f) {
    int* out = &face_nodes_[static_cast<std::size_t>(f) * per_face_];
    for (int c = 0; c < 3; ++c) {
      const int h = 3 * f + c;
      *out++ = mesh.from(h);
      const int base = nv + k_ * mesh.edge(h);
      for (int i = 0; i < k_; ++i) *out++ = base + i;
    }
  }
  vertex_face_offsets_.assign(nv + 1, 0);
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c) ++vertex_face_offsets_[mesh.triangle(f)[c] + 1];
  for (int v = 0; v < nv; ++v) vertex_face_offsets_[v + 1] += vertex_face_offsets_[v];
  vertex_faces_.resize(vertex_face_offsets_[nv]);
  std::vector<int> fill(vertex_face_offsets_.begin(), vertex_face_offsets_.end() - 1);
  for (int f = 0; f < nf; ++f)
    for (int c = 0; c < 3; ++c) vertex_faces_[fill[mesh.triangle(f)[c]]++] = f;
}

SteinerPath shortest_steiner_path(const SteinerGraph& graph, const SurfacePoint& a,
                                  const SurfacePoint& b) {
  const Mesh& mesh = graph.mesh();
  SteinerPath result;
  const Vec3 pa = position(mesh, a), pb = position(mesh, b);
  const std::vector<int> faces_a = faces_containing(mesh, a);
  const std::vector<int> faces_b = faces_containing(mesh, b);
  for (int f : faces_a) {
    if (std::find(faces_b.begin(), faces_b.end(), f) != faces_b.end()) {
      result.found = true;
      result.length = graph.density(f) * (pb - pa).norm();
      return result;
    }
  }
  const int va = as_vertex(mesh, a), vb = as_vertex(mesh, b);
  const double rho = graph.min_density();
  Scratch& s = scratch();
  s.begin(graph.num_nodes());
  const std::uint32_t gen = s.generation;
  auto heuristic = [&](int n) { return rho * (graph.position(n) - pb).norm(); };
  auto push = [&](int n, double d, int parent, int face) {
    if (s.seen[n] == gen && s.dist[n] <= d) return;
    s.seen[n] = gen;
    s.dist[n] = d;
    s.parent[n] = parent;
    s.parent_face[n] = face;
    s.heap.emplace_back(-(d + heuristic(n)), n);
    std::push_heap(s.heap.begin(), s.heap.end());
  };
  if (va >= 0) {
    push(va, 0.0, -1, -1);
  } else {
    for (int f : faces_a) {
      const int* nodes = graph.face_nodes(f);
      for (int j = 0; j < graph.nodes_per_face(); ++j) {
        push(nodes[j], graph.density(f) * (graph.position(nodes[j]) - pa).norm(), -1, f);
      }
    }
  }
  double best = kInf;
  int best_node = -1, best_face = -1;
  auto relax_face = [&](int n, double d, int f) {
    const Vec3& p = graph.position(n);
    const double w = graph.density(f);
    if (vb < 0 && std::find(faces_b.begin(), faces_b.end(), f) != faces_b.end()) {
      const double total = d + w * (pb - p).norm();
      if (total < best) {
        best = total;
        best_node = n;
        best_face = f;
      }
    }
    const int* nodes = graph.face_nodes(f);
    for (int j = 0; j < graph.nodes_per_face(); ++j) {
      const int m = nodes[j];
      if (m == n || s.done[m] == gen) continue;
      push(m, d + w * (graph.position(m) - p).norm(), n, f);
    }
  };
  while (!s.heap.empty()) {
    std::pop_heap(s.heap.begin(), s.heap.end());
    const auto [key, n] = s.heap.back();
    s.heap.pop_back();
    if (s.done[n] == gen) continue;
    if (-key >= best) break;
    s.done[n] = gen;
    ++result.settled;
    const double d = s.dist[n];
    if (n == vb) {
      if (d < best) {
        best = d;
        best_node = n;
        best_face = s.parent_face[n];
      }
      continue;
    }
    if (graph.is_vertex(n)) {
      for (const int* f = graph.vertex_faces_begin(n); f != graph.vertex_faces_end(n); ++f)
        relax_face(n, d, *f);
    } else {
      const int h = mesh.edge_halfedge(graph.edge_of(n));
      relax_face(n, d, mesh.face(h));
      const int t = mesh.twin(h);
      if (!mesh.is_boundary_halfedge(t)) relax_face(n, d, mesh.face(t));
    }
  }
  if (best_node < 0) return result;
  result.found = true;
  result.length = best;
  result.faces.push_back(best_face);
  for (int n = best_node; n >= 0; n = s.parent[n]) {
    result.nodes.push_back(n);
    result.faces.push_back(s.parent_face[n]);
  }
  std::reverse(result.nodes.begin(), result.nodes.end());
  std::reverse(result.faces.begin(), result.faces.end());
  // faces now holds the face arriving at nodes[0] first and the final face last.
  return result;
}

SurfacePath strip_from_steiner_path(const SteinerGraph& graph, const SurfacePoint& a,
                                    const SteinerPath& sp, const SurfacePoint& b) {
  const Mesh& mesh = graph.mesh();
  SurfacePath path;
  path.closed = false;
  path.start = a;
  path.end = b;
  const Vec3 pa = position(mesh, a), pb = position(mesh, b);
  const int m = static_cast<int>(sp.nodes.size());
  if (m == 0) {
    for (int f : faces_containing(mesh, a))
      if (face_contains(mesh, f, b)) path.start_face = f;
    if (path.start_face < 0) throw InvariantError("Steiner strip: a and b share no face");
    return path;
  }
  const int va = as_vertex(mesh, a), vb = as_vertex(mesh, b);
  // Node i sits between faces[i] (arriving) and faces[i + 1] (leaving). A vertex endpoint is a
  // node with no turn of its own: the strip starts in the face after it, ends in the face before.
  int first = 0, last = m - 1;
  if (va >= 0 && sp.nodes.front() == va) first = 1;
  if (vb >= 0 && sp.nodes.back() == vb) last = m - 2;
  int face = sp.faces[first];
  if (face < 0) throw InvariantError("Steiner strip: no start face");
  path.start_face = face;
  for (int i = first; i <= last; ++i) {
    const int n = sp.nodes[i];
    const int next_face = sp.faces[i + 1];
    if (next_face == face) continue;
    if (graph.is_vertex(n)) {
      const Vec3 prev = i > 0 ? graph.position(sp.nodes[i - 1]) : pa;
      const Vec3 next = i + 1 < m ? graph.position(sp.nodes[i + 1]) : pb;
      turn_at(
          mesh, n, &face, prev, next, [&](int f) { return f == next_face; }, &path);
      continue;
    }
    const int e = graph.edge_of(n);
    const int eh = mesh.edge_halfedge(e);
    const int h = mesh.face(eh) == face ? eh : mesh.twin(eh);
    if (mesh.face(h) != face || mesh.is_boundary_halfedge(mesh.twin(h)) ||
        mesh.face(mesh.twin(h)) != next_face) {
      throw InvariantError("Steiner strip: node " + std::to_string(n) + " does not join faces " +
                           std::to_string(face) + " and " + std::to_string(next_face));
    }
    const double t = graph.t_of(n);
    path.halfedges.push_back(h);
    path.lambdas.push_back(h == eh ? t : 1.0 - t);
    face = next_face;
  }
  if (!path.halfedges.empty()) path.start_face = mesh.face(path.halfedges.front());
  return path;
}

}  // namespace windplan
