#include "geometry/geodesic.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <sstream>
#include <unordered_map>

#include "geometry/errors.h"
#include "geometry/unfold.h"

namespace windplan {

const char* to_string(GeodesicTermination t) {
  switch (t) {
    case GeodesicTermination::Converged: return "converged";
    case GeodesicTermination::ObjectiveStalled: return "objective_stalled";
    case GeodesicTermination::MaxIterations: return "max_iterations";
    case GeodesicTermination::MaxReroutes: return "max_reroutes";
    case GeodesicTermination::LineSearchFailed: return "line_search_failed";
  }
  return "unknown";
}

bool GeodesicOptions::is_valid(std::string* why) const {
  auto fail = [&](const char* m) {
    if (why) *why = m;
    return false;
  };
  if (!(gradient_tolerance > 0.0)) return fail("gradient_tolerance must be > 0");
  if (!(objective_tolerance >= 0.0)) return fail("objective_tolerance must be >= 0");
  if (max_iterations < 1) return fail("max_iterations must be >= 1");
  if (max_reroutes < 0) return fail("max_reroutes must be >= 0");
  if (lbfgs_memory < 1) return fail("lbfgs_memory must be >= 1");
  if (max_windows < 0) return fail("max_windows must be >= 0 (0: no limit)");
  if (!(constraint_tolerance > 0.0)) return fail("constraint_tolerance must be > 0");
  if (max_outer_iterations < 1) return fail("max_outer_iterations must be >= 1");
  if (!(penalty_weight >= 0.0) || !std::isfinite(penalty_weight))
    return fail("penalty_weight must be finite and >= 0");
  return true;
}

std::string GeodesicSummary::brief_report() const {
  std::ostringstream s;
  s.precision(10);
  s << "geodesic: " << to_string(termination) << ", length " << initial_length << " -> "
    << final_length << ", " << iterations << " iterations, " << evaluations << " evaluations, "
    << reroutes << " reroutes, " << lifts << " lifts, " << pinned_vertices << " pinned vertices";
  if (outer_iterations > 0) s << ", residual " << constraint_residual;
  s.precision(4);
  s << ", " << time_ms << " ms";
  if (!message.empty()) s << " (" << message << ")";
  return s.str();
}

namespace {

using Clock = std::chrono::steady_clock;
// A crossing this close (in lambda) to a vertex, pushed towards it, triggers the vertex test.
constexpr double kNearVertex = 1e-3;
double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

int outgoing_in_face(const Mesh& mesh, int f, int v) {
  for (int k = 0; k < 3; ++k)
    if (mesh.from(3 * f + k) == v) return 3 * f + k;
  return -1;
}

// Solves a symmetric (cyclic) tridiagonal system in place: diag d, off-diagonal e (e[i] couples
// i and i+1; when cyclic, e[n-1] couples n-1 and 0). rhs is overwritten with the solution.
// Returns false when a pivot vanishes.
bool thomas(const std::vector<double>& d, const std::vector<double>& e, std::vector<double>* x,
            int n, std::vector<double>* work) {
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
      *face = j < k_ ? mesh_.face(path_.halfedges[j])
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
  void evaluate(const std::vector<double>& l, const std::vector<double>& z, bool hessian,
                Eval* ev);
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

void Refiner::evaluate(const std::vector<double>& l, const std::vector<double>& z, bool hessian,
                       Eval* ev) {
  ++evaluations_;
  const int n = k_ + m_;
  ev->value = 0.0;
  ev->length = 0.0;
  ev->g.assign(n, 0.0);
  ev->zero_adjacent.assign(k_, 0);
  if (hessian) {
    ev->hd.assign(k_, 0.0);
    ev->ho.assign(k_, 0.0);
    ev->B.assign(static_cast<std::size_t>(k_) * m_, 0.0);
    ev->C.assign(static_cast<std::size_t>(m_) * m_, 0.0);
  }
  const double tiny = 1e-13 * scale_;
  const int ns = num_segments();
  for (int j = 0; j < ns; ++j) {
    int L, R, f;
    segment(j, &L, &R, &f);
    const Vec3 w = endpoint(R, l) - endpoint(L, l);
    const double c = metric_.cost(f, w);
    ev->length += c;
    if (c <= tiny * (metric_.kind() == PathMetric::Kind::Density ? metric_.densities()[f] : 1.0)) {
      if (L >= 0) ev->zero_adjacent[L] = 1;
      if (R >= 0) ev->zero_adjacent[R] = 1;
      continue;
    }
    const Vec3 gw = metric_.apply(f, w) / c;  // d cost / d w
    if (R >= 0) ev->g[R] += d_[R].dot(gw);
    if (L >= 0) ev->g[L] -= d_[L].dot(gw);
    if (hessian) {
      // Hessian of c wrt w: (G - gw gw^T) / c, pulled back through w = P_R - P_L.
      auto quad = [&](const Vec3& x, const Vec3& y) {
        return (metric_.inner(f, x, y) - x.dot(gw) * y.dot(gw)) / c;
      };
      if (R >= 0) ev->hd[R] += quad(d_[R], d_[R]);
      if (L >= 0) ev->hd[L] += quad(d_[L], d_[L]);
      if (R >= 0 && L >= 0) {
        const double hlr = -quad(d_[L], d_[R]);
        // Off-diagonal slot: e[i] couples i and i+1 (cyclic: e[k-1] couples k-1 and 0).
        if (R == L + 1) ev->ho[L] += hlr;
        else if (L == R + 1) ev->ho[R] += hlr;
        else ev->ho[k_ - 1] += hlr;  // the closing pair (k-1, 0)
      }
    }
  }
  ev->value = ev->length;
  if (penalty_on_ && con_) {
    std::vector<double> drdz(m_);
    const int nres = path_.closed ? k_ : k_ + 2;
    for (int q = 0; q < nres; ++q) {
      const int var = path_.closed || q < k_ ? q : -1;
      const Vec3 p = constraint_point(q, l);
      Vec3 drdp;
      const double r = con_->evaluate(p, z.data(), &drdp, m_ > 0 ? drdz.data() : nullptr);
      ev->value += mu_[q] * r + 0.5 * M_ * r * r;
      const double coef = mu_[q] + M_ * r;
      const double gp = var >= 0 ? drdp.dot(d_[var]) : 0.0;
      if (var >= 0) ev->g[var] += coef * gp;
      for (int c = 0; c < m_; ++c) ev->g[k_ + c] += coef * drdz[c];
      if (hessian) {
        if (var >= 0) {
          ev->hd[var] += M_ * gp * gp;
          for (int c = 0; c < m_; ++c) ev->B[var * m_ + c] += M_ * gp * drdz[c];
        }
        for (int c = 0; c < m_; ++c)
          for (int e = 0; e < m_; ++e) ev->C[c * m_ + e] += M_ * drdz[c] * drdz[e];
      }
    }
  }
}

double Refiner::value_only(const std::vector<double>& l, const std::vector<double>& z) {
  // The objective of evaluate() without derivatives (the line search's trial points).
  ++evaluations_;
  double value = 0.0;
  const int ns = num_segments();
  for (int j = 0; j < ns; ++j) {
    int L, R, f;
    segment(j, &L, &R, &f);
    value += metric_.cost(f, endpoint(R, l) - endpoint(L, l));
  }
  if (penalty_on_ && con_) {
    std::vector<double> drdz(m_);
    Vec3 drdp;
    const int nres = path_.closed ? k_ : k_ + 2;
    for (int q = 0; q < nres; ++q) {
      const Vec3 p = constraint_point(q, l);
      const double r = con_->evaluate(p, z.data(), &drdp, m_ > 0 ? drdz.data() : nullptr);
      value += mu_[q] * r + 0.5 * M_ * r * r;
    }
  }
  return value;
}

double Refiner::max_residual() const {
  if (!con_) return 0.0;
  double worst = 0.0;
  std::vector<double> drdz(m_);
  Vec3 drdp;
  const int nres = path_.closed ? k_ : k_ + 2;
  for (int q = 0; q < nres; ++q) {
    const Vec3 p = constraint_point(q, lambda_);
    worst = std::max(worst, std::fabs(con_->evaluate(p, z_.data(), &drdp,
                                                     m_ > 0 ? drdz.data() : nullptr)));
  }
  return worst;
}

double Refiner::projected_gradient(const Eval& ev) const {
  double worst = 0.0;
  for (int i = 0; i < k_; ++i) {
    if (is_active(ev, i)) continue;
    worst = std::max(worst, std::fabs(ev.g[i]) / d_[i].norm());
  }
  for (int c = 0; c < m_; ++c) worst = std::max(worst, std::fabs(ev.g[k_ + c]) / scale_);
  return worst;
}

bool Refiner::newton_direction(const Eval& ev, std::vector<double>* dir) {
  const int n = k_ + m_;
  dir->assign(n, 0.0);
  if (k_ == 0 && m_ == 0) return true;
  std::vector<double> hd(k_), ho(k_, 0.0);
  std::vector<char> act(k_);
  for (int i = 0; i < k_; ++i) act[i] = is_active(ev, i);
  for (int i = 0; i < k_; ++i) {
    if (act[i]) {
      hd[i] = 1.0;
    } else {
      // Levenberg-style safeguard: the Hessian is only positive semi-definite.
      const double floor = 1e-12 * d_[i].squaredNorm() / scale_;
      hd[i] = ev.hd[i] * (1.0 + 1e-10) + floor;
    }
  }
  for (int i = 0; i < k_; ++i) {
    const int j = (i + 1) % k_;
    if (!path_.closed && i == k_ - 1) break;
    if (!act[i] && !act[j]) ho[i] = ev.ho[i];
  }
  tri_.set(hd, ho, k_, path_.closed);
  std::vector<double> x(k_);
  for (int i = 0; i < k_; ++i) x[i] = act[i] ? 0.0 : -ev.g[i];
  if (k_ > 0 && !tri_.solve(&x)) return false;
  if (m_ > 0) {
    // Bordered system [T B; B^T C] [x; y] = [-g_l; -g_z] via the Schur complement.
    std::vector<std::vector<double>> X(m_, std::vector<double>(k_));
    for (int c = 0; c < m_; ++c) {
      for (int i = 0; i < k_; ++i) X[c][i] = act[i] ? 0.0 : ev.B[i * m_ + c];
      if (k_ > 0 && !tri_.solve(&X[c])) return false;
    }
    Eigen::MatrixXd S(m_, m_);
    Eigen::VectorXd r(m_);
    double trace = 0.0;
    for (int c = 0; c < m_; ++c) trace += ev.C[c * m_ + c];
    for (int c = 0; c < m_; ++c) {
      double bx = 0.0;
      for (int i = 0; i < k_; ++i)
        if (!act[i]) bx += ev.B[i * m_ + c] * x[i];
      r[c] = -ev.g[k_ + c] - bx;
      for (int e = 0; e < m_; ++e) {
        double bX = 0.0;
        for (int i = 0; i < k_; ++i)
          if (!act[i]) bX += ev.B[i * m_ + c] * X[e][i];
        S(c, e) = ev.C[c * m_ + e] - bX;
      }
      S(c, c) += 1e-12 * trace + 1e-300;
    }
    const Eigen::VectorXd y = S.ldlt().solve(r);
    if (!y.allFinite()) return false;
    for (int i = 0; i < k_; ++i)
      for (int c = 0; c < m_; ++c) x[i] -= X[c][i] * y[c];
    for (int c = 0; c < m_; ++c) (*dir)[k_ + c] = y[c];
  }
  for (int i = 0; i < k_; ++i) (*dir)[i] = act[i] ? 0.0 : x[i];
  double slope = 0.0;
  for (int i = 0; i < n; ++i) slope += ev.g[i] * (*dir)[i];
  for (double v : *dir)
    if (!std::isfinite(v)) return false;
  return slope < 0.0;
}

void Refiner::lbfgs_direction(const Eval& ev, std::vector<double>* dir) {
  const int n = k_ + m_;
  std::vector<double> q(n);
  std::vector<char> act(n, 0);
  for (int i = 0; i < k_; ++i) act[i] = is_active(ev, i);
  for (int i = 0; i < n; ++i) q[i] = act[i] ? 0.0 : ev.g[i];
  const int mem = static_cast<int>(s_mem_.size());
  std::vector<double> alpha(mem), rho(mem);
  auto dot = [&](const std::vector<double>& u, const std::vector<double>& v) {
    double s = 0.0;
    for (int i = 0; i < n; ++i)
      if (!act[i]) s += u[i] * v[i];
    return s;
  };
  for (int t = mem - 1; t >= 0; --t) {
    const double sy = dot(s_mem_[t], y_mem_[t]);
    rho[t] = sy > 0.0 ? 1.0 / sy : 0.0;
    alpha[t] = rho[t] * dot(s_mem_[t], q);
    for (int i = 0; i < n; ++i)
      if (!act[i]) q[i] -= alpha[t] * y_mem_[t][i];
  }
  double gamma = 0.0;
  if (mem > 0) {
    const double yy = dot(y_mem_[mem - 1], y_mem_[mem - 1]);
    const double sy = dot(s_mem_[mem - 1], y_mem_[mem - 1]);
    if (yy > 0.0 && sy > 0.0) gamma = sy / yy;
  }
  if (!(gamma > 0.0)) {
    // First step: a diagonal scaling by the edge lengths (a crossing moves ~ a fraction of it).
    double gmax = 0.0;
    for (int i = 0; i < n; ++i) gmax = std::max(gmax, std::fabs(q[i]));
    gamma = gmax > 0.0 ? 0.05 / gmax : 1.0;
  }
  for (int i = 0; i < n; ++i) q[i] *= gamma;
  for (int t = 0; t < mem; ++t) {
    const double beta = rho[t] * dot(y_mem_[t], q);
    for (int i = 0; i < n; ++i)
      if (!act[i]) q[i] += s_mem_[t][i] * (alpha[t] - beta);
  }
  dir->assign(n, 0.0);
  double slope = 0.0;
  for (int i = 0; i < n; ++i) {
    (*dir)[i] = act[i] ? 0.0 : -q[i];
    slope += (*dir)[i] * ev.g[i];
  }
  if (!(slope < 0.0)) {
    s_mem_.clear();
    y_mem_.clear();
    double gmax = 0.0;
    for (int i = 0; i < n; ++i) gmax = std::max(gmax, act[i] ? 0.0 : std::fabs(ev.g[i]));
    const double s = gmax > 0.0 ? 0.05 / gmax : 0.0;
    for (int i = 0; i < n; ++i) (*dir)[i] = act[i] ? 0.0 : -s * ev.g[i];
  }
}

bool Refiner::line_search(const Eval& ev, const std::vector<double>& dir, double* new_value) {
  const int n = k_ + m_;
  std::vector<double> l(k_), z(m_);
  double alpha = 1.0;
  for (int attempt = 0; attempt < 40; ++attempt) {
    double decrease = 0.0;
    for (int i = 0; i < k_; ++i) {
      l[i] = std::clamp(lambda_[i] + alpha * dir[i], 0.0, 1.0);
      decrease += ev.g[i] * (l[i] - lambda_[i]);
    }
    for (int c = 0; c < m_; ++c) {
      z[c] = z_[c] + alpha * dir[k_ + c];
      decrease += ev.g[k_ + c] * (z[c] - z_[c]);
    }
    const double f = value_only(l, z);
    if (f <= ev.value + 1e-4 * decrease || (decrease == 0.0 && f <= ev.value)) {
      if (opt_.solver == GeodesicSolver::Lbfgs) {
        // Store the pair before the variables change.
        std::vector<double> s(n), y(n, 0.0);
        for (int i = 0; i < k_; ++i) s[i] = l[i] - lambda_[i];
        for (int c = 0; c < m_; ++c) s[k_ + c] = z[c] - z_[c];
        s_mem_.push_back(std::move(s));
        y_mem_.push_back(std::move(y));  // completed after the next evaluation
      }
      lambda_ = l;
      z_ = z;
      *new_value = f;
      return true;
    }
    alpha *= 0.5;
  }
  return false;
}

bool Refiner::fan_lift(const std::vector<int>& run, int v, const Vec3& P, const Vec3& Q,
                       bool apply, double* theta) {
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
  sub.start = before >= 0 ? SurfacePoint::on_edge(path_.halfedges[before], lambda_[before])
                          : path_.start;
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
    if (mesh_.from(hs[q]) == v) (*ls)[q] = kFanGap + (1.0 - kFanGap) * l;
    else if (mesh_.to(hs[q]) == v) (*ls)[q] = (1.0 - kFanGap) * l;
    else (*ls)[q] = l;
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
    ids[0] = a; ids[1] = b; ids[2] = c;
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
        Rv[t + 1] = a; R[t + 1] = R[t];
        Lv[t + 1] = d; L[t + 1] = pd;
      } else if (hn == mesh_.prev(tw)) {  // d -> b
        Rv[t + 1] = d; R[t + 1] = pd;
        Lv[t + 1] = b; L[t + 1] = L[t];
      } else {  // back through the same edge (b -> a): a strip that folds back
        Rv[t + 1] = b; R[t + 1] = L[t];
        Lv[t + 1] = a; L[t + 1] = R[t];
      }
    } else {
      ids[0] = a; pos[0] = R[t];
      ids[1] = b; pos[1] = L[t];
      ids[2] = d; pos[2] = pd;
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
      while (j + 1 < k_ && (mesh_.from(path_.halfedges[j + 1]) == v ||
                            mesh_.to(path_.halfedges[j + 1]) == v))
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

bool Refiner::inner_solve(GeodesicSummary* summary, Clock::time_point t0) {
  (void)t0;
  Eval ev;
  evaluate(lambda_, z_, opt_.solver == GeodesicSolver::Newton, &ev);
  s_mem_.clear();
  y_mem_.clear();
  int stalls = 0;
  std::vector<double> dir;
  while (true) {
    if (iterations_ >= opt_.max_iterations) {
      termination_ = GeodesicTermination::MaxIterations;
      break;
    }
    if (reroutes_ + lifts_ > max_reroutes_ || events_ > 4 * max_reroutes_) {
      termination_ = GeodesicTermination::MaxReroutes;
      break;
    }
    if (events_enabled_ && process_vertex_events(ev)) {
      s_mem_.clear();
      y_mem_.clear();
      evaluate(lambda_, z_, opt_.solver == GeodesicSolver::Newton, &ev);
      stalls = 0;
      continue;
    }
    const double pg = projected_gradient(ev);
    summary->projected_gradient = pg;
    if (pg <= opt_.gradient_tolerance) {
      termination_ = GeodesicTermination::Converged;
      break;
    }
    ++iterations_;
    bool have_dir = false;
    if (opt_.solver == GeodesicSolver::Newton) have_dir = newton_direction(ev, &dir);
    if (!have_dir) lbfgs_direction(ev, &dir);
    const std::vector<double> g_old = ev.g;
    double f_new = 0.0;
    bool stepped = line_search(ev, dir, &f_new);
    if (!stepped && have_dir) {
      // The Newton model can be poor next to the path's kinks at vertices: fall back to the
      // scaled projected gradient once before giving up.
      s_mem_.clear();
      y_mem_.clear();
      lbfgs_direction(ev, &dir);
      stepped = line_search(ev, dir, &f_new);
    }
    if (!stepped) {
      double slope = 0.0;
      for (int q = 0; q < k_ + m_; ++q) slope += ev.g[q] * dir[q];
      // Crossings strictly inside their edges are stationary: what is left is the non-smooth
      // part at vertices (zero-length segments), where no descent remains either.
      double interior = 0.0;
      for (int q = 0; q < k_; ++q)
        if (lambda_[q] > 0.0 && lambda_[q] < 1.0)
          interior = std::max(interior, std::fabs(ev.g[q]) / d_[q].norm());
      if (std::fabs(slope) <= 1e-13 * std::max(1.0, std::fabs(ev.value)) ||
          interior <= 10.0 * opt_.gradient_tolerance) {
        termination_ = GeodesicTermination::Converged;
        summary->message = "no decrease left (stationary inside the edges)";
      } else {
        termination_ = GeodesicTermination::LineSearchFailed;
        summary->message = "no decrease along the search direction";
      }
      break;
    }
    const double f_old = ev.value;
    evaluate(lambda_, z_, opt_.solver == GeodesicSolver::Newton, &ev);
    if (opt_.solver == GeodesicSolver::Lbfgs && !y_mem_.empty()) {
      auto& y = y_mem_.back();
      for (int i = 0; i < k_ + m_; ++i) y[i] = ev.g[i] - g_old[i];
      if (static_cast<int>(s_mem_.size()) > opt_.lbfgs_memory) {
        s_mem_.pop_front();
        y_mem_.pop_front();
      }
    }
    if (std::fabs(f_old - ev.value) <= opt_.objective_tolerance * std::max(1.0, std::fabs(f_old))) {
      if (++stalls >= 2) {
        termination_ = GeodesicTermination::ObjectiveStalled;
        // Still process pending vertex events before stopping.
        if (events_enabled_ && process_vertex_events(ev)) {
          evaluate(lambda_, z_, opt_.solver == GeodesicSolver::Newton, &ev);
          stalls = 0;
          continue;
        }
        break;
      }
    } else {
      stalls = 0;
    }
  }
  return true;
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

GeodesicResult Refiner::run() {
  const auto t0 = Clock::now();
  GeodesicSummary summary;
  {
    Eval ev;
    evaluate(lambda_, z_, false, &ev);
    summary.initial_length = ev.length;
  }
  simplify_strip();
  max_reroutes_ = opt_.max_reroutes > 0 ? opt_.max_reroutes : 50 + 10 * k_;
  if (!con_) {
    // The funnel gives the exact Euclidean path; under a density or anisotropic metric it starts
    // the optimisation on a path through many vertices and ends longer (measured on cones and
    // the vessel), so it is used for the Euclidean length only.
    if (opt_.funnel_start && metric_.kind() == PathMetric::Kind::Euclidean) {
      funnel_rounds();
      loop_rounds();
    }
    inner_solve(&summary, t0);
  } else {
    // Penalty weight: the initial penalty at a residual of one mean edge length per point is
    // about 10x the length (the paper's rule of thumb), unless given.
    const double L0 = std::max(summary.initial_length, scale_);
    const int npts = path_.closed ? k_ : k_ + 2;
    if (opt_.penalty_weight > 0.0) {
      M_ = opt_.penalty_weight;
    } else if (opt_.penalty_mode == PenaltyMode::Paper) {
      double h2 = 0.0;
      std::vector<double> drdz(m_);
      Vec3 drdp;
      for (int q = 0; q < npts; ++q) {
        const Vec3 p = constraint_point(q, lambda_);
        const double r = con_->evaluate(p, z_.data(), &drdp, m_ > 0 ? drdz.data() : nullptr);
        h2 += r * r;
      }
      h2 = std::max(h2, npts * 1e-6 * scale_ * scale_);
      M_ = 2.0 * 10.0 * L0 / h2;
    } else {
      M_ = 2.0 * 10.0 * L0 / (npts * scale_ * scale_);
    }
    penalty_on_ = true;
    double last = std::numeric_limits<double>::infinity();
    for (int outer = 0; outer < opt_.max_outer_iterations; ++outer) {
      summary.outer_iterations = outer + 1;
      inner_solve(&summary, t0);
      const double res = max_residual();
      Eval ev;
      evaluate(lambda_, z_, false, &ev);
      const double tol = opt_.constraint_tolerance * std::max(ev.length, scale_);
      if (opt_.penalty_mode == PenaltyMode::Paper || res <= tol) break;
      // Augmented Lagrangian multiplier update, and a stiffer penalty if progress is slow.
      std::vector<double> drdz(m_);
      Vec3 drdp;
      for (int q = 0; q < npts && q < static_cast<int>(mu_.size()); ++q) {
        const Vec3 p = constraint_point(q, lambda_);
        mu_[q] += M_ * con_->evaluate(p, z_.data(), &drdp, m_ > 0 ? drdz.data() : nullptr);
      }
      if (res > 0.25 * last) M_ *= 10.0;
      last = res;
      con_->recentre(z_.data());
    }
    if (m_ > 0) con_->recentre(z_.data());
  }
  Eval ev;
  penalty_on_ = false;
  evaluate(lambda_, z_, false, &ev);
  summary.final_length = ev.length;
  summary.constraint_residual = max_residual();
  if (con_ && termination_ == GeodesicTermination::Converged &&
      summary.constraint_residual >
          opt_.constraint_tolerance * std::max(summary.final_length, scale_) * 10.0) {
    summary.message = "constraint residual above tolerance";
  }
  summary.termination = termination_;
  summary.iterations = iterations_;
  summary.evaluations = evaluations_;
  summary.reroutes = reroutes_;
  summary.lifts = lifts_;
  int pinned = 0;
  for (int i = 0; i < k_; ++i)
    if (fixed_[i] && (i == 0 || !fixed_[i - 1])) ++pinned;
  summary.pinned_vertices = pinned;
  GeodesicResult result;
  result.path = path_;
  if (!result.path.closed && result.path.num_crossings() > 0)
    result.path.start_face = mesh_.face(result.path.halfedges[0]);
  summary.euclidean_length = euclidean_length(mesh_, result.path);
  summary.time_ms = ms_since(t0);
  result.summary = summary;
  result.constraint_variables = z_;
  return result;
}

}  // namespace

GeodesicResult refine_path(const Mesh& mesh, const SurfacePath& initial, const PathMetric& metric,
                           const GeodesicOptions& options, PathConstraint* constraint) {
  std::string why;
  if (!options.is_valid(&why)) throw InputError("geodesic options: " + why);
  if (!is_valid_path(mesh, initial, &why)) throw InputError("initial path: " + why);
  Refiner refiner(mesh, initial, metric, options, constraint);
  return refiner.run();
}

PathObjective evaluate_path_objective(const Mesh& mesh, const SurfacePath& path,
                                      const PathMetric& metric, PathConstraint* constraint,
                                      const std::vector<double>& z, double penalty_weight,
                                      const std::vector<double>& multipliers) {
  std::string why;
  if (!is_valid_path(mesh, path, &why)) throw InputError("path: " + why);
  Refiner refiner(mesh, path, metric, GeodesicOptions{}, constraint);
  return refiner.objective(z, penalty_weight, multipliers);
}

std::vector<VertexPassage> vertex_passages(const Mesh& mesh, const SurfacePath& path) {
  std::vector<VertexPassage> out;
  const int k = path.num_crossings();
  const std::vector<Vec3> pts = polyline(mesh, path);
  const int off = path.closed ? 0 : 1;  // polyline index of crossing i is i + off
  auto at_vertex = [&](int i) {
    const int h = path.halfedges[i];
    const double l = path.lambdas[i];
    return l <= 0.0 ? mesh.from(h) : (l >= 1.0 ? mesh.to(h) : -1);
  };
  for (int i = 0; i < k;) {
    const int v = at_vertex(i);
    if (v < 0) {
      ++i;
      continue;
    }
    int j = i;
    while (j + 1 < k && at_vertex(j + 1) == v) ++j;
    const Vec3& pv = mesh.position(v);
    const int before = i + off - 1, after = j + off + 1;
    if (path.closed && (i == 0 || j == k - 1)) {
      i = j + 1;
      continue;  // a run across the loop's seam: skipped (diagnostics only)
    }
    if (before < 0 || after >= static_cast<int>(pts.size())) {
      i = j + 1;
      continue;
    }
    const Vec3 dP = pts[before] - pv, dQ = pts[after] - pv;
    if (dP.norm() == 0.0 || dQ.norm() == 0.0) {
      i = j + 1;
      continue;
    }
    auto spoke = [&](int m) {
      const int h = path.halfedges[m];
      return mesh.position(mesh.from(h) == v ? mesh.to(h) : mesh.from(h)) - pv;
    };
    double theta = angle_between(dP, spoke(i));
    for (int m = i + 1; m <= j; ++m)
      theta += mesh.corner_angle(outgoing_in_face(mesh, mesh.face(path.halfedges[m]), v));
    theta += angle_between(spoke(j), dQ);
    VertexPassage vp;
    vp.vertex = v;
    vp.first_crossing = i;
    vp.last_crossing = j;
    vp.strip_angle = theta;
    vp.other_angle = mesh.is_boundary_vertex(v) ? 0.0 : mesh.cone_angle(v) - theta;
    out.push_back(vp);
    i = j + 1;
  }
  return out;
}

}  // namespace windplan
