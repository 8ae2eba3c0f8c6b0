#include "planner/pipeline.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "geometry/base/format_number.h"
#include "geometry/region/sharp_edges.h"
#include "planner/cutlines/cutlines.h"
#include "planner/job/job_limits.h"
#include "planner/mandrel/tube_spine.h"
#include "planner/winding/coverage.h"
#include "planner/winding/mesh_tube_surface.h"
#include "planner/winding/tube_coverage.h"
#include "planner/winding/tube_friction_within_mu.h"

namespace windplan {

namespace {

class Stage {
 public:
  Stage(const std::string& name, PlanMetrics* metrics, const PipelineOptions& o)
      : name_(name), metrics_(metrics), options_(o), t0_(std::chrono::steady_clock::now()) {
    if (options_.on_stage_start) options_.on_stage_start(name_);
  }
  void done() {
    StageTiming t{name_,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count()};
    metrics_->timings.push_back(t);
    if (options_.on_stage) options_.on_stage(t);
  }

 private:
  std::string name_;
  PlanMetrics* metrics_;
  const PipelineOptions& options_;
  std::chrono::steady_clock::time_point t0_;
};

std::string general(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", v + 0.0);
  return buf;
}

// "winding.turns = 5 exceeds the 0.65 turns a geodesic can make between ... use turns <= 0.65,
// ...": the beta = 0 passes cannot be geodesics (planner/winding/clairaut.h).
std::string turn_limit_warning(const ClairautLimit& lim, const WindingOptions& wo) {
  const bool s0 = wo.has_start_station(), s1 = wo.has_end_station();
  const std::string ends = !s0 && !s1 ? "the boundary loops (the polar openings or tube ends)"
                           : s0 && s1 ? "winding.start_station and winding.end_station"
                           : s0       ? "winding.start_station and the end loop"
                                      : "the start loop and winding.end_station";
  // The suggestion: N_max rounded down to hundredths, so that it never exceeds the limit (a
  // limit of exactly k / 100 may come out a hundredth lower by rounding); none below 0.01.
  const double suggest = std::floor(100.0 * lim.turns) / 100.0;
  std::string w = "winding.turns = " + format_turns(wo.turns) + " exceeds the " +
                  general(lim.turns) + " turns a geodesic can make between " + ends +
                  " (Clairaut: r sin a = c <= " + format_fixed(lim.min_radius, 2) +
                  " mm, the smallest radius, at " + format_fixed(lim.min_at, 1) +
                  " mm along the axis): with beta = 0 the passes wrap along the smaller end " +
                  "instead of running as geodesics, and the fibre would slip there; use ";
  if (suggest >= 0.01) w += "turns <= " + format_turns(suggest) + ", ";
  return w + "beta > 0, or stations (the limit is recomputed between them)";
}

// The largest turn across an edge of a wound surface off revolution (deg): above it, a corner
// without radius (a tessellated radius turns by a few degrees per edge; the aerobar's square
// edges by 80-90).
constexpr double kSharpEdgeDeg = 60.0;

// Off a shape of revolution, winding.slippage and winding.angle ask for a friction layer at a
// constant angle to the centre line (planner/winding/tube_friction.h), planned on a tube surface
// (planner/winding/tube_surface.h): a parametric bent tube's exact one (TubeSpine::exact), or
// the smooth fit of any other tube-shaped wound region around its centre line
// (planner/winding/mesh_tube_surface.h: meshes, CAD, oval and rounded sections). *tube receives
// the centre line and the surface. Refused where the region is no tube and where the keys it
// does not use are set (they would be silently ignored).
TubeFrictionWinding plan_tube_layer(const Mandrel& md, const Job& job, const WindingOptions& wo,
                                    TubeResult* tube) {
  const std::string keys = wo.slippage > 0.0 ? "winding.slippage" : "winding.angle";
  const bool exact = job.mandrel.source == "bent_tube";
  if (!(wo.slippage > 0.0)) {
    throw ConfigError(
        "winding.angle " + format_turns(wo.angle) + " deg off a shape of revolution: a geodesic " +
        "cannot hold a constant angle to the centre line through a bend or around an oval; give " +
        "winding.slippage (<= mu) to hold it by friction, or remove winding.angle for geodesic "
        "helices");
  }
  if (wo.beta > 0.0) {
    throw ConfigError("winding.beta: a friction layer holds a constant angle on a tube; " +
                      std::string("beta must be 0 with winding.slippage"));
  }
  if (wo.has_start_station() || wo.has_end_station()) {
    throw ConfigError("winding.start_station/end_station: stations along the spindle axis are " +
                      std::string("no sections of a tube; bound the region with its ends ") +
                      "(mandrel.region: {centre_line: ...})");
  }
  tube->centre_line = mandrel_tube_spine(md, job.mandrel);
  double radius = 0.0;
  if (exact) {
    tube->surface = tube->centre_line.exact;
    radius = job.mandrel.bent_tube.radius;
  } else {
    if (tube->centre_line.spine.empty()) {
      throw ConfigError(keys + ": friction layers off a shape of revolution need a wound " +
                        "region that is a tube, and this one has no centre line (" +
                        tube->centre_line.why + "); bound it by sections of a tube " +
                        "(mandrel.region: {centre_line: ...}) or remove winding.slippage and " +
                        "winding.angle to plan geodesic helices");
    }
    MeshTubeSurfaceResult fit =
        mesh_tube_surface(md.winding.mesh, tube->centre_line.spine, md.axis);
    tube->surface = fit.surface;
    tube->surface_report = fit.summary.brief_report();
    radius = fit.summary.mean_radius;
  }
  const TubeSurface& line = *tube->surface;
  // The region's ends: each boundary loop must be a section of the tube (one station).
  std::array<double, 2> ends{};
  for (int e = 0; e < 2; ++e) {
    double lo = 1e300, hi = -1e300, sum = 0.0, off = 0.0;
    for (int v : md.winding.loops[e].vertices) {
      double s = 0.0, th = 0.0, d = 0.0;
      line.locate(md.winding.mesh.position(v), &s, &th, &d);
      lo = std::min(lo, s);
      hi = std::max(hi, s);
      sum += s;
      off = std::max(off, std::abs(d - radius));
    }
    // The surface must be the bare tube (a layup's outer layers are wound on a thicker one,
    // which the centre line's radius does not describe).
    if (exact && off > 0.02 * radius) {
      throw ConfigError("winding.slippage: the wound surface lies " + format_fixed(off, 2) +
                        " mm off the bent tube's radius " + format_fixed(radius, 1) +
                        " mm: friction layers on a bent tube are planned on the bare mandrel " +
                        "only (not as an outer layer of a layup)");
    }
    if (hi - lo > 0.05 * radius) {
      throw ConfigError(std::string("mandrel.region: the wound region's ") +
                        (e == 0 ? "start" : "end") + " edge is no section of the tube (it spans " +
                        format_fixed(hi - lo, 1) + " mm of centre line, " + format_fixed(lo, 1) +
                        " to " + format_fixed(hi, 1) +
                        " mm): friction paths need region ends normal to the centre line");
    }
    ends[e] = sum / std::max<std::size_t>(1, md.winding.loops[e].vertices.size());
  }
  return plan_tube_friction_within_mu(line, std::min(ends[0], ends[1]), std::max(ends[0], ends[1]),
                                      md.winding.mesh, md.winding.face_map, md.axis, wo);
}

// The coverage measurement of the job's bands at its stations, on the sections normal to
// `spine` when there is one (else on planes normal to the axis).
CoverageOptions coverage_options(const WindingOptions& wo, const Spine* spine) {
  CoverageOptions co;
  co.band_width = wo.band_width;
  co.stations = wo.coverage_stations;
  co.spine = spine;
  return co;
}

// Off revolution, on a tube: the geodesic core's passes (kept when they cover every section) or
// the traced level sets of the conformal helices (evenly spread around every section by
// construction, planner/winding/helix.h), laid instead when they cover more and friction holds
// them everywhere (max |k_g/k_n| <= mu). Otherwise the geodesics stay and laid_why gives both
// sets of figures.
void choose_tube_passes(const WindingSurface& ws, const SpindleAxis& axis, const Spine& spine,
                        const std::vector<double>& face_girth, const WindingOptions& wo,
                        PipelineResult* r) {
  const CoverageOptions co = coverage_options(wo, &spine);
  WindingPlan& plan = r->plan;
  const CoverageReport geo = measure_coverage(ws.mesh, axis, plan.circuits, co);
  if (!geo.measured() || geo.bare_fraction == 0.0) return;
  HelixPlan traced = r->helices;
  for (HelixPass& p : traced.passes) p.path = p.initial;
  std::vector<Circuit> circuits = build_circuits(ws.mesh, traced, ws.face_map, axis, wo);
  const CoverageReport cov = measure_coverage(ws.mesh, axis, circuits, co);
  PlanMetrics pm = compute_plan_metrics(ws.mesh, traced, circuits, face_girth, axis, false, wo);
  const std::string figures =
      "the geodesic passes leave " + format_fixed(100.0 * geo.bare_fraction, 2) +
      "% of a section bare (up to " + std::to_string(geo.max_stack) +
      " bands stacked), the evenly spread helices " + format_fixed(100.0 * cov.bare_fraction, 2) +
      "% with |k_g/k_n| up to " + format_fixed(pm.max_slippage, 3) + " (" +
      format_fixed(100.0 * pm.slip_fraction, 2) + "% of their length above mu " +
      format_fixed(wo.mu, 3) + ")";
  if (cov.bare_fraction < geo.bare_fraction && pm.max_slippage <= wo.mu) {
    r->helices = std::move(traced);
    plan.circuits = std::move(circuits);
    plan.metrics = std::move(pm);
    r->laid = "evenly spread helix";
    return;
  }
  // A mesh whose facets are wide against the band is flat under a band (k_n ~ 0 across a facet):
  // what the helices need there is a finer mesh, not more turns. A facet's width is its smallest
  // altitude (2 area / longest edge): long facets along a straight leg are narrow and exact.
  double width_sum = 0.0;
  for (int f = 0; f < ws.mesh.num_faces(); ++f) {
    const Tri& t = ws.mesh.triangle(f);
    const Vec3 &a = ws.mesh.position(t[0]), &b = ws.mesh.position(t[1]),
               &c = ws.mesh.position(t[2]);
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    if (longest > 0.0) width_sum += (b - a).cross(c - a).norm() / longest;
  }
  const double mean_width = ws.mesh.num_faces() > 0 ? width_sum / ws.mesh.num_faces() : 0.0;
  const bool coarse = pm.max_slippage > wo.mu && mean_width > wo.band_width;
  r->laid_why =
      figures + ": the geodesics are laid; " +
      (coarse ? "the mesh is coarse for the band (facets " + format_fixed(mean_width, 1) +
                    " mm across on average, band " + format_fixed(wo.band_width, 1) +
                    " mm: flat facets give k_n ~ 0 under a band); remesh it (mandrel.remesh of "
                    "about the band width)"
       : cov.bare_fraction < geo.bare_fraction
           ? std::string("more turns lower the slippage the helices need, or a ") +
                 "higher winding.mu if the fibre and mandrel hold it"
           : std::string("more circuits or a wider band"));
}

}  // namespace

PipelineResult plan_job(const Job& job, const PipelineOptions& options) {
  PlanMetrics timings;
  Stage mandrel("mandrel", &timings, options);
  Mandrel md = build_mandrel(job);
  check_plan_size(job.winding, md.winding.mesh,
                  md.axis);  // (mesh and CAD mandrels: their size is known now)
  check_plausibility(job, md.winding.mesh, md.axis);  // (issue 28: before any long stage)
  mandrel.done();
  if (options.on_mandrel) options.on_mandrel(md);
  PipelineResult r = plan_winding(std::move(md), job, job.winding, options);
  std::vector<StageTiming>& t = r.plan.metrics.timings;
  t.insert(t.begin(), timings.timings.begin(), timings.timings.end());
  if (!job.cutlines.empty()) {
    Stage cut("cutlines", &r.plan.metrics, options);
    r.plan.cutlines = compute_cutlines(r.mandrel.winding.mesh, r.mandrel.axis, job.cutlines);
    cut.done();
  }
  return r;
}

PipelineResult plan_winding(Mandrel mandrel, const Job& job, const WindingOptions& wo,
                            const PipelineOptions& options) {
  PipelineResult r;
  PlanMetrics timings;  // collected here, moved into the plan at the end
  r.mandrel = std::move(mandrel);
  const Mandrel& md = r.mandrel;
  const WindingSurface& ws = md.winding;
  const std::array<std::vector<int>, 2> loops{ws.loops[0].vertices, ws.loops[1].vertices};

  // Off a shape of revolution, corners without a radius are refused before the long work
  // (geometry/region/sharp_edges.h): the shared aerobar mandrel (a 10 mm slab with square edges)
  // ran 116 s to lay 45% bare with |k_g/k_n| unbounded on half the fibre.
  if (!md.revolution) {
    const SharpEdges sharp = sharp_edges(ws.mesh, kSharpEdgeDeg);
    if (sharp.count > 0) {
      throw InputError("mandrel (" + md.description + "): the wound surface has sharp edges (" +
                       sharp.brief() + "; more than " + format_fixed(kSharpEdgeDeg, 0) +
                       " deg is a corner without a radius): friction holds a turning fibre only "
                       "where the surface curves, and a band over a corner is not laid as "
                       "planned; give the mandrel rounded edges (a radius of at least the band "
                       "width) or choose a region without them (mandrel.region)");
    }
  }
  // Girth: needed for the density (beta > 0) and, off a shape of revolution, for the spacing
  // normalisation; on a shape of revolution with beta = 0, 2 pi r is the exact girth.
  Stage girth("girth", &timings, options);
  // A friction layer on a tube (plan_tube_layer) holds an angle: no girth.
  const bool tube_layer = !md.revolution && (wo.slippage > 0.0 || !std::isnan(wo.angle));
  if (wo.beta > 0.0 || (!md.revolution && !tube_layer)) {
    r.girth = compute_girth_field(ws.mesh, loops, job.girth);
    r.face_girth = r.girth.face_girth(ws.mesh);
    r.has_girth = true;
  } else {
    r.face_girth.resize(ws.mesh.num_faces());
    for (int f = 0; f < ws.mesh.num_faces(); ++f) {
      r.face_girth[f] = 2.0 * M_PI * md.axis.radius(ws.mesh.face_centroid(f));
    }
  }
  girth.done();

  // Shapes of revolution with plain geodesics: Clairaut's integral on the meridian, a closing
  // pattern and circuits that are copies of one another (planner/winding/revolution_winding.h).
  // With beta > 0, off a shape of revolution, or between dwell ends at more turns than a geodesic
  // can make: the geodesic core (planner/winding/helix.h).
  Stage helices("helices", &timings, options);
  if (md.revolution && wo.beta == 0.0) {
    r.revolution = plan_revolution_winding(ws.mesh, ws.face_map, md.axis, wo);
    r.clairaut = r.revolution.planned;
  }
  if (wo.pin_count > 0 && !tube_layer) {
    throw ConfigError("winding.pins: pins are planned for friction layers on a tube only " +
                      std::string("(winding.slippage and winding.angle or turns off revolution)"));
  }
  if (!md.revolution && !tube_layer) r.tube.centre_line = mandrel_tube_spine(md, job.mandrel);
  const Spine* spine = r.tube.centre_line.spine.empty() ? nullptr : &r.tube.centre_line.spine;
  int auto_circuits = 0;  // circuits: auto off revolution, from the sections (below)
  std::vector<double> rho;
  if (tube_layer) {
    r.tube.layer = plan_tube_layer(md, job, wo, &r.tube);
    r.tube.friction = true;
  } else if (!r.clairaut) {
    if (wo.beta > 0.0) rho = density_from_girth(ws.mesh, r.face_girth, wo.beta);
    WindingOptions w = wo;
    if (spine && wo.circuits == 0) {
      // Coverage-first K off revolution: one circuit's bands measured on the sections normal to
      // the centre line (the evenly spread helices': the K circuits are its copies turned by
      // 1/K of the conformal angle); K covers the section where one circuit covers least.
      WindingOptions w1 = wo;
      w1.circuits = 1;
      const HelixPlan one = plan_helices(ws.mesh, loops, rho, md.axis, w1, {}, false);
      const std::vector<Circuit> c1 = build_circuits(ws.mesh, one, ws.face_map, md.axis, w1);
      const CoverageOptions co = coverage_options(wo, spine);
      const CoverageReport cov = measure_coverage(ws.mesh, md.axis, c1, co);
      if (cov.measured() && cov.cover_factor > 0.0) {
        const double k = std::ceil((1.0 - 1e-9) / cov.cover_factor);
        if (!(k <= kMaxCircuits)) {
          throw ConfigError("winding.circuits: auto needs " + general(k) +
                            " circuits to cover the tube with winding.band_width " +
                            general(wo.band_width) + " mm, above " + std::to_string(kMaxCircuits) +
                            "; use a wider band or give winding.circuits");
        }
        auto_circuits = std::max(1, static_cast<int>(k));
        w.circuits = auto_circuits;
      }
    }
    // The evenly spread helices are only nearly even around a bend's sections (the conformal
    // angle runs faster on the outside): add circuits until their bands leave no section bare
    // (at most 6 more, and at most half as many again). The trials measure the traced helices
    // only, so they are not refined; the K chosen is planned and refined once, below.
    const int k_last =
        std::min(kMaxCircuits, auto_circuits + std::max(1, std::min(6, auto_circuits / 2)));
    while (auto_circuits > 0 && w.circuits < k_last) {
      const HelixPlan traced = plan_helices(ws.mesh, loops, rho, md.axis, w, {}, false);
      const CoverageOptions co = coverage_options(wo, spine);
      const CoverageReport cov = measure_coverage(
          ws.mesh, md.axis, build_circuits(ws.mesh, traced, ws.face_map, md.axis, w), co);
      if (!cov.measured() || cov.bare_fraction == 0.0) break;
      ++w.circuits;
    }
    r.helices = plan_helices(ws.mesh, loops, rho, md.axis, w);
    if (auto_circuits > 0) r.helices.summary.circuits_auto = true;
  }
  helices.done();

  Stage metrics("metrics", &timings, options);
  WindingPlan& plan = r.plan;
  plan.job_name = job.name;
  plan.axis = md.axis;
  plan.profile = md.profile;
  if (r.clairaut) {
    RevolutionWinding& rw = r.revolution;
    plan.circuits = std::move(rw.circuits);
    rw.circuits.clear();
    plan.metrics = circuit_plan_metrics(plan.circuits, md.axis, wo);
    const PatternCandidate& pc = rw.pattern;
    PatternInfo& pi = plan.metrics.pattern_info;
    pi.geodesic = true;
    pi.circuits = pc.circuits;
    pi.skip = pc.skip;
    pi.turnaround_radius = pc.c;
    pi.requested_radius = rw.problem.requested_c;
    pi.requested_by = rw.problem.requested_by;
    pi.largest_radius = rw.problem.largest_radius;
    pi.angle_deg = pc.angle_deg;
    pi.geodesic_end = rw.geodesic_end;
    pi.dwell_deg = {pc.dwell[0] * 180.0 / M_PI, pc.dwell[1] * 180.0 / M_PI};
    pi.advance_deg = std::fmod(pc.advance * 180.0 / M_PI, 360.0);
    pi.projection_max = rw.projection_max;
    plan.metrics.turns_per_pass = pc.turns_per_pass;
    plan.metrics.circuits_for_coverage =
        static_cast<int>(std::ceil(pc.circuits * (1.0 - 1e-12) / std::max(1e-12, pc.cover_factor)));
    plan.metrics.pattern =
        "K=" + std::to_string(pc.circuits) + ", skip p=" + std::to_string(pc.skip) + ", advance " +
        format_fixed(pi.advance_deg, 3) + " deg per circuit, closes after " +
        std::to_string(pc.circuits) + " circuits; " +
        (rw.friction ? "the passes' r sin a " : "turnaround radius ") + format_fixed(pc.c, 2) +
        " mm" +
        (std::abs(pc.moved) > 5e-3
             ? " (" + pi.requested_by + " asks " + format_fixed(pi.requested_radius, 2) +
                   " mm: moved " + format_fixed(pc.moved, 2) + " mm to close the pattern)"
             : std::string()) +
        ", " + format_fixed(pc.angle_deg, 2) + " deg on the largest parallel";
    if (rw.friction) {  // friction turnarounds (planner/winding/friction_winding.h)
      FrictionFigures& ff = plan.metrics.friction_turnarounds;
      ff = friction_figures(rw.friction_plan, plan.circuits, wo.mu);
      const FrictionWinding& fw = rw.friction_plan;
      plan.metrics.pattern +=
          fw.transition
              ? "; geodesic domes turning around on " + format_fixed(fw.transition_path.c_from, 2) +
                    " and " + format_fixed(fw.transition_path.c_to, 2) +
                    " mm, joined by a friction " +
                    "transition on the cylinder at |k_g/k_n| = " + format_fixed(fw.slippage, 4) +
                    " over " + format_fixed(ff.transition_axial, 1) + " mm (winding.slippage " +
                    format_fixed(wo.slippage, 3) + ")"
          : rw.problem.narrows
              ? "; the passes turn around on the parallels r = " +
                    format_fixed(rw.problem.apex_c[0], 2) + " and " +
                    format_fixed(rw.problem.apex_c[1], 2) +
                    " mm by friction on the domes at |k_g/k_n| = " + format_fixed(fw.slippage, 4) +
                    " (winding.slippage " + format_fixed(wo.slippage, 3) + ")"
              : "; friction turnarounds at |k_g/k_n| = " + format_fixed(fw.slippage, 4) +
                    " (winding.slippage " + format_fixed(wo.slippage, 3) + "), no pins";
    }
    // Asked more turns (or a higher angle) than a geodesic turning around at the boss makes,
    // without friction: the geodesic turns around further out and leaves the polar region bare.
    const PatternProblem& pp = rw.problem;
    if (pp.narrows && !rw.friction && pp.requested_by != "winding.turnaround") {
      const double boss = std::max(pp.end_radius[0], pp.end_radius[1]) + 0.5 * wo.band_width;
      if (pc.c > boss + 0.25 * wo.band_width) {
        plan.metrics.warnings.push_back(
            "pattern: the passes turn around on r = " + format_fixed(pc.c, 2) + " mm, " +
            format_fixed(pc.c - boss, 2) + " mm outside the bosses' turnaround (" +
            format_fixed(boss, 2) + " mm, the opening + half the band), for " + pp.requested_by +
            ": the domes between " +
            "are not wound; winding.slippage (<= mu) keeps the turnaround on the boss with " +
            "friction on the domes");
      }
    }
    r.passes = circuit_pass_reports(plan.circuits, md.axis, "clairaut");
  } else if (r.tube.friction) {
    TubeFrictionWinding& tw = r.tube.layer;
    plan.circuits = std::move(tw.circuits);
    tw.circuits.clear();
    plan.metrics = circuit_plan_metrics(plan.circuits, md.axis, wo);
    PatternInfo& pi = plan.metrics.pattern_info;
    pi.geodesic = false;
    pi.circuits = tw.K;
    pi.skip = tw.p;
    pi.angle_deg = tw.angle_deg;
    plan.metrics.turns_per_pass = tw.turns_per_pass;
    plan.metrics.circuits_for_coverage = tw.K;
    plan.metrics.pattern =
        "K=" + std::to_string(tw.K) + ", skip p=" + std::to_string(tw.p) + ": a friction layer " +
        "at " + format_fixed(tw.angle_deg, 2) + " deg to the centre line" +
        (std::isnan(wo.angle) ? " (for winding.turns " + format_turns(wo.turns) + ")" : "") +
        (r.tube.centre_line.exact ? ", held on the bend at " : ", held by friction at ") +
        "|k_g/k_n| up to " + format_fixed(tw.required, 4) +
        " (winding.slippage " + format_fixed(wo.slippage, 3) + "); " +
        (tw.pins > 0
             ? "turnarounds on rings of " + std::to_string(tw.pins) + " pins on the stations " +
                   format_fixed(tw.apex_s[0], 1) + " and " + format_fixed(tw.apex_s[1], 1) +
                   " mm of the centre line (far dwells " + format_fixed(tw.dwell_deg[0], 2) +
                   " to " + format_fixed(tw.dwell_deg[1], 2) +
                   " deg to close the pattern, start dwells one pitch)"
             : "friction turnarounds at |k_g/k_n| = " + format_fixed(tw.slippage, 4) +
                   " with their apexes on the stations " + format_fixed(tw.apex_s[0], 1) + " and " +
                   format_fixed(tw.apex_s[1], 1) +
                   " mm of the centre line (the far one moved in by " +
                   format_fixed(tw.apex_moved[0], 2) + " to " + format_fixed(tw.apex_moved[1], 2) +
                   " mm per circuit to close the pattern), no pins") +
        "; the chain of circuits turns " + std::to_string(tw.n) + " times and " +
        (tw.summary.closed ? "closes" : "does not close") + " (starts within " +
        format_fixed(tw.spread_deg, 3) + " deg of even spacing)" +
        (r.tube.surface_report.empty()
             ? std::string()
             : "; planned on the wound mesh's fitted tube surface (" + r.tube.surface_report + ")");
    r.passes = circuit_pass_reports(plan.circuits, md.axis, "friction");
  } else {
    plan.circuits = build_circuits(ws.mesh, r.helices, ws.face_map, md.axis, wo);
    plan.metrics = compute_plan_metrics(ws.mesh, r.helices, plan.circuits, r.face_girth, md.axis,
                                        md.revolution, wo);
    if (spine) choose_tube_passes(ws, md.axis, *spine, r.face_girth, wo, &r);
    r.passes = pass_reports(r.helices, plan.circuits, md.axis);
    if (md.revolution && wo.beta == 0.0) {
      plan.metrics.warnings.push_back("pattern: " + r.revolution.problem.why +
                                      ": the passes are planned by the geodesic core and wrap "
                                      "along the smaller end");
    }
  }
  // Coverage on the laid bands, from the circuits alone (planner/winding/coverage.h).
  CoverageOptions co = coverage_options(wo, spine);
  if (!md.revolution && !r.clairaut && !r.tube.friction) co.height = &r.helices.coords.height;
  PlanMetrics& pm = plan.metrics;
  if (r.tube.friction) {  // on sections normal to the centre line, between the turnarounds
    const TubeFrictionWinding& tw = r.tube.layer;
    // (pins: a band width inside the pin circles, off the dwells)
    const double in = tw.pins > 0 ? wo.band_width : 0.0;
    const double c0 = tw.apex_s[0] + 0.5 * tw.turnaround_span[0] + in,
                 c1 = tw.apex_s[1] - tw.apex_moved[1] - 0.5 * tw.turnaround_span[1] - in;
    pm.coverage = r.tube.centre_line.exact
                      ? measure_tube_coverage(*r.tube.centre_line.exact, plan.circuits,
                                              wo.band_width, c0, c1, wo.coverage_stations)
                      : measure_tube_coverage(*r.tube.surface, plan.circuits, wo.band_width, c0, c1,
                                              wo.coverage_stations);
  } else {
    pm.coverage = measure_coverage(ws.mesh, md.axis, plan.circuits, co);
  }
  pm.cover_factor = pm.coverage.cover_factor;
  if (spine && pm.coverage.measured()) {  // what the sections normal to the centre line need
    const int K = static_cast<int>(plan.circuits.size());
    pm.circuits_for_coverage =
        pm.coverage.cover_factor > 0.0
            ? static_cast<int>(std::ceil(K * (1.0 - 1e-12) / pm.coverage.cover_factor))
            : 0;
    // circuits: auto added circuits until the bands covered every section: that many are needed
    // (the band length alone, above, ignores how evenly the bands are spread).
    if (auto_circuits > 0 && pm.coverage.bare_fraction == 0.0) pm.circuits_for_coverage = K;
    pm.pattern = "K=" + std::to_string(K) + ", advance 1/" + std::to_string(K) +
                 " of the conformal angle per circuit, closes after " + std::to_string(K) +
                 " circuits (a tube: " + r.tube.centre_line.source + ", " + r.laid + " passes" +
                 (auto_circuits > 0 ? ", K auto from the sections normal to the centre line" : "") +
                 ")";
    if (!r.laid_why.empty()) pm.warnings.push_back("tube passes: " + r.laid_why);
  } else if (!md.revolution && !r.clairaut && !r.tube.friction && !r.tube.centre_line.why.empty()) {
    pm.warnings.push_back(
        "coverage: measured on levels of the harmonic height, not on sections "
        "normal to a centre line: " +
        r.tube.centre_line.why);
  }
  if (r.clairaut) {  // the band spacing on the stations (the core's route has its own, per
                     // meridian)
    pm.spacing_cv = pm.coverage.spacing_cv;
    pm.spacing_mean = pm.coverage.spacing_mean;
  }
  if (!pm.coverage.measured()) {
    pm.warnings.push_back(
        "coverage: not measured: no plane normal to the spindle axis cuts the "
        "wound region in a loop around the axis between the passes' ends");
  } else if (pm.coverage.bare_fraction > 0.0) {
    const StationCoverage* worst = &pm.coverage.stations.front();
    for (const StationCoverage& st : pm.coverage.stations) {
      if (st.bare_fraction > worst->bare_fraction) worst = &st;
    }
    pm.warnings.push_back(
        "coverage: the laid bands leave " + format_fixed(100.0 * worst->bare_fraction, 2) +
        "% of the circumference bare at " +
        (spine || r.tube.friction ? format_fixed(worst->station, 1) + " mm along the centre line"
         : co.height ? "height " + format_fixed(worst->station, 3) + " of the wound region"
                     : format_fixed(worst->station, 1) + " mm along the axis") +
        " (widest gap " + format_fixed(pm.coverage.widest_gap, 1) + " mm over " +
        std::to_string(pm.coverage.stations.size()) + " stations): " +
        (r.clairaut        ? "choose a pattern with more circuits (windplan patterns JOB)"
         : r.tube.friction ? "more circuits (winding.circuits)"
                           : "more circuits, a wider band or beta = 0 on a shape of revolution"));
  }
  // The geodesic turn limit (shapes of revolution) between the ends of the passes.
  if (md.revolution) {
    const double x0 = wo.has_start_station() ? wo.start_station : ws.loops[0].axial;
    const double x1 = wo.has_end_station() ? wo.end_station : ws.loops[1].axial;
    const RadiusProfile meridian =
        x1 > x0 ? meridian_profile(ws.mesh, md.axis, x0, x1) : RadiusProfile{};
    if (!meridian.empty()) {
      r.turn_limit = clairaut_turn_limit(meridian, x0, x1);
      r.has_turn_limit = true;
      plan.metrics.geodesic_turn_limit = r.turn_limit.turns;
      plan.metrics.geodesic_min_radius = r.turn_limit.min_radius;
      if (!r.clairaut && wo.beta == 0.0 && r.turn_limit.bounded && wo.turns > r.turn_limit.turns) {
        plan.metrics.warnings.push_back(turn_limit_warning(r.turn_limit, wo));
      }
    }
  }
  for (const std::string& w : md.warnings) plan.metrics.warnings.push_back("mandrel: " + w);
  metrics.done();

  plan.metrics.timings = std::move(timings.timings);
  return r;
}

}  // namespace windplan
