// The refinement's vertex events (geometry/geodesic/refiner.h): lifts, reroutes, pins, fans.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "geometry/base/errors.h"
#include "geometry/geodesic/refiner.h"

namespace windplan {
namespace refine_detail {

bool Refiner::fan_lift(const std::vector<int>& run, int v, const Vec3& P, const Vec3& Q, bool apply,
                       double* theta) {
  // Unfold the fan of strip faces around v crossed by `run` (consecutive crossings, all spokes of
  // v) into the plane; angles are measured from the direction v -> P.
  const Vec3& pv = mesh_.position(v);
  const Vec3 dP = P - pv, dQ = Q - pv;
  const double rP = dP.norm(), rQ = dQ.norm();
  const int n = static_cast<int>(run.size());
  std::vector<double>& phi = fan_phi_;
  phi.resize(n);
  auto spoke = [&](int m) {
    const int h = path_.halfedges[m];
    return mesh_.position(mesh_.from(h) == v ? mesh_.to(h) : mesh_.from(h)) - pv;
  };
  phi[0] = angle_between(dP, spoke(run[0]));
  for (int q = 1; q < n; ++q) {
    const int f = mesh_.face(path_.halfedges[run[q]]);  // strip face between run[q-1] and run[q]
    phi[q] = phi[q - 1] + mesh_.corner_angle(outgoing_in_face(mesh_, f, v));
  }
  *theta = phi.back() + angle_between(spoke(run.back()), dQ);
  if (!apply) return true;
  if (!(rP > 0.0) || !(rQ > 0.0)) return false;
  // The straight segment P'Q' in the unfolding crosses every spoke when theta < pi.
  const Vec2 Pp(rP, 0.0), Qp(rQ * std::cos(*theta), rQ * std::sin(*theta));
  const Vec2 D = Qp - Pp;
  const double cPD = Pp.x() * D.y() - Pp.y() * D.x();
  for (int q = 0; q < n; ++q) {
    const int m = run[q];
    const Vec2 u(std::cos(phi[q]), std::sin(phi[q]));
    const double cuD = u.x() * D.y() - u.y() * D.x();
    double r = cuD != 0.0 ? cPD / cuD : 0.0;
    r = std::clamp(r / d_[m].norm(), 0.0, 1.0);
    lambda_[m] = mesh_.from(path_.halfedges[m]) == v ? r : 1.0 - r;
  }
  return true;
}

bool Refiner::other_side_fan(int i, int j, int v, std::vector<int>* hs) const {
  hs->clear();
  const int f_in = mesh_.face(path_.halfedges[i]);
  const int f_out = mesh_.face(mesh_.twin(path_.halfedges[j]));
  int hv = outgoing_in_face(mesh_, f_in, v);
  // The current side crosses prev(hv) (counter-clockwise) or hv (clockwise) first.
  const bool ccw = path_.halfedges[i] == hv;
  int face = f_in;
  const int limit = 4096;  // a guard only: the walk meets f_out within one turn around v
  for (int step = 0; step < limit && face != f_out; ++step) {
    const int c = ccw ? mesh_.prev(hv) : hv;
    const int t = mesh_.twin(c);
    if (mesh_.is_boundary_halfedge(t)) return false;
    hs->push_back(c);
    face = mesh_.face(t);
    hv = ccw ? t : mesh_.next(t);
  }
  return face == f_out && !hs->empty();
}

void Refiner::rotate_closed(int shift) {
  if (shift == 0) return;
  std::rotate(path_.halfedges.begin(), path_.halfedges.begin() + shift, path_.halfedges.end());
  std::rotate(path_.lambdas.begin(), path_.lambdas.begin() + shift, path_.lambdas.end());
  std::rotate(mu_.begin(), mu_.begin() + shift, mu_.end());
  std::rotate(fixed_.begin(), fixed_.begin() + shift, fixed_.end());
  touched_.clear();
  rebuild();
}

void Refiner::replace_run(int i, int j, const std::vector<int>& hs, const std::vector<double>& ls) {
  path_.halfedges.erase(path_.halfedges.begin() + i, path_.halfedges.begin() + j + 1);
  path_.lambdas.erase(path_.lambdas.begin() + i, path_.lambdas.begin() + j + 1);
  path_.halfedges.insert(path_.halfedges.begin() + i, hs.begin(), hs.end());
  path_.lambdas.insert(path_.lambdas.begin() + i, ls.begin(), ls.end());
  // Multipliers are per point (crossings first, then the two endpoints of an open path); the
  // replaced run's points restart at zero.
  std::vector<double> mu_new;
  mu_new.reserve(mu_.size() - (j - i + 1) + hs.size());
  mu_new.insert(mu_new.end(), mu_.begin(), mu_.begin() + i);
  mu_new.insert(mu_new.end(), hs.size(), 0.0);
  mu_new.insert(mu_new.end(), mu_.begin() + j + 1, mu_.end());
  mu_ = std::move(mu_new);
  fixed_.erase(fixed_.begin() + i, fixed_.begin() + j + 1);
  fixed_.insert(fixed_.begin() + i, hs.size(), 0);
  if (!touched_.empty()) {
    touched_.erase(touched_.begin() + i, touched_.begin() + j + 1);
    touched_.insert(touched_.begin() + i, hs.size(), 1);
  }
  // The strip data of the replaced run only (rebuild() would redo all k crossings).
  a_.erase(a_.begin() + i, a_.begin() + j + 1);
  d_.erase(d_.begin() + i, d_.begin() + j + 1);
  a_.insert(a_.begin() + i, hs.size(), Vec3::Zero());
  d_.insert(d_.begin() + i, hs.size(), Vec3::Zero());
  across_.erase(across_.begin() + i, across_.begin() + j + 1);
  across_.insert(across_.begin() + i, hs.size(), Across());
  k_ = path_.num_crossings();
  fill_strip(i, i + static_cast<int>(hs.size()));
}

Refiner::Action Refiner::handle_vertex(int idx, int v, bool pushed_out, int* run_start,
                                       int* run_length) {
  auto incident = [&](int m) {
    const int h = path_.halfedges[m];
    return mesh_.from(h) == v || mesh_.to(h) == v;
  };
  // The maximal run of consecutive crossings on spokes of v around idx.
  auto free_at = [&](int m) { return incident(m); };
  int i = idx, j = idx, count = 1;
  if (path_.closed) {
    while (count < k_ && free_at((i - 1 + k_) % k_)) {
      i = (i - 1 + k_) % k_;
      ++count;
    }
    while (count < k_ && free_at((j + 1) % k_)) {
      j = (j + 1) % k_;
      ++count;
    }
    if (count >= k_ - 1) return Action::Pinned;  // the whole loop circles one vertex
  } else {
    while (i > 0 && free_at(i - 1)) --i;
    while (j + 1 < k_ && free_at(j + 1)) ++j;
    count = j - i + 1;
  }
  std::vector<int> run(count);
  for (int q = 0; q < count; ++q) run[q] = (i + q) % k_;
  *run_start = i;
  *run_length = count;
  // A run that overlaps crossings another vertex changed in this sweep waits for the next one.
  if (!touched_.empty())
    for (int m : run)
      if (touched_[m]) return Action::None;
  const Vec3& pv = mesh_.position(v);
  const double eps_d = 1e-12 * scale_;
  // Endpoint at the vertex: drop the crossings around it (the path starts/ends at v).
  if (!path_.closed) {
    const bool start_at_v = i == 0 && (ps_ - pv).norm() <= eps_d;
    const bool end_at_v = j == k_ - 1 && (pt_ - pv).norm() <= eps_d;
    if (start_at_v || end_at_v) {
      const int new_start_face =
          start_at_v ? mesh_.face(mesh_.twin(path_.halfedges[j])) : path_.start_face;
      replace_run(i, j, {}, {});
      path_.start_face = k_ > 0 ? mesh_.face(path_.halfedges[0]) : new_start_face;
      return Action::Collapsed;
    }
  }
  const int before = path_.closed ? (i - 1 + k_) % k_ : i - 1;
  const int after = path_.closed ? (j + 1) % k_ : j + 1;
  const Vec3 P = before >= 0 ? point(before, lambda_) : ps_;
  const Vec3 Q = after < k_ ? point(after, lambda_) : pt_;
  if ((P - pv).norm() <= eps_d || (Q - pv).norm() <= eps_d) return Action::Pinned;
  if (metric_.kind() != PathMetric::Kind::Euclidean && !penalty_on_) {
    if (path_.closed && i + count > k_) {
      rotate_closed(i);  // the run wraps around the arrays' end: handled on the next sweep
      return Action::Rotated;
    }
    return metric_vertex_test(i, j, v, before, after, P, Q);
  }

  constexpr double kAngleTol = 1e-12;
  // Guard against lift/reroute ping-pong at one vertex: after this many tries it is pinned.
  constexpr int kMaxTries = 40;
  double theta = 0.0;
  fan_lift(run, v, P, Q, false, &theta);
  int& tries = lifts_at_[v];
  // Under a density or anisotropic metric the Euclidean angle test is only a heuristic: a single
  // crossing that the gradient pushes past v (the bound's multiplier, the paper's rule) is
  // rerouted to the other side; collapsed runs (zero-length segments, no gradient) use the test.
  // The angle test is exact only for the plain Euclidean length; with a density, an anisotropic
  // metric or a constraint penalty, a crossing that the gradient pushes past v is rerouted.
  const bool by_multiplier =
      (metric_.kind() != PathMetric::Kind::Euclidean || penalty_on_) && pushed_out;
  if (!by_multiplier && theta < M_PI - kAngleTol && tries < kMaxTries) {
    std::vector<double> before_lift(run.size());
    for (std::size_t q = 0; q < run.size(); ++q) before_lift[q] = lambda_[run[q]];
    if (penalty_on_) {
      // Under a penalty the straight line of the unfolded fan is not the local optimum: move the
      // run just off v and let the optimiser place it.
      for (int m : run) {
        const bool at_from = mesh_.from(path_.halfedges[m]) == v;
        if (at_from ? lambda_[m] < kNearVertex : lambda_[m] > 1.0 - kNearVertex)
          lambda_[m] = at_from ? kNearVertex : 1.0 - kNearVertex;
      }
    } else {
      fan_lift(run, v, P, Q, true, &theta);
    }
    double change = 0.0;
    for (std::size_t q = 0; q < run.size(); ++q)
      change = std::max(change, std::fabs(lambda_[run[q]] - before_lift[q]));
    if (change <= 1e-12) return Action::None;
    ++tries;
    ++lifts_;
    return Action::Lifted;
  }
  // Pin: the path passes through v. Crossings still near v move onto it.
  auto pin = [&]() {
    bool moved = false;
    for (int m : run) {
      const double target = mesh_.from(path_.halfedges[m]) == v ? 0.0 : 1.0;
      if (lambda_[m] != target && std::fabs(lambda_[m] - target) < kNearVertex) {
        lambda_[m] = target;
        moved = true;
      }
    }
    if (moved) ++tries;
    return moved ? Action::Snapped : Action::Pinned;
  };
  if (mesh_.is_boundary_vertex(v) || tries >= kMaxTries) return pin();
  const double other = cone_angle(v) - theta;
  if (!by_multiplier && !(other < M_PI - kAngleTol)) return pin();
  // Reroute: the fan on the other side of v, its crossings placed at v.
  std::vector<int> hs;
  if (!other_side_fan(i, j, v, &hs)) return Action::Pinned;
  std::vector<double> ls(hs.size());
  for (std::size_t q = 0; q < hs.size(); ++q) ls[q] = mesh_.from(hs[q]) == v ? 0.0 : 1.0;
  if (path_.closed && i + count > k_) {
    // The run wraps around the end of the arrays: rotate so that it starts at index 0 and let
    // the caller re-evaluate (every index changed); the event is handled on the next sweep.
    rotate_closed(i);
    return Action::Rotated;
  }
  replace_run(i, j, hs, ls);
  ++tries;
  std::vector<int> new_run(hs.size());
  for (std::size_t q = 0; q < hs.size(); ++q) new_run[q] = i + static_cast<int>(q);
  fan_lift(new_run, v, P, Q, true, &theta);
  ++reroutes_;
  return Action::Rerouted;
}

double Refiner::solve_fan(int before, int after, const std::vector<int>& hs, int v,
                          std::vector<double>* ls) {
  SurfacePath sub;
  sub.closed = false;
  sub.start =
      before >= 0 ? SurfacePoint::on_edge(path_.halfedges[before], lambda_[before]) : path_.start;
  sub.end = after < k_ ? SurfacePoint::on_edge(path_.halfedges[after], lambda_[after]) : path_.end;
  sub.start_face = mesh_.face(hs.front());
  sub.halfedges = hs;
  sub.lambdas = *ls;
  GeodesicOptions o = opt_;
  o.solver = GeodesicSolver::Newton;
  o.funnel_start = false;
  o.max_iterations = 100;
  Refiner r(mesh_, sub, metric_, o, nullptr);
  r.events_enabled_ = false;
  // The passage through v is the non-smooth corner of the fan problem (zero-length segments);
  // the crossings are kept kFanGap of their spoke away from v, which makes the problem smooth.
  constexpr double kFanGap = 1e-7;
  for (int q = 0; q < r.k_; ++q) {
    if (mesh_.from(hs[q]) == v) r.a_[q] += kFanGap * r.d_[q];
    r.d_[q] *= 1.0 - kFanGap;
    if (mesh_.from(hs[q]) != v && mesh_.to(hs[q]) != v) r.d_[q] /= 1.0 - kFanGap;
  }
  GeodesicSummary summary;
  r.inner_solve(&summary, Clock::now());
  const double cost = r.value_only(r.lambda_, r.z_);
  for (int q = 0; q < r.k_; ++q) {
    const double l = r.lambda_[q];
    if (mesh_.from(hs[q]) == v)
      (*ls)[q] = kFanGap + (1.0 - kFanGap) * l;
    else if (mesh_.to(hs[q]) == v)
      (*ls)[q] = (1.0 - kFanGap) * l;
    else
      (*ls)[q] = l;
  }
  return cost;
}

Refiner::Action Refiner::metric_vertex_test(int i, int j, int v, int before, int after,
                                            const Vec3& P, const Vec3& Q) {
  // Each side's fan problem is convex (a sum of metric norms of affine maps of the lambdas, in a
  // box) and its closure contains the passage through v. Each side is solved kept a tiny gap off
  // v (smooth), and taken when it is lower than the passage through v by more than round-off:
  // every change lowers the objective, so there are no lift/reroute cycles, and a pinned vertex
  // is a local optimum of both fans.
  // Guard against snap/lift cycles at one vertex (a crossing snapped onto v, lifted a hair off
  // it, and drawn back by the optimiser): after this many changes the vertex is pinned.
  constexpr int kMaxChanges = 40;
  int& changes = lifts_at_[v];
  if (changes >= kMaxChanges) return Action::Pinned;
  const int n = j - i + 1;
  // A run found pinned stays pinned while its ends and its crossings are unchanged (the sweeps
  // between two solver steps test it again).
  double signature = 0.0;
  for (int q = 0; q < n; ++q) signature += (q + 1.0) * lambda_[i + q];
  PinnedRun key{P, Q, path_.halfedges[i], path_.halfedges[j], n, signature};
  if (auto it = pinned_runs_.find(v); it != pinned_runs_.end() && it->second == key)
    return Action::Pinned;
  std::vector<int> run_h(n);
  for (int q = 0; q < n; ++q) run_h[q] = path_.halfedges[i + q];
  double current = 0.0;  // the passage as it stands
  {
    Vec3 prev = P;
    for (int q = 0; q < n; ++q) {
      const Vec3 x = point(i + q, lambda_);
      current += metric_.cost(mesh_.face(run_h[q]), x - prev);
      prev = x;
    }
    current += metric_.cost(mesh_.face(mesh_.twin(run_h.back())), Q - prev);
  }
  std::vector<double> run_l(n, 0.5);
  const double same = solve_fan(before, after, run_h, v, &run_l);
  std::vector<int> hs;
  std::vector<double> other_l;
  double other = std::numeric_limits<double>::infinity();
  if (!mesh_.is_boundary_vertex(v) && other_side_fan(i, j, v, &hs)) {
    other_l.assign(hs.size(), 0.5);
    other = solve_fan(before, after, hs, v, &other_l);
  }
  const double tol = 1e-12 * std::max(current, 1e-300);
  if (!(std::min(same, other) < current - tol)) {
    pinned_runs_[v] = key;
    return Action::Pinned;
  }
  ++changes;
  if (same <= other) {
    for (int q = 0; q < n; ++q) lambda_[i + q] = run_l[q];
    ++lifts_;
    return Action::Lifted;
  }
  replace_run(i, j, hs, other_l);
  ++reroutes_;
  return Action::Rerouted;
}

bool Refiner::process_vertex_events(const Eval& ev) {
  // One sweep from the last crossing to the first: a strip change at a run only shifts the
  // indices after it, so the gradient of the crossings still to visit stays valid.
  std::fill(fixed_.begin(), fixed_.end(), 0);
  touched_.assign(k_, 0);
  bool changed = false;
  for (int i = k_ - 1; i >= 0; --i) {
    const double l = lambda_[i];
    if (fixed_[i] || touched_[i]) continue;
    // A crossing at a vertex that the gradient pushes outward, or that touches a zero-length
    // segment, goes to the vertex test. One that converges onto a vertex (within kNearVertex of
    // it, pushed towards it) is snapped onto it: the objective has a kink there and Newton would
    // approach it only linearly; the test then decides on the next sweep.
    const bool at_bound = l <= 0.0 || l >= 1.0;
    const int h = path_.halfedges[i];
    if (!at_bound) {
      // Snapping needs an exact vertex test (the angle test, or the fan test for other
      // metrics): not under a penalty.
      if (penalty_on_) continue;
      const double gn = ev.g[i] / d_[i].norm();
      if (l < kNearVertex && gn > 1e-9) {
        lambda_[i] = 0.0;
      } else if (l > 1.0 - kNearVertex && gn < -1e-9) {
        lambda_[i] = 1.0;
      } else {
        continue;
      }
      touched_[i] = 1;
      changed = true;
      ++events_;
      continue;
    }
    const bool out = (l <= 0.0 && ev.g[i] > 0.0) || (l >= 1.0 && ev.g[i] < 0.0);
    if (!out && !ev.zero_adjacent[i]) continue;
    const int v = l <= 0.0 ? mesh_.from(h) : mesh_.to(h);
    int run_start = i, run_length = 1;
    const Action a = handle_vertex(i, v, out && !ev.zero_adjacent[i], &run_start, &run_length);
    if (a == Action::Rotated) return true;  // indices changed wholesale: re-evaluate first
    if (a == Action::Pinned) {
      for (int q = 0; q < run_length; ++q) {
        const int m = (run_start + q) % k_;
        const int hm = path_.halfedges[m];
        if ((lambda_[m] <= 0.0 && mesh_.from(hm) == v) || (lambda_[m] >= 1.0 && mesh_.to(hm) == v))
          fixed_[m] = 1;
      }
    } else if (a != Action::None) {
      changed = true;
      ++events_;
    }
    // A pinned run changed nothing: the sweep goes on with the next crossing, since a run (the
    // spokes of v) can hold crossings at the far ends of its spokes, at other vertices, which
    // need their own test.
    if (a == Action::Pinned || a == Action::None) continue;
    if (static_cast<int>(touched_.size()) == k_) {
      const int len = a == Action::Rerouted || a == Action::Collapsed
                          ? 0  // indices from run_start on changed; nothing below is touched
                          : run_length;
      for (int q = 0; q < len; ++q) touched_[(run_start + q) % k_] = 1;
    }
    i = std::min(i, run_start);
  }
  return changed;
}

}  // namespace refine_detail
}  // namespace windplan
