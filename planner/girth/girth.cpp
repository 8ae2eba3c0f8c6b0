#include "planner/girth/girth.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <set>
#include <utility>

#include "geometry/base/errors.h"
#include "geometry/base/parallel.h"
#include "geometry/geodesic/edge_path.h"
#include "geometry/geodesic/geodesic.h"
#include "planner/girth/girth_loops.h"

namespace windplan {

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kInf = std::numeric_limits<double>::infinity();
// Samples blended per vertex (the (k+1)-th nearest sets the support radius).
constexpr int kBlend = 8;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Rejects anything but an annulus, and loops that are not its two boundary loops.
void check_annulus(const Mesh& mesh, const std::array<std::vector<int>, 2>& loops) {
  if (mesh.num_faces() == 0) {
    throw TopologyError("girth: the winding surface has no faces (an annulus is needed)");
  }
  const auto boundary = mesh.boundary_loops();
  const int components = mesh.num_components();
  const int genus = mesh.genus();
  if (boundary.size() != 2 || components != 1 || genus != 0) {
    throw TopologyError(
        "girth: the winding surface is not an annulus: it has " + std::to_string(boundary.size()) +
        " boundary loop(s), " + std::to_string(components) + " component(s) and genus " +
        std::to_string(genus) + " (an annulus has 2 boundary loops, 1 component, genus 0)");
  }
  std::vector<int> loop_of(mesh.num_vertices(), -1);
  for (int i = 0; i < 2; ++i)
    for (int v : mesh.loop_vertices(boundary[i])) loop_of[v] = i;
  int ids[2] = {-1, -1};
  for (int i = 0; i < 2; ++i) {
    if (loops[i].empty())
      throw InputError("girth: boundary loop " + std::to_string(i) + " is empty");
    for (int v : loops[i]) {
      if (v < 0 || v >= mesh.num_vertices()) {
        throw InputError("girth: boundary loop " + std::to_string(i) + " names vertex " +
                         std::to_string(v) + ", out of range [0, " +
                         std::to_string(mesh.num_vertices()) + ")");
      }
      if (loop_of[v] < 0 || (ids[i] >= 0 && loop_of[v] != ids[i])) {
        throw InputError("girth: vertex " + std::to_string(v) + " of boundary loop " +
                         std::to_string(i) + " is not on the same boundary loop as the others");
      }
      ids[i] = loop_of[v];
    }
  }
  if (ids[0] == ids[1]) throw InputError("girth: both loops given are the same boundary loop");
}

// Neighbours of v in counter-clockwise order (for a boundary vertex from the most clockwise).
std::vector<int> ring_ccw(const Mesh& mesh, int v) {
  const std::vector<int> hs = mesh.outgoing_halfedges(v);
  std::vector<int> ring;
  for (int h : hs) ring.push_back(mesh.to(h));
  if (mesh.is_boundary_vertex(v) && !hs.empty()) ring.push_back(mesh.from(mesh.prev(hs.back())));
  return ring;
}

// Multi-source Dijkstra on the edge graph.
std::vector<double> graph_distances(const EdgeGraph& g, const std::vector<int>& sources) {
  const int n = static_cast<int>(g.offsets.size()) - 1;
  std::vector<double> dist(n, kInf);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  for (int s : sources) {
    dist[s] = 0.0;
    queue.emplace(0.0, s);
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[v]) continue;
    for (int i = g.offsets[v]; i < g.offsets[v + 1]; ++i) {
      const double nd = d + g.weights[i];
      if (nd < dist[g.neighbors[i]]) {
        dist[g.neighbors[i]] = nd;
        queue.emplace(nd, g.neighbors[i]);
      }
    }
  }
  return dist;
}

}  // namespace

bool GirthOptions::is_valid(std::string* why) const {
  if (samples < 4) {
    if (why) *why = "samples must be >= 4 (got " + std::to_string(samples) + ")";
    return false;
  }
  if (placement != "rings" && placement != "farthest") {
    if (why) *why = "placement must be 'rings' or 'farthest' (got '" + placement + "')";
    return false;
  }
  if (rings < 0) {
    if (why) *why = "rings must be >= 0 (0 = auto; got " + std::to_string(rings) + ")";
    return false;
  }
  return true;
}

