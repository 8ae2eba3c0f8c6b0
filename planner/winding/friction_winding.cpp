#include "planner/winding/friction_winding.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>
#include <utility>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "geometry/base/parallel.h"
#include "planner/winding/revolution_winding.h"

namespace windplan {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const char* end_name(int e) { return e == 0 ? "start" : "far"; }

// One planned variant: the friction parts and the circuit advance at one lambda and c.
struct Trial {
  double lambda = 0.0, c = 0.0, delta = 0.0;  // delta: the domes' turnarounds moved (transition)
  std::array<bool, 2> fe = {false, false};    // friction turnaround per end
  int unreached = -1;                         // an end where friction never brings r sin a to c
  bool fits = true;  // the friction parts leave a geodesic pass between them, in the region
  std::array<FrictionTurnaround, 2> t;
  FrictionTransition tr;
  double phi = 0.0, advance = kNaN;
  bool ok() const { return unreached < 0 && fits && std::isfinite(advance); }
};

struct Setup {
  const PatternProblem* pr;
  MeridianLine line;
  bool transition = false;
  std::array<double, 2> apex_s = {0.0, 0.0};  // turnarounds: the apex per end
  double c = 0.0, step = 2.0, c_top = 0.0;
  double span_lo = 0.0, span_hi = 0.0;  // transition: the largest-radius part (meridian s)
};

Trial evaluate_turnarounds(const Setup& su, double lambda, double c) {
  const PatternProblem& pr = *su.pr;
  Trial tr;
  tr.lambda = lambda;
  tr.c = c;
  for (int e : {0, 1}) {
    tr.fe[e] = pr.narrows ? std::abs(c - pr.apex_c[e]) > 1e-6 * pr.largest_radius
                          : pr.end_radius[e] >= su.c;
  }
  for (int e : {0, 1}) {
    if (!tr.fe[e]) continue;
    tr.t[e] = friction_turnaround(su.line, e, su.apex_s[e], c, lambda, su.step, pr.narrows);
    if (!tr.t[e].reached) {
      tr.unreached = e;
      return tr;
    }
  }
  const double x0 = tr.fe[0] ? tr.t[0].join_x : kNaN;
  const double x1 = tr.fe[1] ? tr.t[1].join_x : kNaN;
  if (tr.fe[0] && tr.fe[1] && !(x0 < x1)) {
    tr.fits = false;
    return tr;
  }
  try {
    const std::vector<Vec2> m = clip_meridian(pr.meridian, x0, x1);
    if (m.size() < 2) throw InputError("no pass");
    tr.phi = clairaut_pass_angle(m, c);
  } catch (const InputError&) {
    tr.fits = false;
    return tr;
  }
  tr.advance = 2.0 * tr.phi + (tr.fe[0] ? tr.t[0].angle : 0.0) + (tr.fe[1] ? tr.t[1].angle : 0.0);
  return tr;
}

// The transition's axial extent on a cylinder of radius R (closed form,
// planner/winding/semi_geodesic.h).
double transition_extent(double R, double c0, double c1, double lambda) {
  return R * std::abs(R / c0 - R / c1) / lambda;
}

Trial evaluate_transition(const Setup& su, double lambda, double delta) {
  const PatternProblem& pr = *su.pr;
  Trial tr;
  tr.lambda = lambda;
  tr.delta = delta;
  const double c0 = pr.apex_c[0] + delta, c1 = pr.apex_c[1] + delta;
  tr.c = c0;
  const double R = pr.largest_radius;
  const double start = 0.5 * (su.span_lo + su.span_hi) - 0.5 * transition_extent(R, c0, c1, lambda);
  if (!(c0 <= su.c_top && c1 <= su.c_top) || start < su.span_lo) {
    tr.fits = false;
    return tr;
  }
  tr.tr = friction_transition(su.line, start, c0, c1, lambda, su.span_hi, su.step);
  if (!tr.tr.reached) {
    tr.fits = false;
    return tr;
  }
  try {
    tr.phi = clairaut_pass_angle(clip_meridian(pr.meridian, kNaN, tr.tr.start_x), c0) +
             clairaut_pass_angle(clip_meridian(pr.meridian, tr.tr.end_x, kNaN), c1);
  } catch (const InputError&) {
    tr.fits = false;
    return tr;
  }
  tr.advance = 2.0 * (tr.phi + tr.tr.angle);
  return tr;
}

// The smallest slippage in (bound, 1] for which `ok(lambda)` holds (NaN: none up to 1).
double needed_slippage(double bound, const std::function<bool(double)>& ok) {
  if (!ok(1.0)) return kNaN;
  double lo = bound, hi = 1.0;
  for (int it = 0; it < 10; ++it) {
    const double mid = 0.5 * (lo + hi);
    (ok(mid) ? hi : lo) = mid;
  }
  return hi;
}

std::string would_need(double lambda, const WindingOptions& o) {
  if (std::isnan(lambda)) return "no slippage up to 1 would do it";
  return "it would need winding.slippage >= " +
         format_fixed(std::ceil(lambda * 1000.0) / 1000.0, 3) +
         (lambda > o.mu
              ? " (above winding.mu = " + format_fixed(o.mu, 3) + ": the fibre would slip)"
              : " (<= winding.mu = " + format_fixed(o.mu, 3) + ")");
}

[[noreturn]] void refuse(const Setup& su, const Trial& tr, const WindingOptions& o) {
  const PatternProblem& pr = *su.pr;
  const std::string head = "winding.slippage = " + format_fixed(o.slippage, 3) + ": ";
  const double need =
      needed_slippage(o.slippage, [&](double l) { return evaluate_turnarounds(su, l, su.c).ok(); });
  const std::string alt = ", raise the winding angle, or wind that end on pins (slippage 0)";
  if (tr.unreached >= 0) {
    const FrictionTurnaround& t = tr.t[tr.unreached];
    const bool up = su.c > t.apex_r;
    throw ConfigError(
        head + "at the " + end_name(tr.unreached) + " end friction turns the " +
        "fibre around on the parallel r = " + format_fixed(t.apex_r, 2) + " mm (" +
        (pr.narrows ? "the dome's turnaround" : "apex half a band in from the end") +
        ") but brings r sin a only " + (up ? "up" : "down") + " to " + format_fixed(t.lowest, 2) +
        " mm within the wound region, not to the passes' " + "Clairaut constant " +
        format_fixed(su.c, 2) + " mm (" + pr.requested_by + "); " + would_need(need, o) +
        (pr.narrows ? "; or ask a winding angle nearer the geodesic's" : alt));
  }
  double total = 0.0;
  std::ostringstream per;
  for (int e : {0, 1}) {
    if (!tr.fe[e]) continue;
    const double ext = std::abs(tr.t[e].apex_x - tr.t[e].join_x) + 0.5 * pr.band_width;
    total += ext;
    per << (per.tellp() > 0 ? ", " : "") << format_fixed(ext, 1) << " mm at the " << end_name(e)
        << " end";
  }
  const double region = pr.meridian.back().x() - pr.meridian.front().x();
  throw ConfigError(
      head + "the friction turnarounds need " + format_fixed(total, 1) + " mm along the axis (" +
      per.str() + ": from the pass angle " +
      format_fixed(std::asin(std::min(1.0, su.c / pr.largest_radius)) * 180.0 / M_PI, 2) +
      " deg to 90 deg at |k_g/k_n| <= " + format_fixed(o.slippage, 3) + ") and a geodesic " +
      "pass between them, but the wound region is " + format_fixed(region, 1) + " mm long; " +
      would_need(need, o) + alt);
}

// The candidates to close, in the order the job asks. A friction plan's advance is not the
// geodesic's, so on domes every skip coprime to K is a candidate (not only those a geodesic
// closes in the window).
std::vector<PatternCandidate> candidates(const PatternProblem& pr, const WindingOptions& o) {
  PatternProblem open = pr;
  if (pr.narrows) {
    open.domes = false;
    open.end_radius = {pr.largest_radius, pr.largest_radius};  // every (K, p), dwell ends
    open.c_lo = open.c_hi = pr.requested_c;
  }
  std::vector<PatternCandidate> all = pattern_candidates(open);
  if (o.circuits > 0) {
    const int K = o.circuits;
    all.erase(std::remove_if(all.begin(), all.end(),
                             [&](const PatternCandidate& k) { return k.circuits != K; }),
              all.end());
    if (all.empty()) {
      for (int p = K == 1 ? 0 : 1; p < std::max(1, K); ++p) {
        if (std::gcd(p, K) == 1)
          all.push_back(pattern_for(open, K, p, open.c_lo, open.c_hi, open.requested_c));
      }
    }
  }
  if (o.skip > 0) {
    all.erase(std::remove_if(all.begin(), all.end(),
                             [&](const PatternCandidate& k) { return k.skip != o.skip; }),
              all.end());
  }
  return all;
}

// A one-parameter family of trials, u on a grid in order.
struct Family {
  std::vector<double> u;
  std::vector<Trial> trial;  // not ok(): a hole, no bracket across it
};

// The grid's trials are independent (each a pure function of u): evaluated in parallel, each
// into its own slot, so the family does not depend on the thread count.
template <typename Eval>
Family family(const std::vector<double>& u, Eval eval) {
  Family f;
  f.u = u;
  f.trial.resize(u.size());
  parallel_for_index(static_cast<int>(u.size()), [&](int i) { f.trial[i] = eval(u[i]); });
  return f;
}

// The trial where advance(u) = T between u0 and u1 (a0, a1 their advances, on either side of T):
// regula falsi with the Illinois step (the advance is smooth in u), ~10 evaluations instead of
// bisection's 60. not ok() when a trial between fails (a hole) or it does not converge.
template <typename Eval>
Trial root_between(Eval eval, double u0, double a0, double u1, double a1, double T, double* u_out) {
  double f0 = a0 - T, f1 = a1 - T;
  int side = 0;
  const Trial none;  // advance NaN: not ok()
  for (int it = 0; it < 80; ++it) {
    const double um = f1 != f0 ? u1 - f1 * (u1 - u0) / (f1 - f0) : 0.5 * (u0 + u1);
    const Trial t = eval(um);
    if (!t.ok()) return none;
    const double fm = t.advance - T;
    if (std::abs(fm) <= 1e-10 || std::abs(u1 - u0) <= 1e-13 * std::max(1.0, std::abs(um))) {
      *u_out = um;
      return std::abs(fm) <= 1e-6 ? t : none;
    }
    if ((fm < 0.0) == (f1 < 0.0)) {
      u1 = um;
      f1 = fm;
      if (side == -1) f0 *= 0.5;  // Illinois: halve the stale end's value
      side = -1;
    } else {
      u0 = um;
      f0 = fm;
      if (side == 1) f1 *= 0.5;
      side = 1;
    }
  }
  return none;
}

// Where a family's advance crosses 2 pi (m + p / K), m whole: the grid interval, the target and
// the crossing interpolated linearly (refined by root_between only when chosen).
struct Crossing {
  std::size_t interval = 0;  // between grid points interval - 1 and interval
  double target = 0.0, u_est = 0.0;
};

std::vector<Crossing> crossings(const Family& f, int K, int p) {
  std::vector<Crossing> out;
  const double base = kTwoPi * p / std::max(1, K);
  for (std::size_t i = 1; i < f.u.size(); ++i) {
    const Trial &a = f.trial[i - 1], &b = f.trial[i];
    if (!a.ok() || !b.ok()) continue;
    const double lo = std::min(a.advance, b.advance), hi = std::max(a.advance, b.advance);
    for (double m = std::ceil((lo - base) / kTwoPi - 1e-12); base + kTwoPi * m <= hi; m += 1.0) {
      const double T = base + kTwoPi * m;
      const double w = b.advance != a.advance ? (T - a.advance) / (b.advance - a.advance) : 0.5;
      out.push_back({i, T, f.u[i - 1] + w * (f.u[i] - f.u[i - 1])});
    }
  }
  return out;
}

// One way to close a pattern: a family of trials, how to evaluate between its grid points, and
// the parameter preferred.
struct Closer {
  Closer(std::function<Family()> m, std::function<Trial(double)> e, double p)
      : make(std::move(m)), eval(std::move(e)), prefer(p) {}
  std::function<Family()> make;  // built when first needed
  std::function<Trial(double)> eval;
  double prefer = 0.0;
  mutable std::optional<Family> family;
  const Family& get() const {
    if (!family) family = make();
    return *family;
  }
};

// The first K (in candidate order) that closes, by the first closer that closes it, with the
// skip whose crossing is nearest that closer's `prefer` (crossings are refined nearest first,
// so a K costs one root solve, not one per skip); false when none.
bool pick(const std::vector<PatternCandidate>& cands, const std::vector<Closer>& closers,
          PatternCandidate* cand, Trial* trial) {
  for (std::size_t i = 0; i < cands.size();) {
    std::size_t j = i;
    while (j < cands.size() && cands[j].circuits == cands[i].circuits) ++j;
    for (const Closer& cl : closers) {
      std::vector<std::pair<std::size_t, Crossing>> all;  // candidate, crossing
      for (std::size_t k = i; k < j; ++k) {
        for (const Crossing& x : crossings(cl.get(), cands[k].circuits, cands[k].skip))
          all.push_back({k, x});
      }
      std::stable_sort(all.begin(), all.end(), [&](const auto& a, const auto& b) {
        return std::abs(a.second.u_est - cl.prefer) < std::abs(b.second.u_est - cl.prefer);
      });
      const Family& f = cl.get();
      for (const auto& [k, x] : all) {
        double u = kNaN;
        const Trial t = root_between(cl.eval, f.u[x.interval - 1], f.trial[x.interval - 1].advance,
                                     f.u[x.interval], f.trial[x.interval].advance, x.target, &u);
        if (!t.ok()) continue;
        *cand = cands[k];
        *trial = t;
        return true;
      }
    }
    i = j;
  }
  return false;
}

std::vector<double> grid(double a, double b, int n) {
  std::vector<double> g;
  for (int i = 0; i <= n; ++i) g.push_back(a + (b - a) * i / n);
  return g;
}

FrictionWinding result(const Setup& su, const PatternCandidate& cand, const Trial& best,
                       double bound) {
  const PatternProblem& pr = *su.pr;
  FrictionWinding w;
  w.requested_c = pr.requested_c;
  if (getenv("FDBG"))
    fprintf(stderr,
            "result lambda %.4f c %.3f fe %d%d joins %.2f %.2f apex %.2f %.2f reached %d %d len "
            "%.1f %.1f\n",
            best.lambda, best.c, best.fe[0], best.fe[1], best.t[0].join_x, best.t[1].join_x,
            best.t[0].apex_x, best.t[1].apex_x, best.t[0].reached, best.t[1].reached,
            best.t[0].length, best.t[1].length);
  w.slippage = best.lambda;
  w.bound = bound;
  w.pattern = cand;
  if (su.transition) {
    const FrictionTransition& T = best.tr;
    w.transition = true;
    w.transition_path = T;
    const double c1 = T.c_to;
    const ClairautPass p0 =
        clairaut_pass(clip_meridian(pr.meridian, kNaN, T.start_x), T.c_from, {su.step});
    const ClairautPass p1 = clairaut_pass(clip_meridian(pr.meridian, T.end_x, kNaN), c1, {su.step});
    ClairautPass& out = w.pass;
    out.c = T.c_from;
    out.turns_around = {p0.turns_around[0], p1.turns_around[1]};
    out.samples = p0.samples;
    for (std::size_t i = 1; i < T.samples.size(); ++i) {
      PassSample q = T.samples[i];
      q.phi += p0.angle;
      q.length += p0.length;
      out.samples.push_back(q);
    }
    for (std::size_t i = 1; i < p1.samples.size(); ++i) {
      PassSample q = p1.samples[i];
      q.phi += p0.angle + T.angle;
      q.length += p0.length + T.length;
      out.samples.push_back(q);
    }
    out.angle = p0.angle + T.angle + p1.angle;
    out.length = p0.length + T.length + p1.length;
    w.pattern.moved = best.delta;
  } else {
    w.friction_end = best.fe;
    w.turnarounds = best.t;
    const double x0 = best.fe[0] ? best.t[0].join_x : kNaN;
    const double x1 = best.fe[1] ? best.t[1].join_x : kNaN;
    w.pass = clairaut_pass(clip_meridian(pr.meridian, x0, x1), best.c, {su.step});
    w.pattern.moved = best.c - pr.requested_c;
  }
  w.pattern.c = best.c;
  const double sa = std::min(1.0, best.c / pr.largest_radius);
  w.pattern.angle_deg = std::asin(sa) * 180.0 / M_PI;
  w.pattern.dwell = {0.0, 0.0};
  w.pattern.advance = best.advance;
  // Turns of a whole pass (friction parts included) on a vessel; between the joins at pipe ends.
  w.pattern.turns_per_pass = pr.narrows ? best.advance / (2.0 * kTwoPi) : best.phi / kTwoPi;
  return w;
}

[[noreturn]] void no_pattern(const WindingOptions& o, const std::string& how) {
  throw ConfigError("winding.slippage = " + format_fixed(o.slippage, 3) + ": no pattern" +
                    (o.circuits > 0 ? " with circuits " + std::to_string(o.circuits) : "") +
                    (o.skip > 0 ? " and skip " + std::to_string(o.skip) : "") + " closes " + how +
                    "; raise winding.slippage (<= winding.mu), widen winding.turnaround_window " +
                    "or change winding.pattern");
}

double window_of(const PatternProblem& pr, const WindingOptions& o) {
  return std::isfinite(o.turnaround_window) ? o.turnaround_window : 0.25 * pr.band_width;
}

// Geodesic domes on their own turnarounds joined by a friction transition on the cylinder.
FrictionWinding plan_transition(Setup& su, const WindingOptions& o) {
  const PatternProblem& pr = *su.pr;
  const double R = pr.largest_radius;
  // The largest-radius part of the meridian, where the transition lies.
  const std::vector<Vec2>& m = pr.meridian;
  su.span_lo = kNaN;
  for (std::size_t i = 0; i < m.size(); ++i) {
    if (m[i].y() < 0.999 * R) continue;  // the cylinder (a mesh section wavers by ~5e-4 R)
    if (std::isnan(su.span_lo)) su.span_lo = su.line.vertex_s(i);
    su.span_hi = su.line.vertex_s(i);
  }
  const double bound = o.slippage;
  const double c0 = pr.apex_c[0], c1 = pr.apex_c[1];
  const double span = su.span_hi - su.span_lo;
  // The lambda whose transition fills the cylinder: the extent formula is symmetric in lambda
  // and the extent (R |R / c0 - R / c1| = lambda * extent).
  const double lambda_min = span > 0.0 ? transition_extent(R, c0, c1, span) : kNaN;
  auto at = [&](double u) { return evaluate_transition(su, 1.0 / u, 0.0); };
  if (!at(1.0 / bound).ok()) {
    const double need = needed_slippage(bound, [&](double l) { return at(1.0 / l).ok(); });
    throw ConfigError("winding.slippage = " + format_fixed(bound, 3) +
                      ": the domes turn around on " + format_fixed(c0, 2) + " and " +
                      format_fixed(c1, 2) + " mm (each polar opening + half the " +
                      "band) and the passes join them by friction on the cylinder, which needs " +
                      format_fixed(transition_extent(R, c0, c1, bound), 1) + " mm of its " +
                      format_fixed(span, 1) + " mm at |k_g/k_n| <= " + format_fixed(bound, 3) +
                      "; " + would_need(need, o) +
                      ", or give winding.angle (friction on the domes instead)");
  }
  // lambda from the bound down to what fills the cylinder, evenly in 1 / lambda.
  const double u_max = 1.0 / std::max(lambda_min * 1.0001, bound / 8.0);
  const Family lam = family(grid(1.0 / bound, std::max(1.0 / bound, u_max), 64), at);
  // Per K: lambda first, then both turnarounds outward by delta in the window at the bound.
  auto moved = [&](double d) { return evaluate_transition(su, bound, d); };
  const std::vector<Closer> closers = {
      {[&] { return lam; }, at, 1.0 / bound},
      {[&] { return family(grid(0.0, window_of(pr, o), 48), moved); }, moved, 0.0}};
  PatternCandidate cand;
  Trial t;
  PatternProblem low = pr;  // the bands are widest along the circumference at the lower angle
  low.requested_c = std::min(c0, c1);
  if (pick(candidates(low, o), closers, &cand, &t)) return result(su, cand, t, bound);
  no_pattern(o, "with a friction transition at |k_g/k_n| in " + format_fixed(1.0 / u_max, 3) +
                    " .. " + format_fixed(bound, 3) + " (nor at " + format_fixed(bound, 3) +
                    " with the turnarounds moved " + "out within winding.turnaround_window)");
}

// winding.turns on domes with friction: the c whose whole pass makes those turns at the bound.
double c_for_turns(const Setup& su, const WindingOptions& o) {
  const PatternProblem& pr = *su.pr;
  const double target = pr.turns * 2.0 * kTwoPi;  // the circuit advance
  auto at = [&](double lambda, int n) {
    return family(grid(0.1 * pr.largest_radius, su.c_top, n),
                  [&](double c) { return evaluate_turnarounds(su, lambda, c); });
  };
  // The turns a pass can make at lambda (a grid of c).
  auto range = [](const Family& f, double* lo, double* hi) {
    *lo = std::numeric_limits<double>::infinity();
    *hi = -*lo;
    for (const Trial& t : f.trial) {
      if (!t.ok()) continue;
      *lo = std::min(*lo, t.advance / (2.0 * kTwoPi));
      *hi = std::max(*hi, t.advance / (2.0 * kTwoPi));
    }
  };
  const Family f = at(o.slippage, 64);
  double best = kNaN;
  for (std::size_t i = 1; i < f.u.size(); ++i) {
    const Trial &a = f.trial[i - 1], &b = f.trial[i];
    if (!a.ok() || !b.ok() || (a.advance - target) * (b.advance - target) > 0.0) continue;
    double root = kNaN;
    auto at_c = [&](double c) { return evaluate_turnarounds(su, o.slippage, c); };
    if (!root_between(at_c, f.u[i - 1], a.advance, f.u[i], b.advance, target, &root).ok()) continue;
    if (std::isnan(best) || std::abs(root - pr.requested_c) < std::abs(best - pr.requested_c))
      best = root;
  }
  if (std::isfinite(best)) return best;
  double lo = 0.0, hi = 0.0;
  range(f, &lo, &hi);
  const double need = needed_slippage(o.slippage, [&](double l) {
    double a = 0.0, b = 0.0;
    range(at(l, 24), &a, &b);
    return a <= pr.turns && pr.turns <= b;
  });
  throw ConfigError(
      "winding.turns = " + format_turns(pr.turns) + ": with the passes turning " + "around at " +
      format_fixed(pr.apex_c[0], 2) + " and " + format_fixed(pr.apex_c[1], 2) +
      " mm and friction up to |k_g/k_n| = " + format_fixed(o.slippage, 3) + " on the domes " +
      (std::isfinite(lo)
           ? "a pass makes " + format_fixed(lo, 3) + " .. " + format_fixed(hi, 3) + " turns"
           : std::string("no pass reaches the cylinder")) +
      "; " + would_need(need, o));
}

}  // namespace

