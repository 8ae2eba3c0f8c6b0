#include "geometry/geodesic/edge_path.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>

#include "geometry/base/errors.h"
#include "geometry/geodesic/unfold.h"
#include "geometry/mesh/closest_point.h"

namespace windplan {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Initial crossings sit this fraction of the spoke away from the vertex the strip turns around:
// close to the edge path, but with no zero-length segments.
constexpr double kInitialOffset = 0.25;

int outgoing_in_face(const Mesh& mesh, int f, int v) {
  for (int k = 0; k < 3; ++k)
    if (mesh.from(3 * f + k) == v) return 3 * f + k;
  return -1;
}

double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Rotation around vertex u from face `face` until `stop(face)` holds, in one direction.
struct Rotation {
  std::vector<int> crossings;
  std::vector<double> lambdas;
  int end_face = -1;
  double angle = kInf;  // swept angle from d_in to d_out
};

Rotation rotate(const Mesh& mesh, int u, int face, bool ccw, const Vec3& d_in, const Vec3& d_out,
                const std::function<bool(int)>& stop) {
  Rotation r;
  int hv = outgoing_in_face(mesh, face, u);
  if (hv < 0) return r;
  const Vec3& pu = mesh.position(u);
  double angle = 0.0;
  bool first = true;
  const int limit = 4 * mesh.valence(u) + 4;
  for (int step = 0; step < limit; ++step) {
    const int c = ccw ? mesh.prev(hv) : hv;
    const int other = ccw ? mesh.from(c) : mesh.to(c);
    const Vec3 spoke = mesh.position(other) - pu;
    if (first) {
      angle += angle_between(d_in, spoke);
      first = false;
    } else {
      angle += mesh.corner_angle(hv);
    }
    const int t = mesh.twin(c);
    if (mesh.is_boundary_halfedge(t)) return r;  // cannot rotate past the boundary
    r.crossings.push_back(c);
    r.lambdas.push_back(ccw ? 1.0 - kInitialOffset : kInitialOffset);
    const int g = mesh.face(t);
    hv = ccw ? t : mesh.next(t);
    if (stop(g)) {
      r.end_face = g;
      r.angle = angle + angle_between(spoke, d_out);
      return r;
    }
  }
  return r;
}

}  // namespace

void turn_at(const Mesh& mesh, int u, int* face, const Vec3& prev_point, const Vec3& next_point,
             const std::function<bool(int)>& stop, SurfacePath* path) {
  if (stop(*face)) return;
  const Vec3& pu = mesh.position(u);
  const Vec3 d_in = prev_point - pu, d_out = next_point - pu;
  Rotation a = rotate(mesh, u, *face, true, d_in, d_out, stop);
  Rotation b = rotate(mesh, u, *face, false, d_in, d_out, stop);
  const Rotation& r = a.angle <= b.angle ? a : b;
  if (r.end_face < 0) {
    throw InvariantError("initial path: cannot turn around vertex " + std::to_string(u));
  }
  path->halfedges.insert(path->halfedges.end(), r.crossings.begin(), r.crossings.end());
  path->lambdas.insert(path->lambdas.end(), r.lambdas.begin(), r.lambdas.end());
  *face = r.end_face;
}

namespace {

bool face_has_vertex(const Mesh& mesh, int f, int v) {
  const Tri& t = mesh.triangle(f);
  return t[0] == v || t[1] == v || t[2] == v;
}

// A face containing the edge (u, w), or -1.
int face_of_edge(const Mesh& mesh, int u, int w) {
  for (int h : mesh.outgoing_halfedges(u)) {
    if (mesh.to(h) == w) return mesh.face(h);
    if (mesh.from(mesh.prev(h)) == w) return mesh.face(h);
  }
  return -1;
}

}  // namespace

