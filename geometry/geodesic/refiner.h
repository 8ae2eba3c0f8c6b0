#pragma once
// The refinement's optimisation state (internal to geometry/geodesic: refine_path.cpp,
// refine_vertices.cpp and refine_funnel.cpp implement it; refine_path.h is the public entry).
//
//   refine_path.cpp      the objective on a fixed strip, Newton and L-BFGS steps, the line
//                        search, the outer (penalty) loop and run()
//   refine_vertices.cpp  vertex events: lifts off a vertex, reroutes around it, pins, the
//                        metric-exact fan test
//   refine_funnel.cpp    the funnel (exact shortest path in a strip) and its rounds, for open
//                        paths and loops; strip simplification
#include <chrono>
#include <cmath>
#include <deque>
#include <unordered_map>
#include <vector>

#include "geometry/geodesic/refine_path.h"
#include "geometry/geodesic/unfold.h"

namespace windplan {
namespace refine_detail {

using Clock = std::chrono::steady_clock;
// A crossing this close (in lambda) to a vertex, pushed towards it, triggers the vertex test.
constexpr double kNearVertex = 1e-3;
inline double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

inline double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

inline int outgoing_in_face(const Mesh& mesh, int f, int v) {
  for (int k = 0; k < 3; ++k)
    if (mesh.from(3 * f + k) == v) return 3 * f + k;
  return -1;
}

// Solves a symmetric (cyclic) tridiagonal system in place: diag d, off-diagonal e (e[i] couples
// i and i+1; when cyclic, e[n-1] couples n-1 and 0). rhs is overwritten with the solution.
// Returns false when a pivot vanishes.
inline bool thomas(const std::vector<double>& d, const std::vector<double>& e,
                   std::vector<double>* x, int n, std::vector<double>* work) {
  std::vector<double>& c = *work;
  c.resize(n);
  double beta = d[0];
  if (!(std::fabs(beta) > 0.0)) return false;
  (*x)[0] /= beta;
  for (int i = 1; i < n; ++i) {
    c[i] = e[i - 1] / beta;
    beta = d[i] - e[i - 1] * c[i];
    if (!(std::fabs(beta) > 0.0)) return false;
    (*x)[i] = ((*x)[i] - e[i - 1] * (*x)[i - 1]) / beta;
  }
  for (int i = n - 2; i >= 0; --i) (*x)[i] -= c[i + 1] * (*x)[i + 1];
  return true;
}

class TridiagonalSolver {
 public:
  // Prepares diag/off for solving; cyclic uses Sherman-Morrison on the corner element.
  void set(const std::vector<double>& diag, const std::vector<double>& off, int n, bool cyclic) {
    n_ = n;
    cyclic_ = cyclic && n >= 3 && off[n - 1] != 0.0;
    d_.assign(diag.begin(), diag.begin() + n);
    e_.assign(off.begin(), off.begin() + n);
    if (cyclic && n == 2) {
      // Both off-diagonal entries couple the same pair.
      e_[0] = off[0] + off[1];
    }
    if (cyclic_) {
      alpha_ = off[n - 1];
      gamma_ = -d_[0];
      d_[0] -= gamma_;
      d_[n - 1] -= alpha_ * alpha_ / gamma_;
      zvec_.assign(n, 0.0);
      zvec_[0] = gamma_;
      zvec_[n - 1] = alpha_;
      ok_ = thomas(d_, e_, &zvec_, n, &work_);
    } else {
      ok_ = true;
    }
  }
  bool solve(std::vector<double>* x) {
    if (!ok_) return false;
    if (!thomas(d_, e_, x, n_, &work_)) return false;
    if (cyclic_) {
      const double vy = (*x)[0] + alpha_ / gamma_ * (*x)[n_ - 1];
      const double vz = zvec_[0] + alpha_ / gamma_ * zvec_[n_ - 1];
      const double f = vy / (1.0 + vz);
      for (int i = 0; i < n_; ++i) (*x)[i] -= f * zvec_[i];
    }
    return true;
  }