bool wants_friction_turnarounds(const PatternProblem& pr, const WindingOptions& o) {
  if (!(o.slippage > 0.0) || !pr.reachable) return false;
  if (pr.narrows) {
    const double tol = 1e-6 * pr.largest_radius;
    if (pr.requested_by == "winding.angle" || std::isfinite(pr.turns)) {
      return std::abs(pr.requested_c - pr.apex_c[0]) > tol ||
             std::abs(pr.requested_c - pr.apex_c[1]) > tol || std::isfinite(pr.turns);
    }
    return std::abs(pr.apex_c[0] - pr.apex_c[1]) > tol;
  }
  if (pr.domes) return false;
  return pr.end_radius[0] >= pr.requested_c || pr.end_radius[1] >= pr.requested_c;
}

FrictionWinding plan_friction_winding(const PatternProblem& problem, const WindingOptions& o) {
  PatternProblem pr = problem;  // winding.turns on domes: requested_c is solved below
  const double step = std::clamp(0.125 * o.band_width, 0.25, 2.0);
  Setup su{&pr, MeridianLine(pr.meridian, 0.5 * o.band_width)};
  su.c = pr.requested_c;
  su.step = step;
  su.c_top = 0.999 * pr.largest_radius;  // a pass at R never leaves the largest parallel
  if (pr.narrows && !(pr.requested_by == "winding.angle" || std::isfinite(pr.turns))) {
    su.transition = true;
    return plan_transition(su, o);
  }
  const double half_band = 0.5 * pr.band_width;
  for (int e : {0, 1}) {
    if (pr.narrows) {
      su.apex_s[e] = su.line.at_radius(pr.apex_c[e], e);
      if (std::isnan(su.apex_s[e])) {
        throw ConfigError("winding.turnaround: the " + std::string(end_name(e)) + " dome never " +
                          "reaches the radius " + format_fixed(pr.apex_c[e], 2) + " mm");
      }
    } else {
      su.apex_s[e] = e == 0 ? half_band : su.line.length() - half_band;
    }
  }
  if (!pr.narrows) {
    for (int e : {0, 1}) {
      if (pr.end_radius[e] >= su.c && !(su.line.point(su.apex_s[e]).y() > su.c)) {
        throw ConfigError("winding.slippage: the " + std::string(end_name(e)) + " end's radius " +
                          format_fixed(su.line.point(su.apex_s[e]).y(), 2) +
                          " mm is not above the " + "turnaround radius " + format_fixed(su.c, 2) +
                          " mm (" + pr.requested_by + "): no friction turnaround can start there");
      }
    }
  }
  if (std::isfinite(pr.turns)) pr.requested_c = su.c = c_for_turns(su, o);
  const double bound = o.slippage;
  {
    const Trial first = evaluate_turnarounds(su, bound, su.c);
    if (!first.ok()) refuse(su, first, o);
  }
  // lambda from the bound down to bound / 4, evenly in 1 / lambda.
  auto at = [&](double u) { return evaluate_turnarounds(su, 1.0 / u, su.c); };
  Family lam = family(grid(1.0 / bound, 4.0 / bound, 96), at);
  for (std::size_t i = 1; i < lam.trial.size(); ++i) {  // up to the first that does not fit
    if (!lam.trial[i].ok()) {
      lam.u.resize(i);
      lam.trial.resize(i);
      break;
    }
  }
  std::vector<Closer> closers = {{[&] { return lam; }, at, 1.0 / bound}};
  // No lambda closes it (on domes lowering lambda soon makes the turnarounds outgrow the
  // region): at lambda = bound, move c within winding.turnaround_window, below the pipe ends'
  // radii and on the same side of each dome's turnaround.
  const double win = window_of(pr, o);
  double c_lo = std::max(1e-3 * su.c, su.c - win), c_hi = std::min(su.c + win, su.c_top);
  for (int e : {0, 1}) {
    const double eps = 1e-6 * pr.largest_radius;
    if (pr.narrows) {
      if (su.c > pr.apex_c[e]) c_lo = std::max(c_lo, pr.apex_c[e] + eps);
      if (su.c < pr.apex_c[e]) c_hi = std::min(c_hi, pr.apex_c[e] - eps);
    } else if (pr.end_radius[e] >= su.c) {
      c_hi = std::min(c_hi, pr.end_radius[e] * (1.0 - 1e-9));
    }
  }
  auto cat = [&](double c) { return evaluate_turnarounds(su, bound, c); };
  if (c_hi > c_lo) {
    closers.emplace_back([&, c_lo, c_hi] { return family(grid(c_lo, c_hi, 48), cat); }, cat, su.c);
  }
  PatternCandidate cand;
  Trial t;
  if (pick(candidates(pr, o), closers, &cand, &t)) return result(su, cand, t, bound);
  no_pattern(o, "with a friction turnaround at |k_g/k_n| in " + format_fixed(bound / 4.0, 3) +
                    " .. " + format_fixed(bound, 3) + " (nor at " + format_fixed(bound, 3) +
                    " with the passes' Clairaut " +
                    "constant within winding.turnaround_window) that fits the wound region");
}