std::vector<double> GirthField::face_girth(const Mesh& mesh) const {
  std::vector<double> out(mesh.num_faces(), 0.0);
  if (vertex_girth.size() != static_cast<std::size_t>(mesh.num_vertices())) return out;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Tri& t = mesh.triangle(f);
    out[f] = (vertex_girth[t[0]] + vertex_girth[t[1]] + vertex_girth[t[2]]) / 3.0;
  }
  return out;
}

// ---- GirthContext ----

struct GirthContext::Impl {
  EdgeGraph graph;
  std::vector<int> seam;
  // Per CSR entry of `graph`: signed seam crossing of the directed edge (+1 left -> right).
  // The seam is taken pushed infinitesimally to its right, so seam vertices are on its left.
  std::vector<signed char> shift;
  // Per halfedge: +1 for the seam halfedge s_i -> s_{i+1} (its face is on the seam's left;
  // crossing it leaves the left side), -1 for its twin, 0 otherwise.
  std::vector<signed char> seam_cross;
};

GirthContext::GirthContext(const Mesh& annulus, const std::array<std::vector<int>, 2>& loops)
    : mesh_(annulus), impl_(std::make_unique<Impl>()) {
  check_annulus(annulus, loops);
  const Mesh& mesh = mesh_;
  Impl& m = *impl_;
  m.graph = build_edge_graph(mesh);
  const EdgeGraph& g = m.graph;
  const int nv = mesh.num_vertices();

  // Seam: shortest edge path from loop 0 to the nearest vertex of loop 1.
  std::vector<char> target(nv, 0);
  for (int v : loops[1]) target[v] = 1;
  {
    std::vector<double> dist(nv, kInf);
    std::vector<int> parent(nv, -1);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    for (int s : loops[0]) {
      dist[s] = 0.0;
      queue.emplace(0.0, s);
    }
    int reached = -1;
    while (!queue.empty()) {
      const auto [d, v] = queue.top();
      queue.pop();
      if (d > dist[v]) continue;
      if (target[v]) {
        reached = v;
        break;
      }
      for (int i = g.offsets[v]; i < g.offsets[v + 1]; ++i) {
        const int w = g.neighbors[i];
        if (d + g.weights[i] < dist[w]) {
          dist[w] = d + g.weights[i];
          parent[w] = v;
          queue.emplace(dist[w], w);
        }
      }
    }
    if (reached < 0) throw TopologyError("girth: boundary loop 1 is unreachable from loop 0");
    for (int v = reached; v >= 0; v = parent[v]) m.seam.push_back(v);
    std::reverse(m.seam.begin(), m.seam.end());
  }
  const std::vector<int>& seam = m.seam;
  const int K = static_cast<int>(seam.size()) - 1;

  // Side of every spoke of every seam vertex; right-side spokes cross the pushed seam.
  m.shift.assign(g.neighbors.size(), 0);
  auto csr_entry = [&](int u, int w) {
    for (int i = g.offsets[u]; i < g.offsets[u + 1]; ++i)
      if (g.neighbors[i] == w) return i;
    throw InvariantError("girth: missing graph edge " + std::to_string(u) + "-" +
                         std::to_string(w));
  };
  std::vector<int> seam_index(nv, -1);
  for (int i = 0; i <= K; ++i) seam_index[seam[i]] = i;
  for (int i = 0; i <= K; ++i) {
    const int s = seam[i];
    const std::vector<int> ring = ring_ccw(mesh, s);
    const int n = static_cast<int>(ring.size());
    auto index_of = [&](int w) {
      const auto it = std::find(ring.begin(), ring.end(), w);
      if (it == ring.end()) throw InvariantError("girth: seam is not an edge path");
      return static_cast<int>(it - ring.begin());
    };
    std::vector<char> right(n, 0);
    if (i > 0 && i < K) {
      // Interior: left is strictly ccw from forward to backward, right from backward to forward.
      const int fi = index_of(seam[i + 1]), bi = index_of(seam[i - 1]);
      for (int j = (bi + 1) % n; j != fi; j = (j + 1) % n) right[j] = 1;
    } else if (i == 0) {
      const int fi = index_of(seam[1]);
      for (int j = 0; j < fi; ++j) right[j] = 1;  // clockwise of forward
    } else {
      const int bi = index_of(seam[K - 1]);
      for (int j = bi + 1; j < n; ++j) right[j] = 1;  // counter-clockwise of backward
    }
    for (int j = 0; j < n; ++j) {
      const int w = ring[j];
      if (!right[j] || seam_index[w] >= 0) continue;  // seam-to-seam edges never cross
      m.shift[csr_entry(s, w)] = +1;
      m.shift[csr_entry(w, s)] = -1;
    }
  }
  m.seam_cross.assign(mesh.num_halfedges(), 0);
  for (int i = 0; i < K; ++i) {
    for (int h : mesh.outgoing_halfedges(seam[i])) {
      if (mesh.to(h) == seam[i + 1]) {
        m.seam_cross[h] = +1;
        m.seam_cross[mesh.twin(h)] = -1;
      }
    }
    // The edge may be a boundary edge whose interior halfedge runs s_{i+1} -> s_i.
    for (int h : mesh.outgoing_halfedges(seam[i + 1])) {
      if (mesh.to(h) == seam[i]) {
        m.seam_cross[h] = -1;
        m.seam_cross[mesh.twin(h)] = +1;
      }
    }
  }
}