int as_vertex(const Mesh& mesh, const SurfacePoint& p) {
  switch (p.kind) {
    case SurfacePoint::Kind::Vertex:
      return p.element;
    case SurfacePoint::Kind::Edge:
      if (p.t <= kOnVertex) return mesh.from(p.element);
      if (p.t >= 1.0 - kOnVertex) return mesh.to(p.element);
      return -1;
    case SurfacePoint::Kind::Face:
      for (int k = 0; k < 3; ++k)
        if (p.bary[k] >= 1.0 - kOnVertex) return mesh.triangle(p.element)[k];
      return -1;
  }
  return -1;
}

std::vector<int> faces_containing(const Mesh& mesh, const SurfacePoint& p) {
  std::vector<int> faces;
  switch (p.kind) {
    case SurfacePoint::Kind::Vertex:
      for (int h : mesh.outgoing_halfedges(p.element)) faces.push_back(mesh.face(h));
      break;
    case SurfacePoint::Kind::Edge:
      if (p.t <= kOnVertex)
        return faces_containing(mesh, SurfacePoint::at_vertex(mesh.from(p.element)));
      if (p.t >= 1.0 - kOnVertex)
        return faces_containing(mesh, SurfacePoint::at_vertex(mesh.to(p.element)));
      for (int h : {p.element, mesh.twin(p.element)})
        if (!mesh.is_boundary_halfedge(h)) faces.push_back(mesh.face(h));
      break;
    case SurfacePoint::Kind::Face:
      for (int k = 0; k < 3; ++k)
        if (p.bary[k] >= 1.0 - kOnVertex)
          return faces_containing(mesh, SurfacePoint::at_vertex(mesh.triangle(p.element)[k]));
      faces.push_back(p.element);
      break;
  }
  return faces;
}

EdgeGraph build_edge_graph(const Mesh& mesh, const PathMetric& metric, bool diagonals) {
  EdgeGraph g;
  const int nv = mesh.num_vertices();
  g.anisotropic = metric.kind() == PathMetric::Kind::Anisotropic;
  if (metric.kind() == PathMetric::Kind::Density) {
    g.min_density = *std::min_element(metric.densities().begin(), metric.densities().end());
  }
  diagonals = diagonals && !g.anisotropic;
  struct Entry {
    int a, b;
    double w;
    int via_ab, via_ba;
  };
  std::vector<Entry> entries;
  entries.reserve(mesh.num_edges() * (diagonals ? 2 : 1));
  for (int e = 0; e < mesh.num_edges(); ++e) {
    const int h = mesh.edge_halfedge(e);
    const int a = mesh.from(h), b = mesh.to(h);
    const Vec3 w = mesh.position(b) - mesh.position(a);
    double weight = metric.cost(mesh.face(h), w);
    const int t = mesh.twin(h);
    if (!mesh.is_boundary_halfedge(t)) weight = std::min(weight, metric.cost(mesh.face(t), w));
    entries.push_back({a, b, weight, -1, -1});
    if (!diagonals || mesh.is_boundary_halfedge(t)) continue;
    // The diagonal c-d across edge a-b, when the unfolded quad is convex there.
    const int c = mesh.opposite_vertex(h), d = mesh.opposite_vertex(t);
    if (c == d) continue;
    const Vec3 &A = mesh.position(a), &B = mesh.position(b), &C = mesh.position(c),
               &D = mesh.position(d);
    const double L = (B - A).norm();
    if (!(L > 0.0)) continue;
    const Vec2 a2(0, 0), b2(L, 0);
    const Vec2 c2 = place_third(a2, b2, (C - A).norm(), (C - B).norm(), true);
    const Vec2 d2 = place_third(a2, b2, (D - A).norm(), (D - B).norm(), false);
    if (!(c2.y() > 0.0) || !(d2.y() < 0.0)) continue;
    const double s = c2.y() / (c2.y() - d2.y());
    const double x = c2.x() + s * (d2.x() - c2.x());
    if (!(x > 1e-6 * L && x < (1.0 - 1e-6) * L)) continue;
    const Vec2 X(x, 0.0);
    double wd = (c2 - X).norm() + (X - d2).norm();
    if (metric.kind() == PathMetric::Kind::Density) {
      wd = metric.densities()[mesh.face(h)] * (c2 - X).norm() +
           metric.densities()[mesh.face(t)] * (X - d2).norm();
    }
    entries.push_back({c, d, wd, h, t});
  }
  g.offsets.assign(nv + 1, 0);
  for (const Entry& en : entries) {
    ++g.offsets[en.a + 1];
    ++g.offsets[en.b + 1];
  }
  for (int v = 0; v < nv; ++v) g.offsets[v + 1] += g.offsets[v];
  g.neighbors.resize(g.offsets[nv]);
  g.weights.resize(g.offsets[nv]);
  if (diagonals) g.via.assign(g.offsets[nv], -1);
  std::vector<int> fill(g.offsets.begin(), g.offsets.end() - 1);
  for (const Entry& en : entries) {
    if (diagonals) g.via[fill[en.a]] = en.via_ab;
    g.neighbors[fill[en.a]] = en.b;
    g.weights[fill[en.a]++] = en.w;
    if (diagonals) g.via[fill[en.b]] = en.via_ba;
    g.neighbors[fill[en.b]] = en.a;
    g.weights[fill[en.b]++] = en.w;
  }
  return g;
}

