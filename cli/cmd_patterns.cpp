// windplan patterns <job.yaml> [--json] [--top N]
// The pattern table of a job on a shape of revolution: the closing patterns near the requested
// winding, each planned and measured on its laid bands (planner/winding/winding_pattern.h,
// planner/winding/coverage.h), as the pattern tables of winding software list them; on a tube
// that is not one (a bent tube, a duct), K circuits near what the job winds, each planned as the
// run plans it and measured on the sections normal to the centre line.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "cli/args.h"
#include "cli/commands.h"
#include "geometry/base/errors.h"
#include "geometry/base/json.h"
#include "planner/job/job.h"
#include "planner/mandrel/mandrel_builder.h"
#include "planner/pipeline.h"
#include "planner/winding/coverage.h"
#include "planner/winding/revolution_winding.h"

namespace windplan::cli {

const char* const kPatternsHelp =
    "usage: windplan patterns <job.yaml> [--json] [--top N]\n\n"
    "Lists the winding patterns that close near the job's requested winding on a shape of\n"
    "revolution (winding.turnaround, winding.angle or winding.turns; on domes the default\n"
    "turnaround is the polar opening + half the band). A pattern of K circuits with skip p\n"
    "advances the mandrel by 2 pi p / K per circuit; on domes the turnaround radius moves\n"
    "within winding.turnaround_window to close it, between dwell ends the dwells close it.\n"
    "Each row is planned and measured on its laid bands: K, p, winding angle on the largest\n"
    "parallel, turnaround radius (and how far it moved), nominal cover factor, measured bare\n"
    "fraction, widest gap and overlap (everywhere, and on the largest sections: a vessel's\n"
    "cylinder, where the bands lie side by side), most bands stacked and plies built (2 for one "
    "full\n"
    "helical layer). The first row is what `winding.pattern: auto` winds; a job picks another\n"
    "with `winding.pattern: {circuits: K, skip: p}`.\n"
    "On a tube that is not a shape of revolution (a bent tube, a duct) the rows are K circuits\n"
    "(p = 1) from 3 below to 3 above what the job winds, each planned as `windplan run` plans\n"
    "it: which passes are laid, coverage on the sections normal to the centre line, the largest\n"
    "|k_g/k_n|.\n\n"
    "  --json      print the table as JSON\n"
    "  --top N     rows to plan and measure (default 12)\n";

namespace {

// Off a shape of revolution: the patterns are K circuits (p = 1, each 1/K of the conformal angle
// after the last), each planned as the run plans it (planner/pipeline.h: the passes laid, the
// coverage on the sections normal to the centre line), K from 3 below to 3 above what the job
// winds (at most `top` rows).
int tube_patterns(const Job& job, const Mandrel& md, int top, bool json) {
  const PipelineResult run = plan_winding(md, job, job.winding);
  const int k0 = static_cast<int>(run.plan.circuits.size());
  if (run.tube.friction || run.tube.centre_line.spine.empty()) {
    throw InputError(job.path.string() + ": the mandrel is not a shape of revolution and its " +
                     "wound region has no centre line (" + run.tube.centre_line.why +
                     "): patterns are listed for shapes of revolution and tubes only");
  }
  struct Row {
    int k = 0;
    std::string laid;
    PlanMetrics m;
  };
  std::vector<Row> rows{{k0, run.laid, run.plan.metrics}};
  for (int d = 1; d <= 3 && static_cast<int>(rows.size()) < top; ++d) {
    for (int k : {k0 - d, k0 + d}) {
      if (k < 1 || k > kMaxCircuits || static_cast<int>(rows.size()) >= top) continue;
      WindingOptions w = job.winding;
      w.circuits = k;
      const PipelineResult r = plan_winding(md, job, w);
      rows.push_back({k, r.laid, r.plan.metrics});
    }
  }
  std::sort(rows.begin() + 1, rows.end(), [](const Row& a, const Row& b) { return a.k < b.k; });
  if (json) {
    JsonWriter j;
    j.begin_object();
    j.field("job", job.name);
    j.field("tube", run.tube.centre_line.source);
    j.field("centre_line_mm", run.tube.centre_line.spine.length());
    j.key("patterns").begin_array();
    for (const Row& r : rows) {
      j.begin_object();
      j.field("circuits", r.k);
      j.field("skip", 1);
      j.field("turns_per_pass", job.winding.turns);
      j.field("laid", r.laid);
      j.field("cover_factor", r.m.coverage.cover_factor);
      j.field("bare_fraction", r.m.coverage.bare_fraction);
      j.field("widest_gap", r.m.coverage.widest_gap);
      j.field("max_stack", r.m.coverage.max_stack);
      j.field("plies", r.m.coverage.mean_plies);
      j.field("max_slippage", r.m.max_slippage);
      j.end_object();
    }
    j.end_array();
    j.end_object();
    std::cout << j.str() << "\n";
    return 0;
  }
  std::ostringstream s;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "patterns: %s: a tube (%s, centre line %.1f mm), %s turns per pass; coverage on "
                "%d sections normal to the centre line\n",
                job.name.c_str(), run.tube.centre_line.source.c_str(),
                run.tube.centre_line.spine.length(), format_turns(job.winding.turns).c_str(),
                job.winding.coverage_stations);
  s << buf;
  s << "     K    p  laid                 cover  bare[%]  gap[mm]  stack  plies  max|kg/kn|\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    const CoverageReport& c = r.m.coverage;
    std::snprintf(buf, sizeof buf, "%s %4d %4d  %-19s  %5.3f  %7.2f  %7.2f  %5d  %5.2f  %10.4f\n",
                  i == 0 ? "*" : " ", r.k, 1, r.laid.c_str(), c.cover_factor,
                  100.0 * c.bare_fraction, c.widest_gap, c.max_stack, c.mean_plies,
                  r.m.max_slippage);
    s << buf;
  }
  s << "  * what the run winds (winding.circuits" +
           std::string(job.winding.circuits == 0 ? ": auto" : "") + ")\n";
  std::cout << s.str();
  return 0;
}

}  // namespace

