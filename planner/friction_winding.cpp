#include "planner/friction_winding.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "geometry/errors.h"
#include "planner/revolution_winding.h"

namespace windplan {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string num(double v, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v + 0.0;
  return s.str();
}

const char* end_name(int e) { return e == 0 ? "start" : "far"; }

// The turnarounds, pass angle and circuit advance at one lambda.
struct Trial {
  double lambda = 0.0, c = 0.0;
  int unreached = -1;  // an end where friction never turns the fibre back to c
  bool fits = true;    // the joins leave a geodesic pass between them
  std::array<FrictionTurnaround, 2> t;
  double phi = 0.0, advance = 0.0;
};

struct Setup {
  const PatternProblem* pr;
  MeridianLine line;
  std::array<bool, 2> fe;
  std::array<double, 2> apex_s;
  double c, step;
};

Trial evaluate(const Setup& su, double lambda, double c) {
  Trial tr;
  tr.lambda = lambda;
  tr.c = c;
  for (int e : {0, 1}) {
    if (!su.fe[e]) continue;
    tr.t[e] = friction_turnaround(su.line, e, su.apex_s[e], c, lambda, su.step);
    if (!tr.t[e].reached) {
      tr.unreached = e;
      return tr;
    }
  }
  const double x0 = su.fe[0] ? tr.t[0].join_x : kNaN;
  const double x1 = su.fe[1] ? tr.t[1].join_x : kNaN;
  if (su.fe[0] && su.fe[1] && !(x0 < x1)) {
    tr.fits = false;
    return tr;
  }
  try {
    const std::vector<Vec2> m = clip_meridian(su.pr->meridian, x0, x1);
    if (m.size() < 2) throw InputError("no pass");
    tr.phi = clairaut_pass_angle(m, c);
  } catch (const InputError&) {
    tr.fits = false;
    return tr;
  }
  tr.advance = 2.0 * tr.phi + (su.fe[0] ? tr.t[0].angle : 0.0) + (su.fe[1] ? tr.t[1].angle : 0.0);
  return tr;
}

[[noreturn]] void refuse(const Setup& su, const Trial& tr, const WindingOptions& o) {
  const PatternProblem& pr = *su.pr;
  const std::string head = "winding.slippage = " + num(o.slippage, 3) + ": ";
  const std::string raise = "raise winding.slippage (<= winding.mu = " + num(o.mu, 3) + ")";
  if (tr.unreached >= 0) {
    const FrictionTurnaround& t = tr.t[tr.unreached];
    throw ConfigError(head + "at the " + end_name(tr.unreached) + " end friction turns the " +
                      "fibre around on the parallel r = " + num(t.apex_r, 2) + " mm (apex half a " +
                      "band in from the end) but brings r sin a only down to " + num(t.lowest, 2) +
                      " mm within the wound region, not to the passes' " + "Clairaut constant " +
                      num(su.c, 2) + " mm (" + pr.requested_by + "); " + raise +
                      ", raise the winding angle, or wind that end on pins (slippage 0)");
  }
  double need = 0.0;
  std::ostringstream per;
  for (int e : {0, 1}) {
    if (!su.fe[e]) continue;
    const double ext = std::abs(tr.t[e].apex_x - tr.t[e].join_x) + 0.5 * pr.band_width;
    need += ext;
    per << (per.tellp() > 0 ? ", " : "") << num(ext, 1) << " mm at the " << end_name(e) << " end";
  }
  const double region = pr.meridian.back().x() - pr.meridian.front().x();
  throw ConfigError(head + "the friction turnarounds need " + num(need, 1) +
                    " mm along the axis (" + per.str() + ": from the pass angle " +
                    num(std::asin(std::min(1.0, su.c / pr.largest_radius)) * 180.0 / M_PI, 2) +
                    " deg to 90 deg at |k_g/k_n| <= " + num(o.slippage, 3) + ", apex half a " +
                    "band in from the end) and a geodesic pass between them, but the wound " +
                    "region is " + num(region, 1) + " mm long; " + raise +
                    ", raise the winding angle, or wind a longer region");
}

// The candidates to close, in the order the job asks.
std::vector<PatternCandidate> candidates(const PatternProblem& pr, const WindingOptions& o) {
  std::vector<PatternCandidate> all = pattern_candidates(pr);
  if (o.circuits > 0) {
    const int K = o.circuits;
    all.erase(std::remove_if(all.begin(), all.end(),
                             [&](const PatternCandidate& k) { return k.circuits != K; }),
              all.end());
    if (all.empty()) {
      for (int p = K == 1 ? 0 : 1; p < std::max(1, K); ++p) {
        if (std::gcd(p, K) == 1)
          all.push_back(pattern_for(pr, K, p, pr.c_lo, pr.c_hi, pr.requested_c));
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

FrictionWinding result(const Setup& su, const PatternCandidate& cand, const Trial& best,
                       double bound) {
  const PatternProblem& pr = *su.pr;
  FrictionWinding w;
  w.friction_end = su.fe;
  w.turnarounds = best.t;
  w.slippage = best.lambda;
  w.bound = bound;
  const double x0 = su.fe[0] ? best.t[0].join_x : kNaN;
  const double x1 = su.fe[1] ? best.t[1].join_x : kNaN;
  w.pass = clairaut_pass(clip_meridian(pr.meridian, x0, x1), best.c, {su.step});
  w.pattern = cand;
  w.pattern.c = best.c;
  w.pattern.moved = best.c - pr.requested_c;
  const double sa = std::min(1.0, best.c / pr.largest_radius);
  w.pattern.angle_deg = std::asin(sa) * 180.0 / M_PI;
  w.pattern.dwell = {0.0, 0.0};
  w.pattern.advance = best.advance;
  w.pattern.turns_per_pass = best.phi / kTwoPi;
  return w;
}

}  // namespace

bool wants_friction_turnarounds(const PatternProblem& pr, const WindingOptions& o) {
  if (!(o.slippage > 0.0) || pr.domes || !pr.reachable) return false;
  return pr.end_radius[0] >= pr.requested_c || pr.end_radius[1] >= pr.requested_c;
}

FrictionWinding plan_friction_winding(const PatternProblem& pr, const WindingOptions& o) {
  const double step = std::clamp(0.125 * o.band_width, 0.25, 2.0);
  Setup su{&pr, MeridianLine(pr.meridian), {false, false}, {0.0, 0.0}, pr.requested_c, step};
  for (int e : {0, 1}) su.fe[e] = pr.end_radius[e] >= su.c;
  const double half_band = 0.5 * pr.band_width;
  su.apex_s = {half_band, su.line.length() - half_band};
  for (int e : {0, 1}) {
    if (su.fe[e] && !(su.line.point(su.apex_s[e]).y() > su.c)) {
      throw ConfigError("winding.slippage: the " + std::string(end_name(e)) + " end's radius " +
                        num(su.line.point(su.apex_s[e]).y(), 2) + " mm is not above the " +
                        "turnaround radius " + num(su.c, 2) + " mm (" + pr.requested_by +
                        "): no friction turnaround can start there");
    }
  }
  // lambda from the bound down to bound / 4, evenly in 1 / lambda.
  const double bound = o.slippage;
  constexpr int kGrid = 96;
  std::vector<Trial> grid;
  for (int i = 0; i <= kGrid; ++i) {
    const double u = (1.0 + 3.0 * i / kGrid) / bound;
    Trial tr = evaluate(su, 1.0 / u, su.c);
    if (tr.unreached >= 0 || !tr.fits) {
      if (i == 0) refuse(su, tr, o);
      break;
    }
    grid.push_back(std::move(tr));
  }
  for (const PatternCandidate& cand : candidates(pr, o)) {
    const int K = cand.circuits, p = cand.skip;
    const double base = kTwoPi * p / std::max(1, K);
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const double a = grid[i == 0 ? 0 : i - 1].advance, b = grid[i].advance;
      const double lo = std::min(a, b), hi = std::max(a, b);
      const double m = std::ceil((lo - base) / kTwoPi - 1e-12);
      const double T = base + kTwoPi * m;
      if (T > hi + 1e-12) continue;
      // Bisect on 1 / lambda between the two grid points.
      double u0 = 1.0 / grid[i == 0 ? 0 : i - 1].lambda, u1 = 1.0 / grid[i].lambda;
      const bool rising = b >= a;
      for (int it = 0; it < 60 && i > 0; ++it) {
        const double um = 0.5 * (u0 + u1);
        const Trial t = evaluate(su, 1.0 / um, su.c);
        ((t.advance < T) == rising ? u0 : u1) = um;
      }
      const Trial best = evaluate(su, 1.0 / (i == 0 ? u0 : 0.5 * (u0 + u1)), su.c);
      if (best.unreached >= 0 || !best.fits) continue;
      return result(su, cand, best, bound);
    }
  }
  // No lambda closes it (on domes friction moves r sin a slowly, so the turnarounds soon
  // outgrow the region as lambda falls): at lambda = bound, move the passes' c within
  // winding.turnaround_window, keeping it below the friction ends' radii.
  const double win =
      std::isfinite(o.turnaround_window) ? o.turnaround_window : 0.25 * pr.band_width;
  double c_lo = std::max(1e-3 * su.c, su.c - win), c_hi = su.c + win;
  for (int e : {0, 1}) {
    if (su.fe[e]) c_hi = std::min(c_hi, pr.end_radius[e] * (1.0 - 1e-9));
  }
  std::vector<Trial> cg;
  for (int i = 0; i <= kGrid && c_hi > c_lo; ++i) {
    Trial tr = evaluate(su, bound, c_lo + (c_hi - c_lo) * i / kGrid);
    if (tr.unreached < 0 && tr.fits)
      cg.push_back(std::move(tr));
    else
      cg.push_back(Trial{});  // a hole: no bracket across it
  }
  for (const PatternCandidate& cand : candidates(pr, o)) {
    const int K = cand.circuits, p = cand.skip;
    const double base = kTwoPi * p / std::max(1, K);
    double best_c = kNaN;
    for (std::size_t i = 1; i < cg.size(); ++i) {
      if (cg[i - 1].c == 0.0 || cg[i].c == 0.0) continue;
      const double a = cg[i - 1].advance, b = cg[i].advance;
      const double lo = std::min(a, b), hi = std::max(a, b);
      for (double m = std::ceil((lo - base) / kTwoPi - 1e-12); base + kTwoPi * m <= hi; m += 1.0) {
        const double T = base + kTwoPi * m;
        double x0 = cg[i - 1].c, x1 = cg[i].c;
        const bool rising = b >= a;
        for (int it = 0; it < 60; ++it) {
          const double xm = 0.5 * (x0 + x1);
          const Trial t = evaluate(su, bound, xm);
          if (t.unreached >= 0 || !t.fits) break;
          ((t.advance < T) == rising ? x0 : x1) = xm;
        }
        const double root = 0.5 * (x0 + x1);
        if (std::isnan(best_c) || std::abs(root - su.c) < std::abs(best_c - su.c)) best_c = root;
      }
    }
    if (std::isnan(best_c)) continue;
    const Trial best = evaluate(su, bound, best_c);
    if (best.unreached >= 0 || !best.fits) continue;
    return result(su, cand, best, bound);
  }
  throw ConfigError("winding.slippage = " + num(bound, 3) + ": no pattern" +
                    (o.circuits > 0 ? " with circuits " + std::to_string(o.circuits) : "") +
                    (o.skip > 0 ? " and skip " + std::to_string(o.skip) : "") +
                    " closes with a friction turnaround at |k_g/k_n| in " + num(bound / 4.0, 3) +
                    " .. " + num(bound, 3) + " (nor at " + num(bound, 3) + " with the turnaround " +
                    "radius within winding.turnaround_window) that fits the wound region; raise " +
                    "winding.slippage (<= winding.mu), widen winding.turnaround_window or change " +
                    "winding.pattern");
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
  // Roles of the segments in circuit order.
  std::vector<int> roles = {-1};  // -1: a pass, 0 / 1: the turnaround at that end
  if (w.friction_end[1]) roles.push_back(1);
  roles.push_back(-1);
  if (w.friction_end[0]) roles.push_back(0);
  for (const Circuit& c : circuits) {
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
