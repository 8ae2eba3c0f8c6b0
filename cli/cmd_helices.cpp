// windplan helices <job.yaml> [--json] [-o dir]
// Plans the job's helices (mandrel -> girth -> density -> level-set helices -> refinement ->
// circuits) and reports every pass and the plan metrics; -o writes the plan's CSV, PLY and report.
#include <iostream>
#include <sstream>

#include "cli/args.h"
#include "cli/commands.h"
#include "export/export_plan.h"
#include "export/files/report.h"
#include "geometry/base/json.h"
#include "planner/job/job.h"
#include "planner/pipeline.h"

namespace windplan::cli {

const char* const kHelicesHelp =
    "usage: windplan helices <job.yaml> [--json] [-o DIR]\n\n"
    "Plans the equally spaced geodesic helices of a job (winding: turns, the turns N of a pass\n"
    "about the axis, > 0 and not necessarily whole, e.g. 0.5; circuits, band_width, beta, mu,\n"
    "start_station, end_station): conformal coordinates of the wound region, level-set\n"
    "helices, refinement under the density rho = (g / mean g)^-beta, continuous circuits with\n"
    "turnarounds on the openings or the stations. Prints one line per pass (length, winding\n"
    "angle at its two ends, max slippage, refinement) and the plan metrics (spacing, coverage,\n"
    "pattern, stability of the passes and, apart from them, of the turnarounds at each end,\n"
    "warnings). On a shape of revolution it also prints the geodesic turn limit N_max\n"
    "(Clairaut: r sin a = c <= the smallest radius; the most turns a geodesic can make between\n"
    "the ends of the passes) and, with beta = 0 and turns > N_max, warns and suggests\n"
    "turns <= N_max rounded down to hundredths.\n\n"
    "  --json          print the report as JSON on stdout\n"
    "  -o, --out DIR   also write fibre_path.csv, paths.ply, mesh.ply and report.json/md there\n";

int run_helices(const std::vector<std::string>& argv) {
  const Args args(argv, {"--json"}, {"-o", "--out"});
  args.expect_positional(1, "a job file");
  const Job job = load_job(args.positional()[0]);
  const PipelineResult r = plan_job(job);
  const WindingPlan& plan = r.plan;
  const PlanMetrics& m = plan.metrics;

  const std::string out = args.has("-o") ? args.value("-o") : args.value("--out");
  if (!out.empty()) {
    OutputOptions o = job.output;
    o.gcode = false;
    o.svg = false;
    o.viewer = false;
    export_plan(plan, r.mandrel.mesh, job.machine, o, out);
  }

  if (args.flag("--json")) {
    JsonWriter j;
    j.begin_object();
    j.field("job", job.name);
    j.field("turns", job.winding.turns);
    j.field("circuits", static_cast<int>(plan.circuits.size()));
    j.field("circuits_auto", job.winding.circuits == 0);
    j.field("route", r.clairaut ? "clairaut" : "geodesic core");
    j.field("turns_per_pass", m.turns_per_pass);
    j.field("beta", job.winding.beta);
    j.field("girth_field", r.has_girth);
    j.field("conformal_error_deg", r.helices.coords.conformal_error);
    if (r.has_turn_limit) {
      const ClairautLimit& lim = r.turn_limit;
      j.key("geodesic_turn_limit").begin_object();
      j.field("bounded", lim.bounded);
      j.field("turns", lim.turns);  // null when unbounded
      j.field("angle_rad", lim.angle);
      j.field("min_radius_mm", lim.min_radius);
      j.field("min_at_mm", lim.min_at);
      j.field("from_mm", lim.x0);
      j.field("to_mm", lim.x1);
      j.field("reason", lim.reason);
      j.end_object();
    }
    j.key("passes").begin_array();
    for (const PassReport& p : r.passes) {
      j.begin_object();
      j.field("circuit", p.circuit);
      j.field("hand", p.hand);
      j.field("length", p.length);
      j.field("angle_start", p.angle_start);
      j.field("angle_end", p.angle_end);
      j.field("radius_start", p.radius_start);
      j.field("radius_end", p.radius_end);
      j.field("max_slippage", p.max_slippage);
      j.field("iterations", p.iterations);
      j.field("time_ms", p.time_ms);
      j.field("termination", p.termination);
      j.end_object();
    }
    j.end_array();
    j.key("metrics").begin_object();
    j.field("fibre_length", m.fibre_length);
    j.field("spacing_mean", m.spacing_mean);
    j.field("spacing_cv", m.spacing_cv);
    j.field("circuits_for_coverage", m.circuits_for_coverage);
    j.field("cover_factor", m.cover_factor);
    j.field("pattern", m.pattern);
    j.field("max_slippage", m.max_slippage);
    j.field("friction", m.friction);
    j.field("slip_fraction", m.slip_fraction);
    j.field("bridging_length", m.bridging_length);
    // The turnarounds (dwell arcs), apart from the passes' figures above; lengths in mm.
    j.field("turnaround_length", m.turnarounds.length);
    j.field("turnaround_max_slippage", m.turnarounds.max_slippage);
    j.field("turnaround_slip_length", m.turnarounds.slip_length);
    j.field("turnaround_slip_fraction", m.turnarounds.slip_fraction);
    j.field("turnaround_bridging_length", m.turnarounds.bridging_length);
    j.key("turnarounds");
    turnarounds_json(j, m, false);
    if (m.pattern_info.geodesic) {
      j.key("pattern_info");
      pattern_json(j, m.pattern_info, false);
    }
    j.key("coverage");
    coverage_json(j, m.coverage, false);
    j.key("warnings").begin_array();
    for (const std::string& w : m.warnings) j.value(w);
    j.end_array();
    j.end_object();
    j.key("timings_s").begin_object();
    for (const StageTiming& t : m.timings) j.field(t.stage, t.seconds);
    j.end_object();
    j.end_object();
    std::cout << j.str() << "\n";
    return 0;
  }
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(3);
  s << "helices: " << job.name << ": K = " << plan.circuits.size()
    << (job.winding.circuits == 0 ? " (auto)" : "")
    << " circuits of N = " << format_turns(m.turns_per_pass)
    << " turns per pass, beta = " << job.winding.beta
    << (r.has_girth ? " (girth field)" : " (girth 2 pi r)")
    << (r.clairaut ? ", Clairaut geodesics on the meridian" : ", geodesic core") << "\n";
  if (!r.clairaut) s << "  conformal error " << r.helices.coords.conformal_error << " deg\n";
  if (r.has_turn_limit) {
    const ClairautLimit& lim = r.turn_limit;
    s << "  geodesic turn limit: ";
    if (lim.bounded) {
      s << "N_max = " << lim.turns << " turns (" << lim.angle << " rad)";
    } else {
      s << "none (" << lim.reason << ")";
    }
    s << " between " << lim.x0 << " and " << lim.x1 << " mm along the axis, smallest radius "
      << lim.min_radius << " mm at " << lim.min_at << " mm\n";
  }
  for (const PassReport& p : r.passes) {
    s << "  circuit " << p.circuit << (p.hand > 0 ? " out   " : " return") << ": length "
      << p.length << " mm, angle " << p.angle_start << " deg at r = " << p.radius_start << " mm -> "
      << p.angle_end << " deg at r = " << p.radius_end << " mm, max slippage " << p.max_slippage
      << ", " << p.iterations << " it, " << p.time_ms << " ms, " << p.termination << "\n";
  }
  s << "  fibre length " << m.fibre_length << " mm\n";
  s << "  spacing: mean " << m.spacing_mean << " mm, CV (girth-normalised) " << m.spacing_cv
    << "\n";
  s << "  coverage (laid bands): " << m.coverage.brief_report() << "\n";
  s << "  pattern: " << m.pattern << "\n";
  s << "  stability: max |k_g/k_n| " << m.max_slippage << " vs mu " << m.friction << ", "
    << 100.0 * m.slip_fraction << "% above, bridging " << m.bridging_length << " mm (passes)\n";
  s << "  turnarounds: max |k_g/k_n| " << m.turnarounds.max_slippage << " vs mu " << m.friction
    << ", " << m.turnarounds.slip_length << " mm (" << 100.0 * m.turnarounds.slip_fraction
    << "%) of " << m.turnarounds.length << " mm above, bridging " << m.turnarounds.bridging_length
    << " mm\n";
  for (int e = 0; e < 2; ++e) {
    const TurnaroundStability& t = m.turnaround_ends[e];
    s << "    " << (e == 0 ? "start" : "end  ") << " ";
    if (t.at_station()) {
      s << "station " << t.station << " mm";
    } else {
      s << "loop";
    }
    s << ": max |k_g/k_n| " << t.max_slippage << ", " << t.slip_length << " mm ("
      << 100.0 * t.slip_fraction << "%) of " << t.length << " mm above, bridging "
      << t.bridging_length << " mm\n";
  }
  for (const std::string& w : m.warnings) s << "  warning: " << w << "\n";
  s << "  time:";
  for (const StageTiming& t : m.timings) s << " " << t.stage << " " << t.seconds << " s";
  s << "\n";
  std::cout << s.str();
  return 0;
}

}  // namespace windplan::cli