 private:
  int n_ = 0;
  bool cyclic_ = false, ok_ = false;
  double alpha_ = 0.0, gamma_ = 1.0;
  std::vector<double> d_, e_, zvec_, work_;
};

// The optimisation state of one refinement.
class Refiner {
 public:
  Refiner(const Mesh& mesh, const SurfacePath& path, const PathMetric& metric,
          const GeodesicOptions& options, PathConstraint* constraint)
      : mesh_(mesh), metric_(metric), opt_(options), con_(constraint), path_(path) {
    m_ = con_ ? con_->num_variables() : 0;
    z_.assign(m_, 0.0);
    if (con_ && m_ > 0) con_->initial_variables(z_.data());
    // Length scale for tolerances: the mean length of the crossed edges (O(k), not O(E): this
    // runs once per query).
    double sum = 0.0;
    for (int h : path_.halfedges) sum += mesh.halfedge_length(h);
    if (!path_.halfedges.empty()) sum /= static_cast<double>(path_.halfedges.size());
    if (!(sum > 0.0) && !path_.closed) {
      sum = (position(mesh, path_.start) - position(mesh, path_.end)).norm();
      const int f = path_.start_face;
      if (f >= 0) sum = std::max(sum, std::sqrt(mesh.face_area(f)));
    }
    scale_ = sum > 0.0 ? sum : 1.0;
    if (!path_.closed) {
      ps_ = position(mesh, path_.start);
      pt_ = position(mesh, path_.end);
    }
    rebuild();
  }

  GeodesicResult run();
  PathObjective objective(const std::vector<double>& z, double M, const std::vector<double>& mu) {
    if (!z.empty()) z_ = z;
    M_ = M;
    penalty_on_ = con_ != nullptr;
    if (!mu.empty()) mu_ = mu;
    Eval ev;
    evaluate(lambda_, z_, true, &ev);
    PathObjective o;
    o.value = ev.value;
    o.length = ev.length;
    o.gradient = ev.g;
    o.hessian_diag = ev.hd;
    o.hessian_off = ev.ho;
    return o;
  }

 private:
  // ---- strip data ----
  void rebuild() {
    k_ = path_.num_crossings();
    a_.resize(k_);
    d_.resize(k_);
    across_.resize(k_);
    if (static_cast<int>(fixed_.size()) != k_) fixed_.assign(k_, 0);
    fill_strip(0, k_);
    const int nres = path_.closed ? k_ : k_ + 2;
    if (static_cast<int>(mu_.size()) != nres) mu_.assign(nres, 0.0);
  }
  // a_ and d_ (crossing i = a_[i] + l d_[i]) of crossings lo..hi-1 from their halfedges.
  void fill_strip(int lo, int hi) {
    for (int i = lo; i < hi; ++i) {
      const int h = path_.halfedges[i];
      a_[i] = mesh_.position(mesh_.from(h));
      d_[i] = mesh_.position(mesh_.to(h)) - a_[i];
      across_[i] = across(h);
    }
  }
  // The face after a crossing, for the funnel's unfolding: its far corner d (across the
  // crossed edge) and across_coefficients, and the edge's twin (computed once per crossing
  // instead of once per crossing and funnel round).
  struct Across {
    int twin = -1, d = -1;
    Vec2 uw = Vec2::Zero();
  };
  Across across(int h) const {
    Across x;
    x.twin = mesh_.twin(h);
    x.d = mesh_.to(mesh_.next(x.twin));
    x.uw = across_coefficients(mesh_.position(mesh_.from(h)), mesh_.position(mesh_.to(h)),
                               mesh_.position(x.d));
    return x;
  }
  Vec3 point(int i, const std::vector<double>& l) const { return a_[i] + l[i] * d_[i]; }
  // Constraint residual point q: the crossings, then (open paths) the start and the end.
  Vec3 constraint_point(int q, const std::vector<double>& l) const {
    return path_.closed || q < k_ ? point(q, l) : (q == k_ ? ps_ : pt_);
  }
  int num_segments() const { return path_.closed ? k_ : k_ + 1; }
  // Segment j: endpoints as variable indices (-1: start, -2: end) and its face.
  void segment(int j, int* left, int* right, int* face) const {
    if (path_.closed) {
      *left = j;
      *right = (j + 1) % k_;
      *face = mesh_.face(mesh_.twin(path_.halfedges[j]));
    } else {
      *left = j == 0 ? -1 : j - 1;
      *right = j == k_ ? -2 : j;
      *face = j < k_
                  ? mesh_.face(path_.halfedges[j])
                  : (k_ == 0 ? path_.start_face : mesh_.face(mesh_.twin(path_.halfedges[k_ - 1])));
    }
  }
  Vec3 endpoint(int idx, const std::vector<double>& l) const {
    return idx == -1 ? ps_ : idx == -2 ? pt_ : point(idx, l);
  }

