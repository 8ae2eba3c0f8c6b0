#include "export/files/robot_report.h"

#include <sstream>

#include "geometry/base/format_number.h"

namespace windplan {

namespace {

std::string fmt(const char* f, double v) { return format_number(f, v); }

}  // namespace

void robot_replay_fields(JsonWriter& j, const RobotReplayResult& rp) {
  j.field("max_deviation_mm", rp.fibre.max_deviation);
  j.field("max_deviation_at", rp.max_deviation_at);
  j.field("mean_deviation_mm", rp.fibre.mean_deviation);
  j.field("max_eye_deviation_mm", rp.max_eye_deviation);
  j.field("max_eye_deviation_at", rp.max_eye_deviation_at);
  j.field("min_eye_clearance_mm", rp.fibre.min_clearance);
  j.field("min_link_clearance_mm", rp.min_link_clearance);
  j.field("min_link_clearance_at", rp.min_link_clearance_at);
  j.field("min_joint_margin_deg", rp.min_joint_margin);
  j.field("min_wrist_angle_deg", rp.min_wrist_angle);
  j.field("max_joint_speed_ratio", rp.max_joint_speed_ratio);
  j.field("configuration_changes", rp.configuration_changes);
  j.field("cycle_time_s", rp.cycle_time);
}

void robot_json(JsonWriter& j, const ExportResult& r) {
  const RobotOptions& ro = r.machine.robot;
  const RobotMotion& m = r.robot;
  const RobotReplayResult& rp = r.robot_replay;
  j.key("robot").begin_object();
  j.field("arm", ro.arm_name);
  j.field("positioner", ro.positioner_name);
  j.field("dialect", ro.dialect);
  j.field("main_program", r.robot_main);
  j.field("targets", static_cast<int>(m.targets.size()));
  j.field("cycle_time_s", m.cycle_time);
  j.field("planned_time_s", m.planned_time);
  j.field("slowed_moves", m.slowed_moves);
  j.field("max_joint_speed_ratio_planned", m.max_joint_speed_ratio);
  j.field("min_joint_margin_deg", m.min_joint_margin);
  j.field("min_joint_margin_joint", m.min_joint_margin_joint);
  j.field("min_wrist_angle_deg", m.min_wrist_angle);
  j.field("configuration_changes_between_passes", m.configuration_changes);
  j.field("configuration_changes_inside_passes", 0);
  j.field("e1_reversals_inside_passes", m.positioner.reversals_in_passes);
  j.field("e1_reversals_inside_passes_if_e1_were_a", m.positioner.a_reversals_in_passes);
  j.field("e1_max_offset_from_a_deg", m.positioner.max_offset);
  if (r.has_robot_replay) {
    j.key("replay").begin_object();
    robot_replay_fields(j, rp);
    j.end_object();
  }
  j.end_object();
}

std::string robot_markdown(const ExportResult& r) {
  const RobotOptions& ro = r.machine.robot;
  const RobotMotion& m = r.robot;
  const RobotReplayResult& rp = r.robot_replay;
  std::ostringstream o;
  o << "## Robot cell\n\n| | |\n|---|---|\n";
  o << "| arm | " << ro.arm_name << " |\n| positioner (E1) | " << ro.positioner_name << " |\n";
  o << "| program | " << r.robot_main << " (" << ro.dialect << ", " << m.targets.size()
    << " targets) |\n";
  o << "| cycle time | " << fmt("%.1f", m.cycle_time) << " s (planned "
    << fmt("%.1f", m.planned_time) << " s; " << m.slowed_moves
    << " moves slowed for joint speeds) |\n";
  o << "| joint margin | " << fmt("%.1f", m.min_joint_margin) << " deg ("
    << m.min_joint_margin_joint
    << ") |\n| wrist singularity | |A5| >= " << fmt("%.1f", m.min_wrist_angle) << " deg |\n";
  o << "| configuration | one per pass; " << m.configuration_changes
    << " changes between passes |\n";
  o << "| positioner E1 | monotone and smooth within each circuit: "
    << m.positioner.reversals_in_passes << " reversals inside passes (E1 = A would make "
    << m.positioner.a_reversals_in_passes << "); the arm takes up to "
    << fmt("%.1f", m.positioner.max_offset) << " deg about the E1 axis |\n";
  if (r.has_robot_replay) {
    o << "| replay deviation | " << fmt("%.4f", rp.fibre.max_deviation) << " mm max ("
      << rp.max_deviation_at << "), mean " << fmt("%.4f", rp.fibre.mean_deviation)
      << " mm; eye path " << fmt("%.4f", rp.max_eye_deviation) << " mm max |\n";
    o << "| replay clearance | eye " << fmt("%.2f", rp.fibre.min_clearance)
      << " mm, flange and last link " << fmt("%.1f", rp.min_link_clearance) << " mm |\n";
    o << "| replay joints | margin " << fmt("%.1f", rp.min_joint_margin) << " deg, speed ratio "
      << fmt("%.2f", rp.max_joint_speed_ratio) << ", cycle " << fmt("%.1f", rp.cycle_time)
      << " s |\n";
  }
  o << "\n";
  return o.str();
}

}  // namespace windplan