EdgePath shortest_edge_path(const Mesh& mesh, const EdgeGraph& graph, const SurfacePoint& a,
                            const SurfacePoint& b, const EdgePathOptions& options) {
  EdgePath result;
  const int nv = mesh.num_vertices();
  const Vec3 pa = position(mesh, a), pb = position(mesh, b);
  const double rho = graph.min_density;
  const bool astar = options.use_astar && !graph.anisotropic;

  std::vector<double> dist(nv, kInf);
  std::vector<int> parent(nv, -1);
  std::vector<int> parent_via(graph.via.empty() ? 0 : nv, -1);
  std::vector<char> done(nv, 0);
  // Target legs: straight distance from each target vertex to b (within b's face).
  // A vertex endpoint is the only source/target; otherwise the corners of its face(s).
  std::vector<std::pair<int, double>> targets;
  if (as_vertex(mesh, b) >= 0) {
    targets.emplace_back(as_vertex(mesh, b), 0.0);
  } else {
    for (int f : faces_containing(mesh, b))
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.triangle(f)[k];
        targets.emplace_back(v, rho * (mesh.position(v) - pb).norm());
      }
  }
  auto leg_to_b = [&](int v) {
    double best = kInf;
    for (const auto& t : targets)
      if (t.first == v) best = std::min(best, t.second);
    return best;
  };
  auto heuristic = [&](int v) { return astar ? rho * (mesh.position(v) - pb).norm() : 0.0; };

  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  if (as_vertex(mesh, a) >= 0) {
    const int v = as_vertex(mesh, a);
    dist[v] = 0.0;
    queue.emplace(heuristic(v), v);
  } else {
    for (int f : faces_containing(mesh, a))
      for (int k = 0; k < 3; ++k) {
        const int v = mesh.triangle(f)[k];
        const double d = rho * (mesh.position(v) - pa).norm();
        if (d < dist[v]) {
          dist[v] = d;
          queue.emplace(d + heuristic(v), v);
        }
      }
  }
  double best = kInf;
  int best_vertex = -1;
  while (!queue.empty()) {
    const auto [key, v] = queue.top();
    queue.pop();
    if (done[v]) continue;
    if (key >= best) break;
    done[v] = 1;
    ++result.settled;
    const double leg = leg_to_b(v);
    if (dist[v] + leg < best) {
      best = dist[v] + leg;
      best_vertex = v;
    }
    for (int i = graph.offsets[v]; i < graph.offsets[v + 1]; ++i) {
      const int w = graph.neighbors[i];
      const double d = dist[v] + graph.weights[i];
      if (d < dist[w]) {
        dist[w] = d;
        parent[w] = v;
        if (!parent_via.empty()) parent_via[w] = graph.via[i];
        queue.emplace(d + heuristic(w), w);
      }
    }
  }
  if (best_vertex < 0) return result;
  result.found = true;
  result.length = best;
  for (int v = best_vertex; v >= 0; v = parent[v]) {
    result.vertices.push_back(v);
    result.via.push_back(parent_via.empty() ? -1 : parent_via[v]);
  }
  std::reverse(result.vertices.begin(), result.vertices.end());
  std::reverse(result.via.begin(), result.via.end());
  result.via.front() = -1;
  return result;
}

