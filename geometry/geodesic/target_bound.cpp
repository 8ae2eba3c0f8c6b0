// The A* lower bound of geometry/geodesic/target_bound.h: why each step is as it is.
#include "geometry/geodesic/target_bound.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "geometry/base/errors.h"
#include "geometry/geodesic/edge_path.h"
#include "geometry/geodesic/geodesic_windows.h"
#include "geometry/geodesic/refine_path.h"

namespace windplan {

bool TargetBoundOptions::is_valid(std::string* why) const {
  if (!(min_detour >= 1.0)) {
    if (why) *why = "min_detour must be >= 1 (dimensionless; 1: always build the bound)";
    return false;
  }
  if (!(min_edges >= 0.0)) {
    if (why) *why = "min_edges must be >= 0 (longest edges; +inf: by min_detour alone)";
    return false;
  }
  if (!(clamp_slope == 0.0 || (clamp_slope >= 1.0 && std::isfinite(clamp_slope)))) {
    if (why) *why = "clamp_slope must be 0 (no clamp) or a finite slope >= 1 (dimensionless)";
    return false;
  }
  return true;
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The point source S in the plane with |S P| = up and |S Q| = uq, on the side of P Q away from
// R (P at the origin, Q at lq (ex, ey), per_lq = 1 / lq), given R in the frame of P Q: re
// along it, rm > 0 along its normal towards R. Returns S's distance to R, or +infinity when no
// such S exists or the segment S R misses P Q (the corners' values then come from no one
// source seen through the edge). Exact where the surface unfolds flat between S and R, which
// the plane wave (a source at infinity) is not: on the bunnies, 3 % fewer windows
// (bench/README.md, session 16). No division here: the caller's one reciprocal serves.
inline double point_source(double up, double lq, double per_lq, double uq, double re, double rm) {
  if (!(rm > 0.0)) return kInf;
  // S = (a, -b): |S P| = up, |S Q| = uq.
  const double a = (up * up - uq * uq + lq * lq) * (0.5 * per_lq);
  const double bb = up * up - a * a;
  if (!(bb >= 0.0)) return kInf;
  const double b = std::sqrt(bb);
  // S R crosses the line of P Q at x = a + (re - a) b / (b + rm), which must lie on P Q
  // (compared times b + rm > 0).
  const double cross = a * (b + rm) + (re - a) * b;
  if (!(cross >= 0.0 && cross <= lq * (b + rm))) return kInf;
  return std::sqrt((re - a) * (re - a) + (rm + b) * (rm + b));
}

// The face's third corner C = (cx, cy), cy > 0, lit through A B (A at the origin, B at
// (len, 0)) by the source at distances ua from A and ub from B.
inline double source_through_next(double ua, double ub, double len, double cx, double cy) {
  return point_source(ua, len, 1.0 / len, ub, cx, cy);
}

// B = (len, 0) lit through A C (C at (cx, cy), cy > 0, |A C| = la) by the source at distances
// ua from A and uc from C. In the frame of A C (unit e = C / la), B lies at len (ex, ey),
// ey > 0 on the normal's side away from the source.
inline double source_through_after(double ua, double uc, double la, double len, double cx,
                                   double cy) {
  const double per_la = 1.0 / la;
  return point_source(ua, la, per_la, uc, len * (cx * per_la), len * (cy * per_la));
}

// Step 1's graph path (from `source`, each vertex's parent_entry the graph entry of the vertex
// after it towards `target`) straightened into a locally shortest geodesic of its corridor: its
// length (+infinity when the corridor cannot be built). A diagonal entry u -> w names the edge it
// crosses in u's face; the path runs w -> u, so its strip crosses that edge's twin.
double straightened_length(const WindowMesh& wm, int source, int target,
                           const std::vector<int>& parent_entry) {
  const Mesh& mesh = wm.order.mesh;
  const EdgeGraph& graph = wm.graph;
  std::vector<int> vertices{source}, via{-1};
  for (int v = source; v != target;) {
    if (vertices.size() > static_cast<std::size_t>(mesh.num_vertices())) return kInf;
    const int j = parent_entry[v];
    const auto row = std::upper_bound(graph.offsets.begin(), graph.offsets.end(), j);
    const int u = static_cast<int>(row - graph.offsets.begin()) - 1;  // the entry's vertex
    vertices.push_back(u);
    via.push_back(graph.via.empty() || graph.via[j] < 0 ? -1 : mesh.twin(graph.via[j]));
    v = u;
  }
  // The straightening's rounds stop at 100 iterations: any path it leaves is a surface path,
  // hence a valid U (the funnel already gives the shortest path of the corridor).
  GeodesicOptions options;
  options.max_iterations = 100;
  try {
    const SurfacePath strip = strip_from_vertex_path(
        mesh, SurfacePoint::at_vertex(source), vertices, SurfacePoint::at_vertex(target), &via);
    const double length = refine_path(mesh, strip, {}, options).summary.final_length;
    return length > 0.0 ? length : kInf;
  } catch (const Error&) {
    // A corridor the strip code cannot follow (its invariants name it): U stays the graph
    // path's length, and the search runs as A* (nothing it finds depends on this).
    return kInf;
  }
}

}  // namespace

double level_set_distance(const Vec3 corner[3], const double value[3], double r, const Vec3& t) {
  // The points where the level set crosses the edges; through a corner it crosses two edges
  // there (three points, one twice), so the segment is one of the pairs, not always the first.
  Vec3 p[3];
  int n = 0;
  for (int e = 0; e < 3; ++e) {
    const int a = e, z = (e + 1) % 3;
    if ((value[a] - r) * (value[z] - r) > 0.0) continue;
    const double w = value[a] == value[z] ? 0.0 : (r - value[a]) / (value[z] - value[a]);
    p[n++] = corner[a] + w * (corner[z] - corner[a]);
  }
  double dist = kInf;
  for (int i = 0; i < n; ++i) {
    for (int j = i; j < n; ++j) {
      const Vec3 d = p[j] - p[i];
      const double dd = d.squaredNorm();
      const double q = dd > 0.0 ? std::clamp((t - p[i]).dot(d) / dd, 0.0, 1.0) : 0.0;
      dist = std::min(dist, (p[i] + q * d - t).norm());
    }
  }
  return dist;
}

void build_target_bound(const WindowMesh& wm, int source, int target, double upper_bound,
                        const TargetBoundOptions& options, TargetBound* b) {
  const Mesh& mesh = wm.order.mesh;
  const int nv = mesh.num_vertices();
  b->active = false;
  b->upper = upper_bound;
  b->slope = 1.0;
  b->excess = 0.0;
  b->radius = 0.0;
  b->vertices = 0;
  b->faces = 0;
  b->faces_out = 0;
  b->clamped = 0;
  b->local_length = kInf;
  if (source == target) return;
  using State = TargetBound::State;
  if (static_cast<int>(b->state_.size()) != nv) {
    b->state_.assign(nv, State{0u, 0, 0, kInf, kInf, -1.0, 0.0});
    b->parent_entry_.assign(nv, -1);
    b->stamp_ = 0;
  }
  if (++b->stamp_ == 0) {
    for (State& s : b->state_) s.mark = 0u;
    b->stamp_ = 1;
  }
  const unsigned stamp = b->stamp_;
  State* state = b->state_.data();
  const auto touch = [&](int v) -> State& {
    State& s = state[v];
    if (s.mark != stamp) s = State{stamp, 0, 0, kInf, kInf, -1.0, 0.0};
    return s;
  };
  const int* ring_start = wm.ring_start.data();
  const RingCorner* ring = wm.ring.data();
  const EdgeGraph& graph = wm.graph;
  const Vec3 ps = mesh.position(source), pt = mesh.position(target);
  const double chord = (ps - pt).norm();
  // |w s| + |w t| (w touched), computed once per query (the A* of 1 keys by |w s|, the
  // marching of 2 stops at the ellipsoid by the sum).
  const auto foci = [&](State& s, int w) {
    if (s.foci < 0.0) {
      const Vec3& p = mesh.position(w);
      s.to_target = (p - pt).norm();
      s.foci = (p - ps).norm() + s.to_target;
    }
    return s.foci;
  };
  // Both passes keep Dijkstra's order only to within a bucket, a 32nd of the longest edge
  // (geometry/geodesic/bucket_queue.h): neither needs it exact (below), and the windows are the
  // same to within 2e-5 of their number (bench/README.md, session 21).
  auto& queue = b->queue_;
  const double bucket = wm.max_edge > 0.0 ? wm.max_edge / 32.0 : 1.0;

  // 1. U: A* from the target to the source over the vertex graph with diagonals (a mesh edge,
  // or the straight line across the edge between two faces whose unfolding is convex: the
  // straight distance to the source is consistent). Such a path is a surface path, so its
  // length bounds D from above; the diagonals bring it within about a per cent of D (a few per
  // cent along edges alone), which narrows the ellipsoid of 2 and 3 (bench/README.md,
  // session 16). (A vertex closed out of order keeps a path a little longer than its shortest:
  // still a path.)
  queue.reset(bucket);
  touch(target).graph = 0.0;
  queue.push({chord, target});
  double graph_path = kInf;
  while (!queue.empty()) {
    const TargetBound::Item e = queue.pop();
    const int v = e.v;
    State& sv = state[v];
    if (sv.closed) continue;
    sv.closed = 1;
    // The states of the next vertex's neighbours, fetched while this one is expanded (with 2's
    // prefetch, about 1 % less time per path on the benchmark meshes, at the edge of the
    // paired runs' noise: bench/README.md, session 25).
    if (const TargetBound::Item* next = queue.peek()) {
      for (int j = graph.offsets[next->v]; j < graph.offsets[next->v + 1]; ++j)
        __builtin_prefetch(state + graph.neighbors[j]);
    }
    const double gv = sv.graph;
    if (v == source) {
      graph_path = gv;
      break;
    }
    for (int j = graph.offsets[v]; j < graph.offsets[v + 1]; ++j) {
      const int w = graph.neighbors[j];
      State& sw = touch(w);
      const double g = gv + graph.weights[j];
      if (g < sw.graph) {
        sw.graph = g;
        b->parent_entry_[w] = j;
        queue.push({g + (foci(sw, w) - sw.to_target), w});
      }
    }
  }
  if (options.straighten_upper && std::isfinite(graph_path)) {
    const double l = straightened_length(wm, source, target, b->parent_entry_);
    if (l < graph_path) b->local_length = l;
  }
  const double U = std::min({upper_bound, graph_path, b->local_length * (1.0 + 1e-9)});
  b->upper = U;
  if (!std::isfinite(U) ||
      (U < options.min_detour * chord && U < options.min_edges * wm.max_edge))
    return;

  // 3 (its statistics, gathered while 2 runs). L and E over the faces the ellipsoid may meet:
  // every corner of a face that meets it has |y s| + |y t| <= U + 2 (the face's longest edge)
  // (the sum is 2-Lipschitz and every point of the face is within its longest edge of each
  // corner), so a face with a corner beyond does not meet it, and every corner of a face that
  // meets it lies within U + 2 max_edge, hence is reached by 2 (a shortest path's faces join
  // the target's through edges of faces that meet the ellipsoid, or through the vertices it
  // passes). A corner not reached lies on a part of the surface that no such edge joins to the
  // target's: the face is not a shortest path's. Each face is taken when the last of its
  // corners is accepted, its values then final (until session 17 by a pass over the accepted
  // vertices after 2, which read each vertex's state again: a fifth of the bound's time).
  //
  // The steepest faces lie round the target (a cone's apex, which no linear piece follows), so
  // the path's last stretch, inside {psi <= r}, is left out: from x with psi(x) > r, the
  // shortest path first reaches psi = r at a point y of a face that the level set crosses,
  // so d(y, t) >= |y t| >= rho(r), the least distance from t to those level-set segments;
  // before y it crosses only faces with a corner above r. Hence
  //   psi(x) <= r + L (d(x, t) - rho(r)) + E(r),   E(r): the excess of those faces,
  //   h(x) = (psi(x) - r - E(r)) / L + rho(r) <= d(x, t),
  // at every vertex with psi > r (and so along the edges between them). r = 0 is the bound
  // without it (rho(0) = 0); the radii are fractions of U, known before 2 (U is within a few
  // per mille of psi(s)).
  // The limits L tried (16 rather than session 20's 7: 1-2 % fewer windows on the benchmark
  // meshes for 2 % more time in the bound; 21 gained nothing more: bench/README.md, session 21).
  constexpr int kLimits = 16;
  constexpr double kLimit[kLimits] = {1.01, 1.015, 1.02,  1.025, 1.03, 1.035, 1.04, 1.05,
                                      1.06, 1.07,  1.085, 1.1,   1.15, 1.2,   1.3,  1.4};
  constexpr int kRadii = 6;
  const double radius[kRadii] = {0.0, 0.01 * U, 0.02 * U, 0.04 * U, 0.08 * U, 0.16 * U};
  double rho[kRadii] = {0.0, kInf, kInf, kInf, kInf, kInf};
  // steepest[k]: the largest slope of a face with a corner above radius k, gathered per face in
  // the bucket of the last radius below its top and taken downwards after 2. The mild faces
  // (below kLimit[0], most of them) enter as slope^2 = num / den, the largest kept as its pair
  // (compared by cross products: no division or root for them).
  double steepest[kRadii] = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  double mild_num[kRadii] = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  double mild_den[kRadii] = {1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  // How many radii lie below a face's top: a prefix, the radii rising (most faces lie above
  // them all).
  const auto radii_below = [&](double top) {
    if (top > radius[kRadii - 1]) return kRadii;
    int n = 0;
    while (n < kRadii && top > radius[n]) ++n;
    return n;
  };
  auto& steep = b->steep_;
  steep.clear();
  long faces = 0;
  double face_spread = 0.0;
  // The face v, c.next, c.after (v at the origin of c's frame), all accepted.
  const auto face_statistics = [&](int v, const RingCorner& c, const State& sa, const State& sb,
                                   const State& sc) {
    const double longest = std::max({c.len, c.len_after, c.len_across});
    if (std::max({sa.foci, sb.foci, sc.foci}) - 2.0 * longest > U) return;
    ++faces;
    const double u[3] = {sa.value, sb.value, sc.value};
    const double top = std::max({u[0], u[1], u[2]}), low = std::min({u[0], u[1], u[2]});
    face_spread = std::max(face_spread, top - low);
    for (int k = 1; k < kRadii; ++k) {
      const double r = radius[k];
      if (!(low <= r && r <= top)) continue;
      const Vec3 corner[3] = {mesh.position(v), mesh.position(c.next), mesh.position(c.after)};
      const double dist = low == top ? std::min({sa.to_target, sb.to_target, sc.to_target}) -
                                           longest  // (a face level at r)
                                     : level_set_distance(corner, u, r, pt);
      rho[k] = std::min(rho[k], dist);
    }
    const int n = radii_below(top);
    // psi's gradient g in the frame: g . (len, 0) = d1, g . (cx, cy) = d2, so
    // |g|^2 = ((d1 cy)^2 + (d2 len - d1 cx)^2) / (len cy)^2 = num / den. A face below the least
    // limit by more than 1e-9 (far beyond round-off) is mild: it only enters steepest. Any other
    // face takes its slope as before, and so does a face whose den lies outside [1e-140, 1e140]
    // (edges beyond about 1e-35 and 1e35), where den could lose its precision or the cross
    // products below overflow.
    double slope = kInf;
    if (c.cy > 0.0 && c.len > 0.0) {
      const double d1 = u[1] - u[0], d2 = u[2] - u[0];
      const double p = d1 * c.cy, q = d2 * c.len - d1 * c.cx, area = c.len * c.cy;
      const double num = p * p + q * q, den = area * area;
      if (den >= 1e-140 && den <= 1e140 && num <= (1.0 - 1e-9) * kLimit[0] * kLimit[0] * den) {
        if (n > 0 && num * mild_den[n - 1] > mild_num[n - 1] * den) {
          mild_num[n - 1] = num;
          mild_den[n - 1] = den;
        }
        return;
      }
      const double gx = d1 / c.len, gy = (d2 - gx * c.cx) / c.cy;
      slope = std::sqrt(gx * gx + gy * gy);
      if (std::isnan(slope)) slope = kInf;  // (an overflow: taken as the steepest)
    }
    if (n > 0) steepest[n - 1] = std::max(steepest[n - 1], slope);
    if (!(slope <= kLimit[0])) {
      const double near_s =
          std::min({sa.foci - sa.to_target, sb.foci - sb.to_target, sc.foci - sc.to_target}) -
          longest;
      steep.push_back({slope, top - low, top, low, near_s, 0});
    }
  };

  // 2. psi: fast marching from the target over the vertices within U + 2 max_edge of the foci
  // (every corner of a face that the ellipsoid meets: see 3), in Dijkstra's order to within a
  // bucket (a point-source value may fall below the current bucket: the queue takes it there,
  // and psi may be any function for 3). (Until session 16 it reached U + 4 max_edge: the same
  // windows, 2-5 % more time per path.)
  const double reach = U + 2.0 * wm.max_edge;
  const double clamp = options.clamp_slope;
  // The clamp's test of a face: |g|^2 > clamp^2 as in 3 (num > clamp^2 den), with a margin far
  // beyond round-off (a face lowered to the limit tests at it again).
  const double clamp_check = clamp * clamp * (1.0 + 1e-9);
  long clamped = 0;
  // 2's clamp at v, just accepted: with v at the origin of a face's frame and its other corners'
  // values fixed, psi's gradient is affine in v's value x, g = a + x b, and |g| <= clamp on an
  // interval of x (|b|^2 x^2 + 2 (a . b) x + |a|^2 - clamp^2 <= 0). When some face v completes
  // is steeper than the limit (tested first, without divisions: most vertices have none), v's
  // value falls to the least of the intervals' tops if the intervals meet below it; otherwise it
  // stays. Returns whether it fell.
  const auto completes = [&](const RingCorner& c) {
    const State& sb = state[c.next];
    const State& sc = state[c.after];
    return sb.mark == stamp && sb.accepted && sc.mark == stamp && sc.accepted &&
           c.next != target && c.after != target && c.cy > 0.0 && c.len > 0.0;
  };
  const auto clamp_value = [&](int v, State& sv) -> bool {
    const double x = sv.value;
    bool steep_face = false;
    for (int i = ring_start[v]; i < ring_start[v + 1] && !steep_face; ++i) {
      const RingCorner& c = ring[i];
      if (!completes(c)) continue;
      const double d1 = state[c.next].value - x, d2 = state[c.after].value - x;
      const double p = d1 * c.cy, q = d2 * c.len - d1 * c.cx, area = c.len * c.cy;
      steep_face = p * p + q * q > clamp_check * (area * area);
    }
    if (!steep_face) return false;
    double lo = -kInf, hi = kInf;
    for (int i = ring_start[v]; i < ring_start[v + 1]; ++i) {
      const RingCorner& c = ring[i];
      if (!completes(c)) continue;
      const double ax = state[c.next].value / c.len, ay = (state[c.after].value - ax * c.cx) / c.cy;
      const double bx = -1.0 / c.len, by = (c.cx / c.len - 1.0) / c.cy;
      const double bb = bx * bx + by * by, ab = ax * bx + ay * by, aa = ax * ax + ay * ay;
      const double disc = ab * ab - bb * (aa - clamp * clamp);
      if (!(disc >= 0.0 && bb > 0.0)) return false;  // no value of v's makes it mild
      const double root = std::sqrt(disc);
      lo = std::max(lo, (-ab - root) / bb);
      hi = std::min(hi, (-ab + root) / bb);
    }
    if (!(hi < x && lo <= hi && std::isfinite(hi))) return false;
    sv.value = hi;
    return true;
  };
  queue.reset(bucket);
  auto& order = b->order_;
  order.clear();
  state[target].value = 0.0;
  state[target].foci = chord;
  state[target].to_target = 0.0;
  queue.push({0.0, target});
  while (!queue.empty()) {
    const TargetBound::Item e = queue.pop();
    const int v = e.v;
    State& sv = state[v];
    if (sv.accepted) continue;
    sv.accepted = 1;
    order.push_back(v);
    // The next vertex's faces (a few cache lines: the first reading of a vertex's ring was the
    // marching's costliest load), fetched while this one is marched: every 64-byte line the
    // ring touches, from the line its first byte lies in.
    if (const TargetBound::Item* next = queue.peek()) {
      const std::uintptr_t end = reinterpret_cast<std::uintptr_t>(ring + ring_start[next->v + 1]);
      for (std::uintptr_t line = reinterpret_cast<std::uintptr_t>(ring + ring_start[next->v]) &
                                 ~std::uintptr_t{63};
           line < end; line += 64)
        __builtin_prefetch(reinterpret_cast<const void*>(line));
    }
    if (clamp > 0.0 && v != target) clamped += clamp_value(v, sv);
    const double uv = sv.value;
    for (int i = ring_start[v]; i < ring_start[v + 1]; ++i) {
      // v at the origin, B = next at (len, 0), C = after at (cx, cy).
      const RingCorner& c = ring[i];
      State& sb = touch(c.next);
      State& sc = touch(c.after);
      if (sb.accepted && sc.accepted) {
        face_statistics(v, c, sv, sb, sc);
        continue;
      }
      const bool b_open = !sb.accepted && foci(sb, c.next) <= reach;
      const bool c_open = !sc.accepted && foci(sc, c.after) <= reach;
      if (!b_open && !c_open) continue;
      const auto offer = [&](State& s, int w, double u) {
        if (u < s.value) {
          if (s.value == kInf) __builtin_prefetch(ring + ring_start[w]);
          s.value = u;
          queue.push({u, w});
        }
      };
      if (b_open) offer(sb, c.next, uv + c.len);
      if (c_open) offer(sc, c.after, uv + c.len_after);
      if (!(c.cy > 0.0 && c.len > 0.0 && c.len_after > 0.0)) continue;
      if (c_open && sb.accepted)
        offer(sc, c.after, source_through_next(uv, sb.value, c.len, c.cx, c.cy));
      if (b_open && sc.accepted)
        offer(sb, c.next, source_through_after(uv, sc.value, c.len_after, c.len, c.cx, c.cy));
    }
  }
  for (int k = kRadii - 1; k >= 0; --k) {
    steepest[k] = std::max(steepest[k], std::sqrt(mild_num[k] / mild_den[k]));
    if (k + 1 < kRadii) steepest[k] = std::max(steepest[k], steepest[k + 1]);
  }
  b->vertices = static_cast<long>(order.size());
  b->clamped = clamped;
  if (!(state[source].mark == stamp && state[source].accepted)) return;
  const double us = state[source].value;
  b->faces = faces;
  // The (r, L) that makes the bound largest halfway, at psi = psi(s) / 2, with its rho and E,
  // over the steep faces not ruled out (Steep::out). Every (r, L) gives a bound; halfway is
  // where the band of windows A* must look at is widest (chosen at psi(s), the bound had 7 %
  // more windows on the bunnies: bench/README.md, session 16).
  double best = -kInf, R = 0.0, L = 1.0, E = 0.0, rho_r = 0.0, L_raw = kInf;
  // A steep face's excess over the limit L (3): spread (1 - L / g); all its spread when g
  // overflowed.
  const auto face_excess = [](const TargetBound::Steep& f, double limit) {
    return std::isfinite(f.slope) ? f.spread * (1.0 - limit / f.slope) : f.spread;
  };
  // Each face's sums are gathered in one pass: a face counts for the radii below its top (the
  // first few, the radii rising), so it is added to the bucket of the last of them and the
  // buckets are summed downwards; its excess over each limit is computed once per pass (it
  // was once per radius).
  const auto choose = [&]() {
    best = -kInf;
    double excess[kRadii][kLimits] = {};
    double steepest_in[kRadii];
    std::fill(steepest_in, steepest_in + kRadii, kLimit[0]);
    for (const TargetBound::Steep& f : steep) {
      if (f.out) continue;
      const int n = radii_below(f.top);
      if (n == 0) continue;
      steepest_in[n - 1] = std::max(steepest_in[n - 1], f.slope);
      for (int l = 0; l < kLimits && f.slope > kLimit[l]; ++l)
        excess[n - 1][l] += face_excess(f, kLimit[l]);
    }
    for (int k = kRadii - 2; k >= 0; --k) {
      steepest_in[k] = std::max(steepest_in[k], steepest_in[k + 1]);
      for (int l = 0; l < kLimits; ++l) excess[k][l] += excess[k + 1][l];
    }
    // The excess that step 6 leaves at psi = psi(s) / 2 (the faces whose least corner is
    // below halfway + spread + E): the halfway bound as built (chosen by the whole E, 1.3 %
    // more windows at 100K and on the kitten: bench/README.md, session 20).
    // excess[k][l] falls as k rises, so the radii whose threshold a face's least corner is
    // under are a prefix of those below its top: the face goes to the bucket of the last of
    // them, and the buckets are summed downwards (as above).
    double threshold[kLimits][kRadii];
    for (int l = 0; l < kLimits; ++l) {
      for (int k = 0; k < kRadii; ++k) threshold[l][k] = 0.5 * us + face_spread + excess[k][l];
    }
    double excess_half[kRadii][kLimits] = {};
    for (const TargetBound::Steep& f : steep) {
      if (f.out) continue;
      const int n = radii_below(f.top);
      for (int l = 0; l < kLimits && f.slope > kLimit[l]; ++l) {
        int m = 0;
        while (m < n && f.low <= threshold[l][m]) ++m;
        if (m > 0) excess_half[m - 1][l] += face_excess(f, kLimit[l]);
      }
    }
    for (int k = kRadii - 2; k >= 0; --k) {
      for (int l = 0; l < kLimits; ++l) excess_half[k][l] += excess_half[k + 1][l];
    }
    for (int k = 0; k < kRadii; ++k) {
      if (!(radius[k] < us) || !std::isfinite(rho[k])) continue;
      // (Every face steeper than kLimit[0] is in `steep`: with none ruled out this is
      // steepest[k].)
      const double steepest_k = std::min(steepest[k], steepest_in[k]);
      const auto consider = [&](double limit, double e, double e_half) {
        if (!std::isfinite(limit)) return;
        const double raw = e > 0.0 ? limit : kInf;  // (step 6's faces: steeper than this)
        // Margins for round-off (1e-9 relative: far below what moves a window, far above the
        // slopes' own error).
        limit *= 1.0 + 1e-9;
        e = e * (1.0 + 1e-9) + 1e-12 * us;
        e_half = e_half * (1.0 + 1e-9) + 1e-12 * us;
        const double rh = std::max(0.0, rho[k] * (1.0 - 1e-12));
        const double halfway = (0.5 * us - radius[k] - e_half) / limit + rh;
        if (halfway > best) {
          best = halfway;
          R = radius[k];
          L = limit;
          E = e;
          rho_r = rh;
          L_raw = raw;
        }
      };
      consider(steepest_k, 0.0, 0.0);
      for (int l = 0; l < kLimits; ++l) {
        if (kLimit[l] < steepest_k) consider(kLimit[l], excess[k][l], excess_half[k][l]);
      }
    }
  };
  // 5. A steep face each of whose points y has |y s| + h(y) > U meets no shortest path from s
  // to t (at a point y of one, h(y) <= d(y, t) by 3 and 4, so |y s| + h(y) <= d(s, y) +
  // d(y, t) = D <= U). The bound at a point x of such a path needs only the faces that the
  // path's tail from x to t crosses, so L and E are chosen again without those faces. Over a
  // face, |y s| >= (its corners' least |v s|) - (its longest edge), and h, linear there, is
  // least at a corner (-infinity: a corner with psi <= r, the face kept).
  choose();
  if (best > -kInf) {
    long out = 0;
    for (TargetBound::Steep& f : steep) {
      const double h_low = R == 0.0 || f.low > R ? (f.low - R - E) / L + rho_r : -kInf;
      f.out = f.near_s + h_low > U;
      out += f.out;
    }
    if (out > 0) choose();
    b->faces_out = out;
  }
  if (!(best > -kInf && (us - R - E) / L + rho_r > 0.0)) return;
  // 6. E by level (the header's proof): each vertex takes E(psi + spread + E), spread the
  // largest psi range of a face that entered 3, so h stays linear along every edge a shortest
  // path crosses; each face is counted one level early (round-off in the level's index).
  auto& by_level = b->by_level_;
  by_level.clear();
  b->level_width_ = 0.0;
  double top_value = 0.0;
  for (const int v : order) top_value = std::max(top_value, state[v].value);
  constexpr int kLevels = 256;
  const double shift = face_spread + E;
  const double width = (top_value + shift) / kLevels;
  if (std::isfinite(L_raw) && width > 0.0) {
    by_level.assign(kLevels, 0.0);
    for (const TargetBound::Steep& f : steep) {
      if (!(f.top > R) || f.out || !(f.slope > L_raw)) continue;
      const int level = std::clamp(static_cast<int>(std::floor(f.low / width)) - 1, 0, kLevels - 1);
      by_level[level] += face_excess(f, L_raw);
    }
    for (int i = 1; i < kLevels; ++i) by_level[i] += by_level[i - 1];
    for (double& e : by_level) e = std::min(E, e * (1.0 + 1e-9) + 1e-12 * us);
    b->level_width_ = width;
  }
  // (Products by the reciprocals, not divisions: L carries a margin of 1e-9, and each face is
  // counted a level early, far beyond the reciprocals' round-off.)
  const double per_width = width > 0.0 ? 1.0 / width : 0.0, per_limit = 1.0 / L;
  for (const int v : order) {
    State& sv = state[v];
    if (!(R == 0.0 || sv.value > R)) {
      sv.value = -kInf;
      continue;
    }
    double e = E;
    if (!by_level.empty()) {
      const double level = std::floor((sv.value + shift) * per_width);
      e = level < kLevels ? by_level[static_cast<int>(level)] : E;
    }
    sv.value = (sv.value - R - e) * per_limit + rho_r;
  }
  b->slope = L;
  b->excess = E;
  b->radius = R;
  b->active = true;
}

}  // namespace windplan