GirthContext::~GirthContext() = default;

const std::vector<int>& GirthContext::seam() const { return impl_->seam; }

int GirthContext::winding_number(const SurfacePath& path) const {
  const Mesh& mesh = mesh_;
  const Impl& m = *impl_;
  int w = 0;
  for (int h : path.halfedges) w += m.seam_cross[h];
  if (path.closed) return w;
  // Close the face chain by rotating around the start vertex from the last face to the first.
  if (path.start.kind != SurfacePoint::Kind::Vertex) return w;
  const int p = path.start.element;
  const int first = strip_face(mesh, path, 0);
  const int last = strip_face(mesh, path, path.num_crossings());
  if (first == last) return w;
  auto outgoing_in = [&](int f) {
    for (int k = 0; k < 3; ++k)
      if (mesh.from(3 * f + k) == p) return 3 * f + k;
    return -1;
  };
  for (bool ccw : {true, false}) {
    int hv = outgoing_in(last);
    if (hv < 0) return w;
    int sum = 0;
    bool ok = false;
    for (int step = 0; step < 4 * mesh.valence(p) + 4; ++step) {
      const int c = ccw ? mesh.prev(hv) : hv;  // the halfedge of the face we leave
      const int t = mesh.twin(c);
      if (mesh.is_boundary_halfedge(t)) break;
      sum += m.seam_cross[c];
      hv = ccw ? t : mesh.next(t);
      if (mesh.face(t) == first) {
        ok = true;
        break;
      }
    }
    if (ok) return w + sum;
  }
  return w;
}