SurfacePath strip_from_vertex_path(const Mesh& mesh, const SurfacePoint& a,
                                   const std::vector<int>& vertices, const SurfacePoint& b,
                                   const std::vector<int>* via) {
  SurfacePath path;
  path.closed = false;
  path.start = a;
  path.end = b;
  const Vec3 pa = position(mesh, a), pb = position(mesh, b);

  // Shared face: no crossings at all.
  for (int f : faces_containing(mesh, a)) {
    if (face_contains(mesh, f, b)) {
      path.start_face = f;
      return path;
    }
  }
  if (vertices.empty()) throw InvariantError("initial path: empty vertex path");

  std::size_t first = 0;
  int face = -1;
  const bool a_is_vertex = as_vertex(mesh, a) == vertices.front();
  auto via_at = [&](std::size_t i) { return via && i < via->size() ? (*via)[i] : -1; };
  if (a_is_vertex && vertices.size() >= 2 && via_at(1) >= 0) {
    // The first step is a diagonal: start in the face of the crossed edge that contains a.
    face = mesh.face(via_at(1));
    first = 0;
  } else if (a_is_vertex && vertices.size() >= 2) {
    face = face_of_edge(mesh, vertices[0], vertices[1]);
    first = 1;
  } else {
    for (int f : faces_containing(mesh, a))
      if (face_has_vertex(mesh, f, vertices.front())) face = f;
    if (a_is_vertex) first = 0;  // a single-vertex path: turn at a towards b below
  }
  if (face < 0) throw InvariantError("initial path: the start face does not touch the path");
  path.start_face = face;

  const bool b_is_vertex = as_vertex(mesh, b) == vertices.back();
  for (std::size_t i = first; i < vertices.size(); ++i) {
    const int u = vertices[i];
    const Vec3 prev = i == 0 ? pa : mesh.position(vertices[i - 1]);
    if (i + 1 < vertices.size() && via_at(i + 1) >= 0) {
      // Diagonal step: turn to the face of the crossed edge, then cross it into w's face.
      const int hc = via_at(i + 1);
      const int fc = mesh.face(hc);
      const int w = vertices[i + 1];
      if (!(i == 0 && a_is_vertex && face == fc)) {
        turn_at(
            mesh, u, &face, prev, mesh.position(w), [&](int f) { return f == fc; }, &path);
      }
      path.halfedges.push_back(hc);
      path.lambdas.push_back(0.5);
      face = mesh.face(mesh.twin(hc));
      (void)w;
    } else if (i + 1 < vertices.size()) {
      const int w = vertices[i + 1];
      turn_at(
          mesh, u, &face, prev, mesh.position(w),
          [&](int f) { return face_has_vertex(mesh, f, w); }, &path);
    } else if (!b_is_vertex) {
      turn_at(
          mesh, u, &face, prev, pb, [&](int f) { return face_contains(mesh, f, b); }, &path);
    }
  }
  if (!path.halfedges.empty()) path.start_face = mesh.face(path.halfedges.front());
  return path;
}

