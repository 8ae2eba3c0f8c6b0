// The refinement's funnel (geometry/geodesic/refiner.h): exact paths in a strip, rounds, loops.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "geometry/base/errors.h"
#include "geometry/geodesic/refiner.h"

namespace windplan {
namespace refine_detail {

void Refiner::funnel_straighten(int lo, int hi, int start_vertex, int end_vertex) {
  if ((path_.closed && !loop_anchor_) || lo >= hi) return;
  const int n = hi - lo;  // portals lo..hi-1
  // Unfold the window's strip: portal t runs from R[t] (from(h)) to L[t] (to(h)); the face after
  // it is placed from the portal by place_across with the crossing's cached coefficients
  // (member buffers: this runs every round).
  std::vector<Vec2>& L = unfold_L_;
  std::vector<Vec2>& R = unfold_R_;
  std::vector<int>& Lv = unfold_Lv_;
  std::vector<int>& Rv = unfold_Rv_;
  L.resize(n + 1);
  R.resize(n + 1);
  Lv.resize(n + 1);
  Rv.resize(n + 1);
  const int h0 = path_.halfedges[lo];
  const int f0 = mesh_.face(h0);
  // The current face's corners and their placement (f0 first, then the face after each portal).
  Vec2 pos[3];
  int ids[3];
  {
    const int a = mesh_.from(h0), b = mesh_.to(h0), c = mesh_.to(mesh_.next(h0));
    const Vec3 &A = mesh_.position(a), &B = mesh_.position(b), &C = mesh_.position(c);
    ids[0] = a;
    ids[1] = b;
    ids[2] = c;
    pos[0] = Vec2(0, 0);
    pos[1] = Vec2((B - A).norm(), 0);
    pos[2] = place_third(pos[0], pos[1], (C - A).norm(), (C - B).norm(), true);
  }
  auto local = [&](int v) {
    for (int q = 0; q < 3; ++q)
      if (ids[q] == v) return pos[q];
    return Vec2(NAN, NAN);
  };
  // A loop's anchor: crossing 0, on an edge of the faces before portal 1 and after k-1.
  auto anchor = [&]() -> Vec2 {
    const int ha = path_.halfedges[0];
    return (1.0 - lambda_[0]) * local(mesh_.from(ha)) + lambda_[0] * local(mesh_.to(ha));
  };
  // Start point in f0's placement: the path's start, a vertex of f0, or the loop's anchor.
  Vec2 s2 = Vec2::Zero();
  if (start_vertex >= 0) {
    s2 = local(start_vertex);
  } else if (loop_anchor_) {
    s2 = anchor();
  } else {
    const Vec3 bs = barycentric_in_face(mesh_, f0, path_.start);
    for (int q = 0; q < 3; ++q) s2 += bs[q] * local(mesh_.triangle(f0)[q]);
  }
  // Portal 0's corners come from f0's placement; each next portal is an edge of the face after
  // the current one (b -> a -> d, d placed across the portal a -> b): either a -> d or d -> b.
  Rv[0] = mesh_.from(h0);
  Lv[0] = mesh_.to(h0);
  R[0] = local(Rv[0]);
  L[0] = local(Lv[0]);
  for (int t = 0; t < n; ++t) {
    // Portal t is h = halfedges[lo + t] from a = from(h) to b = to(h), b on the left of the travel.
    const int a = Rv[t], b = Lv[t];
    const Across& x = across_[lo + t];
    const int tw = x.twin, d = x.d;
    const Vec2 pd = place_across(R[t], L[t], x.uw);
    if (t + 1 < n) {
      const int hn = path_.halfedges[lo + t + 1];
      if (hn == mesh_.next(tw)) {  // a -> d
        Rv[t + 1] = a;
        R[t + 1] = R[t];
        Lv[t + 1] = d;
        L[t + 1] = pd;
      } else if (hn == mesh_.prev(tw)) {  // d -> b
        Rv[t + 1] = d;
        R[t + 1] = pd;
        Lv[t + 1] = b;
        L[t + 1] = L[t];
      } else {  // back through the same edge (b -> a): a strip that folds back
        Rv[t + 1] = b;
        R[t + 1] = L[t];
        Lv[t + 1] = a;
        L[t + 1] = R[t];
      }
    } else {
      ids[0] = a;
      pos[0] = R[t];
      ids[1] = b;
      pos[1] = L[t];
      ids[2] = d;
      pos[2] = pd;
    }
  }
  Vec2 t2 = Vec2::Zero();
  if (end_vertex >= 0) {
    t2 = local(end_vertex);
  } else if (loop_anchor_) {
    t2 = anchor();
  } else {
    const int fk = mesh_.face(mesh_.twin(path_.halfedges[hi - 1]));
    const Vec3 bt = barycentric_in_face(mesh_, fk, path_.end);
    for (int q = 0; q < 3; ++q) t2 += bt[q] * local(mesh_.triangle(fk)[q]);
  }
  L[n] = R[n] = t2;
  Lv[n] = Rv[n] = -1;

  // Simple stupid funnel (Mononen): corners of the shortest path with their portal indices.
  std::vector<Vec2>& corner = corner_;
  std::vector<int>& corner_portal = corner_portal_;
  std::vector<int>& corner_vertex = corner_vertex_;
  corner.assign(1, s2);
  corner_portal.assign(1, -1);
  corner_vertex.assign(1, -1);
  Vec2 apex = s2, left = L[0], right = R[0];
  int apex_i = -1, left_i = 0, right_i = 0;
  const double eps = 1e-14 * scale_ * scale_;
  for (int i = 1; i <= n; ++i) {
    const Vec2 &nl = L[i], &nr = R[i];
    // Tighten the right side.
    if (cross2(right - apex, nr - apex) >= -eps) {
      if ((apex - right).squaredNorm() == 0.0 || cross2(nr - apex, left - apex) > eps) {
        right = nr;
        right_i = i;
      } else {
        corner.push_back(left);
        corner_portal.push_back(left_i);
        corner_vertex.push_back(Lv[left_i]);
        apex = left;
        apex_i = left_i;
        left = right = apex;
        left_i = right_i = apex_i;
        i = apex_i;
        continue;
      }
    }
    // Tighten the left side.
    if (cross2(nl - apex, left - apex) >= -eps) {
      if ((apex - left).squaredNorm() == 0.0 || cross2(right - apex, nl - apex) > eps) {
        left = nl;
        left_i = i;
      } else {
        corner.push_back(right);
        corner_portal.push_back(right_i);
        corner_vertex.push_back(Rv[right_i]);
        apex = right;
        apex_i = right_i;
        left = right = apex;
        left_i = right_i = apex_i;
        i = apex_i;
        continue;
      }
    }
  }
  corner.push_back(t2);
  corner_portal.push_back(n);
  corner_vertex.push_back(-1);

  // Crossing parameters: portal t is cut by the corner segment that spans it.
  std::size_t m = 0;
  for (int t = 0; t < n; ++t) {
    while (m + 1 < corner.size() && corner_portal[m + 1] < t) ++m;
    const int h = path_.halfedges[lo + t];
    double& lam = lambda_[lo + t];
    if (corner_portal[m + 1] == t && corner_vertex[m + 1] >= 0) {
      lam = corner_vertex[m + 1] == mesh_.from(h) ? 0.0 : 1.0;
      continue;
    }
    const Vec2 a = corner[m], b = corner[m + 1];
    const Vec2 e = L[t] - R[t];  // from(h) -> to(h)
    const double den = cross2(b - a, e);
    double l = den != 0.0 ? cross2(b - a, a - R[t]) / den : 0.5;
    if (corner_vertex[m] >= 0) {
      if (corner_vertex[m] == mesh_.from(h)) l = std::min(l, 1.0) * (l > 1e-12);
    }
    lam = std::clamp(l, 0.0, 1.0);
    if (lam < 1e-13) lam = 0.0;
    if (lam > 1.0 - 1e-13) lam = 1.0;
  }
}

void Refiner::funnel_rounds() {
  if (path_.closed) return;
  // Each round: the shortest path in the strip, then every vertex it wraps is tested with the
  // angle rule; all reroutes of a round are spliced into the strip in one pass. A full round
  // straightens the whole strip; after a splice only windows do: the stretch between the vertex
  // passages (anchors) around each rerouted run, straightened with the anchors held. When the
  // windows bring no more reroutes, a full round checks the whole strip again (anchors may let
  // go), and the rounds end only after a full round without a reroute: the result is the exact
  // shortest path of the final strip, as before, at a fraction of the unfolding work.
  struct Splice {
    int i, j;
    std::vector<int> hs;
  };
  struct Window {
    int lo, hi, start_vertex, end_vertex;
  };
  std::vector<Splice> splices;
  std::vector<Window> windows;
  std::vector<std::pair<int, int>> ranges;  // crossings first..last to test in a round
  const double eps_d = 1e-12 * scale_;
  auto vertex_at = [&](int i) {
    const double l = lambda_[i];
    const int h = path_.halfedges[i];
    return l <= 0.0 ? mesh_.from(h) : l >= 1.0 ? mesh_.to(h) : -1;
  };
  bool full = true;
  for (int round = 0; round < 100000; ++round) {
    if (full) {
      funnel_straighten(0, k_, -1, -1);
    } else {
      for (const Window& w : windows) funnel_straighten(w.lo, w.hi, w.start_vertex, w.end_vertex);
    }
    splices.clear();
    bool collapsed = false;
    // What to test: the whole path after a full straightening; after windows only the windows
    // with their anchor runs (elsewhere the path and its vertex passages are as they were when
    // the last scan found nothing to reroute there).
    ranges.clear();
    if (full) {
      ranges.emplace_back(0, k_ - 1);
    } else {
      for (const Window& w : windows) {
        int first = w.lo;
        if (w.lo > 0 && w.start_vertex >= 0) {
          first = w.lo - 1;
          while (first > 0 && vertex_at(first - 1) == w.start_vertex) --first;
        }
        ranges.emplace_back(first, std::min(w.hi, k_ - 1));
      }
    }
    // One pass over the ranges in order (they may share an anchor run: each run is tested once).
    std::size_t r = 0;
    for (int i = ranges.empty() ? 0 : ranges[0].first; r < ranges.size();) {
      if (i > ranges[r].second) {
        if (++r < ranges.size()) i = std::max(i, ranges[r].first);
        continue;
      }
      const int v = vertex_at(i);
      if (v < 0) {
        ++i;
        continue;
      }
      int j = i;
      while (j + 1 < k_ &&
             (mesh_.from(path_.halfedges[j + 1]) == v || mesh_.to(path_.halfedges[j + 1]) == v))
        ++j;
      const Vec3& pv = mesh_.position(v);
      const Vec3 P = i > 0 ? point(i - 1, lambda_) : ps_;
      const Vec3 Q = j + 1 < k_ ? point(j + 1, lambda_) : pt_;
      if ((P - pv).norm() <= eps_d || (Q - pv).norm() <= eps_d) {
        // The path starts or ends at v (or a neighbouring crossing sits on it): the general
        // handler drops the crossings around an endpoint at v; anything else stays pinned.
        // A change of the strip there (a collapse or a reroute) shifts the indices: the round
        // starts again. A pinned run is passed over, and so is a lift (the next straightening
        // places those crossings anyway; restarting on it made rounds spin).
        int rs = i, rl = 1;
        const Action a = handle_vertex(i, v, false, &rs, &rl);
        if (a == Action::Collapsed || a == Action::Rerouted || a == Action::Rotated) {
          collapsed = true;
          break;
        }
        i = j + 1;
        continue;
      }
      if (mesh_.is_boundary_vertex(v)) {  // no other side to reroute to
        i = j + 1;
        continue;
      }
      std::vector<int>& run = scan_run_;
      run.resize(j - i + 1);
      for (int q = i; q <= j; ++q) run[q - i] = q;
      double theta = 0.0;
      fan_lift(run, v, P, Q, false, &theta);
      const double other = cone_angle(v) - theta;
      if (theta >= M_PI && other < M_PI - 1e-12) {
        std::vector<int> hs;
        if (other_side_fan(i, j, v, &hs)) splices.push_back({i, j, std::move(hs)});
      }
      i = j + 1;
    }
    if (collapsed) {  // the path changed under the scan: straighten it all again
      full = true;
      continue;
    }
    if (splices.empty()) {
      if (full) break;
      full = true;
      continue;
    }
    // Splice every reroute in one pass, keeping the new index range of each rerouted run; the
    // strip data (a_, d_) of the kept crossings move with them.
    std::vector<int>& nh = splice_h_;
    std::vector<double>& nl = splice_l_;
    std::vector<Vec3>& na = splice_a_;
    std::vector<Vec3>& nd = splice_d_;
    std::vector<Across>& nx = splice_x_;
    nh.clear();
    nl.clear();
    na.clear();
    nd.clear();
    nx.clear();
    std::vector<std::pair<int, int>> spliced;
    // A crossing followed by its own twin (the strip enters a face and leaves it through the
    // same edge) is a fold: both are dropped (the funnel would only pin the path to a corner).
    auto pop = [&]() {
      nh.pop_back();
      nl.pop_back();
      na.pop_back();
      nd.pop_back();
      nx.pop_back();
    };
    auto push = [&](int h, double l, const Vec3& a, const Vec3& d) {
      const Across x = across(h);
      if (!nh.empty() && nh.back() == x.twin) {
        pop();
        return;
      }
      nh.push_back(h);
      nl.push_back(l);
      na.push_back(a);
      nd.push_back(d);
      nx.push_back(x);
    };
    // Kept crossings lo..hi-1: a fold can only form where the range meets what came before;
    // the rest is copied as a block.
    auto keep = [&](int lo, int hi) {
      for (; lo < hi && !nh.empty() && nh.back() == across_[lo].twin; ++lo) pop();
      if (lo >= hi) return;
      nh.insert(nh.end(), path_.halfedges.begin() + lo, path_.halfedges.begin() + hi);
      nl.insert(nl.end(), lambda_.begin() + lo, lambda_.begin() + hi);
      na.insert(na.end(), a_.begin() + lo, a_.begin() + hi);
      nd.insert(nd.end(), d_.begin() + lo, d_.begin() + hi);
      nx.insert(nx.end(), across_.begin() + lo, across_.begin() + hi);
    };
    const int first_face = mesh_.face(path_.halfedges[0]);
    int next = 0;
    for (const Splice& s : splices) {
      keep(next, s.i);
      const int first = static_cast<int>(nh.size());
      for (int c : s.hs) {
        const Vec3& a = mesh_.position(mesh_.from(c));
        push(c, 0.5, a, mesh_.position(mesh_.to(c)) - a);
      }
      spliced.emplace_back(first, static_cast<int>(nh.size()) - 1);
      next = s.j + 1;
      ++reroutes_;
    }
    keep(next, k_);
    const int size = static_cast<int>(nh.size());
    for (auto& [a, b] : spliced) {  // folds may have dropped crossings of a spliced run
      a = std::min(a, size);
      b = std::min(b, size - 1);
    }
    path_.halfedges.swap(nh);
    lambda_.swap(nl);
    a_.swap(na);
    d_.swap(nd);
    across_.swap(nx);
    k_ = static_cast<int>(path_.halfedges.size());
    fixed_.assign(k_, 0);
    mu_.assign(k_ + 2, 0.0);  // open paths only here: the crossings and the two endpoints
    path_.start_face = k_ > 0 ? mesh_.face(path_.halfedges[0]) : first_face;
    if (reroutes_ > max_reroutes_) break;
    // Windows: from the last crossing of the anchor run before each rerouted run to the first
    // crossing of the anchor run after it (or the path's ends); overlapping windows merge.
    windows.clear();
    for (const auto& [a, b] : spliced) {
      int p = a - 1;
      while (p >= 0 && vertex_at(p) < 0) --p;
      int q = b + 1;
      while (q < k_ && vertex_at(q) < 0) ++q;
      Window w{p + 1, q, p >= 0 ? vertex_at(p) : -1, q < k_ ? vertex_at(q) : -1};
      if (!windows.empty() && w.lo <= windows.back().hi) {
        windows.back().hi = std::max(windows.back().hi, w.hi);
        windows.back().end_vertex = w.end_vertex;
      } else {
        windows.push_back(w);
      }
    }
    full = false;
  }
  std::fill(fixed_.begin(), fixed_.end(), 0);
}

void Refiner::loop_rounds() {
  if (!path_.closed) return;
  auto length = [&]() {
    double len = 0.0;
    for (int i = 0; i < k_; ++i) len += (point((i + 1) % k_, lambda_) - point(i, lambda_)).norm();
    return len;
  };
  // Rotates the arrays so that crossing 0 is the one near it that lies farthest inside its edge
  // (an anchor held at a vertex would keep the loop's corner there, and a vertex run across the
  // arrays' seam would only be rotated by the vertex sweep).
  auto pick_anchor = [&]() {
    int best = 0;
    auto inside = [&](int q) { return std::min(lambda_[q], 1.0 - lambda_[q]); };
    for (int d = 0; d < std::max(1, k_ / 4); ++d)
      for (int q : {d, (k_ - d) % k_})
        if (inside(q) > inside(best) + 0.05) best = q;
    rotate_closed(best);
  };
  double last = length();
  for (int round = 0; round < 200 && k_ >= 3; ++round) {
    // Two straightenings, held at crossing 0 and at the crossing half way round.
    for (int half = 0; half < 2; ++half) {
      pick_anchor();
      // A strip that winds round a vertex unfolds onto itself, and the funnel's answer is then
      // not a path of the strip: a straightening that lengthens the loop is undone.
      const std::vector<double> kept = lambda_;
      const double len0 = length();
      loop_anchor_ = true;
      funnel_straighten(1, k_, -1, -1);
      loop_anchor_ = false;
      if (length() > len0) lambda_ = kept;
      rotate_closed(k_ / 2);
    }
    pick_anchor();
    const int before = reroutes_ + lifts_ + events_;
    for (int sweep = 0; sweep < 4; ++sweep) {  // a Rotated event returns before the sweep ends
      Eval ev;
      evaluate(lambda_, z_, false, &ev);
      if (!process_vertex_events(ev)) break;
    }
    const bool changed = reroutes_ + lifts_ + events_ != before;
    const double now = length();
    if (!changed && last - now <= 1e-15 * std::max(1.0, last)) break;
    last = now;
    if (reroutes_ + lifts_ > max_reroutes_) break;
  }
  std::fill(fixed_.begin(), fixed_.end(), 0);
}

void Refiner::simplify_strip() {
  if (path_.closed || k_ == 0) return;
  auto holds = [&](const SurfacePoint& p, int h) {
    switch (p.kind) {
      case SurfacePoint::Kind::Vertex:
        return mesh_.from(h) == p.element || mesh_.to(h) == p.element;
      case SurfacePoint::Kind::Edge:
        return mesh_.edge(h) == mesh_.edge(p.element);
      case SurfacePoint::Kind::Face:
        return false;
    }
    return false;
  };
  std::vector<int> h;
  std::vector<double> l;
  h.reserve(k_);
  l.reserve(k_);
  for (int q = 0; q < k_; ++q) {
    const int c = path_.halfedges[q];
    if (!h.empty() && h.back() == mesh_.twin(c)) {
      h.pop_back();
      l.pop_back();
      continue;
    }
    h.push_back(c);
    l.push_back(lambda_[q]);
  }
  // Leading crossings on edges through the start: the path may start in the face after them.
  int first = 0, last = static_cast<int>(h.size());
  while (first < last && holds(path_.start, h[first])) ++first;
  while (last > first && holds(path_.end, h[last - 1])) --last;
  if (first == 0 && last == static_cast<int>(h.size()) && last == k_) return;
  if (first == last) {
    // Nothing left: one face must hold both endpoints. The face after the dropped leading
    // crossings holds the start; it holds the end when every crossing went that way.
    const int f = first > 0 ? mesh_.face(mesh_.twin(h[first - 1]))
                            : (h.empty() ? path_.start_face : mesh_.face(h[0]));
    path_.start_face = f;
  } else {
    path_.start_face = mesh_.face(h[first]);
  }
  path_.halfedges.assign(h.begin() + first, h.begin() + last);
  lambda_.assign(l.begin() + first, l.begin() + last);
  mu_.clear();
  fixed_.clear();
  rebuild();
}

}  // namespace refine_detail
}  // namespace windplan