SurfacePath GirthContext::initial_loop(int p, double* edge_length, std::vector<double>* distances,
                                       std::vector<int>* cycle_out) const {
  const Mesh& mesh = mesh_;
  const Impl& m = *impl_;
  const EdgeGraph& g = m.graph;
  const int nv = mesh.num_vertices();
  if (p < 0 || p >= nv) {
    throw InputError("girth: vertex " + std::to_string(p) + " out of range [0, " +
                     std::to_string(nv) + ")");
  }
  // Dijkstra on the double cover: node 2 v + c, an edge with a seam crossing flips c.
  std::vector<double> dist(2 * static_cast<std::size_t>(nv), kInf);
  std::vector<int> parent(2 * static_cast<std::size_t>(nv), -1);
  std::vector<char> done(2 * static_cast<std::size_t>(nv), 0);
  if (distances) distances->assign(nv, kInf);
  int base_settled = 0;
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  const int source = 2 * p, goal = 2 * p + 1;
  dist[source] = 0.0;
  queue.emplace(0.0, source);
  while (!queue.empty()) {
    const auto [d, node] = queue.top();
    queue.pop();
    if (done[node]) continue;
    done[node] = 1;
    const int v = node >> 1, c = node & 1;
    if (distances && (*distances)[v] == kInf) {
      (*distances)[v] = d;
      ++base_settled;
    }
    if (done[goal] && (!distances || base_settled == nv)) break;
    for (int i = g.offsets[v]; i < g.offsets[v + 1]; ++i) {
      const int next = 2 * g.neighbors[i] + (c ^ (m.shift[i] != 0 ? 1 : 0));
      const double nd = d + g.weights[i];
      if (nd < dist[next]) {
        dist[next] = nd;
        parent[next] = node;
        queue.emplace(nd, next);
      }
    }
  }
  if (!done[goal]) throw InvariantError("girth: no loop through vertex " + std::to_string(p));

  if (edge_length) *edge_length = dist[goal];
  // The cycle v_1, ..., v_{m-1}, p (p last, so that its turn and the closing crossing come last).
  std::vector<int> cycle;
  for (int node = parent[goal]; node != source && node >= 0; node = parent[node]) {
    cycle.push_back(node >> 1);
  }
  std::reverse(cycle.begin(), cycle.end());
  cycle.push_back(p);
  if (cycle_out) {
    cycle_out->assign(1, p);
    cycle_out->insert(cycle_out->end(), cycle.begin(), cycle.end() - 1);
  }
  SurfacePath closed = strip_from_vertex_cycle(mesh, cycle);
  // Open it at p: drop the trailing crossings of edges at p (the turn at p and the closing
  // crossing); the face before such a crossing still contains p.
  SurfacePath path;
  path.closed = false;
  path.start = path.end = SurfacePoint::at_vertex(p);
  path.halfedges = std::move(closed.halfedges);
  path.lambdas = std::move(closed.lambdas);
  auto touches_p = [&](int h) { return mesh.from(h) == p || mesh.to(h) == p; };
  while (!path.halfedges.empty() && touches_p(path.halfedges.back())) {
    path.halfedges.pop_back();
    path.lambdas.pop_back();
  }
  if (path.halfedges.empty())
    throw InvariantError("girth: empty loop strip at vertex " + std::to_string(p));
  path.start_face = mesh.face(path.halfedges.front());
  std::string why;
  if (!is_valid_path(mesh, path, &why)) {
    throw InvariantError("girth: initial loop at vertex " + std::to_string(p) + ": " + why);
  }
  return path;
}

SurfacePath GirthContext::refined_halves(int p, const std::vector<int>& cycle) const {
  const Mesh& mesh = mesh_;
  const int m = static_cast<int>(cycle.size());
  SurfacePath joined;
  if (m < 3) return joined;
  // q: the interior vertex of the cycle nearest its middle (a geodesic ending at a boundary
  // vertex the loop hugs can take the core seconds).
  int j = m / 2;
  for (int off = 0; off < m; ++off) {
    const int c1 = m / 2 + off, c2 = m / 2 - off;
    if (c1 < m && !mesh.is_boundary_vertex(cycle[c1])) {
      j = c1;
      break;
    }
    if (c2 > 0 && !mesh.is_boundary_vertex(cycle[c2])) {
      j = c2;
      break;
    }
  }
  const int q = cycle[j];
  std::vector<int> first_half(cycle.begin(), cycle.begin() + j + 1);
  std::vector<int> second_half(cycle.begin() + j, cycle.end());
  second_half.push_back(p);
  GeodesicResult a, b;
  try {
    a = refine_path(mesh, strip_from_vertex_path(mesh, SurfacePoint::at_vertex(p), first_half,
                                                 SurfacePoint::at_vertex(q)));
    b = refine_path(mesh, strip_from_vertex_path(mesh, SurfacePoint::at_vertex(q), second_half,
                                                 SurfacePoint::at_vertex(p)));
  } catch (const Error&) {
    return joined;  // the direct refinement is the fallback
  }
  joined = join_at_vertex(mesh, a.path, b.path, q);
  if (joined.start_face < 0) return SurfacePath{};
  std::string why;
  if (!is_valid_path(mesh, joined, &why) || std::abs(winding_number(joined)) != 1) {
    return SurfacePath{};
  }
  return joined;
}

