#include "export/files/motion_report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "geometry/base/format_number.h"

namespace windplan {

namespace {

std::string fmt(const char* f, double v) { return format_number(f, v); }

const char* const kAxisNames[4] = {"A", "X", "Y", "B"};

std::string axis_name(int a) { return a >= 0 && a < 4 ? kAxisNames[a] : "-"; }

}  // namespace

void motion_json(JsonWriter& j, const Motion& mo, const ReplayResult* rp) {
  j.key("motion").begin_object();
  j.field("envelope", mo.envelope);
  if (std::isnan(mo.min_clearance)) {
    j.key("min_clearance_mm").null();
  } else {
    j.field("min_clearance_mm", mo.min_clearance);
  }
  j.field("required_clearance_mm", mo.required_clearance);
  j.field("min_clearance_circuit", mo.min_clearance_circuit);
  j.field("min_clearance_point", mo.min_clearance_index);
  // A robot's true-distance eye only (export/machine/clearance_eye.h): the lathes' files stay as
  // they were.
  if (mo.fibre_into_mandrel >= 0) j.field("fibre_into_mandrel_points", mo.fibre_into_mandrel);
  j.field("carriage_reversals", mo.carriage_reversals);
  j.field("max_carriage_reversals_per_circuit", mo.max_carriage_reversals_per_circuit);
  j.field("mid_pass_carriage_reversals", mo.mid_pass_carriage_reversals);
  j.field("spindle_reversals", mo.spindle_reversals);
  j.field("spindle_reversals_in_passes", mo.spindle_reversals_in_passes);
  j.field("max_tangent_smoothing_deg", mo.max_tangent_change);
  j.field("max_monotone_change_X_mm", mo.max_monotone_change_x);
  j.field("max_monotone_change_A_deg", mo.max_monotone_change_a);
  // lathe4's eyes slid along their tangents (export/machine/monotone_by_payout.h), only when some
  // were: the other jobs' files stay as they were.
  if (mo.payout_slid > 0) {
    j.field("eyes_slid_along_tangent", mo.payout_slid);
    j.field("max_eye_slide_mm", mo.max_payout_slide);
  }
  j.field("max_velocity_ratio", mo.limits.velocity_ratio);
  j.field("max_acceleration_ratio", mo.limits.acceleration_ratio);
  j.field("wind_time_s", mo.wind_time);
  j.field_array("circuit_time_s", mo.circuit_time);
  if (rp) {
    j.key("replay").begin_object();
    j.field("blocks", rp->blocks);
    j.field("max_deviation_mm", rp->max_deviation);
    j.field("max_deviation_line", rp->max_deviation_line);
    j.field("mean_deviation_mm", rp->mean_deviation);
    j.field("min_clearance_mm", rp->min_clearance);
    j.field("wind_time_s", rp->wind_time);
    j.field("carriage_reversals", rp->carriage_reversals);
    j.field("spindle_reversals", rp->spindle_reversals);
    j.field("max_velocity_ratio", rp->limits.velocity_ratio);
    j.field("max_acceleration_ratio", rp->limits.acceleration_ratio);
    j.end_object();
  }
  j.end_object();
}

std::string motion_markdown(const Motion& mo, const ReplayResult* rp) {
  std::ostringstream o;
  o << "## Motion\n\n| figure | value |\n|---|---|\n"
    << "| eye envelope | " << mo.envelope << " |\n"
    << (mo.clearance_on_layers ? "| min eye distance from the layer in work | "
                               : "| min eye-mandrel distance | ")
    << (std::isnan(mo.min_clearance) ? std::string("not checked")
                                     : fmt("%.3f", mo.min_clearance) + " mm (required " +
                                           fmt("%.3f", mo.required_clearance) + " mm)")
    << " |\n"
    << "| carriage reversals | " << mo.carriage_reversals << " (at most "
    << mo.max_carriage_reversals_per_circuit << " per circuit, " << mo.mid_pass_carriage_reversals
    << " mid-pass) |\n"
    << "| spindle reversals | " << mo.spindle_reversals << " (" << mo.spindle_reversals_in_passes
    << " inside passes) |\n"
    << "| axis velocity / limit | " << fmt("%.3f", mo.limits.velocity_ratio) << " (axis "
    << axis_name(mo.limits.velocity_axis) << ") |\n"
    << "| axis acceleration / limit | " << fmt("%.3f", mo.limits.acceleration_ratio) << " (axis "
    << axis_name(mo.limits.acceleration_axis) << ") |\n"
    << "| wind time | " << fmt("%.2f", mo.wind_time) << " s |\n";
  if (rp) {
    o << "| replay deviation | " << fmt("%.4f", rp->max_deviation) << " mm max (line "
      << rp->max_deviation_line << "), " << fmt("%.4f", rp->mean_deviation) << " mm mean |\n";
  }
  o << "\n";
  return o.str();
}

std::string motion_summary(const Motion& mo, const ReplayResult* rp) {
  std::ostringstream o;
  o << "  eye envelope     " << mo.envelope << "\n"
    << "  clearance        "
    << (std::isnan(mo.min_clearance) ? std::string("not checked")
                                     : "min " + fmt("%.2f", mo.min_clearance) + " mm (required " +
                                           fmt("%.2f", mo.required_clearance) + ")")
    << (mo.fibre_into_mandrel >= 0 ? ", free fibre into the mandrel at " +
                                         std::to_string(mo.fibre_into_mandrel) + " points"
                                   : std::string())
    << "\n"
    << "  reversals        carriage " << mo.carriage_reversals << " (max "
    << mo.max_carriage_reversals_per_circuit << " per circuit, " << mo.mid_pass_carriage_reversals
    << " mid-pass), spindle " << mo.spindle_reversals << " (" << mo.spindle_reversals_in_passes
    << " in passes)\n"
    << "  axis limits      velocity " << fmt("%.3f", mo.limits.velocity_ratio) << ", acceleration "
    << fmt("%.3f", mo.limits.acceleration_ratio) << " of the limit\n";
  if (rp) {
    o << "  replay           deviation max " << fmt("%.3f", rp->max_deviation) << " mm, mean "
      << fmt("%.4f", rp->mean_deviation) << " mm, wind time " << fmt("%.1f", rp->wind_time)
      << " s\n";
  }
  return o.str();
}

}  // namespace windplan
