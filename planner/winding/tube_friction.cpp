#include "planner/winding/tube_friction.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numeric>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "geometry/base/parallel.h"
#include "geometry/mesh/closest_point.h"
#include "planner/winding/fibre_metrics.h"

namespace windplan {

namespace {

constexpr double kStep = 1.0;  // mm of fibre per RK4 step

struct State {
  double s = 0.0, th = 0.0, a = 0.0;
};

// One stretch of fibre: a held (pass) or turned by friction at lambda on side sigma.
struct Law {
  bool hold = true;
  int sigma = 1;
  double lambda = 0.0;
};

// The rates with the piece `pc` fixed over a step (its formulas are smooth beyond its ends).
State rate(const TubeSurface& line, const State& y, const Law& law, int pc) {
  const TubeSurface::Rates q = line.rates(pc, y.s, y.th, y.a);
  State d;
  d.s = q.ds;
  d.th = q.dth;
  d.a = law.hold ? 0.0 : -q.w + law.sigma * law.lambda * q.k_n;
  return d;
}

State rk4(const TubeSurface& line, const State& y, double h, const Law& law, int b) {
  auto add = [](const State& a, const State& c, double t) {
    return State{a.s + t * c.s, a.th + t * c.th, a.a + t * c.a};
  };
  const State k1 = rate(line, y, law, b);
  const State k2 = rate(line, add(y, k1, 0.5 * h), law, b);
  const State k3 = rate(line, add(y, k2, 0.5 * h), law, b);
  const State k4 = rate(line, add(y, k3, h), law, b);
  State n = y;
  n.s += h / 6.0 * (k1.s + 2 * k2.s + 2 * k3.s + k4.s);
  n.th += h / 6.0 * (k1.th + 2 * k2.th + 2 * k3.th + k4.th);
  n.a += h / 6.0 * (k1.a + 2 * k2.a + 2 * k3.a + k4.a);
  return n;
}

// The largest step in (lo, hi] whose end keeps g(end) on the side of `neg` (bisection): where
// g changes sign within the step, to ~1e-15 of it.
template <typename G>
double bisect_step(const TubeSurface& line, const State& y, const Law& law, int b, double hi,
                   bool neg, G g) {
  double lo = 0.0;
  for (int it = 0; it < 55; ++it) {
    const double mid = 0.5 * (lo + hi);
    ((g(rk4(line, y, mid, law, b)) < 0.0) != neg ? hi : lo) = mid;
  }
  return hi;
}

// One step of a trace from y: 1 mm, cut to end on a piece's end (so that a step never mixes two
// pieces' rates: the path is then smooth in its start, which the pattern's root finding needs).
struct Step {
  State y, n;  // from, to
  double h = 0.0;
  int piece = -1;
};

Step next_step(const TubeSurface& line, const State& y, const Law& law,
               const std::vector<double>& edges) {
  Step st;
  st.y = y;
  st.piece = line.piece_at(y.s + (std::cos(y.a) >= 0.0 ? 1e-9 : -1e-9));
  st.h = kStep;
  st.n = rk4(line, y, st.h, law, st.piece);
  for (double edge : edges) {
    if ((y.s - edge) * (st.n.s - edge) < 0.0) {
      st.h = bisect_step(line, y, law, st.piece, st.h, y.s < edge,
                         [edge](const State& q) { return q.s - edge; });
      st.n = rk4(line, y, st.h, law, st.piece);
    }
  }
  return st;
}

// The step `st` ended past the event: the part of it up to the event (bisection).
State last_step(const TubeSurface& line, const Step& st, const Law& law, bool neg0,
                const std::function<double(const State&)>& event, double* h) {
  *h = bisect_step(line, st.y, law, st.piece, st.h, neg0, event);
  return rk4(line, st.y, *h, law, st.piece);
}

constexpr char kNoEnd[] = "winding.slippage: a friction path never met its end in 100 m of fibre";

// Traces from y until event(y) changes sign (located by bisection on the last step); appends
// the states after y to `out` when given. Returns the end state; `length` adds the fibre.
State trace(const TubeSurface& line, State y, const Law& law,
            const std::function<double(const State&)>& event, std::vector<State>* out,
            double* length) {
  const bool neg0 = event(y) < 0.0;
  const std::vector<double> edges = line.piece_ends();
  for (double l = 0.0; l < 1e5;) {
    const Step st = next_step(line, y, law, edges);
    if ((event(st.n) < 0.0) != neg0) {
      double h = 0.0;
      const State n = last_step(line, st, law, neg0, event, &h);
      if (out) out->push_back(n);
      *length += h;
      return n;
    }
    if (out) out->push_back(st.n);
    *length += st.h;
    l += st.h;
    y = st.n;
  }
  throw ConfigError(kNoEnd);
}

// A pass (held at its angle) from y0, its steps kept: traced to a station `leave` again and
// again (the shooting for a turnaround's apex) it is stepped once; the same steps, so the same
// states, as trace() would take.
class HeldPass {
 public:
  HeldPass(const TubeSurface& line, const State& y0)
      : line_(line), y0_(y0), edges_(line.piece_ends()) {}
  State to_station(double leave, std::vector<State>* out, double* length) {
    auto event = [leave](const State& y) { return y.s - leave; };
    const bool neg0 = event(y0_) < 0.0;
    double l = 0.0;
    for (std::size_t i = 0;; ++i) {
      if (i == steps_.size()) {
        if (l >= 1e5) throw ConfigError(kNoEnd);
        steps_.push_back(next_step(line_, i == 0 ? y0_ : steps_.back().n, kHold, edges_));
      }
      const Step& st = steps_[i];
      if ((event(st.n) < 0.0) != neg0) {
        double h = 0.0;
        const State n = last_step(line_, st, kHold, neg0, event, &h);
        if (out) out->push_back(n);
        *length += h;
        return n;
      }
      if (out) out->push_back(st.n);
      *length += st.h;
      l += st.h;
    }
  }