SurfacePath strip_from_vertex_cycle(const Mesh& mesh, const std::vector<int>& cycle) {
  const int m = static_cast<int>(cycle.size());
  if (m < 3) throw InputError("a closed loop needs at least 3 distinct vertices");
  SurfacePath path;
  path.closed = true;
  int face = face_of_edge(mesh, cycle[m - 1], cycle[0]);
  if (face < 0) {
    throw InputError("closed loop: vertices " + std::to_string(cycle[m - 1]) + " and " +
                     std::to_string(cycle[0]) + " are not joined by an edge");
  }
  const int start_face = face;
  for (int i = 0; i < m; ++i) {
    const int u = cycle[i];
    const int w = cycle[(i + 1) % m];
    if (face_of_edge(mesh, u, w) < 0) {
      throw InputError("closed loop: vertices " + std::to_string(u) + " and " + std::to_string(w) +
                       " are not joined by an edge");
    }
    turn_at(
        mesh, u, &face, mesh.position(cycle[(i + m - 1) % m]), mesh.position(w),
        [&](int f) { return face_has_vertex(mesh, f, w); }, &path);
  }
  // Close the strip: cross the last edge back into the start face if needed.
  if (face != start_face) {
    const int u = cycle[m - 1], w = cycle[0];
    int c = -1;
    for (int k = 0; k < 3; ++k) {
      const int h = 3 * face + k;
      if ((mesh.from(h) == u && mesh.to(h) == w) || (mesh.from(h) == w && mesh.to(h) == u)) c = h;
    }
    if (c < 0 || mesh.face(mesh.twin(c)) != start_face) {
      throw InvariantError("closed loop: the strip does not close");
    }
    path.halfedges.push_back(c);
    path.lambdas.push_back(0.5);
  }
  if (path.halfedges.size() < 2) throw InputError("closed loop: the loop is degenerate");
  // Rotate so that halfedges[0] leaves the face the last crossing enters.
  return path;
}

SurfacePath join_at_vertex(const Mesh& mesh, const SurfacePath& first, const SurfacePath& second,
                           int q) {
  SurfacePath joined;
  const int f1 = strip_face(mesh, first, first.num_crossings());
  const int f2 = strip_face(mesh, second, 0);
  std::vector<int> best;
  double best_angle = std::numeric_limits<double>::infinity();
  if (f1 != f2) {
    for (const bool ccw : {true, false}) {
      int hv = -1;
      for (int k = 0; k < 3; ++k)
        if (mesh.from(3 * f1 + k) == q) hv = 3 * f1 + k;
      if (hv < 0) return joined;
      std::vector<int> crossings;
      double angle = 0.0;
      bool reached = false;
      for (int step = 0; step < 4 * mesh.valence(q) + 4 && !reached; ++step) {
        angle += mesh.corner_angle(hv);
        const int c = ccw ? mesh.prev(hv) : hv;
        const int t = mesh.twin(c);
        if (mesh.is_boundary_halfedge(t)) break;
        crossings.push_back(c);
        hv = ccw ? t : mesh.next(t);
        reached = mesh.face(t) == f2;
      }
      if (reached && angle < best_angle) {
        best_angle = angle;
        best = std::move(crossings);
      }
    }
    if (best.empty()) return joined;
  }
  joined.start = first.start;
  joined.end = second.end;
  joined.halfedges = first.halfedges;
  joined.lambdas = first.lambdas;
  for (const int c : best) {
    joined.halfedges.push_back(c);
    joined.lambdas.push_back(mesh.from(c) == q ? 0.0 : 1.0);
  }
  joined.halfedges.insert(joined.halfedges.end(), second.halfedges.begin(), second.halfedges.end());
  joined.lambdas.insert(joined.lambdas.end(), second.lambdas.begin(), second.lambdas.end());
  joined.start_face =
      joined.halfedges.empty() ? first.start_face : mesh.face(joined.halfedges.front());
  return joined;
}

std::vector<int> remove_spurs(const std::vector<int>& chain) {
  std::vector<int> clean;
  for (int v : chain) {
    if (!clean.empty() && clean.back() == v) continue;
    if (clean.size() >= 2 && clean[clean.size() - 2] == v) {
      clean.pop_back();
      continue;
    }
    clean.push_back(v);
  }
  return clean;
}

