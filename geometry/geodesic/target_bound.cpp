// The A* lower bound of geometry/geodesic/target_bound.h: why each step is as it is.
#include "geometry/geodesic/target_bound.h"

#include <algorithm>
#include <cmath>

#include "geometry/geodesic/geodesic_windows.h"

namespace windplan {

bool TargetBoundOptions::is_valid(std::string* why) const {
  if (!(min_detour >= 1.0)) {
    if (why) *why = "min_detour must be >= 1 (dimensionless; 1: always build the bound)";
    return false;
  }
  return true;
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The plane wave through corners P (at the origin, value up) and Q (value uq), of slope 1,
// moving towards the side of R; its value at R, or +infinity when the wave does not reach R
// from inside the segment P Q (its characteristic through R misses the segment) or cannot
// have slope 1 (|uq - up| >= |PQ|).
double plane_wave(double up, double qx, double qy, double lq, double uq, double rx, double ry) {
  const double np = (uq - up) / lq;
  if (!(std::abs(np) < 1.0)) return kInf;
  const double nq = std::sqrt(1.0 - np * np);
  const double ex = qx / lq, ey = qy / lq;
  // The unit normal of P Q towards R.
  double mx = -ey, my = ex;
  if (mx * rx + my * ry < 0.0) {
    mx = -mx;
    my = -my;
  }
  const double nx = np * ex + nq * mx, ny = np * ey + nq * my;
  // R - tau n = sigma Q: sigma = cross(R, n) / cross(Q, n).
  const double den = qx * ny - qy * nx;
  if (den == 0.0) return kInf;
  const double sigma = (rx * ny - ry * nx) / den;
  if (!(sigma >= 0.0 && sigma <= 1.0)) return kInf;
  return up + nx * rx + ny * ry;
}

}  // namespace

void build_target_bound(const WindowMesh& wm, int source, int target, double upper_bound,
                        const TargetBoundOptions& options, TargetBound* b) {
  const Mesh& mesh = wm.order.mesh;
  const int nv = mesh.num_vertices();
  b->active = false;
  b->upper = upper_bound;
  b->slope = 1.0;
  b->excess = 0.0;
  b->vertices = 0;
  b->faces = 0;
  if (source == target) return;
  using State = TargetBound::State;
  if (static_cast<int>(b->state_.size()) != nv) {
    b->state_.assign(nv, State{0u, 0, 0, kInf, kInf, -1.0});
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
    if (s.mark != stamp) s = State{stamp, 0, 0, kInf, kInf, -1.0};
    return s;
  };
  const int* ring_start = wm.ring_start.data();
  const RingCorner* ring = wm.ring.data();
  const Vec3 ps = mesh.position(source), pt = mesh.position(target);
  const double chord = (ps - pt).norm();
  auto& queue = b->queue_;

  // 1. U: A* over the vertex graph from the target to the source (the straight distance to the
  // source is consistent). An edge path is a surface path, so its length bounds D from above.
  // (Every edge is seen from both of its faces: twice, harmlessly.)
  queue.clear();
  touch(target).graph = 0.0;
  queue.push({chord, target});
  double edge_path = kInf;
  while (!queue.empty()) {
    const TargetBound::Item e = queue.pop();
    const int v = e.v;
    State& sv = state[v];
    if (sv.closed) continue;
    sv.closed = 1;
    const double gv = sv.graph;
    if (v == source) {
      edge_path = gv;
      break;
    }
    for (int i = ring_start[v]; i < ring_start[v + 1]; ++i) {
      const RingCorner& c = ring[i];
      for (const auto& [w, len] : {std::pair<int, double>{c.next, c.len},
                                   std::pair<int, double>{c.after, c.len_after}}) {
        State& sw = touch(w);
        const double g = gv + len;
        if (g < sw.graph) {
          sw.graph = g;
          queue.push({g + (mesh.position(w) - ps).norm(), w});
        }
      }
    }
  }
  const double U = std::min(upper_bound, edge_path);
  b->upper = U;
  if (!std::isfinite(U) || U < options.min_detour * chord) return;

  // 2. psi: fast marching from the target over the vertices within U + 4 max_edge of the foci
  // (every corner of a face that the ellipsoid meets: see 3), in Dijkstra's order.
  const double reach = U + 4.0 * wm.max_edge;
  // |w s| + |w t| (w touched), computed once per query.
  const auto foci = [&](State& s, int w) {
    if (s.foci < 0.0) {
      const Vec3& p = mesh.position(w);
      s.foci = (p - ps).norm() + (p - pt).norm();
    }
    return s.foci;
  };
  queue.clear();
  auto& order = b->order_;
  order.clear();
  state[target].value = 0.0;
  state[target].foci = chord;
  queue.push({0.0, target});
  while (!queue.empty()) {
    const TargetBound::Item e = queue.pop();
    const int v = e.v;
    State& sv = state[v];
    if (sv.accepted) continue;
    sv.accepted = 1;
    order.push_back(v);
    const double uv = sv.value;
    for (int i = ring_start[v]; i < ring_start[v + 1]; ++i) {
      // v at the origin, B = next at (len, 0), C = after at (cx, cy).
      const RingCorner& c = ring[i];
      State& sb = touch(c.next);
      State& sc = touch(c.after);
      const bool b_open = !sb.accepted && foci(sb, c.next) <= reach;
      const bool c_open = !sc.accepted && foci(sc, c.after) <= reach;
      if (!b_open && !c_open) continue;
      const auto offer = [&](State& s, int w, double u) {
        if (u < s.value) {
          s.value = u;
          queue.push({u, w});
        }
      };
      if (b_open) offer(sb, c.next, uv + c.len);
      if (c_open) offer(sc, c.after, uv + c.len_after);
      if (!(c.cy > 0.0 && c.len > 0.0 && c.len_after > 0.0)) continue;
      if (c_open && sb.accepted)
        offer(sc, c.after, plane_wave(uv, c.len, 0.0, c.len, sb.value, c.cx, c.cy));
      if (b_open && sc.accepted)
        offer(sb, c.next, plane_wave(uv, c.cx, c.cy, c.len_after, sc.value, c.len, 0.0));
    }
  }
  b->vertices = static_cast<long>(order.size());
  if (!(state[source].mark == stamp && state[source].accepted)) return;

  // 3. L and E over the faces the ellipsoid may meet: a face whose corners' |y s| + |y t| all
  // exceed U + 2 (its longest edge) does not meet it (the sum is 2-Lipschitz and every point
  // of the face is within its longest edge of a corner), and every corner of a face that
  // meets it lies within U + 4 max_edge, hence was reached by 2 (a shortest path's faces join
  // the target's through edges of faces that meet the ellipsoid, or through the vertices it
  // passes). A corner not reached lies on a part of the surface that no such edge joins to
  // the target's: the face is not a shortest path's. Each face is taken at its least corner.
  constexpr int kLimits = 7;
  constexpr double kLimit[kLimits] = {1.01, 1.02, 1.03, 1.05, 1.1, 1.2, 1.4};
  auto& steep = b->steep_;
  steep.clear();
  double steepest = 1.0;
  long faces = 0;
  for (const int v : order) {
    const double ua = state[v].value;
    const double fa = state[v].foci;
    for (int i = ring_start[v]; i < ring_start[v + 1]; ++i) {
      const RingCorner& c = ring[i];
      if (c.next < v || c.after < v) continue;
      const State& sb = state[c.next];
      const State& sc = state[c.after];
      if (!(sb.mark == stamp && sb.accepted && sc.mark == stamp && sc.accepted)) continue;
      const double len_bc = std::sqrt((c.len - c.cx) * (c.len - c.cx) + c.cy * c.cy);
      const double longest = std::max({c.len, c.len_after, len_bc});
      if (std::min({fa, sb.foci, sc.foci}) - 2.0 * longest > U) continue;
      ++faces;
      const double ub = sb.value, uc = sc.value;
      double slope = kInf;
      if (c.cy > 0.0 && c.len > 0.0) {
        const double gx = (ub - ua) / c.len, gy = ((uc - ua) - gx * c.cx) / c.cy;
        slope = std::sqrt(gx * gx + gy * gy);
      }
      steepest = std::max(steepest, slope);
      if (!(slope <= kLimit[0])) {
        const double spread = std::max({ua, ub, uc}) - std::min({ua, ub, uc});
        steep.push_back({v, c.next, c.after, slope, spread, longest});
      }
    }
  }
  b->faces = faces;
  const double us = state[source].value;
  // The (L, E) that makes the source's bound largest, E summed over the steep faces that
  // `counts`.
  const auto choose = [&](auto&& counts, double* L, double* E) {
    double excess[kLimits] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    for (const TargetBound::Steep& f : steep) {
      if (!counts(f)) continue;
      for (int k = 0; k < kLimits; ++k) {
        if (f.slope > kLimit[k])
          excess[k] += std::isfinite(f.slope) ? f.spread * (1.0 - kLimit[k] / f.slope) : f.spread;
      }
    }
    *L = steepest;
    *E = 0.0;
    for (int k = 0; k < kLimits; ++k) {
      if (!(kLimit[k] < steepest)) break;
      if ((us - excess[k]) / kLimit[k] > (us - *E) / *L) {
        *L = kLimit[k];
        *E = excess[k];
      }
    }
    // Margins for round-off (1e-9 relative: far below what moves a window, far above the
    // slopes' own error).
    *L *= 1.0 + 1e-9;
    *E = *E * (1.0 + 1e-9) + 1e-12 * us;
  };
  double L = 1.0, E = 0.0;
  choose([](const TargetBound::Steep&) { return true; }, &L, &E);
  if (!std::isfinite(L) || !((us - E) / L > 0.0)) return;
  // 4. Once more over a thinner region: h0 = (psi - E) / L bounds d(y, t) on a shortest path,
  // so its points have |y s| + h0(y) <= D <= U. On a face, |y s| is 1-Lipschitz and h0
  // (slope / L)-Lipschitz: a face whose corners all have |v s| + h0(v) > U + (1 + slope / L)
  // (its longest edge) holds no such point, and its excess does not count.
  const auto h0_plus_s = [&](int v) {
    return (mesh.position(v) - ps).norm() + (state[v].value - E) / L;
  };
  const double L0 = L;
  choose(
      [&](const TargetBound::Steep& f) {
        const double least = std::min({h0_plus_s(f.a), h0_plus_s(f.b), h0_plus_s(f.c)});
        return !(least - (1.0 + f.slope / L0) * f.longest > U);
      },
      &L, &E);
  if (!std::isfinite(L) || !((us - E) / L > 0.0)) return;
  for (const int v : order) state[v].value = (state[v].value - E) / L;
  b->slope = L;
  b->excess = E;
  b->active = true;
}

}  // namespace windplan