  // ---- objective ----
  struct Eval {
    double value = 0.0, length = 0.0;
    std::vector<double> g;            // k + m
    std::vector<double> hd, ho;       // k, k
    std::vector<double> B;            // k * m (row major: i*m + c)
    std::vector<double> C;            // m * m
    std::vector<char> zero_adjacent;  // k: touches a zero-length segment
  };
  void evaluate(const std::vector<double>& l, const std::vector<double>& z, bool hessian, Eval* ev);
  double value_only(const std::vector<double>& l, const std::vector<double>& z);
  double max_residual() const;

  // ---- steps ----
  bool newton_direction(const Eval& ev, std::vector<double>* dir);
  void lbfgs_direction(const Eval& ev, std::vector<double>* dir);
  bool line_search(const Eval& ev, const std::vector<double>& dir, double* new_value);
  double projected_gradient(const Eval& ev) const;
  bool is_active(const Eval& ev, int i) const {
    if (fixed_[i]) return true;
    return (lambda_[i] <= 0.0 && ev.g[i] > 0.0) || (lambda_[i] >= 1.0 && ev.g[i] < 0.0);
  }

  // ---- vertex events ----
  enum class Action { None, Lifted, Rerouted, Pinned, Snapped, Collapsed, Rotated };
  bool process_vertex_events(const Eval& ev);
  Action handle_vertex(int idx, int v, bool pushed_out, int* run_start, int* run_length);
  bool fan_lift(const std::vector<int>& run, int v, const Vec3& P, const Vec3& Q, bool apply,
                double* theta);
  void rotate_closed(int shift);
  // The crossings of the fan on the other side of v, from face(h_i) around v the other way to
  // face(twin(h_j)) (crossings i..j are the current side's spokes of v). False past a boundary.
  bool other_side_fan(int i, int j, int v, std::vector<int>* hs) const;
  void replace_run(int i, int j, const std::vector<int>& hs, const std::vector<double>& ls);

  // Metric-exact vertex test (density, anisotropic; no penalty): the cheapest passage from the
  // crossing before the run to the one after it, on the current side of v and on the other side,
  // each the global optimum of its fan (a convex problem), against the current passage.
  Action metric_vertex_test(int i, int j, int v, int before, int after, const Vec3& P,
                            const Vec3& Q);
  // A fan sub-problem: from crossing `before` (or the start) over the crossings hs (around v) to
  // crossing `after` (or the end), solved from *ls; returns the optimum's cost, *ls the optimum.
  double solve_fan(int before, int after, const std::vector<int>& hs, int v,
                   std::vector<double>* ls);