namespace {
// Other corridors tried per girth loop, and how much longer (as edge loops) than the shortest
// edge loop they may be: the edge loops are a few per cent longer than the loops they lead to.
constexpr int kOtherCorridors = 2;
constexpr double kCorridorWindow = 1.15;
bool finite_length(const GeodesicResult& r) { return std::isfinite(r.summary.euclidean_length); }
}  // namespace

GirthContext::Loop GirthContext::girth(int p, std::vector<double>* distances) const {
  const Mesh& mesh = mesh_;
  Loop loop;
  std::vector<int> cycle;
  SurfacePath path = initial_loop(p, &loop.edge_length, distances, &cycle);
  const int initial_winding = winding_number(path);

  // A loop lying exactly on mesh edges through flat vertices (a cylinder's ring) ends with no
  // decrease along the search direction at the optimum: accepted as converged (non-smooth
  // optimum); the summary keeps the core's own termination. A result that did not converge,
  // lost the winding or got longer than the edge loop is retried without the funnel start
  // (the Newton/reroute path of the core), which some core versions need for a path from p
  // back to p.
  auto acceptable = [&](const GeodesicResult& r, int winding) {
    const bool done =
        r.summary.converged() || r.summary.termination == GeodesicTermination::LineSearchFailed;
    return done && std::abs(winding) == 1 &&
           r.summary.euclidean_length <= loop.edge_length * (1 + 1e-9);
  };
  // A loop winding around the mandrel is rerouted around many vertices (on a cone every one
  // between the edge loop and the chord): the core's default cap (20 + 4 crossings) is too
  // tight for the funnel start, so the cap is raised.
  GeodesicOptions first;
  first.max_reroutes = 1000 + 32 * path.num_crossings();
  // Two halves first (p -> q -> p, q the edge loop's middle vertex): ordinary open geodesics
  // with distinct ends, which the core refines quickly; joined at q they give a start close to
  // the loop, which is then refined from p to p. (Refining the edge loop from p to p directly
  // can take the core seconds on some strips of sliver-rich meshes.)
  GeodesicResult r;
  bool have = false;
  if (const SurfacePath joined = refined_halves(p, cycle); joined.num_crossings() > 0) {
    r = refine_path(mesh, joined, PathMetric{}, first);
    have = true;
  }
  if (!have) r = refine_path(mesh, path, PathMetric{}, first);
  int winding = winding_number(r.path);
  if (!acceptable(r, winding)) {
    GeodesicOptions retry = first;
    retry.funnel_start = false;
    GeodesicResult r2 = refine_path(mesh, path, PathMetric{}, retry);
    const int winding2 = winding_number(r2.path);
    loop.retried = true;
    const bool better =
        acceptable(r2, winding2) || (std::abs(winding2) == 1 && std::abs(winding) != 1) ||
        (std::abs(winding2) == 1 && r2.summary.euclidean_length < r.summary.euclidean_length);
    if (better) {
      r = std::move(r2);
      winding = winding2;
    }
  }
  // The shortest loop, not only a locally shortest one: refine also from edge loops in other
  // corridors (planner/girth/girth_loops.h) and keep the shortest that winds once.
  bool other_corridor = false;
  for (const std::vector<int>& other : alternative_edge_loops(
           mesh, impl_->graph, impl_->shift, p, cycle, kOtherCorridors, kCorridorWindow)) {
    const SurfacePath joined = refined_halves(p, other);
    if (joined.num_crossings() == 0) continue;
    GeodesicResult ro = refine_path(mesh, joined, PathMetric{}, first);
    const int wo = winding_number(ro.path);
    const bool done =
        ro.summary.converged() || ro.summary.termination == GeodesicTermination::LineSearchFailed;
    if (done && std::abs(wo) == 1 && finite_length(ro) &&
        ro.summary.euclidean_length < r.summary.euclidean_length * (1.0 - 1e-12)) {
      r = std::move(ro);
      winding = wo;
      other_corridor = true;
    }
  }
  loop.summary = r.summary;
  loop.winding = winding;
  loop.converged = other_corridor || acceptable(r, winding);
  if (std::abs(winding) == 1 &&
      (other_corridor || r.summary.euclidean_length <= loop.edge_length * (1 + 1e-9))) {
    loop.girth = r.summary.euclidean_length;
    loop.path = std::move(r.path);
  } else {
    // The refinement lost the winding or did not shorten the loop: keep the initial loop.
    loop.girth = euclidean_length(mesh, path);
    loop.winding = initial_winding;
    loop.converged = false;
    loop.path = std::move(path);
  }
  return loop;
}