 private:
  static constexpr Law kHold{true, 1, 0.0};
  const TubeSurface& line_;
  State y0_;
  std::vector<double> edges_;
  std::vector<Step> steps_;
};

// One circuit, apex to apex.
struct OneCircuit {
  std::vector<State> pts;  // kept only when asked
  int far_apex = 0;        // index of the far apex in pts
  State end;
  double turn = 0.0, len = 0.0;             // fibre in turnarounds, in passes (mm)
  std::array<double, 2> span = {0.0, 0.0};  // centre line of each end's turnaround (mm)
};

class Planner {
 public:
  Planner(const TubeSurface& line, double a0, double lambda, std::array<double, 2> apex)
      : line_(line), a0_(a0), lambda_(lambda), apex_(apex) {
    // The straight-leg closed form of a turnaround half's centre line (the first guess).
    half_ = line.section_radius() * (1.0 / std::sin(a0) - 1.0) / lambda;
  }

  // The even angle at the station s_ref of the pass that leaves the start apex at theta (the
  // pass continued at a0 past its far turnaround when s_ref lies beyond it).
  double phase(double theta, double s_ref) const {
    State y{apex_[0], theta, 0.5 * M_PI};
    double len = 0.0;
    y = trace(line_, y, {false, -1, lambda_}, angle_event(a0_), nullptr, &len);
    y = trace(
        line_, y, {true, 1, 0.0}, [s_ref](const State& q) { return q.s - s_ref; }, nullptr, &len);
    return line_.even_angle(s_ref, y.th);
  }

  // The circuit from the start apex at theta with the far apex moved inward by delta.
  OneCircuit circuit(double theta, double delta, bool keep) const {
    OneCircuit c;
    State y{apex_[0], theta, 0.5 * M_PI};
    std::vector<State>* out = keep ? &c.pts : nullptr;
    if (keep) c.pts.push_back(y);
    // Leave the start apex: a falls to a0.
    y = trace(line_, y, {false, -1, lambda_}, angle_event(a0_), out, &c.turn);
    c.span[0] += y.s - apex_[0];
    y = pass_and_turn(y, 1, apex_[1] - delta, out, &c.len, &c.turn, &c.span[1]);
    c.far_apex = keep ? static_cast<int>(c.pts.size()) - 1 : 0;
    // Leave the far apex: a rises on to pi - a0.
    const State apex1 = y;
    y = trace(line_, y, {false, 1, lambda_}, angle_event(M_PI - a0_), out, &c.turn);
    c.span[1] += apex1.s - y.s;
    c.end = pass_and_turn(y, 0, apex_[0], out, &c.len, &c.turn, &c.span[0]);
    return c;
  }

 private:
  static std::function<double(const State&)> angle_event(double a) {
    return [a](const State& y) { return y.a - a; };
  }