int run_patterns(const std::vector<std::string>& argv) {
  const Args args(argv, {"--json"}, {"--top"});
  args.expect_positional(1, "a job file");
  const Job job = load_job(args.positional()[0]);
  int top = 12;
  if (args.has("--top")) {
    const std::string v = args.value("--top");
    char* end = nullptr;
    const long n = std::strtol(v.c_str(), &end, 10);
    if (v.empty() || *end != '\0' || n < 1 || n > 200) {
      throw UsageError("--top takes a whole number from 1 to 200 (got '" + v + "')");
    }
    top = static_cast<int>(n);
  }
  const Mandrel md = build_mandrel(job);
  if (!md.revolution) return tube_patterns(job, md, top, args.flag("--json"));
  const WindingOptions& wo = job.winding;
  const std::vector<Vec2> meridian = wound_meridian(md.winding.mesh, md.axis, wo);
  const PatternProblem pr = pattern_problem(meridian, wo);
  if (!pr.reachable) throw ConfigError(pr.why);
  struct Row {
    PatternCandidate k;
    CoverageReport cov;
  };
  std::vector<Row> rows;
  CoverageOptions co;
  co.band_width = wo.band_width;
  co.stations = wo.coverage_stations;
  // With winding.slippage the run winds a friction plan (planner/winding/friction_winding.h),
  // closed by its slippage or c: the one row is that plan, measured like the others.
  const bool friction = wants_friction_turnarounds(pr, wo);
  std::vector<PatternCandidate> all;
  if (friction) {
    const RevolutionWinding w = plan_revolution_winding(md.winding.mesh, {}, md.axis, wo);
    rows.push_back({w.pattern, measure_coverage(md.winding.mesh, md.axis, w.circuits, co)});
  } else {
    all = pattern_candidates(pr);
    if (static_cast<int>(all.size()) > top) all.resize(top);
  }
  for (const PatternCandidate& k : all) {
    const ClairautPass pass = clairaut_pass(meridian, k.c, {fibre_step(wo)});
    const std::vector<Circuit> circuits =
        revolution_circuits(md.winding.mesh, {}, md.axis, pass, k, wo);
    rows.push_back({k, measure_coverage(md.winding.mesh, md.axis, circuits, co)});
  }
  if (args.flag("--json")) {
    JsonWriter j;
    j.begin_object();
    j.field("job", job.name);
    j.field("requested_by", pr.requested_by);
    j.field("requested_radius", pr.requested_c);
    j.field("largest_radius", pr.largest_radius);
    j.field("domes", pr.domes);
    j.field("friction", friction);
    j.field("window_lo", pr.c_lo);
    j.field("window_hi", pr.c_hi);
    j.key("patterns").begin_array();
    for (const Row& r : rows) {
      j.begin_object();
      j.field("circuits", r.k.circuits);
      j.field("skip", r.k.skip);
      j.field("angle_deg", r.k.angle_deg);
      j.field("turnaround_radius", r.k.c);
      j.field("moved", r.k.moved);
      j.field("turns_per_pass", r.k.turns_per_pass);
      j.field("cover_factor", r.k.cover_factor);
      j.field("bare_fraction", r.cov.bare_fraction);
      j.field("widest_gap", r.cov.widest_gap);
      j.field("widest_overlap", r.cov.widest_overlap);
      j.field("widest_overlap_largest", r.cov.widest_overlap_largest);
      j.field("max_stack", r.cov.max_stack);
      j.field("plies", r.cov.mean_plies);
      j.end_object();
    }
    j.end_array();
    j.end_object();
    std::cout << j.str() << "\n";
    return 0;
  }
  std::ostringstream s;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "patterns: %s: %s asks a turnaround radius of %.2f mm (%.2f deg on R = %.2f mm); "
                "%s\n",
                job.name.c_str(), pr.requested_by.c_str(), pr.requested_c,
                std::asin(std::min(1.0, pr.requested_c / pr.largest_radius)) * 180.0 / M_PI,
                pr.largest_radius,
                friction   ? "winding.slippage > 0: the friction plan the run winds (closed by "
                             "its slippage or c; docs/config.md, \"Friction turnarounds\")"
                : pr.domes ? "geodesic turnarounds on both domes, radius searched in the window"
                           : "dwell ends: the dwells close every pattern");
  s << buf;
  if (pr.domes && !friction) {
    std::snprintf(buf, sizeof buf, "  window %.2f .. %.2f mm\n", pr.c_lo, pr.c_hi);
    s << buf;
  }
  s << "     K    p  angle[deg]  turnaround[mm]  moved[mm]  turns/pass  cover  bare[%]  gap[mm]"
       "  overlap[mm] (largest)  stack  plies\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    std::snprintf(
        buf, sizeof buf,
        "%s %4d %4d  %10.3f  %14.3f  %9.3f  %10.4f  %5.3f  %7.2f  %7.2f  %11.2f %9.2f  %5d  "
        "%5.2f\n",
        i == 0 ? "*" : " ", r.k.circuits, r.k.skip, r.k.angle_deg, r.k.c, r.k.moved,
        r.k.turns_per_pass, r.k.cover_factor, 100.0 * r.cov.bare_fraction, r.cov.widest_gap,
        r.cov.widest_overlap, r.cov.widest_overlap_largest, r.cov.max_stack, r.cov.mean_plies);
    s << buf;
  }
  s << "  * what winding.pattern: auto winds\n";
  std::cout << s.str();
  return 0;
}

}  // namespace windplan::cli