double girth_at(const Mesh& annulus, const std::array<std::vector<int>, 2>& loops, int vertex,
                SurfacePath* loop_out) {
  const GirthContext context(annulus, loops);
  GirthContext::Loop loop = context.girth(vertex);
  if (loop_out) *loop_out = std::move(loop.path);
  return loop.girth;
}

// ---- the field ----

namespace {

// Farthest-point selection of `count` vertices among `candidates` by Euclidean distance,
// starting from the first candidate.
std::vector<int> farthest_euclidean(const Mesh& mesh, const std::vector<int>& candidates,
                                    int count) {
  std::vector<int> chosen;
  if (candidates.empty() || count <= 0) return chosen;
  std::vector<double> d(candidates.size(), kInf);
  std::size_t next = 0;
  while (static_cast<int>(chosen.size()) < count && chosen.size() < candidates.size()) {
    chosen.push_back(candidates[next]);
    const Vec3& q = mesh.position(candidates[next]);
    double best = -1.0;
    for (std::size_t i = 0; i < candidates.size(); ++i) {
      d[i] = std::min(d[i], (mesh.position(candidates[i]) - q).norm());
      if (d[i] > best) {
        best = d[i];
        next = i;
      }
    }
    if (best <= 0.0) break;
  }
  return chosen;
}

// Samples on rings of the intrinsic axial coordinate t = d0 / (d0 + d1).
std::vector<int> ring_samples(const Mesh& mesh, const EdgeGraph& graph,
                              const std::array<std::vector<int>, 2>& loops,
                              const std::vector<double>& t, double meridian,
                              const GirthOptions& options) {
  const int nv = mesh.num_vertices();
  // Auto: about as far apart along the axis as around it. With S samples on R rings over a
  // meridian of length L and a mean circumference A / L: L / (R - 1) ~ (A / L) / (S / R), i.e.
  // R ~ sqrt(S L^2 / A): sqrt(S) for a surface as long as it is round.
  int rings = options.rings;
  if (rings <= 0) {
    const double area = mesh.total_area();
    const double aspect = area > 0.0 ? meridian * meridian / area : 1.0;
    rings = static_cast<int>(std::lround(std::sqrt(options.samples * aspect)));
    rings = std::clamp(rings, 2, std::max(2, options.samples / 3));
  }
  rings = std::min(rings, options.samples);
  std::vector<int> chosen;
  std::set<int> seen;
  for (int j = 0; j < rings; ++j) {
    const int count = options.samples / rings + (j < options.samples % rings ? 1 : 0);
    std::vector<int> candidates;
    if (rings > 1 && j == 0) {
      candidates = loops[0];
    } else if (rings > 1 && j == rings - 1) {
      candidates = loops[1];
    } else {
      const double level = rings > 1 ? double(j) / (rings - 1) : 0.5;
      // The endpoint nearer the level of every edge that crosses it.
      std::vector<char> mark(nv, 0);
      for (int v = 0; v < nv; ++v) {
        for (int i = graph.offsets[v]; i < graph.offsets[v + 1]; ++i) {
          const int w = graph.neighbors[i];
          if (w < v) continue;
          if ((t[v] - level) * (t[w] - level) > 0.0) continue;
          mark[std::abs(t[v] - level) <= std::abs(t[w] - level) ? v : w] = 1;
        }
      }
      for (int v = 0; v < nv; ++v)
        if (mark[v]) candidates.push_back(v);
    }
    for (int v : farthest_euclidean(mesh, candidates, count))
      if (seen.insert(v).second) chosen.push_back(v);
  }
  return chosen;
}

}  // namespace

