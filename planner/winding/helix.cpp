#include "planner/winding/helix.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>

#include "geometry/base/errors.h"
#include "geometry/base/parallel.h"

namespace windplan {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::string num_str(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}
// The same open path traversed backwards (crossings through the twin halfedges).
SurfacePath reversed(const Mesh& m, const SurfacePath& p) {
  SurfacePath r;
  r.closed = false;
  r.start = p.end;
  r.end = p.start;
  const int k = p.num_crossings();
  r.start_face = k > 0 ? m.face(m.twin(p.halfedges[k - 1])) : p.start_face;
  for (int i = k - 1; i >= 0; --i) {
    r.halfedges.push_back(m.twin(p.halfedges[i]));
    r.lambdas.push_back(1.0 - p.lambdas[i]);
  }
  return r;
}

// Every crossing parameter and end point finite (a refined path can come back with NaN).
bool finite_path(const Mesh& m, const SurfacePath& p) {
  for (double l : p.lambdas) {
    if (!std::isfinite(l)) return false;
  }
  return position(m, p.start).allFinite() && position(m, p.end).allFinite();
}
}  // namespace
double turnaround_dwell(double turns, int circuits, int pattern_step) {
  // A circuit advances theta by 4 pi N + 2 dwell; it must be 2 pi p / K modulo 2 pi, so the
  // dwell is pi + pi p / K modulo pi, less 2 pi N. Only the fractional part of N matters
  // (N - floor(N) is exact), so whole N give exactly pi + pi p / K as before fractional turns;
  // the correction is the one nearest 0 (half turns: none), keeping the dwell near half a turn.
  const double frac = turns - std::floor(turns);
  const double c = std::remainder(-kTwoPi * frac, M_PI);
  return M_PI + M_PI * pattern_step / circuits + c;
}

std::vector<double> density_from_girth(const Mesh& m, const std::vector<double>& g, double beta) {
  if (static_cast<int>(g.size()) != m.num_faces()) {
    throw InputError("density: " + std::to_string(g.size()) + " girth values for " +
                     std::to_string(m.num_faces()) + " faces");
  }
  double sum = 0.0, area = 0.0;
  for (int f = 0; f < m.num_faces(); ++f) {
    if (!(g[f] > 0.0) || !std::isfinite(g[f])) {
      throw InputError("density: girth of face " + std::to_string(f) + " is " +
                       std::to_string(g[f]) + " (must be > 0)");
    }
    const double a = m.face_area(f);
    sum += a * g[f];
    area += a;
  }
  const double mean = area > 0.0 ? sum / area : 1.0;
  std::vector<double> rho(g.size());
  for (std::size_t f = 0; f < g.size(); ++f) rho[f] = std::pow(g[f] / mean, -beta);
  return rho;
}