SurfacePath initial_open_path(const Mesh& mesh, const EdgeGraph& graph, const SurfacePoint& a,
                              const SurfacePoint& b, const EdgePathOptions& options,
                              EdgePath* diagnostics) {
  SurfacePath direct;
  for (int f : faces_containing(mesh, a)) {
    if (face_contains(mesh, f, b)) {
      direct.start = a;
      direct.end = b;
      direct.start_face = f;
      if (diagnostics) *diagnostics = EdgePath{};
      return direct;
    }
  }
  EdgePath ep = shortest_edge_path(mesh, graph, a, b, options);
  if (diagnostics) *diagnostics = ep;
  if (!ep.found) {
    throw InputError("no path from " + to_string(mesh, a) + " to " + to_string(mesh, b) +
                     ": the points lie on different components of the mesh");
  }
  return strip_from_vertex_path(mesh, a, ep.vertices, b, &ep.via);
}

SurfacePath path_from_curve(const Mesh& mesh, const EdgeGraph& graph,
                            const std::vector<Vec3>& points, bool closed, double max_distance) {
  if (points.size() < 2) throw InputError("a curve needs at least 2 points");
  ClosestPointQuery query(mesh);
  std::vector<SurfacePoint> snapped;
  std::vector<int> nearest_vertex;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw InputError("curve point " + std::to_string(i) + " is not finite");
    }
    const auto hit = query.closest(points[i]);
    if (!(hit.distance <= max_distance)) {
      throw InputError("curve point " + std::to_string(i) + " is " + std::to_string(hit.distance) +
                       " mm from the mesh (more than " + std::to_string(max_distance) + " mm)");
    }
    snapped.push_back(hit.point);
    const Tri& t = mesh.triangle(hit.point.element);
    int k = 0;
    hit.point.bary.maxCoeff(&k);
    nearest_vertex.push_back(t[k]);
  }
  // Chain the nearest vertices with shortest edge paths.
  std::vector<int> chain;
  const std::size_t n = points.size();
  const std::size_t legs = closed ? n : n - 1;
  for (std::size_t i = 0; i < legs; ++i) {
    const int u = nearest_vertex[i], w = nearest_vertex[(i + 1) % n];
    if (chain.empty()) chain.push_back(u);
    if (u == w) continue;
    const EdgePath ep =
        shortest_edge_path(mesh, graph, SurfacePoint::at_vertex(u), SurfacePoint::at_vertex(w));
    if (!ep.found) {
      throw InputError("curve points " + std::to_string(i) + " and " + std::to_string((i + 1) % n) +
                       " lie on different components of the mesh");
    }
    for (std::size_t j = 1; j < ep.vertices.size(); ++j) {
      if (ep.via[j] >= 0) {
        // A diagonal across edge (p, q): go through the nearer of p and q (both are adjacent).
        const int h = ep.via[j], p = mesh.from(h), q = mesh.to(h);
        const Vec3& s = mesh.position(ep.vertices[j - 1]);
        const Vec3& t = mesh.position(ep.vertices[j]);
        const double dp = (mesh.position(p) - s).norm() + (t - mesh.position(p)).norm();
        const double dq = (mesh.position(q) - s).norm() + (t - mesh.position(q)).norm();
        chain.push_back(dp <= dq ? p : q);
      }
      chain.push_back(ep.vertices[j]);
    }
  }
  std::vector<int> clean = remove_spurs(chain);
  if (closed) {
    while (clean.size() > 1 && clean.back() == clean.front()) clean.pop_back();
    while (clean.size() >= 3 && clean[clean.size() - 1] == clean[1]) {
      clean.erase(clean.begin());
      clean.pop_back();
    }
    return strip_from_vertex_cycle(mesh, clean);
  }
  return strip_from_vertex_path(mesh, snapped.front(), clean, snapped.back());
}

}  // namespace windplan