GirthField compute_girth_field(const Mesh& annulus, const std::array<std::vector<int>, 2>& loops,
                               const GirthOptions& options) {
  std::string why;
  if (!options.is_valid(&why)) throw ConfigError("girth: " + why);
  const auto t0 = Clock::now();
  const GirthContext context(annulus, loops);
  const Mesh& mesh = annulus;
  const int nv = mesh.num_vertices();
  const int samples = std::min(options.samples, nv);

  GirthField field;
  // Intrinsic axial coordinate t = d0 / (d0 + d1) in [0, 1] (0 on loop 0, 1 on loop 1).
  const EdgeGraph graph = build_edge_graph(mesh);
  const std::vector<double> d0 = graph_distances(graph, loops[0]);
  const std::vector<double> d1 = graph_distances(graph, loops[1]);
  std::vector<double> t(nv, 0.5);
  double meridian = 0.0;
  for (int v = 0; v < nv; ++v) {
    const double s = d0[v] + d1[v];
    t[v] = s > 0.0 ? d0[v] / s : 0.5;
    meridian += s / nv;
  }

  // 1. Where: the planned rings, then farthest-point sampling (which also tops up rings that
  // had fewer candidates than samples). `nearest` is kept by a Dijkstra from each new sample
  // pruned to where it improves (it only explores the new sample's Voronoi cell).
  std::vector<int> chosen;
  if (options.placement == "rings") chosen = ring_samples(mesh, graph, loops, t, meridian, options);
  if (static_cast<int>(chosen.size()) > samples) chosen.resize(samples);
  std::vector<double> nearest(nv, kInf);
  {
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    auto add = [&](int v) {
      nearest[v] = 0.0;
      queue.emplace(0.0, v);
      while (!queue.empty()) {
        const auto [d, u] = queue.top();
        queue.pop();
        if (d > nearest[u]) continue;
        for (int i = graph.offsets[u]; i < graph.offsets[u + 1]; ++i) {
          const int w = graph.neighbors[i];
          if (d + graph.weights[i] < nearest[w]) {
            nearest[w] = d + graph.weights[i];
            queue.emplace(nearest[w], w);
          }
        }
      }
    };
    for (int v : chosen) add(v);
    if (chosen.empty()) {
      chosen.push_back(loops[0].front());
      add(chosen.back());
    }
    while (static_cast<int>(chosen.size()) < samples) {
      int v = -1;
      double best = 0.0;
      for (int u = 0; u < nv; ++u)
        if (nearest[u] > best) best = nearest[u], v = u;
      if (v < 0) break;  // every vertex is a sample
      chosen.push_back(v);
      add(v);
    }
  }
  for (int v = 0; v < nv; ++v)
    field.lipschitz_bound = std::max(field.lipschitz_bound, 2.0 * nearest[v]);

  // 2. The exact loops, independent of each other: spread over the threads
  // (geometry/base/parallel.h; each loop writes its own slot, so the field does not depend on the
  // thread count).
  const int count = static_cast<int>(chosen.size());
  std::vector<GirthContext::Loop> exact(count);
  parallel_for_index(count, [&](int k) { exact[k] = context.girth(chosen[k]); });
  for (int k = 0; k < count; ++k) {
    const GirthContext::Loop& loop = exact[k];
    if (!loop.converged || std::abs(loop.winding) != 1) ++field.unconverged_samples;
    field.samples.push_back({chosen[k], loop.girth, mesh.position(chosen[k])});
  }

  // 3. The (kBlend + 1) nearest samples of every vertex, ascending, by one Dijkstra that carries
  // up to kKeep labels per vertex: a sample stops spreading through a vertex that already has
  // kKeep nearer ones (then they are nearer at every vertex beyond too).
  constexpr int kKeep = kBlend + 1;
  std::vector<double> near_d(static_cast<std::size_t>(nv) * kKeep, kInf);
  std::vector<int> near_s(static_cast<std::size_t>(nv) * kKeep, -1);
  std::vector<int> labels(nv, 0);
  {
    struct Item {
      double d;
      int v, s;
      bool operator>(const Item& o) const { return d > o.d; }
    };
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
    auto has = [&](int v, int s) {
      const int* ns = &near_s[static_cast<std::size_t>(v) * kKeep];
      for (int j = 0; j < labels[v]; ++j)
        if (ns[j] == s) return true;
      return false;
    };
    for (int k = 0; k < count; ++k) queue.push({0.0, chosen[k], k});
    while (!queue.empty()) {
      const Item it = queue.top();
      queue.pop();
      if (labels[it.v] >= kKeep || has(it.v, it.s)) continue;
      const std::size_t slot = static_cast<std::size_t>(it.v) * kKeep + labels[it.v]++;
      near_d[slot] = it.d;
      near_s[slot] = it.s;
      for (int i = graph.offsets[it.v]; i < graph.offsets[it.v + 1]; ++i) {
        const int w = graph.neighbors[i];
        if (labels[w] < kKeep && !has(w, it.s)) queue.push({it.d + graph.weights[i], w, it.s});
      }
    }
  }

  std::vector<double> sample_t;
  for (const GirthSample& s : field.samples) sample_t.push_back(t[s.vertex]);
  field.vertex_girth.assign(nv, 0.0);
  for (int u = 0; u < nv; ++u) {
    const double* nd = &near_d[static_cast<std::size_t>(u) * kKeep];
    const int* ns = &near_s[static_cast<std::size_t>(u) * kKeep];
    if (ns[0] < 0) continue;
    if (nd[0] <= 0.0) {
      field.vertex_girth[u] = field.samples[ns[0]].girth;
      continue;
    }
    int used = 0;
    while (used < kBlend && ns[used] >= 0) ++used;
    // Support radius: the next nearest sample, or past the farthest one used.
    const double radius = ns[kKeep - 1] >= 0 ? nd[kKeep - 1] : 2.0 * nd[used - 1];
    // Weighted linear least squares g ~ a + b (t_j - t_u); the value is a. Falls back to the
    // weighted mean (b = 0) when the samples used span no range of t.
    double w[kKeep], sw = 0.0, lo = -kInf, hi = kInf;
    for (int j = 0; j < used; ++j) {
      w[j] = std::pow(std::max(0.0, radius - nd[j]) / (radius * nd[j]), 2);
      sw += w[j];
    }
    if (!(sw > 0.0))
      for (int j = 0; j < used; ++j) w[j] = 1.0, sw += 1.0;
    double st = 0.0, sg = 0.0;
    for (int j = 0; j < used; ++j) {
      const int i = ns[j];
      st += w[j] * (sample_t[i] - t[u]);
      sg += w[j] * field.samples[i].girth;
    }
    st /= sw;
    sg /= sw;
    double stt = 0.0, stg = 0.0;
    for (int j = 0; j < used; ++j) {
      const int i = ns[j];
      const double dt = sample_t[i] - t[u] - st;
      stt += w[j] * dt * dt;
      stg += w[j] * dt * (field.samples[i].girth - sg);
      const double gj = field.samples[i].girth;
      lo = std::max(lo, gj - 2.0 * nd[j]);
      hi = std::min(hi, gj + 2.0 * nd[j]);
    }
    double value = sg;
    if (stt > 1e-12 * sw) value = sg - (stg / stt) * st;
    if (lo <= hi) value = std::clamp(value, lo, hi);
    field.vertex_girth[u] = value;
  }
  field.time_ms = ms_since(t0);
  return field;
}

}  // namespace windplan