HelixPlan plan_helices(const Mesh& m, const std::array<std::vector<int>, 2>& loops,
                       const std::vector<double>& rho, const SpindleAxis& axis,
                       const WindingOptions& options, const GeodesicOptions& geodesic,
                       bool refine_passes) {
  if (std::string why; !options.is_valid(&why)) throw ConfigError("winding: " + why);
  HelixPlan plan;
  plan.coords = compute_harmonic_coordinates(m, loops);
  plan.summary.harmonic_ms = plan.coords.time_ms;
  const HarmonicCoordinates& hc = plan.coords;
  // Axial stations: the passes run between their circles instead of the boundary loops.
  std::array<std::optional<StationCircle>, 2> stations;
  {
    const std::array<bool, 2> given = {options.has_start_station(), options.has_end_station()};
    const std::array<double, 2> at = {options.start_station, options.end_station};
    const std::array<const char*, 2> keys = {"winding.start_station", "winding.end_station"};
    if (given[0] || given[1]) {
      const std::array<double, 2> range = station_range(m, loops, axis);
      for (int e = 0; e < 2; ++e) {
        if (!given[e]) continue;
        check_station(keys[e], at[e], range);
        stations[e] = station_circle(m, hc, axis, at[e], keys[e]);
        plan.summary.heights[e] = stations[e]->height;
      }
      if (!(plan.summary.heights[1] > plan.summary.heights[0])) {
        throw ConfigError(
            "winding.start_station, winding.end_station: the harmonic height does "
            "not increase from the start to the end of the passes (" +
            num_str(plan.summary.heights[0]) + " -> " + num_str(plan.summary.heights[1]) + ")");
      }
    }
  }
  HelixTraceOptions to_end, to_start;  // out passes stop at the end, return passes at the start
  to_end.height_span = to_start.height_span = plan.summary.heights[1] - plan.summary.heights[0];
  to_end.axis = to_start.axis = axis;
  if (stations[1]) to_end.stop_station = options.end_station;
  if (stations[0]) to_start.stop_station = options.start_station;
  const PathMetric metric = rho.empty() ? PathMetric() : PathMetric::density(m, rho);
  const GeodesicOptions& gopt = geodesic;
  const double N = options.turns;

  // Refines one pass; writes only to the pass and to `warnings` and `ms`, so that passes can
  // be refined in parallel (below).
  auto refine_pass = [&](HelixPass* p, std::vector<std::string>* warnings, double* ms) -> bool {
    if (!refine_passes) {  // (a trial: the traced level set, in the pass's own direction)
      p->path = p->initial;
      return true;
    }
    const auto t0 = std::chrono::steady_clock::now();
    // Every pass is refined from loop 0 (return passes are reversed and back): measured in
    // session 1, return passes refined as traced took far longer. With beta = 0 (Euclidean) the
    // core starts from the exact funnel path of the strip (GeodesicOptions::funnel_start); under
    // a density it refines the level set directly. A pass that must sweep over many vertices
    // (turns beyond what a geodesic can make, hugging an opening) needs more reroutes than the
    // core's default cap (50 + 10 k).
    const SurfacePath init = p->hand < 0 ? reversed(m, p->initial) : p->initial;
    GeodesicOptions go = gopt;
    if (go.max_reroutes == 0) {  // (in 64 bits: 20 k overflowed int for 1e8 crossings)
      go.max_reroutes =
          static_cast<int>(std::min<long long>(INT_MAX, 1000 + 20LL * init.num_crossings()));
    }
    GeodesicResult r = refine_path(m, init, metric, go);
    // A guard: a path with non-finite crossings would put NaN points into every output. The
    // funnel rounds once produced one (a broken strip spliced with stale indices, the shipped
    // vessel at N = 0.5, fixed in the core); should it happen again the pass is refined from the
    // level set, and if that fails too the level set is kept and counted as not converged.
    const std::string which =
        "circuit " + std::to_string(p->circuit) + (p->hand > 0 ? " out pass" : " return pass");
    if (!finite_path(m, r.path) && go.funnel_start) {
      GeodesicOptions direct = go;
      direct.funnel_start = false;
      r = refine_path(m, init, metric, direct);
      warnings->push_back(which +
                          ": the geodesic core's funnel start gave a non-finite path; "
                          "refined from the traced level set instead");
    }
    const bool finite = finite_path(m, r.path);
    if (!finite) {
      r.path = init;
      warnings->push_back(which +
                          ": the geodesic refinement gave a non-finite path; the "
                          "traced level set is kept");
    }
    *ms = ms_since(t0);
    p->path = p->hand < 0 ? reversed(m, r.path) : std::move(r.path);
    p->summary = r.summary;
    return finite;
  };
  auto count_pass = [&](const HelixPass& p, const std::vector<std::string>& warnings, double ms,
                        bool finite) {
    plan.summary.refine_ms += ms;
    plan.summary.warnings.insert(plan.summary.warnings.end(), warnings.begin(), warnings.end());
    if (!finite || !p.summary.converged()) ++plan.summary.not_converged;
  };
  auto refine = [&](HelixPass* p) {
    std::vector<std::string> warnings;
    double ms = 0.0;
    const bool finite = refine_pass(p, &warnings, &ms);
    count_pass(*p, warnings, ms, finite);
  };
  // The start of circuit 0: theta of the first loop vertex (or station crossing), nudged off the
  // vertices.
  const SurfacePoint first = [&] {
    if (stations[0]) return station_arc(m, *stations[0], stations[0]->crossings[0], 1e-6).end;
    const int v = loops[0][0];
    const int h = m.vertex_halfedge(v);
    const double th = hc.corner_theta(m, m.face(h), h % 3);
    return loop_point_at_theta(m, hc, loops[0], th + 1e-6);
  }();

  // K: given, or from the coverage of the first out pass at its largest radius.
  int K = options.circuits;
  HelixPass first_pass;
  {
    const auto t0 = std::chrono::steady_clock::now();
    first_pass.initial = trace_helix(m, hc, first, N, +1, to_end);
    plan.summary.trace_ms += ms_since(t0);
    refine(&first_pass);
  }
  if (K == 0) {
    plan.summary.circuits_auto = true;
    const std::vector<Vec3> pl = polyline(m, first_pass.path);
    const std::vector<int> sf = segment_faces(m, first_pass.path);
    std::size_t best = 0;
    double rmax = -1.0;
    for (std::size_t i = 0; i < pl.size(); ++i) {
      const double r = axis.radius(pl[i]);
      if (r > rmax) {
        rmax = r;
        best = i;
      }
    }
    // The direction there: a chord over about a band width (robust to tiny segments).
    std::size_t a = best, b = best;
    double before = 0.0, after = 0.0;
    while (a > 0 && before < 0.5 * options.band_width) {
      before += (pl[a] - pl[a - 1]).norm();
      --a;
    }
    while (b + 1 < pl.size() && after < 0.5 * options.band_width) {
      after += (pl[b + 1] - pl[b]).norm();
      ++b;
    }
    const Vec3 n = m.face_normal(sf[std::min(best, sf.size() - 1)]);
    Vec3 t = pl[b] - pl[a];
    t -= t.dot(n) * n;
    t.normalize();
    Vec3 mer = axis.direction - axis.direction.dot(n) * n;
    double ca = 1.0;
    if (mer.norm() > 1e-12) ca = std::fabs(t.dot(mer.normalized()));
    ca = std::clamp(ca, 0.0, 1.0);
    plan.summary.auto_radius = rmax;
    plan.summary.auto_angle_deg = std::acos(ca) * 180.0 / M_PI;
    // Checked before the conversion to int (band_width: 1e-9 overflowed it to 1 circuit).
    const double k_auto = std::ceil(kTwoPi * rmax * ca / options.band_width - 1e-9);
    const int k_max = kMaxCircuits;
    if (!(k_auto <= k_max)) {
      std::ostringstream s;
      s << "winding.band_width = " << options.band_width << " mm gives " << k_auto
        << " circuits (circuits: auto, largest radius " << rmax << " mm), above the bound " << k_max
        << "; use a wider band or give winding.circuits";
      throw ConfigError(s.str());
    }
    K = std::max(1, static_cast<int>(k_auto));
  }
  plan.summary.circuits = K;
  plan.summary.pattern_step = 1;
  const double advance = kTwoPi * plan.summary.pattern_step / K;
  const double dwell = turnaround_dwell(N, K, plan.summary.pattern_step);
  const double theta_first = surface_point_coordinates(m, hc, first)[0];

  SurfacePoint start = first;
  for (int k = 0; k < K; ++k) {
    HelixPass out;
    if (k == 0) {
      out = std::move(first_pass);
    } else {
      out.circuit = k;  // (named in refine's warnings)
      const auto t0 = std::chrono::steady_clock::now();
      out.initial = trace_helix(m, hc, start, N, +1, to_end);
      plan.summary.trace_ms += ms_since(t0);
      // (refined below, with the other passes: the refinement keeps the end points)
    }
    out.circuit = k;
    out.hand = +1;
    Turnaround top;
    top.circuit = k;
    top.loop = 1;
    top.dwell = dwell;
    if (stations[1]) {
      top.station = options.end_station;
      top.arc = station_arc(m, *stations[1], out.initial.end, dwell);
    } else {
      top.arc = loop_arc(m, hc, out.initial.end, dwell);
    }
    HelixPass back;
    back.circuit = k;
    back.hand = -1;
    {
      const auto t0 = std::chrono::steady_clock::now();
      back.initial = trace_helix(m, hc, top.arc.end, N, -1, to_start);
      plan.summary.trace_ms += ms_since(t0);
    }
    Turnaround bottom;
    bottom.circuit = k;
    bottom.loop = 0;
    bottom.dwell = dwell;
    if (stations[0] || stations[1]) {
      // h is constant on a loop but on a station circle only up to the tessellation, so the two
      // passes advance theta by 4 pi N only nearly: the bottom dwell takes up the difference, so
      // that circuit k + 1 starts exactly (k + 1) advance after circuit 0 and the pattern closes.
      const double now = surface_point_coordinates(m, hc, back.initial.end)[0] + dwell;
      const double want = theta_first + (k + 1) * advance;
      bottom.dwell = dwell + std::remainder(want - now, kTwoPi);
    }
    if (stations[0]) {
      bottom.station = options.start_station;
      bottom.arc = station_arc(m, *stations[0], back.initial.end, bottom.dwell);
    } else {
      bottom.arc = loop_arc(m, hc, back.initial.end, bottom.dwell);
    }
    start = bottom.arc.end;
    plan.passes.push_back(std::move(out));
    plan.passes.push_back(std::move(back));
    plan.turnarounds.push_back(std::move(top));
    plan.turnarounds.push_back(std::move(bottom));
  }
  // The passes' refinements are independent (each keeps its traced end points, which the
  // turnarounds above used): run them in parallel, each writing its own slot, and count them in
  // pass order, so that the plan does not depend on the thread count.
  {
    const int count = static_cast<int>(plan.passes.size());
    std::vector<std::vector<std::string>> warnings(count);
    std::vector<double> ms(count, 0.0);
    std::vector<char> finite(count, 1);
    parallel_for_index(count - 1, [&](int i) {
      finite[i + 1] = refine_pass(&plan.passes[i + 1], &warnings[i + 1], &ms[i + 1]);
    });
    for (int i = 1; i < count; ++i) count_pass(plan.passes[i], warnings[i], ms[i], finite[i]);
  }
  if (plan.summary.not_converged > 0) {
    plan.summary.warnings.push_back(std::to_string(plan.summary.not_converged) + " of " +
                                    std::to_string(plan.passes.size()) +
                                    " passes did not converge in the geodesic refinement");
  }
  return plan;
}

}  // namespace windplan
