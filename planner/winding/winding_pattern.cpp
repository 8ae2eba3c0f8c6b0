#include "planner/winding/winding_pattern.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "planner/winding/clairaut_pass.h"
#include "planner/winding/helix.h"

namespace windplan {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Phi(c) sampled on the window, for the closing searches.
struct PhiGrid {
  std::vector<double> c, phi;
};

PhiGrid phi_grid(const PatternProblem& pr, double lo, double hi, int n = 240) {
  PhiGrid g;
  for (int i = 0; i <= n; ++i) {
    const double c = lo + (hi - lo) * i / n;
    g.c.push_back(c);
    g.phi.push_back(clairaut_pass_angle(pr.meridian, c));
  }
  return g;
}

// The c in the grid's range nearest `near` where 2 Phi(c) = 2 pi (m + p / K), m whole; NaN
// when none. Roots are bracketed on the grid and bisected on Phi itself.
double closing_c(const PatternProblem& pr, const PhiGrid& g, int K, int p, double near) {
  double best = kNaN;
  for (std::size_t i = 1; i < g.c.size(); ++i) {
    const double a = g.phi[i - 1], b = g.phi[i];
    if (!std::isfinite(a) || !std::isfinite(b)) continue;
    const double lo = std::min(a, b), hi = std::max(a, b);
    // Targets T = pi m + pi p / K in [lo, hi].
    const double base = M_PI * p / K;
    for (double m = std::ceil((lo - base) / M_PI - 1e-12); base + M_PI * m <= hi; m += 1.0) {
      const double T = base + M_PI * m;
      double x0 = g.c[i - 1], x1 = g.c[i], f0 = a - T;
      for (int it = 0; it < 60; ++it) {
        const double xm = 0.5 * (x0 + x1);
        const double fm = clairaut_pass_angle(pr.meridian, xm) - T;
        if ((fm < 0.0) == (f0 < 0.0)) {
          x0 = xm;
          f0 = fm;
        } else {
          x1 = xm;
        }
      }
      const double root = 0.5 * (x0 + x1);
      if (std::isnan(best) || std::abs(root - near) < std::abs(best - near)) best = root;
    }
  }
  return best;
}

PatternCandidate fill(const PatternProblem& pr, int K, int p, double c) {
  PatternCandidate k;
  k.circuits = K;
  k.skip = p;
  k.c = c;
  k.moved = c - pr.requested_c;
  const double R = pr.largest_radius;
  const double sa = std::min(1.0, c / R);
  k.angle_deg = std::asin(sa) * 180.0 / M_PI;
  const double ca = std::sqrt(std::max(0.0, 1.0 - sa * sa));
  const double phi = clairaut_pass_angle(pr.meridian, c);
  k.turns_per_pass = phi / kTwoPi;
  const bool dwell0 = pr.end_radius[0] >= c, dwell1 = pr.end_radius[1] >= c;
  const double target = kTwoPi * p / K;
  if (dwell0 && dwell1) {
    const double d = turnaround_dwell(k.turns_per_pass, K, p);
    k.dwell = {d, d};
  } else if (dwell0 || dwell1) {
    double d = std::fmod(target - 2.0 * phi, kTwoPi);
    while (d < M_PI) d += kTwoPi;
    while (d >= 3.0 * M_PI) d -= kTwoPi;
    k.dwell[dwell0 ? 0 : 1] = d;
  }
  k.advance = 2.0 * phi + k.dwell[0] + k.dwell[1];
  k.cover_factor = K * pr.band_width / (kTwoPi * R * ca);
  k.overlap = pr.band_width - kTwoPi * R * ca / K;
  return k;
}

int coverage_count(const PatternProblem& pr, double c) {
  const double sa = std::min(1.0, c / pr.largest_radius);
  const double ca = std::sqrt(std::max(0.0, 1.0 - sa * sa));
  return std::max(
      1, static_cast<int>(std::ceil(kTwoPi * pr.largest_radius * ca / pr.band_width - 1e-9)));
}

// Solves Phi(c) = target on [lo, hi] (Phi increasing there); NaN when out of range.
double solve_phi(const std::vector<Vec2>& m, double target, double lo, double hi) {
  auto f = [&](double c) { return clairaut_pass_angle(m, c) - target; };
  double flo = f(lo), fhi = f(hi);
  if (!(flo <= 0.0 && fhi >= 0.0)) return kNaN;
  for (int it = 0; it < 80; ++it) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The largest Clairaut constant whose pass exists: no point of the meridian may dip below c
// between the first and the last point with r >= c. A tessellated cylinder's radius wavers by
// the chord sagitta, so this is a little below the largest radius.
double largest_turnaround(const std::vector<Vec2>& m) {
  const std::size_t n = m.size();
  std::vector<double> left(n), right(n);
  for (std::size_t i = 0; i < n; ++i) left[i] = std::max(i ? left[i - 1] : 0.0, m[i].y());
  for (std::size_t i = n; i-- > 0;) right[i] = std::max(i + 1 < n ? right[i + 1] : 0.0, m[i].y());
  double top = left.back();
  for (std::size_t i = 0; i < n; ++i) {
    if (m[i].y() < std::min(left[i], right[i])) top = std::min(top, m[i].y());
  }
  return top * (1.0 - 1e-9);
}

}  // namespace

std::string PatternCandidate::name() const {
  return "K=" + std::to_string(circuits) + ", p=" + std::to_string(skip);
}

PatternProblem pattern_problem(const std::vector<Vec2>& meridian, const WindingOptions& o) {
  PatternProblem pr;
  pr.meridian = meridian;
  pr.band_width = o.band_width;
  for (const Vec2& p : meridian) pr.largest_radius = std::max(pr.largest_radius, p.y());
  pr.end_radius = {meridian.front().y(), meridian.back().y()};
  const double R = pr.largest_radius;
  const double r_open = std::max(pr.end_radius[0], pr.end_radius[1]);
  const bool narrows = pr.end_radius[0] < 0.95 * R && pr.end_radius[1] < 0.95 * R;
  const double c_top = largest_turnaround(meridian);
  pr.narrows = narrows;
  const bool friction_domes = narrows && o.slippage > 0.0;
  if (friction_domes) {
    for (int e : {0, 1}) {
      pr.apex_c[e] =
          std::isfinite(o.turnaround) ? o.turnaround : pr.end_radius[e] + 0.5 * o.band_width;
      if (!(pr.apex_c[e] > pr.end_radius[e] && pr.apex_c[e] <= c_top)) {
        throw ConfigError("winding.turnaround = " + format_fixed(pr.apex_c[e], 2) + " mm: with " +
                          "winding.slippage the passes turn around on this parallel at both " +
                          "domes, so it must lie between the polar openings (" +
                          format_fixed(pr.end_radius[0], 2) + ", " +
                          format_fixed(pr.end_radius[1], 2) + " mm) and " + format_fixed(c_top, 2) +
                          " mm");
      }
    }
  }
  auto check = [&](double c, const std::string& key, const std::string& value) {
    if (!(c <= c_top)) {
      throw ConfigError(key + " = " + value + " puts the turnaround at or beyond the largest " +
                        "radius R = " + format_fixed(R, 2) +
                        " mm: a geodesic there is a hoop and never " +
                        "leaves that parallel (the geodesic turn limit); use a turnaround " +
                        "radius below " + format_fixed(c_top, 2) + " mm");
    }
    // With winding.slippage the passes reach the dome's end by friction
    // (planner/winding/friction_winding.h): a Clairaut constant below the opening is then allowed.
    if (narrows && c < r_open && !(o.slippage > 0.0)) {
      throw ConfigError(
          key + " = " + value + " puts the turnaround below the polar opening " + "radius " +
          format_fixed(r_open, 2) + " mm: the pass would run off the dome into the " +
          "opening; use a turnaround radius >= " + format_fixed(r_open, 2) + " mm (" +
          format_fixed(r_open + 0.5 * o.band_width, 2) + " keeps the band's edge off the boss)" +
          ", or winding.slippage (<= mu) to turn around by friction");
    }
    if (!(c > 0.0)) throw ConfigError(key + " = " + value + ": must be > 0");
  };
  if (std::isfinite(o.turnaround)) {
    pr.requested_c = o.turnaround;
    pr.requested_by = "winding.turnaround";
    check(o.turnaround, pr.requested_by, format_fixed(o.turnaround, 2) + " mm");
  } else if (std::isfinite(o.angle)) {
    pr.requested_c = R * std::sin(o.angle * M_PI / 180.0);
    pr.requested_by = "winding.angle";
    check(pr.requested_c, pr.requested_by,
          format_fixed(o.angle, 2) + " deg (turnaround radius " + format_fixed(pr.requested_c, 2) +
              " mm)");
  } else if (narrows && !o.turns_given) {
    pr.requested_c = r_open + 0.5 * o.band_width;
    pr.requested_by = "winding.turnaround";
    check(pr.requested_c,
          "winding.turnaround (default: the polar opening radius + half the "
          "band width)",
          format_fixed(pr.requested_c, 2) + " mm");
  } else {
    // From the turns: on domes Phi(c) grows from the opening towards R; between dwell ends
    // from 0 to the smaller end radius.
    const double lo = narrows ? r_open : 1e-9 * R;
    const double hi = narrows ? c_top : std::min(pr.end_radius[0], pr.end_radius[1]);
    const double target = kTwoPi * o.turns;
    double c = solve_phi(meridian, target, lo, hi);
    if (friction_domes) {  // the friction plan solves c for the turns (friction_winding.h)
      pr.turns = o.turns;
      if (std::isnan(c)) c = std::max(pr.apex_c[0], pr.apex_c[1]);
    }
    if (std::isnan(c)) {
      const double at_lo = clairaut_pass_angle(meridian, lo) / kTwoPi;
      const double at_hi = clairaut_pass_angle(meridian, hi) / kTwoPi;
      std::ostringstream s;
      s << "winding.turns = " << format_turns(o.turns) << ": a geodesic ";
      if (narrows) {
        s << "turning around on the domes makes " << format_turns(at_lo)
          << " turns per pass with its turnaround at the polar opening (" << format_fixed(lo, 2)
          << " mm) and more as the turnaround moves out; use turns >= "
          << format_turns(std::ceil(100.0 * at_lo) / 100.0)
          << ", winding.turnaround / winding.angle, or winding.slippage (<= mu) to turn "
             "around at the opening by friction";
      } else {
        s << "between the ends makes at most " << format_turns(at_hi)
          << " turns per pass (the geodesic turn limit)";
        pr.reachable = false;
        pr.why = s.str();
        return pr;
      }
      throw ConfigError(s.str());
    }
    pr.requested_c = c;
    pr.requested_by = "winding.turns";
  }
  const double c = pr.requested_c;
  pr.domes = pr.end_radius[0] < c && pr.end_radius[1] < c;
  const double w = std::isfinite(o.turnaround_window) ? o.turnaround_window : 0.25 * o.band_width;
  if (pr.domes) {
    const bool upward = pr.requested_by == "winding.turnaround";
    pr.c_lo = upward ? c : std::max(r_open, c - 0.5 * w);
    pr.c_hi = std::min(c_top, upward ? c + w : c + 0.5 * w);
    if (narrows) pr.c_lo = std::max(pr.c_lo, r_open);
  } else {
    pr.c_lo = pr.c_hi = c;
  }
  return pr;
}

PatternCandidate pattern_for(const PatternProblem& pr, int K, int p, double lo, double hi,
                             double near) {
  if (!pr.domes) return fill(pr, K, p, pr.requested_c);
  const PhiGrid g = phi_grid(pr, lo, hi);
  const double c = closing_c(pr, g, K, p, near);
  if (std::isnan(c)) {
    PatternCandidate k;
    k.circuits = K;
    k.skip = p;
    k.c = kNaN;
    return k;
  }
  return fill(pr, K, p, c);
}

std::vector<PatternCandidate> pattern_candidates(const PatternProblem& pr) {
  std::vector<PatternCandidate> out;
  const int kc = coverage_count(pr, pr.requested_c);
  PhiGrid g;
  if (pr.domes) g = phi_grid(pr, pr.c_lo, pr.c_hi);
  for (int K = std::max(1, kc - 2); K <= kc + 3; ++K) {
    for (int p = K == 1 ? 0 : 1; p < std::max(1, K); ++p) {
      if (std::gcd(p, K) != 1) continue;
      if (!pr.domes) {
        out.push_back(fill(pr, K, p, pr.requested_c));
        continue;
      }
      const double c = closing_c(pr, g, K, p, pr.requested_c);
      if (!std::isnan(c)) out.push_back(fill(pr, K, p, c));
    }
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const PatternCandidate& a, const PatternCandidate& b) {
                     if (a.full_cover() != b.full_cover()) return a.full_cover();
                     if (a.circuits != b.circuits) return a.circuits < b.circuits;
                     if (std::abs(a.moved) != std::abs(b.moved))
                       return std::abs(a.moved) < std::abs(b.moved);
                     return a.skip < b.skip;
                   });
  return out;
}