  bool inner_solve(GeodesicSummary* summary, Clock::time_point t0);
  // Drops what only makes an open strip longer: a crossing followed by its own twin (a fold:
  // the strip enters a face and leaves it through the same edge), and crossings of edges that
  // hold the start or the end point (the strip turning around its own endpoint). Such strips
  // come from edge paths that start along an edge; the funnel and the vertex tests would pin
  // the path at the fold.
  void simplify_strip();
  // Exact Euclidean shortest path inside the current strip (funnel algorithm on the unfolded
  // strip), then reroutes around every vertex the path wraps with an angle < pi on the other
  // side; repeated until no reroute happens. Open paths only.
  void funnel_rounds();
  // The exact shortest path through portals lo..hi-1 (crossings), from the path's start (or
  // start_vertex, a vertex of face(h_lo)) to its end (or end_vertex, a vertex of the face after
  // h_{hi-1}): the funnel algorithm on the unfolded strip; sets those crossings' lambdas.
  void funnel_straighten(int lo, int hi, int start_vertex, int end_vertex);
  // Closed loops (Euclidean): the shortest loop through the strip is straightened with the
  // crossing at index 0 held (the funnel from it round the loop back to it, portals 1..k-1),
  // then again with the crossing half way round held, and so on while the length drops; vertex
  // events (lifts, reroutes, pins) are processed between the straightenings. The optimiser then
  // starts on the exact loop of the final strip.
  void loop_rounds();
  bool loop_anchor_ = false;  // funnel_straighten: start and end at crossing 0 (closed loops)

  const Mesh& mesh_;
  const PathMetric& metric_;
  GeodesicOptions opt_;
  PathConstraint* con_;
  SurfacePath path_;
  int k_ = 0, m_ = 0;
  double scale_ = 1.0;
  Vec3 ps_ = Vec3::Zero(), pt_ = Vec3::Zero();
  std::vector<Vec3> a_, d_;
  std::vector<Across> across_;
  std::vector<double>& lambda_ = path_.lambdas;
  std::vector<double> z_, mu_;
  std::vector<char> fixed_;
  std::vector<char> touched_;  // per sweep: crossings already decided by a vertex event
  int events_ = 0;             // strip/parameter changes made by vertex events
  double M_ = 0.0;
  bool penalty_on_ = false;
  int evaluations_ = 0, iterations_ = 0, reroutes_ = 0, lifts_ = 0, max_reroutes_ = 0;
  std::unordered_map<int, int> lifts_at_;
  // L-BFGS memory
  std::deque<std::vector<double>> s_mem_, y_mem_;
  TridiagonalSolver tri_;
  GeodesicTermination termination_ = GeodesicTermination::Converged;
  bool events_enabled_ = true;  // false for the fan sub-problems of metric_vertex_test
  struct PinnedRun {
    Vec3 P, Q;
    int first, last, count;
    double signature;  // of the run's lambdas
    bool operator==(const PinnedRun& o) const {
      return P == o.P && Q == o.Q && first == o.first && last == o.last && count == o.count &&
             signature == o.signature;
    }
  };
  std::unordered_map<int, PinnedRun> pinned_runs_;  // metric_vertex_test's pinned decisions
  // Cone angles of the vertices met (a vertex is tested in many funnel rounds and sweeps).
  std::unordered_map<int, double> cone_angles_;
  // funnel_straighten's buffers (it runs every funnel round).
  std::vector<Vec2> unfold_L_, unfold_R_, corner_;
  std::vector<int> unfold_Lv_, unfold_Rv_, corner_portal_, corner_vertex_;
  // funnel_rounds' splice buffers (swapped with the path's arrays).
  std::vector<int> splice_h_;
  std::vector<double> splice_l_;
  std::vector<Vec3> splice_a_, splice_d_;
  std::vector<Across> splice_x_;
  std::vector<int> scan_run_;
  std::vector<double> fan_phi_;  // fan_lift's spoke angles
  double cone_angle(int v) {
    auto [it, inserted] = cone_angles_.try_emplace(v, 0.0);
    if (inserted) it->second = mesh_.cone_angle(v);
    return it->second;
  }
};

}  // namespace refine_detail
}  // namespace windplan