  // From a pass's first point y (a = a0 towards end 1, pi - a0 towards end 0): the pass, then
  // the arriving half of the turnaround at `end` up to its apex on the station `target`
  // (shooting on where the pass leaves).
  State pass_and_turn(const State& y0, int end, double target, std::vector<State>* out, double* len,
                      double* turn, double* span) const {
    const double dir = end == 1 ? 1.0 : -1.0;
    const int sigma = end == 1 ? 1 : -1;
    double leave = target - dir * half_, prev_leave = leave, prev_err = 0.0;
    const std::size_t keep_from = out ? out->size() : 0;
    HeldPass pass(line_, y0);
    for (int it = 0;; ++it) {
      if (dir * (leave - y0.s) < 0.0) {
        throw ConfigError(
            "winding.slippage " + format_fixed(lambda_, 3) + ": the friction turnarounds do not " +
            "fit between the stations " + format_fixed(apex_[0], 1) + " and " +
            format_fixed(apex_[1], 1) + " mm of the centre line (each half needs about " +
            format_fixed(half_, 1) + " mm at this angle): a longer region, a higher " +
            "slippage (<= mu) or a higher angle");
      }
      if (out) out->resize(keep_from);
      double l_pass = 0.0, l_turn = 0.0;
      const State at = pass.to_station(leave, out, &l_pass);
      const State apex =
          trace(line_, at, {false, sigma, lambda_}, angle_event(0.5 * M_PI), out, &l_turn);
      const double err = apex.s - target;
      if (std::abs(err) < 1e-7 || it == 40) {
        *len += l_pass;
        *turn += l_turn;
        *span += dir * (apex.s - at.s);
        return apex;
      }
      // The apex moves about as much as the leaving point (exactly so on a circular straight
      // leg, where the first step lands); elsewhere (a bend, an oval section) by the secant's
      // slope, so the shooting converges where the plain step would oscillate.
      double next = leave - err;
      if (it > 0 && leave != prev_leave) {
        const double slope = (err - prev_err) / (leave - prev_leave);
        // A secant step at most twice the plain one: where the apex barely moves with the
        // leaving point (a turnaround below the bend's demand turns back a little) a flat
        // slope would throw the pass out of the region.
        if (slope > 0.05 && slope < 20.0 && std::abs(err / slope) <= 2.0 * std::abs(err)) {
          next = leave - err / slope;
        }
      }
      prev_leave = leave;
      prev_err = err;
      leave = next;
    }
  }