PatternCandidate choose_pattern(const PatternProblem& pr, const WindingOptions& o) {
  const int K = o.circuits;
  if (K > 0) {
    if (o.skip > 0 || K == 1) {
      const int p = K == 1 ? 0 : o.skip;
      if (std::gcd(p, K) != 1 || p >= std::max(1, K)) {
        throw ConfigError("winding.pattern: circuits " + std::to_string(K) + " and skip " +
                          std::to_string(p) + " are not coprime (or skip >= circuits): the " +
                          "circuits would close into " + std::to_string(std::gcd(p, K)) +
                          " separate patterns; choose a skip coprime to " + std::to_string(K));
      }
      PatternCandidate k = pattern_for(pr, K, p, pr.c_lo, pr.c_hi, pr.requested_c);
      if (std::isnan(k.c)) {
        // Where would it close? Search the whole range of turnaround radii.
        const double lo = std::max(pr.end_radius[0], pr.end_radius[1]);
        // Up to 85 deg on the largest parallel: beyond, Phi grows without bound (the hoop).
        const double hi = std::min(largest_turnaround(pr.meridian),
                                   pr.largest_radius * std::sin(85.0 * M_PI / 180.0));
        const PatternCandidate any = pattern_for(pr, K, p, lo, hi, pr.requested_c);
        throw ConfigError("winding.pattern: K=" + std::to_string(K) + ", p=" + std::to_string(p) +
                          " closes with no turnaround radius in " + format_fixed(pr.c_lo, 2) +
                          " .. " + format_fixed(pr.c_hi, 2) + " mm (" + pr.requested_by + " asks " +
                          format_fixed(pr.requested_c, 2) + " mm)" +
                          (std::isnan(any.c)
                               ? std::string(" nor anywhere on this mandrel")
                               : "; the nearest that closes it is " + format_fixed(any.c, 3) +
                                     " mm (set winding.turnaround or widen "
                                     "winding.turnaround_window)"));
      }
      return k;
    }
    // K given, p free: the candidate with that K nearest the request.
    for (const PatternCandidate& k : pattern_candidates(pr)) {
      if (k.circuits == K) return k;
    }
    // K far from the coverage count: search its p directly (on domes over one Phi grid).
    const PhiGrid g = pr.domes ? phi_grid(pr, pr.c_lo, pr.c_hi) : PhiGrid{};
    for (int p = 1; p < K; ++p) {
      if (std::gcd(p, K) != 1) continue;
      if (!pr.domes) return fill(pr, K, p, pr.requested_c);
      const double c = closing_c(pr, g, K, p, pr.requested_c);
      if (!std::isnan(c)) return fill(pr, K, p, c);
    }
    throw ConfigError("winding.circuits: no skip closes K=" + std::to_string(K) +
                      " circuits with a turnaround radius in " + format_fixed(pr.c_lo, 2) + " .. " +
                      format_fixed(pr.c_hi, 2) +
                      " mm; widen winding.turnaround_window or change K");
  }
  std::vector<PatternCandidate> all = pattern_candidates(pr);
  if (o.skip > 0) {
    all.erase(std::remove_if(all.begin(), all.end(),
                             [&](const PatternCandidate& k) { return k.skip != o.skip; }),
              all.end());
  }
  if (all.empty()) {
    throw ConfigError(
        "winding.pattern: auto found no closing pattern with a turnaround radius "
        "in " +
        format_fixed(pr.c_lo, 2) + " .. " + format_fixed(pr.c_hi, 2) + " mm" +
        (o.skip > 0 ? " and skip " + std::to_string(o.skip) : std::string()) +
        "; widen winding.turnaround_window");
  }
  return all.front();
}

}  // namespace windplan