FrictionFigures friction_figures(const FrictionWinding& w, const std::vector<Circuit>& circuits,
                                 double mu) {
  FrictionFigures f;
  f.planned = true;
  f.bound = w.bound;
  f.mu = mu;
  f.at_end = w.friction_end;
  for (int e : {0, 1}) {
    if (!w.friction_end[e]) continue;
    const FrictionTurnaround& t = w.turnarounds[e];
    f.lambda[e] = t.slippage;
    f.length[e] = t.length;
    f.axial[e] = std::abs(t.apex_x - t.join_x);
    f.angle_deg[e] = t.angle * 180.0 / M_PI;
    f.pass_angle_deg[e] = t.pass_angle * 180.0 / M_PI;
  }
  if (w.transition) {
    const FrictionTransition& T = w.transition_path;
    f.transition = true;
    f.pass_lambda = T.slippage;
    f.transition_c = {T.c_from, T.c_to};
    f.transition_length = T.length;
    f.transition_axial = std::abs(T.end_x - T.start_x);
    f.transition_angle_deg = T.angle * 180.0 / M_PI;
  }
  for (const Circuit& c : circuits) {
    // Roles of the segments in circuit order: out pass, far turnaround, return pass, start
    // turnaround; revolution_circuits splits each turnaround at its apex (two segments).
    const int n_fe = static_cast<int>(w.friction_end[0]) + static_cast<int>(w.friction_end[1]);
    const int per = c.segments.size() == static_cast<std::size_t>(2 + 2 * n_fe) ? 2 : 1;
    std::vector<int> roles = {-1};  // -1: a pass, 0 / 1: the turnaround at that end
    for (int k = 0; k < per && w.friction_end[1]; ++k) roles.push_back(1);
    roles.push_back(-1);
    for (int k = 0; k < per && w.friction_end[0]; ++k) roles.push_back(0);
    // A split start turnaround leads the circuit (it starts at its apex): rotate right by one.
    if (per == 2 && w.friction_end[0])
      std::rotate(roles.rbegin(), roles.rbegin() + 1, roles.rend());
    for (std::size_t i = 0; i < c.segments.size(); ++i) {
      const CircuitSegment& seg = c.segments[i];
      const int role = roles[i % roles.size()];
      // A segment's last point carries the next segment's annotation (append_circuit_segment),
      // except at the circuit's end.
      const int own_last = i + 1 < c.segments.size() ? seg.last - 1 : seg.last;
      double worst = 0.0;
      for (int j = seg.first; j <= own_last; ++j) worst = std::max(worst, c.points[j].slippage);
      if (role < 0) {
        f.pass_measured = std::max(f.pass_measured, worst);
        f.pass_length += c.points[seg.last].s - c.points[seg.first].s;
      } else {
        f.measured[role] = std::max(f.measured[role], worst);
      }
    }
  }
  return f;
}

}  // namespace windplan
