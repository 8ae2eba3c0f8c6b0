// The refinement (geometry/geodesic/refiner.h): objective, steps, outer loop, public entries.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "geometry/base/errors.h"
#include "geometry/geodesic/refiner.h"

namespace windplan {
namespace refine_detail {

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
        if (R == L + 1)
          ev->ho[L] += hlr;
        else if (L == R + 1)
          ev->ho[R] += hlr;
        else
          ev->ho[k_ - 1] += hlr;  // the closing pair (k-1, 0)
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
    worst = std::max(
        worst, std::fabs(con_->evaluate(p, z_.data(), &drdp, m_ > 0 ? drdz.data() : nullptr)));
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

}  // namespace refine_detail

using refine_detail::angle_between;
using refine_detail::outgoing_in_face;
using refine_detail::Refiner;

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
