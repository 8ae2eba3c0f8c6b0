#include "export/files/report.h"

#include <limits>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "export/files/layup_report.h"
#include "export/files/motion_report.h"
#include "export/files/robot_report.h"
#include "geometry/base/format_number.h"
#include "geometry/base/json.h"
#include "planner/winding/winding_options.h"
#include "windplan_version.h"

namespace windplan {

namespace {

std::string fmt(const char* f, double v) { return format_number(f, v); }
// A slippage figure: "unbounded" where the fibre does not press on the mandrel (plan.h).
std::string slip(double v) {
  return is_unbounded_slippage(v) ? "unbounded (k_n = 0: nothing presses the fibre on)"
                                  : fmt("%.4f", v);
}
// The same in JSON: null when unbounded.
double slip_json(double v) {
  return is_unbounded_slippage(v) ? std::numeric_limits<double>::quiet_NaN() : v;
}

/// Per-circuit figures.
struct CircuitFigures {
  int index = 0;
  int points = 0;
  int machine_points = 0;
  double length = 0.0;
  double time = 0.0;
  double min_angle = 0.0, max_angle = 0.0;
  double max_slippage = 0.0;
};

std::vector<CircuitFigures> circuit_figures(const WindingPlan& plan, const Motion& motion) {
  std::vector<CircuitFigures> out;
  for (std::size_t k = 0; k < plan.circuits.size(); ++k) {
    const Circuit& c = plan.circuits[k];
    CircuitFigures f;
    f.index = c.index;
    f.points = static_cast<int>(c.points.size());
    if (!c.points.empty()) {
      f.length = c.points.back().s - c.points.front().s;
      f.min_angle = f.max_angle = c.points.front().winding_angle;
    }
    for (const FibrePoint& p : c.points) {
      f.min_angle = std::min(f.min_angle, p.winding_angle);
      f.max_angle = std::max(f.max_angle, p.winding_angle);
      f.max_slippage = std::max(f.max_slippage, p.slippage);
    }
    for (const MachineState& s : motion.states) {
      if (s.ordinal != static_cast<int>(k)) continue;
      ++f.machine_points;
      f.time += s.duration;
    }
    out.push_back(f);
  }
  return out;
}

void range_json(JsonWriter& j, const std::string& key, const Range& r) {
  j.key(key).begin_object().field("min", r.min).field("max", r.max).end_object();
}

const char* const kEndName[2] = {"start", "end"};

// "loop" or "station 50.000 mm": what the turnarounds of one end run along (report.md, summary).
std::string turnaround_along(const TurnaroundStability& t) {
  return t.at_station() ? "station " + fmt("%.3f", t.station) + " mm" : std::string("loop");
}

std::string feed_name(const Motion& m) {
  return m.inverse_time ? "G93 inverse time (F = 1/min)" : "G94 per minute (deg counted as mm)";
}

}  // namespace

void turnarounds_json(JsonWriter& j, const PlanMetrics& m, bool mm_keys) {
  const std::string mm = mm_keys ? "_mm" : "";
  j.begin_array();
  for (int e = 0; e < 2; ++e) {
    const TurnaroundStability& t = m.turnaround_ends[e];
    j.begin_object();
    j.field("end", kEndName[e]);
    j.field("along", t.at_station() ? "station" : "loop");
    if (t.at_station()) j.field("station" + mm, t.station);
    j.field("length" + mm, t.length);
    j.field("max_slippage", slip_json(t.max_slippage));
    j.field("slip_length" + mm, t.slip_length);
    j.field("slip_fraction", t.slip_fraction);
    j.field("bridging_length" + mm, t.bridging_length);
    j.end_object();
  }
  j.end_array();
}

void friction_json(JsonWriter& j, const FrictionFigures& f) {
  j.begin_object();
  j.field("slippage_bound", f.bound);
  j.field("mu", f.mu);
  j.key("pass").begin_object();
  j.field("planned_slippage", f.pass_lambda);
  j.field("measured_max_slippage", f.pass_measured);
  j.field("length_mm", f.pass_length);
  j.field("transition", f.transition);
  if (f.transition) {  // a friction transition on each pass (unequal openings)
    j.field("transition_from_c_mm", f.transition_c[0]);
    j.field("transition_to_c_mm", f.transition_c[1]);
    j.field("transition_friction_length_mm", f.transition_length);
    j.field("transition_axial_length_mm", f.transition_axial);
    j.field("transition_turn_deg", f.transition_angle_deg);
  }
  j.end_object();
  j.key("ends").begin_array();
  for (int e = 0; e < 2; ++e) {
    j.begin_object();
    j.field("end", kEndName[e]);
    j.field("friction", f.at_end[e]);
    if (f.at_end[e]) {
      j.field("planned_slippage", f.lambda[e]);
      j.field("measured_max_slippage", f.measured[e]);
      j.field("friction_length_mm", f.length[e]);
      j.field("axial_length_mm", f.axial[e]);
      j.field("turn_deg", f.angle_deg[e]);
      j.field("pass_angle_deg", f.pass_angle_deg[e]);
    }
    j.end_object();
  }
  j.end_array();
  j.end_object();
}

void coverage_json(JsonWriter& j, const CoverageReport& c, bool mm_keys) {
  const std::string mm = mm_keys ? "_mm" : "";
  j.begin_object();
  j.field("measured", c.measured());
  j.field("bare_fraction", c.bare_fraction);
  j.field("widest_gap" + mm, c.widest_gap);
  j.field("widest_overlap" + mm, c.widest_overlap);
  j.field("widest_overlap_largest" + mm, c.widest_overlap_largest);
  j.field("max_stack", c.max_stack);
  j.field("cover_factor", c.cover_factor);
  j.field("mean_plies", c.mean_plies);
  j.field("spacing_cv", c.spacing_cv);
  j.field("stations_skipped", c.skipped);
  j.key("stations").begin_array();
  for (const StationCoverage& st : c.stations) {
    j.begin_object();
    j.field("station" + mm, st.station);
    j.field("loop_length" + mm, st.loop_length);
    j.field("bands_out", st.bands[0]);
    j.field("bands_return", st.bands[1]);
    j.field("bare_fraction", st.bare_fraction);
    j.field("bare_fraction_out", st.family_bare[0]);
    j.field("bare_fraction_return", st.family_bare[1]);
    j.field("widest_gap" + mm, st.widest_gap);
    j.field("widest_overlap" + mm, st.widest_overlap);
    j.field("max_stack", st.max_stack);
    j.field("mean_plies", st.mean_plies);
    j.field("cover_factor", st.cover_factor);
    j.end_object();
  }
  j.end_array();
  j.end_object();
}

void pattern_json(JsonWriter& j, const PatternInfo& p, bool mm_keys) {
  const std::string mm = mm_keys ? "_mm" : "";
  j.begin_object();
  j.field("geodesic", p.geodesic);
  if (p.geodesic) {
    j.field("circuits", p.circuits);
    j.field("skip", p.skip);
    j.field("turnaround_radius" + mm, p.turnaround_radius);
    j.field("requested_radius" + mm, p.requested_radius);
    j.field("requested_by", p.requested_by);
    j.field("largest_radius" + mm, p.largest_radius);
    j.field("angle_deg", p.angle_deg);
    j.field("advance_deg", p.advance_deg);
    j.key("ends").begin_array();
    for (int e = 0; e < 2; ++e) {
      j.begin_object();
      j.field("end", e == 0 ? "start" : "end");
      j.field("turnaround", p.geodesic_end[e] ? "geodesic" : "dwell");
      j.field("dwell_deg", p.dwell_deg[e]);
      j.end_object();
    }
    j.end_array();
    j.field("projection_max" + mm, p.projection_max);
  }
  j.end_object();
}

std::string report_json(const WindingPlan& plan, const ExportResult& r) {
  const PlanMetrics& m = plan.metrics;
  const Motion& mo = r.motion;
  JsonWriter j(2, 10);
  j.begin_object();
  j.field("windplan_version", WINDPLAN_VERSION);
  j.field("job", plan.job_name);
  j.key("summary").begin_object();
  j.field("fibre_length_mm", m.fibre_length);
  j.field("wind_time_s", mo.wind_time);
  j.field("circuits", static_cast<int>(plan.circuits.size()));
  j.field("turns_per_pass", m.turns_per_pass);
  j.field("band_width_mm", m.band_width);
  j.field("circuits_for_coverage", m.circuits_for_coverage);
  j.field("cover_factor", m.cover_factor);
  j.field("pattern", m.pattern);
  j.field("spacing_cv", m.spacing_cv);
  j.field("spacing_mean_mm", m.spacing_mean);
  j.field("max_slippage", slip_json(m.max_slippage));
  j.field("friction", m.friction);
  j.field("slip_fraction", m.slip_fraction);
  j.field("bridging_length_mm", m.bridging_length);
  // The turnarounds (dwell arcs), apart from the passes' figures above.
  j.field("turnaround_length_mm", m.turnarounds.length);
  j.field("turnaround_max_slippage", slip_json(m.turnarounds.max_slippage));
  j.field("turnaround_slip_length_mm", m.turnarounds.slip_length);
  j.field("turnaround_slip_fraction", m.turnarounds.slip_fraction);
  j.field("turnaround_bridging_length_mm", m.turnarounds.bridging_length);
  if (!std::isnan(m.geodesic_turn_limit)) {                 // shapes of revolution only
    j.field("geodesic_turn_limit", m.geodesic_turn_limit);  // null: no limit (a cylinder)
    j.field("geodesic_min_radius_mm", m.geodesic_min_radius);
  }
  j.end_object();
  if (m.pattern_info.geodesic) {  // planned from Clairaut's integral (shapes of revolution)
    j.key("pattern");
    pattern_json(j, m.pattern_info, true);
  }
  if (m.friction_turnarounds.planned) {
    j.key("friction_turnarounds");
    friction_json(j, m.friction_turnarounds);
  }
  j.key("coverage");
  coverage_json(j, m.coverage, true);
  j.key("turnarounds");
  turnarounds_json(j, m, true);
  j.key("machine").begin_object();
  j.field("kind", r.machine.kind);
  j.field("dialect", r.machine.gcode.dialect);
  j.field("feed", feed_name(mo));
  j.field("envelope", r.machine.envelope.mode());
  j.field("chord_tolerance_mm", r.machine.chord_tolerance);
  j.field("dense_points", mo.dense_points);
  j.field("machine_points", static_cast<int>(mo.states.size()));
  j.field("max_chord_deviation_mm", mo.max_chord_deviation);
  range_json(j, "free_length_mm", mo.free_length);
  j.end_object();
  j.key("axis_ranges").begin_object();
  range_json(j, "A_deg", mo.a);
  range_json(j, "X_mm", mo.x);
  range_json(j, "Y_mm", mo.y);
  range_json(j, "B_deg", mo.b);
  j.end_object();
  motion_json(j, mo, r.has_replay ? &r.replay : nullptr);
  if (r.has_robot) robot_json(j, r);  // export/files/robot_report.h
  j.key("circuits").begin_array();
  for (const CircuitFigures& f : circuit_figures(plan, mo)) {
    j.begin_object();
    j.field("index", f.index);
    j.field("points", f.points);
    j.field("machine_points", f.machine_points);
    j.field("length_mm", f.length);
    j.field("time_s", f.time);
    j.field("min_winding_angle_deg", f.min_angle);
    j.field("max_winding_angle_deg", f.max_angle);
    j.field("max_slippage", slip_json(f.max_slippage));
    j.end_object();
  }
  j.end_array();
  j.key("cutlines").begin_array();
  for (const CutLine& c : plan.cutlines) {
    j.begin_object();
    j.field("name", c.name);
    j.field("closed", c.closed);
    j.field("points", static_cast<int>(c.points.size()));
    j.field("length_mm", c.length);
    j.field_array("plane_normal", {c.plane_normal.x(), c.plane_normal.y(), c.plane_normal.z()});
    j.field("plane_offset_mm", c.plane_offset);
    j.field("residual_mm", c.residual);
    j.end_object();
  }
  j.end_array();
  layers_json(j, plan, r.motion);  // layups only (export/files/layup_report.h)
  j.key("warnings").begin_array();
  for (const std::string& w : m.warnings) j.value(w);
  j.end_array();
  j.key("files").begin_array();
  for (const std::string& f : r.files) j.value(f);
  j.end_array();
  if (r.timings) {
    j.key("timings_s").begin_object();
    for (const StageTiming& t : m.timings) j.field(t.stage, t.seconds);
    j.end_object();
  }
  j.end_object();
  return j.str() + "\n";
}

std::string report_markdown(const WindingPlan& plan, const ExportResult& r) {
  const PlanMetrics& m = plan.metrics;
  const Motion& mo = r.motion;
  std::ostringstream o;
  o << "# Winding plan: " << plan.job_name << "\n\n"
    << "windplan " << WINDPLAN_VERSION << "\n\n"
    << "## Summary\n\n| figure | value |\n|---|---|\n"
    << "| fibre length | " << fmt("%.3f", m.fibre_length) << " mm |\n"
    << "| wind time | " << fmt("%.3f", mo.wind_time) << " s |\n"
    << "| circuits | " << plan.circuits.size() << " |\n"
    << "| turns per pass | " << format_turns(m.turns_per_pass) << " |\n"
    << "| band width | " << fmt("%.3f", m.band_width) << " mm |\n"
    << "| circuits for coverage | " << m.circuits_for_coverage << " |\n"
    << "| cover factor | " << fmt("%.4f", m.cover_factor) << " |\n"
    << "| pattern | " << m.pattern << " |\n"
    << "| spacing CV | " << fmt("%.4f", m.spacing_cv) << " |\n"
    << "| mean spacing | " << fmt("%.3f", m.spacing_mean) << " mm |\n"
    << "| max slippage | " << slip(m.max_slippage) << " (friction " << fmt("%.3f", m.friction)
    << ") |\n"
    << "| slip fraction | " << fmt("%.4f", m.slip_fraction) << " |\n"
    << "| bridging length | " << fmt("%.3f", m.bridging_length) << " mm |\n"
    << "| turnaround max slippage | " << slip(m.turnarounds.max_slippage) << " (friction "
    << fmt("%.3f", m.friction) << ") |\n"
    << "| turnaround above mu | " << fmt("%.3f", m.turnarounds.slip_length) << " mm ("
    << fmt("%.4f", m.turnarounds.slip_fraction) << " of " << fmt("%.3f", m.turnarounds.length)
    << " mm) |\n"
    << "| turnaround bridging length | " << fmt("%.3f", m.turnarounds.bridging_length) << " mm |\n";
  if (!std::isnan(m.geodesic_turn_limit)) {
    o << "| geodesic turn limit | "
      << (std::isfinite(m.geodesic_turn_limit) ? fmt("%.4f", m.geodesic_turn_limit) + " turns"
                                               : std::string("none"))
      << " (Clairaut, smallest radius " << fmt("%.3f", m.geodesic_min_radius) << " mm) |\n";
  }
  o << "\n"
    << "## Turnarounds\n\n"
    << "| end | along | length [mm] | max slippage | above mu [mm] | above mu "
       "[fraction] | bridging [mm] |\n|---|---|---|---|---|---|---|\n";
  for (int e = 0; e < 2; ++e) {
    const TurnaroundStability& t = m.turnaround_ends[e];
    o << "| " << kEndName[e] << " | " << turnaround_along(t) << " | " << fmt("%.3f", t.length)
      << " | " << fmt("%.4f", t.max_slippage) << " | " << fmt("%.3f", t.slip_length) << " | "
      << fmt("%.4f", t.slip_fraction) << " | " << fmt("%.3f", t.bridging_length) << " |\n";
  }
  const PatternInfo& pi = m.pattern_info;
  if (pi.geodesic) {
    o << "\n## Pattern\n\n"
      << m.pattern << ".\n\n| end | turnaround | dwell [deg] |\n"
      << "|---|---|---|\n";
    for (int e = 0; e < 2; ++e) {
      o << "| " << kEndName[e] << " | "
        << (pi.geodesic_end[e]
                ? "geodesic, tangent to r = " + fmt("%.3f", pi.turnaround_radius) + " mm"
            : m.friction_turnarounds.at_end[e]
                ? "friction, |k_g/k_n| " + fmt("%.4f", m.friction_turnarounds.lambda[e])
                : std::string("dwell (fibre held by pins or a ring)"))
        << " | " << fmt("%.2f", pi.dwell_deg[e]) << " |\n";
    }
  }
  const FrictionFigures& ff = m.friction_turnarounds;
  if (ff.planned) {
    o << "\n## Friction turnarounds\n\nwinding.slippage " << fmt("%.4f", ff.bound) << ", mu "
      << fmt("%.4f", ff.mu) << "; |k_g/k_n| planned and measured on the laid points.\n\n"
      << "| where | planned | measured max | friction length [mm] | along the axis [mm] | "
         "turn [deg] |\n|---|---|---|---|---|---|\n"
      << (ff.transition
              ? "| passes (a friction transition from r sin a = " +
                    fmt("%.2f", ff.transition_c[0]) + " to " + fmt("%.2f", ff.transition_c[1]) +
                    " mm) | " + fmt("%.4f", ff.pass_lambda) + " | " +
                    fmt("%.4f", ff.pass_measured) + " | " + fmt("%.1f", ff.transition_length) +
                    " per pass | " + fmt("%.1f", ff.transition_axial) + " | " +
                    fmt("%.2f", ff.transition_angle_deg) + " |\n"
              : "| passes (geodesic) | " + fmt("%.4f", ff.pass_lambda) + " | " +
                    fmt("%.4f", ff.pass_measured) + " | 0 | - | - |\n");
    for (int e = 0; e < 2; ++e) {
      if (!ff.at_end[e]) continue;
      o << "| " << kEndName[e] << " turnaround | " << fmt("%.4f", ff.lambda[e]) << " | "
        << fmt("%.4f", ff.measured[e]) << " | " << fmt("%.1f", ff.length[e]) << " | "
        << fmt("%.1f", ff.axial[e]) << " | " << fmt("%.2f", ff.angle_deg[e]) << " |\n";
    }
  }
  const CoverageReport& cv = m.coverage;
  o << "\n## Coverage on the laid bands\n\n" << cv.brief_report() << ".\n";
  if (cv.measured()) {
    o << "\n| station [mm] | loop [mm] | bands out/return | bare [%] | widest gap [mm] | widest "
         "overlap [mm] | most stacked | plies | cover factor |\n"
      << "|---|---|---|---|---|---|---|---|---|\n";
    for (const StationCoverage& st : cv.stations) {
      o << "| " << fmt("%.1f", st.station) << " | " << fmt("%.1f", st.loop_length) << " | "
        << st.bands[0] << "/" << st.bands[1] << " | " << fmt("%.2f", 100.0 * st.bare_fraction)
        << " | " << fmt("%.2f", st.widest_gap) << " | " << fmt("%.2f", st.widest_overlap) << " | "
        << st.max_stack << " | " << fmt("%.2f", st.mean_plies) << " | "
        << fmt("%.3f", st.cover_factor) << " |\n";
    }
  }
  o << "\n"
    << "## Machine\n\n| figure | value |\n|---|---|\n"
    << "| kind | " << r.machine.kind << " |\n"
    << "| G-code dialect | " << r.machine.gcode.dialect << " |\n"
    << "| feed | " << feed_name(mo) << " |\n"
    << "| envelope | " << r.machine.envelope.mode() << " |\n"
    << "| chord tolerance | " << fmt("%.4f", r.machine.chord_tolerance) << " mm |\n"
    << "| points (dense / machine) | " << mo.dense_points << " / " << mo.states.size() << " |\n"
    << "| max chord deviation | " << fmt("%.4f", mo.max_chord_deviation) << " mm |\n"
    << "| free fibre length | " << fmt("%.3f", mo.free_length.min) << " .. "
    << fmt("%.3f", mo.free_length.max) << " mm |\n\n"
    << "## Axis ranges\n\n| axis | min | max |\n|---|---|---|\n"
    << "| A [deg] | " << fmt("%.4f", mo.a.min) << " | " << fmt("%.4f", mo.a.max) << " |\n"
    << "| X [mm] | " << fmt("%.4f", mo.x.min) << " | " << fmt("%.4f", mo.x.max) << " |\n"
    << "| Y [mm] | " << fmt("%.4f", mo.y.min) << " | " << fmt("%.4f", mo.y.max) << " |\n"
    << "| B [deg] | " << fmt("%.4f", mo.b.min) << " | " << fmt("%.4f", mo.b.max) << " |\n\n"
    << motion_markdown(mo, r.has_replay ? &r.replay : nullptr)
    << (r.has_robot ? robot_markdown(r) : std::string()) << "## Circuits\n";
  for (const CircuitFigures& f : circuit_figures(plan, mo)) {
    o << "\n### Circuit " << f.index << "\n\n| figure | value |\n|---|---|\n"
      << "| points (dense / machine) | " << f.points << " / " << f.machine_points << " |\n"
      << "| length | " << fmt("%.3f", f.length) << " mm |\n"
      << "| time | " << fmt("%.3f", f.time) << " s |\n"
      << "| winding angle | " << fmt("%.3f", f.min_angle) << " .. " << fmt("%.3f", f.max_angle)
      << " deg |\n"
      << "| max slippage | " << slip(f.max_slippage) << " |\n";
  }
  if (!plan.cutlines.empty()) {
    o << "\n## Cut-lines\n\n| name | closed | length [mm] | plane normal | offset [mm] | "
         "residual [mm] |\n|---|---|---|---|---|---|\n";
    for (const CutLine& c : plan.cutlines) {
      o << "| " << c.name << " | " << (c.closed ? "yes" : "no") << " | " << fmt("%.3f", c.length)
        << " | (" << fmt("%.6f", c.plane_normal.x()) << ", " << fmt("%.6f", c.plane_normal.y())
        << ", " << fmt("%.6f", c.plane_normal.z()) << ") | " << fmt("%.4f", c.plane_offset) << " | "
        << fmt("%.2e", c.residual) << " |\n";
    }
  }
  o << layers_markdown(plan, mo);  // layups only (export/files/layup_report.h)
  if (!m.warnings.empty()) {
    o << "\n## Warnings\n\n";
    for (const std::string& w : m.warnings) o << "- " << w << "\n";
  }
  o << "\n## Files\n\n";
  for (const std::string& f : r.files) o << "- `" << f << "`\n";
  if (r.timings && !m.timings.empty()) {
    o << "\n## Timings\n\n| stage | s |\n|---|---|\n";
    for (const StageTiming& t : m.timings)
      o << "| " << t.stage << " | " << fmt("%.3f", t.seconds) << " |\n";
  }
  return o.str();
}

std::string summary_text(const WindingPlan& plan, const ExportResult& r) {
  const PlanMetrics& m = plan.metrics;
  const Motion& mo = r.motion;
  std::ostringstream o;
  o << "job " << plan.job_name << "\n"
    << "  fibre length     " << fmt("%.1f", m.fibre_length) << " mm\n"
    << "  wind time        " << fmt("%.1f", mo.wind_time) << " s\n"
    << "  circuits         " << plan.circuits.size() << " (coverage needs "
    << m.circuits_for_coverage << ")\n"
    << "  cover factor     " << fmt("%.3f", m.cover_factor) << "\n"
    << "  coverage         " << m.coverage.brief_report() << "\n"
    << "  pattern          " << m.pattern << "\n"
    << "  spacing CV       " << fmt("%.4f", m.spacing_cv) << "\n"
    << "  max slippage     " << slip(m.max_slippage) << "\n";
  const PatternInfo& pi = m.pattern_info;
  const FrictionFigures& ff = m.friction_turnarounds;
  if (ff.planned && ff.transition) {
    o << "  friction         on the passes: |k_g/k_n| planned " << fmt("%.4f", ff.pass_lambda)
      << ", measured <= " << fmt("%.4f", ff.pass_measured) << " (mu " << fmt("%.3f", ff.mu) << "), "
      << fmt("%.1f", ff.transition_length)
      << " mm of each pass from r sin a = " << fmt("%.2f", ff.transition_c[0]) << " to "
      << fmt("%.2f", ff.transition_c[1]) << " mm; geodesic turnarounds on the domes\n";
  } else if (ff.planned) {
    o << "  turnarounds      friction, no pins: |k_g/k_n| planned "
      << fmt("%.4f", std::max(ff.lambda[0], ff.lambda[1]))
      << ", measured <= " << fmt("%.4f", std::max(ff.measured[0], ff.measured[1])) << " (mu "
      << fmt("%.3f", ff.mu) << "), " << fmt("%.1f", std::max(ff.length[0], ff.length[1]))
      << " mm of fibre each\n";
  } else if (pi.geodesic && pi.geodesic_end[0] && pi.geodesic_end[1]) {
    o << "  turnarounds      geodesic at both ends, tangent to r = "
      << fmt("%.2f", pi.turnaround_radius) << " mm: no dwell arc\n";
  } else {
    o << "  dwell arcs       max slippage " << fmt("%.4f", m.turnarounds.max_slippage) << ", "
      << fmt("%.1f", m.turnarounds.slip_length) << " mm above mu ("
      << fmt("%.2f", 100.0 * m.turnarounds.slip_fraction) << "%), bridging "
      << fmt("%.1f", m.turnarounds.bridging_length) << " mm (held by pins or a ring)\n";
  }

  const bool domes =
      m.pattern_info.geodesic && m.pattern_info.geodesic_end[0] && m.pattern_info.geodesic_end[1];
  if (domes) {
    o << "  turns per pass   " << fmt("%.4f", m.turns_per_pass)
      << " (geodesic, turning around at r = " << fmt("%.2f", m.pattern_info.turnaround_radius)
      << " mm";
    if (std::isfinite(m.geodesic_turn_limit)) {
      o << "; " << fmt("%.2f", m.geodesic_turn_limit) << " would reach the openings";
    }
    o << ")\n";
  } else if (!std::isnan(m.geodesic_turn_limit)) {
    o << "  geodesic limit   "
      << (std::isfinite(m.geodesic_turn_limit) ? fmt("%.2f", m.geodesic_turn_limit) + " turns"
                                               : std::string("none"))
      << " per pass (N = " << format_turns(m.turns_per_pass) << ")\n";
  }
  o << "  axis A           " << fmt("%.2f", mo.a.min) << " .. " << fmt("%.2f", mo.a.max) << " deg\n"
    << "  axis X           " << fmt("%.2f", mo.x.min) << " .. " << fmt("%.2f", mo.x.max) << " mm\n"
    << "  axis Y           " << fmt("%.2f", mo.y.min) << " .. " << fmt("%.2f", mo.y.max) << " mm\n"
    << "  axis B           " << fmt("%.2f", mo.b.min) << " .. " << fmt("%.2f", mo.b.max) << " deg\n"
    << "  machine points   " << mo.states.size() << " of " << mo.dense_points
    << " (chord deviation " << fmt("%.4f", mo.max_chord_deviation) << " mm)\n"
    << motion_summary(mo, r.has_replay ? &r.replay : nullptr);
  if (r.has_robot) {
    o << "  " << r.robot.brief_report() << "\n";
    if (r.has_robot_replay) o << "  " << r.robot_replay.summary << "\n";
  }
  o << layers_summary(plan, mo);  // layups only (export/files/layup_report.h)
  for (const StageTiming& t : m.timings) {
    o << "  time " << t.stage << std::string(t.stage.size() < 12 ? 12 - t.stage.size() : 1, ' ')
      << fmt("%.3f", t.seconds) << " s\n";
  }
  o << "  files in " << r.directory.string() << ":";
  for (const std::string& f : r.files) o << " " << f;
  o << "\n";
  return o.str();
}

}  // namespace windplan
