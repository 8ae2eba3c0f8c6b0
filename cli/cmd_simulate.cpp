// windplan simulate <job.yaml> <program> [--json FILE]
// Reads back a G-code program (windplan's or a user's edit, in the job's dialect), runs it through
// the job's machine model and replays where the fibre lands (export/program/replay.h).
#include <fstream>
#include <iostream>
#include <sstream>
#include <vector>

#include "cli/args.h"
#include "cli/commands.h"
#include "export/files/robot_report.h"
#include "export/machine/kinematics.h"
#include "export/program/check_program_extent.h"
#include "export/program/gcode_reader.h"
#include "export/program/replay.h"
#include "export/robot/robot_program_reader.h"
#include "export/robot/robot_replay.h"
#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/base/input_file.h"
#include "geometry/base/json.h"
#include "planner/job/job.h"
#include "planner/pipeline.h"
#include "planner/plan_layup.h"

namespace windplan::cli {

const char* const kSimulateHelp =
    "usage: windplan simulate <job.yaml> <program> [--json FILE]\n\n"
    "Reads back a G-code program in the job's dialect (machine.gcode.dialect; one windplan wrote\n"
    "or one a user edited), runs it through the job's machine model and reconstructs where the\n"
    "fibre lands on the mandrel from the eye position and spindle angle of every block. Prints\n"
    "the largest deviation from the planned fibre path, the eye's least distance from the\n"
    "surface it winds on (the mandrel, or the layer in work), axis ranges, reversals, the axis\n"
    "velocity and acceleration against their limits and the wind time, and writes them to a\n"
    "JSON file. Exit 1 for a program with an unknown word, another\n"
    "dialect's words or a move beyond an axis's travel (the line is named), or when the\n"
    "deviation exceeds machine.replay_tolerance or the eye comes nearer the surface of the layer\n"
    "in work than machine.envelope.clearance less chord_tolerance (both when replay_tolerance\n"
    "> 0; a lathe2 layup's eye radius is the one named at each layer's stop, M0).\n"
    "A robot cell's job (machine.robot.arm) reads a KRL (.src, with its .dat and parts) or\n"
    "RAPID (.mod) program instead (machine.robot.dialect), solves every target by inverse\n"
    "kinematics, runs forward kinematics and the positioner E1, and also reports the clearance\n"
    "of the flange and last link, joint margins and speeds, the wrist angle and the cycle time;\n"
    "a target out of reach or past a joint limit is an error naming its file and line.\n\n"
    "  --json FILE   the JSON report (default: <program>.simulate.json)\n";

namespace {

/// Writes the replay's JSON report (--json, else <program>.simulate.json) and prints the
/// replay's summary with the report's path.
void write_simulate_report(const Args& args, const std::filesystem::path& program_file,
                           const std::string& json, const std::string& summary) {
  const std::filesystem::path out =
      args.has("--json") ? std::filesystem::path(args.value("--json"))
                         : std::filesystem::path(program_file.string() + ".simulate.json");
  write_text_atomically(out, json + "\n");
  std::cout << summary << "\n  report: " << out.string() << "\n";
}

/// The job planned as windplan run plans it: a layup (planner/plan_layup.h: every layer, each
/// circuit on the surface its layer was wound on) or one layer.
struct PlannedJob {
  bool layered = false;
  PipelineResult single;
  LayupResult layup;
  const WindingPlan& plan() const { return layered ? layup.plan : single.plan; }
  const Mesh& mesh() const { return layered ? layup.mandrel.mesh : single.mandrel.mesh; }
  /// Per circuit, the surface it was wound on (empty: the mandrel under all).
  std::vector<const Mesh*> surfaces() const {
    return layered ? layup_circuit_surfaces(layup) : std::vector<const Mesh*>{};
  }
};

PlannedJob plan_as_run(const Job& job) {
  PipelineOptions po;
  PlannedJob p;
  p.layered = !job.layers.empty() || job.design.present;
  if (p.layered) {
    p.layup = plan_layup(job, po);
  } else {
    p.single = plan_job(job, po);
  }
  return p;
}

/// A robot cell's program (export/robot/robot_replay.h).
int simulate_robot(const Job& job, const std::filesystem::path& program_file, const Args& args) {
  const RobotProgram program = read_robot_program(program_file, job.machine.robot.dialect);
  const PlannedJob pj = plan_as_run(job);
  const std::vector<const Mesh*> surfaces = pj.surfaces();
  // The planned motion: the eye path the targets are measured against.
  const Motion planned = compute_motion(pj.plan(), job.machine, &pj.mesh(), surfaces);
  const RobotReplayResult rp =
      replay_robot_program(program, pj.plan(), pj.mesh(), job.machine, &planned, {}, surfaces);
  JsonWriter j(2, 10);
  j.begin_object();
  j.field("job", pj.plan().job_name);
  j.field("program", program_file.string());
  j.field("dialect", job.machine.robot.dialect);
  j.field("kind", job.machine.kind);
  j.field("arm", job.machine.robot.arm_name);
  j.field("targets", rp.targets);
  j.field("substeps", rp.fibre.substeps);
  robot_replay_fields(j, rp);
  j.field("min_joint_margin_joint", rp.min_joint_margin_joint);
  j.field("max_joint_speed_at", rp.max_joint_speed_at);
  j.field("replay_seconds", rp.seconds);
  j.end_object();
  write_simulate_report(args, program_file, j.str(), rp.summary);
  if (ReplayExcess e; !rp.within(job.machine.replay_tolerance, &e)) {
    throw InputError(e.located(program_file.string()));
  }
  if (std::string why; job.machine.envelope.mode() == "clearance" &&
                       !rp.keeps_clearance(job.machine.envelope.clearance, &why)) {
    throw InputError(why);
  }
  return 0;
}

}  // namespace

int run_simulate(const std::vector<std::string>& argv) {
  const Args args(argv, {}, {"--json"});
  args.expect_positional(2, "a job file and a G-code program");
  const Job job = load_job(args.positional()[0]);
  const std::filesystem::path program_file = args.positional()[1];
  if (job.machine.kind == "robot" && job.machine.robot.has_arm()) {
    return simulate_robot(job, program_file, args);
  }
  const std::string text = read_input_file(program_file, kProgramFileCap, "a G-code program");
  const GcodeProgram program = read_gcode(text, job.machine, program_file.string());

  // A layup: every layer, each circuit replayed on the surface its layer was wound on.
  const PlannedJob pj = plan_as_run(job);
  const WindingPlan& plan = pj.plan();
  // The stops' eye radii outside the part and the eye's travel bounded, before the sub-steps.
  check_program_extent(program, plan, pj.mesh(), job.machine, program_file.string());
  const ReplayResult rp = replay_program(program, plan, pj.mesh(), job.machine, {}, pj.surfaces());

  JsonWriter j(2, 10);
  j.begin_object();
  j.field("job", plan.job_name);
  j.field("program", program_file.string());
  j.field("dialect", job.machine.gcode.dialect);
  j.field("kind", job.machine.kind);
  j.field("blocks", rp.blocks);
  j.field("substeps", rp.substeps);
  j.field("held_substeps", rp.held_substeps);
  j.field("max_deviation_mm", rp.max_deviation);
  j.field("max_deviation_line", rp.max_deviation_line);
  j.field("mean_deviation_mm", rp.mean_deviation);
  j.field("min_clearance_mm", rp.min_clearance);
  j.field("min_clearance_line", rp.min_clearance_line);
  j.field("wind_time_s", rp.wind_time);
  j.field("carriage_reversals", rp.carriage_reversals);
  j.field("spindle_reversals", rp.spindle_reversals);
  j.field("max_velocity_ratio", rp.limits.velocity_ratio);
  j.field("max_acceleration_ratio", rp.limits.acceleration_ratio);
  j.key("axis_ranges").begin_object();
  j.key("A_deg").begin_object().field("min", rp.a_min).field("max", rp.a_max).end_object();
  j.key("X_mm").begin_object().field("min", rp.x_min).field("max", rp.x_max).end_object();
  j.key("Y_mm").begin_object().field("min", rp.y_min).field("max", rp.y_max).end_object();
  j.key("B_deg").begin_object().field("min", rp.b_min).field("max", rp.b_max).end_object();
  j.end_object();
  j.field("replay_seconds", rp.seconds);
  j.end_object();
  write_simulate_report(args, program_file, j.str(), rp.summary);
  if (ReplayExcess e; !rp.within(job.machine.replay_tolerance, &e)) {
    throw InputError(e.located(program_file.string()));
  }
  // The eye kept the clearance from the layer in work (a lathe2 layup's program without its
  // stops' eye radii replays on the mandrel's cylinder: 16.32 mm on a two-layer pipe).
  const double clearance =
      job.machine.envelope.mode() == "free_length" ? 0.0 : job.machine.envelope.clearance;
  if (const std::string why =
          rp.clearance_short(program_file.string(), clearance, job.machine.chord_tolerance, true);
      job.machine.replay_tolerance > 0.0 && !why.empty()) {
    throw InputError(why);
  }
  return 0;
}

}  // namespace windplan::cli