  const TubeSurface& line_;
  double a0_ = 0.0, lambda_ = 0.0, half_ = 0.0;
  std::array<double, 2> apex_;
};

// Ends on rings of pins (winding.pins): the passes run at a0 between the pin circles and dwell
// along them (Kind::Turnaround segments, held by the pins): the far dwell of circuit k is chosen
// (regula falsi) so that the circuit advances by exactly A, the start dwell is one pin pitch.
void plan_pinned(const TubeSurface& line, double s0, double s1, double a0, const Mesh& annulus,
                 const std::vector<int>& face_map, const SpindleAxis& axis, const WindingOptions& o,
                 TubeFrictionWinding* w) {
  const double r = line.section_radius(), B = o.band_width, d = o.pin_diameter;
  const int N = o.pin_count, K = w->K;
  const double offset = std::isnan(o.pin_offset) ? 0.5 * B + d : o.pin_offset;
  const double pitch = 2.0 * M_PI / N;
  // Pins that do not fit: around the section each needs its own diameter of gap.
  if (2.0 * N * d > 2.0 * M_PI * r) {
    throw ConfigError("winding.pins: " + std::to_string(N) + " pins of " + format_fixed(d, 1) +
                      " mm do not fit around the " + format_fixed(2.0 * M_PI * r, 1) +
                      " mm section (at most " +
                      std::to_string(static_cast<int>(std::floor(M_PI * r / d))) +
                      " with a gap of one diameter between them)");
  }
  if (offset < 0.5 * d || 2.0 * offset + 4.0 * B > s1 - s0) {
    throw ConfigError(
        "winding.pins: offset " + format_fixed(offset, 1) + " mm puts the pin circles " +
        (offset < 0.5 * d ? std::string("off the tube's ends (below half a pin diameter)")
                          : "too near each other (the region is " + format_fixed(s1 - s0, 1) +
                                " mm, the passes need 4 band widths)"));
  }
  const std::array<double, 2> ring = {s0 + offset, s1 - offset};
  w->apex_s = ring;
  w->pins = N;
  const Law hold{true, 1, 0.0};
  auto to_station = [](double target) {
    return std::function<double(const State&)>([target](const State& y) { return y.s - target; });
  };
  struct Run {
    std::vector<State> out, back;
    State end;
    double len = 0.0;
  };
  // The circuit from (ring[0], theta) with the far dwell phi and the start dwell one pitch.
  auto circuit = [&](double theta, double phi, bool keep) {
    Run c;
    State y{ring[0], theta, a0};
    if (keep) c.out.push_back(y);
    y = trace(line, y, hold, to_station(ring[1]), keep ? &c.out : nullptr, &c.len);
    State b{ring[1], y.th + phi, M_PI - a0};
    if (keep) c.back.push_back(b);
    b = trace(line, b, hold, to_station(ring[0]), keep ? &c.back : nullptr, &c.len);
    c.end = State{ring[0], b.th + pitch, a0};
    return c;
  };
  // Advances are measured in the even angle at the start ring (planner/winding/tube_surface.h:
  // theta itself on a circular section), so the circuits' starts are spread evenly along it.
  auto advance = [&](double psi, double phi) {
    ++w->summary.evaluations;
    const double theta = line.from_even_angle(ring[0], psi);
    return line.even_angle(ring[0], circuit(theta, phi, false).end.th) - psi;
  };
  double most = -1e300, least = 1e300;
  for (int j = 0; j < 48; ++j) {
    const double a = advance(2.0 * M_PI * j / 48.0, pitch);
    most = std::max(most, a);
    least = std::min(least, a);
  }
  // A: the least 2 pi q / K above every sampled advance with one pitch of far dwell.
  const double margin = 0.02 * (most - least) + 1e-6;
  long long q = static_cast<long long>(std::ceil((most + margin) / (2.0 * M_PI) * K));
  auto fits = [&](long long v) {
    const int rem = static_cast<int>(((v % K) + K) % K);
    return o.skip > 0 ? rem == w->p % K : K == 1 || (rem != 0 && std::gcd(rem, K) == 1);
  };
  while (!fits(q)) ++q;
  if (o.skip <= 0) w->p = static_cast<int>(q % K);
  w->n = static_cast<int>(q);
  const double A = 2.0 * M_PI * static_cast<double>(q) / K;
  std::vector<double> phis(K);
  double theta = 0.0;
  for (int k = 0; k < K; ++k) {
    double lo = pitch, f_lo = advance(theta, lo) - A;
    double hi = lo - f_lo + 0.5, f_hi = advance(theta, hi) - A;
    while (f_hi < 0.0) {
      hi += 1.0;
      f_hi = advance(theta, hi) - A;
    }
    double phi = hi;
    int side = 0;
    for (int it = 0; it < 80 && hi - lo > 1e-13; ++it) {
      phi = hi - f_hi * (hi - lo) / (f_hi - f_lo);
      const double f = advance(theta, phi) - A;
      if (std::abs(f) < 1e-11) break;
      if (f < 0.0) {
        lo = phi;
        f_lo = f;
        if (side == -1) f_hi *= 0.5;
        side = -1;
      } else {
        hi = phi;
        f_hi = f;
        if (side == 1) f_lo *= 0.5;
        side = 1;
      }
    }
    phis[k] = phi;
    theta += A;
  }
  const auto [pmin, pmax] = std::minmax_element(phis.begin(), phis.end());
  w->dwell_deg = {*pmin * 180.0 / M_PI, *pmax * 180.0 / M_PI};
  // Lay the circuits: each segment annotated on its own (the dwells' corners are held by pins).
  const std::vector<Vec3> vn = vertex_normals(annulus);
  const ClosestPointQuery query(annulus);
  auto place = [&](const State& y) {
    const ClosestPointQuery::Hit hit = query.closest(line.point(y.s, y.th));
    w->projection_max = std::max(w->projection_max, hit.distance);
    FibrePoint pt;
    pt.position = hit.position;
    pt.normal = point_normal(annulus, vn, hit.point);
    const int f = hit.point.element;
    pt.face = face_map.empty() || f < 0 || f >= static_cast<int>(face_map.size()) ? f : face_map[f];
    return pt;
  };
  auto dwell = [&](double s, double from, double by) {
    std::vector<FibrePoint> pts;
    const int n = std::max(2, static_cast<int>(std::ceil(r * by)));  // ~1 mm of arc a sample
    for (int i = 0; i <= n; ++i) pts.push_back(place(State{s, from + by * i / n, 0.5 * M_PI}));
    w->turnaround_length += r * by;
    return pts;
  };
  const double window = o.curvature_window > 0.0 ? o.curvature_window : o.band_width;
  theta = 0.0;
  for (int k = 0; k < K; ++k) {
    w->starts_deg.push_back(line.even_angle(ring[0], theta) * 180.0 / M_PI);
    const Run c = circuit(theta, phis[k], true);
    Circuit circ;
    circ.index = k;
    std::vector<FibrePoint> pts;
    for (const State& y : c.out) pts.push_back(place(y));
    append_circuit_segment(&circ, std::move(pts), CircuitSegment::Kind::Pass, axis, window);
    append_circuit_segment(&circ, dwell(ring[1], c.out.back().th, phis[k]),
                           CircuitSegment::Kind::Turnaround, axis, window);
    pts.clear();
    for (const State& y : c.back) pts.push_back(place(y));
    append_circuit_segment(&circ, std::move(pts), CircuitSegment::Kind::Pass, axis, window);
    append_circuit_segment(&circ, dwell(ring[0], c.back.back().th, pitch),
                           CircuitSegment::Kind::Turnaround, axis, window);
    w->fibre_length += circ.points.back().s;
    w->circuits.push_back(std::move(circ));
    theta = c.end.th;
  }
  const double miss = theta - 2.0 * M_PI * static_cast<double>(q);
  w->summary.closed = std::abs(miss) < 1e-6;
  w->summary.termination = "passes between rings of " + std::to_string(N) + " pins, far dwells " +
                           format_fixed(w->dwell_deg[0], 2) + " to " +
                           format_fixed(w->dwell_deg[1], 2) + " deg, start dwells one pitch (" +
                           format_fixed(pitch * 180.0 / M_PI, 2) + " deg), the chain turns " +
                           std::to_string(q) + " times (closure " +
                           format_fixed(miss * 180.0 / M_PI, 6) + " deg)";
  w->turns_per_pass = theta / (2.0 * M_PI) / (2.0 * K);
  for (int k = 0; k < K; ++k) {
    const double even = 2.0 * M_PI * static_cast<double>(static_cast<long long>(k) * w->p % K) / K;
    const double off = std::remainder(w->starts_deg[k] * M_PI / 180.0 - even, 2.0 * M_PI);
    w->spread_deg = std::max(w->spread_deg, std::abs(off) * 180.0 / M_PI);
  }
}

}  // namespace

double tube_turns_per_pass(const TubeSurface& line, double s0, double s1, double a0, double lambda,
                           double band_width) {
  const Planner planner(line, a0, lambda, {s0 + 0.5 * band_width, s1 - 0.5 * band_width});
  double sum = 0.0;
  const int n = 8;
  for (int j = 0; j < n; ++j) {
    const double th = 2.0 * M_PI * j / n;
    sum += planner.circuit(th, 0.0, false).end.th - th;
  }
  return sum / n / (4.0 * M_PI);
}

double tube_angle_for_turns(const TubeSurface& line, double s0, double s1,
                            const WindingOptions& o) {
  // Turns grow with the angle; an angle whose turnarounds do not fit turns too little.
  auto turns = [&](double a) {
    try {
      return tube_turns_per_pass(line, s0, s1, a, o.slippage, o.band_width);
    } catch (const ConfigError&) {
      return 0.0;
    }
  };
  // Turns are not monotone in the angle: at low angles the turnarounds wrap more than the
  // passes lose. The root wanted is the highest angle (the shortest turnarounds): scan down
  // from 80 deg in 5 deg steps to the first angle that turns less, then refine between.
  double hi = 80.0 * M_PI / 180.0, f_hi = turns(hi) - o.turns;
  if (!(f_hi > 0.0)) {
    throw ConfigError("winding.turns " + format_turns(o.turns) + ": a friction layer on this " +
                      "tube at winding.slippage " + format_turns(o.slippage) + " makes at " +
                      "most " + format_fixed(f_hi + o.turns, 2) + " turns per pass (at 80 deg)");
  }
  double lo = hi, f_lo = f_hi;
  while (f_lo > 0.0) {
    hi = lo;
    f_hi = f_lo;
    lo -= 5.0 * M_PI / 180.0;
    if (lo < 4.0 * M_PI / 180.0) {
      throw ConfigError("winding.turns " + format_turns(o.turns) + ": a friction layer on " +
                        "this tube at winding.slippage " + format_turns(o.slippage) +
                        " makes more turns per pass at every angle from 5 to 80 deg");
    }
    f_lo = turns(lo) - o.turns;
  }
  // Illinois regula falsi (turns are smooth in the angle where the turnarounds fit).
  double a = lo;
  int side = 0;
  for (int it = 0; it < 100 && hi - lo > 1e-12; ++it) {
    a = hi - f_hi * (hi - lo) / (f_hi - f_lo);
    const double f = turns(a) - o.turns;
    if (std::abs(f) < 1e-10) break;
    if (f < 0.0) {
      lo = a;
      f_lo = f;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    } else {
      hi = a;
      f_hi = f;
      if (side == 1) f_lo *= 0.5;
      side = 1;
    }
  }
  return a;
}

std::string TubeFrictionSummary::brief_report() const {
  return std::string(closed ? "closed" : "not closed") + " after " + std::to_string(evaluations) +
         " circuit traces: " + termination;
}

TubeFrictionWinding plan_tube_friction(const TubeSurface& line, double s0, double s1,
                                       const Mesh& annulus, const std::vector<int>& face_map,
                                       const SpindleAxis& axis, const WindingOptions& o,
                                       double turnaround_slippage) {
  TubeFrictionWinding w;
  if (std::isnan(o.angle) && !o.turns_given) {
    throw ConfigError(
        "winding.angle: friction paths off a shape of revolution hold a winding angle to the "
        "centre line; give winding.angle (deg) or winding.turns with winding.slippage");
  }
  if (!std::isnan(o.angle) && o.turns_given) {
    throw ConfigError("winding.turns: give winding.angle or winding.turns, not both");
  }
  if (!(o.slippage > 0.0)) {
    throw ConfigError("winding.slippage must be > 0 for friction turnarounds off revolution");
  }
  const double angle_deg =
      std::isnan(o.angle) ? tube_angle_for_turns(line, s0, s1, o) * 180.0 / M_PI : o.angle;
  const double a0 = angle_deg * M_PI / 180.0;
  w.angle_deg = angle_deg;
  const std::string asked = std::isnan(o.angle) ? "winding.turns " + format_turns(o.turns) + " (" +
                                                      format_fixed(angle_deg, 2) + " deg)"
                                                : "winding.angle " + format_turns(o.angle) + " deg";
  w.bound = o.slippage;
  const ConstantAngleDemand d = line.demand(s0, s1, a0);
  w.required = d.slippage;
  w.required_s = d.s;
  w.required_theta_deg = d.theta_outside * 180.0 / M_PI;
  if (!(d.min_k_n > -kFlatCurvature) || std::isinf(d.slippage)) {
    if (line.even_is_theta()) {
      throw ConfigError(asked + ": on the inside of the bend the fibre would bridge (k_n " +
                        format_fixed(d.min_k_n * 1000.0, 3) +
                        " /m <= 0): friction cannot hold it; use a higher angle");
    }
    // A fitted section: concave sides, or the inside of a bend (flat sides read as held:
    // planner/winding/tube_surface.h's kFlatCurvature).
    throw ConfigError(asked + ": the fibre would bridge where the tube is concave across it (k_n " +
                      format_fixed(d.min_k_n * 1000.0, 3) +
                      " /m < 0 on the fitted surface: the inside of a bend or a concave side of " +
                      "the section): friction cannot hold it; use a higher angle, a gentler bend " +
                      "or a convex section");
  }
  if (d.slippage > o.slippage) {
    throw ConfigError(
        asked + " needs |k_g/k_n| up to " + format_fixed(d.slippage, 3) +
        " to hold it on the bend (at " + format_fixed(d.s, 1) + " mm along the centre line, " +
        format_fixed(std::abs(w.required_theta_deg), 1) +
        " deg from the outside), above winding.slippage " + format_turns(o.slippage) + " (mu " +
        format_turns(o.mu) + "): a slippage of " + format_fixed(d.slippage, 3) +
        (d.slippage <= o.mu ? "" : " with a mu to match") + ", a higher angle or a gentler bend");
  }
  const double B = o.band_width, r = line.section_radius();
  const std::array<double, 2> apex = {s0 + 0.5 * B, s1 - 0.5 * B};
  w.apex_s = apex;
  w.K = o.circuits > 0 ? o.circuits
                       : std::max(1, static_cast<int>(std::ceil(2.0 * M_PI * r * std::cos(a0) / B *
                                                                (1.0 - 1e-12))));
  w.p = o.skip > 0 ? o.skip : 1;
  if (o.skip > 0 && w.K > 1 && std::gcd(w.p, w.K) != 1) {
    throw ConfigError("winding.pattern: skip " + std::to_string(w.p) + " and " +
                      std::to_string(w.K) + " circuits must be coprime");
  }
  if (o.pin_count > 0) {
    plan_pinned(line, s0, s1, a0, annulus, face_map, axis, o, &w);
    return w;
  }
  const int K = w.K;
  const double lambda = std::isnan(turnaround_slippage) ? o.slippage : turnaround_slippage;
  w.slippage = lambda;
  const Planner planner(line, a0, lambda, apex);
  // The advance of one circuit entering at theta with the far apex moved in by delta: shorter
  // passes turn less, about 2 delta tan(a0) / r per circuit.
  // Measured in the phase of a start: theta on a circular tube; on any other section the even
  // angle (planner/winding/tube_surface.h) at mid-region of the pass that leaves it (where the
  // turnarounds, longer where the section is flatter, no longer shift the passes), so the
  // passes are spread evenly along the section loops rather than their starts in theta.
  const bool even_theta = line.even_is_theta();
  const double s_ref = 0.5 * (s0 + s1);
  auto phase = [&](double theta) { return even_theta ? theta : planner.phase(theta, s_ref); };
  auto circuit_advance = [&](double theta, double phase_theta, double delta) {
    return phase(planner.circuit(theta, delta, false).end.th) - phase_theta;
  };
  auto advance_from = [&](double theta, double phase_theta, double delta) {
    ++w.summary.evaluations;
    return circuit_advance(theta, phase_theta, delta);
  };
  // The advance sampled round the section: 48 circuits, independent of one another (traced in
  // parallel, folded in order; counted here, not in the threads).
  std::array<double, 48> sampled;
  parallel_for_index(48, [&](int j) {
    const double theta = 2.0 * M_PI * j / 48.0;
    sampled[j] = circuit_advance(theta, phase(theta), 0.0);
  });
  w.summary.evaluations += 48;
  double least = std::numeric_limits<double>::infinity(), most = 0.0;
  for (const double a : sampled) {
    least = std::min(least, a);
    most = std::max(most, a);
  }
  // A = 2 pi (m + p / K): the largest such advance a little below the least sampled one (the
  // samples miss the true least by O(1/48^2) of the variation), p the job's skip or any p
  // coprime to K.
  const double margin = 0.02 * (most - least) + 1e-6;
  long long q = static_cast<long long>(std::floor((least - margin) / (2.0 * M_PI) * K));
  auto fits = [&](long long v) {
    const int rem = static_cast<int>(((v % K) + K) % K);
    return o.skip > 0 ? rem == w.p % K : K == 1 || (rem != 0 && std::gcd(rem, K) == 1);
  };
  while (q > 0 && !fits(q)) --q;
  if (q <= 0) throw ConfigError("winding.angle: a circuit turns the section less than once");
  if (o.skip <= 0) w.p = static_cast<int>(q % K);
  const double A = 2.0 * M_PI * static_cast<double>(q) / K;
  w.n = static_cast<int>(q);  // the chain of K circuits turns q times
  // The far apex moves in by delta_k for circuit k so that it advances by exactly A.
  const double per_mm = 2.0 * std::tan(a0) / r;  // rad of advance per mm of delta
  const double limit = 0.25 * (s1 - s0);
  std::vector<double> deltas(K, 0.0);
  double theta = 0.0, phase_k = phase(theta);
  for (int k = 0; k < K; ++k) {
    // (phase_k: circuit k's target phase; theta its start, where the chain puts it)
    auto advance = [&](double th, double delta) { return advance_from(th, phase_k, delta); };
    const double f0 = advance(theta, 0.0) - A;
    double delta = 0.0;
    if (f0 > 1e-10) {
      double b = std::max(1e-3, 1.5 * f0 / per_mm), fb = advance(theta, b) - A;
      while (fb > 0.0) {
        if (b > limit) {
          throw ConfigError("winding.slippage: circuit " + std::to_string(k) + " closes its " +
                            "pattern only with the far turnaround more than " +
                            format_fixed(limit, 1) + " mm inside the region: other circuits " +
                            "(winding.pattern)");
        }
        b *= 2.0;
        fb = advance(theta, b) - A;
      }
      // Illinois regula falsi on f = advance - A: f(a) > 0, f(b) < 0.
      double a = 0.0, fa = f0;
      int side = 0;
      delta = b;
      for (int it = 0; it < 80 && b - a > 1e-12; ++it) {
        const double c = b - fb * (b - a) / (fb - fa);
        const double fc = advance(theta, c) - A;
        delta = c;
        if (std::abs(fc) < 1e-11) break;
        if (fc > 0.0) {
          a = c;
          fa = fc;
          if (side == -1) fb *= 0.5;
          side = -1;
        } else {
          b = c;
          fb = fc;
          if (side == 1) fa *= 0.5;
          side = 1;
        }
      }
    }
    deltas[k] = delta;
    if (even_theta) {
      theta += A;
      phase_k = theta;
    } else {
      theta = planner.circuit(theta, delta, false).end.th;
      phase_k += A;
    }
  }
  // The circuits, chained: each starts where the last ended.
  std::vector<OneCircuit> chain;
  theta = 0.0;
  for (int k = 0; k < K; ++k) {
    chain.push_back(planner.circuit(theta, deltas[k], true));
    w.starts_deg.push_back((phase(theta) - phase(0.0)) * 180.0 / M_PI);
    theta = chain.back().end.th;
    w.turnaround_length += chain.back().turn;
    w.fibre_length += chain.back().turn + chain.back().len;
    w.turnaround_span[0] += chain.back().span[0] / K;
    w.turnaround_span[1] += chain.back().span[1] / K;
  }
  const double target = 2.0 * M_PI * static_cast<double>(q);
  const double miss = theta - target;
  w.summary.closed = std::abs(miss) < 1e-6;
  const auto [dmin, dmax] = std::minmax_element(deltas.begin(), deltas.end());
  w.apex_moved = {*dmin, *dmax};
  w.summary.termination = "turnarounds at |k_g/k_n| = " + format_fixed(lambda, 4) +
                          ", far apexes moved in by " + format_fixed(*dmin, 3) + " to " +
                          format_fixed(*dmax, 3) + " mm, the chain of " + std::to_string(K) +
                          " circuits turns " + std::to_string(q) + " times (closure " +
                          format_fixed(miss * 180.0 / M_PI, 6) + " deg)";
  w.turns_per_pass = theta / (2.0 * M_PI) / (2.0 * K);
  for (int k = 0; k < K; ++k) {
    // Circuit k should start p k / K of a turn on (mod 1): its offset from that, in degrees.
    const double even = 2.0 * M_PI * static_cast<double>(static_cast<long long>(k) * w.p % K) / K;
    const double off = std::remainder(w.starts_deg[k] * M_PI / 180.0 - even, 2.0 * M_PI);
    w.spread_deg = std::max(w.spread_deg, std::abs(off) * 180.0 / M_PI);
  }
  // Place the samples on the mesh and annotate the whole fibre as one curve.
  const std::vector<Vec3> vn = vertex_normals(annulus);
  const ClosestPointQuery query(annulus);
  std::vector<FibrePoint> all;
  std::vector<int> circuit_start;
  for (int k = 0; k < K; ++k) {
    circuit_start.push_back(static_cast<int>(all.size()));
    const std::vector<State>& pts = chain[k].pts;
    for (std::size_t i = k == 0 ? 0 : 1; i < pts.size(); ++i) {
      const ClosestPointQuery::Hit hit = query.closest(line.point(pts[i].s, pts[i].th));
      w.projection_max = std::max(w.projection_max, hit.distance);
      FibrePoint q;
      q.position = hit.position;
      q.normal = point_normal(annulus, vn, hit.point);
      const int f = hit.point.element;
      q.face =
          face_map.empty() || f < 0 || f >= static_cast<int>(face_map.size()) ? f : face_map[f];
      all.push_back(q);
    }
  }
  const double window = o.curvature_window > 0.0 ? o.curvature_window : o.band_width;
  annotate_fibre_points(&all, axis, window);
  for (int k = 0; k < K; ++k) {
    Circuit circ;
    circ.index = k;
    const int b = k == 0 ? 0 : circuit_start[k] - 1;
    const int e = k + 1 < K ? circuit_start[k + 1] - 1 : static_cast<int>(all.size()) - 1;
    circ.points.assign(all.begin() + b, all.begin() + e + 1);
    const double s_first = circ.points.front().s;
    for (FibrePoint& q : circ.points) q.s -= s_first;
    const int far = chain[k].far_apex;
    circ.segments.push_back({CircuitSegment::Kind::Pass, 0, far});
    circ.segments.push_back(
        {CircuitSegment::Kind::Pass, far, static_cast<int>(circ.points.size()) - 1});
    w.circuits.push_back(std::move(circ));
  }
  return w;
}

}  // namespace windplan
