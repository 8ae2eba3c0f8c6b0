#include "export/export_plan.h"

#include "export/files/cutlines_csv.h"
#include "export/plots/axes_svg.h"
#include "export/plots/joints_svg.h"
#include "export/plots/stability_svg.h"

#include <algorithm>
#include <map>

#include "export/files/output_set.h"
#include "export/files/ply_polylines.h"
#include "export/files/report.h"
#include "export/plots/svg.h"
#include "export/plots/unroll.h"
#include "export/plots/viewer.h"
#include "export/program/gcode.h"
#include "export/program/gcode_reader.h"
#include "export/robot/robot_program.h"
#include "export/robot/robot_program_reader.h"
#include "export/robot/robot_replay.h"
#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/base/parallel.h"
#include "geometry/mesh/mesh_io.h"

namespace windplan {

std::filesystem::path resolve_output_directory(const OutputOptions& output,
                                               const std::filesystem::path& job_file,
                                               const std::string& job_name) {
  if (!output.directory.empty()) return output.directory;
  return job_file.parent_path() / (job_name + ".out");
}

CsvTable fibre_path_table(const WindingPlan& plan) {
  CsvTable t;
  t.header = {"circuit",
              "index",
              "x [mm]",
              "y [mm]",
              "z [mm]",
              "nx",
              "ny",
              "nz",
              "tx",
              "ty",
              "tz",
              "s [mm]",
              "winding_angle [deg]",
              "k_n [1/mm]",
              "k_g [1/mm]",
              "slippage"};
  for (const Circuit& c : plan.circuits) {
    for (std::size_t i = 0; i < c.points.size(); ++i) {
      const FibrePoint& p = c.points[i];
      t.rows.push_back({double(c.index), double(i), p.position.x(), p.position.y(), p.position.z(),
                        p.normal.x(), p.normal.y(), p.normal.z(), p.tangent.x(), p.tangent.y(),
                        p.tangent.z(), p.s, p.winding_angle, p.k_n, p.k_g, p.slippage});
    }
  }
  return t;
}

CsvTable payout_table(const Motion& motion) {
  CsvTable t;
  t.header = {"circuit",          "index",      "eye_x [mm]",
              "eye_y [mm]",       "eye_z [mm]", "free_length [mm]",
              "fibre_length [mm]"};
  for (const MachineState& s : motion.states) {
    t.rows.push_back({double(s.circuit), double(s.index), s.eye.x(), s.eye.y(), s.eye.z(),
                      s.free_length, s.paid_out});
  }
  return t;
}

CsvTable axes_table(const Motion& motion) {
  CsvTable t;
  t.header = {
      "circuit",   "index",     "t_s [s]",     "A_deg [deg]",
      "X_mm [mm]", "Y_mm [mm]", "B_deg [deg]", motion.inverse_time ? "F [1/min]" : "F [units/min]"};
  for (const MachineState& s : motion.states) {
    t.rows.push_back(
        {double(s.circuit), double(s.index), s.t_s, s.a_deg, s.x_mm, s.y_mm, s.b_deg, s.feed});
  }
  return t;
}

/// The joint-space CSV of a robot cell: E1 and A1..A6 at every machine state (its last target:
/// the targets inserted before it, export/robot/robot_motion.h, count in its time), Status and
/// Turn; one row per row of axes.csv.
CsvTable joints_table(const Motion& motion, const RobotMotion& robot) {
  CsvTable t;
  t.header = {"circuit",  "index",    "t_s [s]",  "E1 [deg]", "A1 [deg]", "A2 [deg]",
              "A3 [deg]", "A4 [deg]", "A5 [deg]", "A6 [deg]", "S",        "T"};
  double time = 0.0;
  for (std::size_t k = 0; k < robot.targets.size(); ++k) {
    const RobotTarget& g = robot.targets[k];
    const MachineState& s = motion.states[g.state];
    time += g.duration;
    if (k + 1 < robot.targets.size() && robot.targets[k + 1].state == g.state) continue;
    t.rows.push_back({double(s.circuit), double(s.index), time, g.e1, g.q[0], g.q[1], g.q[2],
                      g.q[3], g.q[4], g.q[5], double(g.status), double(g.turn)});
  }
  return t;
}

CsvTable eye_pose_table(const Motion& motion) {
  CsvTable t;
  t.header = {"circuit",    "index",      "t_s [s]", "A_deg [deg]", "eye_x [mm]",
              "eye_y [mm]", "eye_z [mm]", "dir_x",   "dir_y",       "dir_z",
              "radial_x",   "radial_y",   "radial_z"};
  for (const MachineState& s : motion.states) {
    t.rows.push_back({double(s.circuit), double(s.index), s.t_s, s.a_deg, s.eye.x(), s.eye.y(),
                      s.eye.z(), s.direction.x(), s.direction.y(), s.direction.z(), s.radial.x(),
                      s.radial.y(), s.radial.z()});
  }
  return t;
}

ExportResult export_plan(const WindingPlan& plan, const Mesh& mandrel_mesh,
                         const MachineOptions& machine, const OutputOptions& output,
                         const std::filesystem::path& dir, const ExportContext& context) {
  ExportResult r;
  r.directory = dir;
  r.machine = machine;
  r.timings = output.timings;
  r.motion = compute_motion(plan, machine, &mandrel_mesh, context.circuit_surfaces);
  const bool robot = machine.kind == "robot";
  std::string program;
  std::vector<ProgramFile> robot_files;
  if (robot && machine.robot.has_arm()) {
    // A robot cell: the arm's targets and joints, its KRL or RAPID program (read back and
    // replayed by run_replay below).
    r.robot = compute_robot_motion(r.motion, plan, machine);
    r.has_robot = true;
    robot_files = robot_program(r.robot, plan.job_name, machine);
    r.robot_main = robot_files.front().name;
  }
  if (!robot) program = gcode_program(r.motion, plan.job_name, machine);
  // The replay (long, serial) runs beside the writing of the files that do not need it; the
  // reports, which do, are written after both. When both fail, the replay's error is the one
  // thrown (parallel_for_index: the lowest index), as when the replay ran first.
  const bool replay =
      (!robot || r.has_robot) && mandrel_mesh.num_faces() > 0 && !r.motion.states.empty();
  auto run_replay = [&] {
    if (r.has_robot) {
      std::map<std::string, std::string> texts;
      for (const ProgramFile& f : robot_files) texts[f.name] = f.text;
      r.robot_replay =
          replay_robot_program(read_robot_program(texts, r.robot_main, machine.robot.dialect), plan,
                               mandrel_mesh, machine, &r.motion, {}, context.circuit_surfaces);
      r.has_robot_replay = true;
      r.replay = r.robot_replay.fibre;
      r.has_replay = true;
      if (ReplayExcess e; !r.robot_replay.within(machine.replay_tolerance, &e)) {
        throw InputError(e.refused(r.robot_main));
      }
      // The eye keeps the clearance between the targets too (no slack below it).
      if (std::string why; machine.envelope.mode() == "clearance" &&
                           !r.robot_replay.keeps_clearance(machine.envelope.clearance, &why)) {
        throw InputError("machine.envelope.clearance: " + why + " (" + r.robot_main +
                         "); no program written");
      }
      return;
    }
    const std::string name = "toolpath" + gcode_extension(machine.gcode.dialect);
    r.replay = replay_program(read_gcode(program, machine, name), plan, mandrel_mesh, machine, {},
                              context.circuit_surfaces);
    r.has_replay = true;
    if (ReplayExcess e; !r.replay.within(machine.replay_tolerance, &e)) {
      throw InputError(e.refused(name));
    }
    // The eye kept the clearance from the layer in work (issue #26: lathe2's eye radius).
    if (const std::string why = r.replay.clearance_short(name, r.motion.required_clearance,
                                                         machine.chord_tolerance, false);
        machine.replay_tolerance > 0.0 && !why.empty()) {
      throw InputError(why);
    }
  };

  // The list first, so that the reports can name every file (themselves included).
  const bool cutlines = output.csv && !plan.cutlines.empty();
  if (output.csv) {
    r.files.insert(r.files.end(), {"fibre_path.csv", "payout.csv", "axes.csv"});
    if (robot) r.files.push_back("eye_pose.csv");
    if (r.has_robot) r.files.push_back("joints.csv");
    if (cutlines) r.files.push_back("cutlines.csv");
  }
  const std::string gcode_name = "toolpath" + gcode_extension(machine.gcode.dialect);
  if (output.gcode && !robot) r.files.push_back(gcode_name);
  if (output.gcode) {
    for (const ProgramFile& f : robot_files) r.files.push_back(f.name);
  }
  if (output.ply) r.files.insert(r.files.end(), {"mesh.ply", "paths.ply"});
  if (output.svg) r.files.insert(r.files.end(), {"development.svg", "axes.svg", "stability.svg"});
  if (output.svg && r.has_robot) r.files.push_back("joints.svg");
  if (output.viewer) r.files.push_back("viewer.html");
  r.files.insert(r.files.end(), context.also_written.begin(), context.also_written.end());
  if (output.report) r.files.insert(r.files.end(), {"report.json", "report.md"});

  int done = 0;
  const int total = static_cast<int>(r.files.size());
  auto wrote = [&](const std::string& name) {
    ++done;
    if (context.on_file) context.on_file(name, done, total);
    output_test_pause(name);  // (a test hook: export/files/output_set.h)
  };
  // A robot cell's joints for the viewer's joint panel, one row per machine state, as joints.csv
  // holds them (a state's last target); joints.svg takes their names and limits.
  ViewerJoints joints;
  if (r.has_robot) {
    joints.arm = machine.robot.arm_name;
    joints.series.resize(7);
    joints.series[0].name = "E1";
    for (int j = 0; j < 6; ++j) {
      joints.series[j + 1].name = machine.robot.joints[j].name;
      joints.series[j + 1].min = machine.robot.joints[j].min;
      joints.series[j + 1].max = machine.robot.joints[j].max;
    }
    // One row per machine state (the viewer's states): a state's target, or the one before it.
    std::vector<int> target_of(r.motion.states.size(), -1);
    std::vector<double> end_time(r.robot.targets.size());
    double time = 0.0;
    for (std::size_t k = 0; k < r.robot.targets.size(); ++k) {
      const RobotTarget& g = r.robot.targets[k];
      time += g.duration;
      end_time[k] = time;
      if (g.state >= 0 && g.state < static_cast<int>(target_of.size()))
        target_of[g.state] = static_cast<int>(k);
    }
    for (std::size_t i = 1; i < target_of.size(); ++i)
      if (target_of[i] < 0) target_of[i] = target_of[i - 1];
    for (std::size_t i = 0; i < target_of.size(); ++i) {
      const int k = std::max(0, target_of[i]);
      if (r.robot.targets.empty()) break;
      const RobotTarget& g = r.robot.targets[k];
      joints.time.push_back(end_time[k]);
      joints.series[0].values.push_back(g.e1);
      for (int j = 0; j < 6; ++j) joints.series[j + 1].values.push_back(g.q[j]);
    }
  }
  auto write_files = [&] {
    if (output.csv) {
      write_csv_file(dir / "fibre_path.csv", fibre_path_table(plan));
      wrote("fibre_path.csv");
      write_csv_file(dir / "payout.csv", payout_table(r.motion));
      wrote("payout.csv");
      write_csv_file(dir / "axes.csv", axes_table(r.motion));
      wrote("axes.csv");
      if (robot) {
        write_csv_file(dir / "eye_pose.csv", eye_pose_table(r.motion));
        wrote("eye_pose.csv");
      }
      if (r.has_robot) {
        write_csv_file(dir / "joints.csv", joints_table(r.motion, r.robot));
        wrote("joints.csv");
      }
      if (cutlines) {
        write_cutlines_csv(dir / "cutlines.csv", plan.cutlines);
        wrote("cutlines.csv");
      }
    }
    if (output.gcode && !robot) {
      write_text_atomically(dir / gcode_name, program);
      wrote(gcode_name);
    }
    if (output.gcode) {
      for (const ProgramFile& f : robot_files) {
        write_text_atomically(dir / f.name, f.text);
        wrote(f.name);
      }
    }
    if (output.ply) {
      write_mesh(dir / "mesh.ply", mandrel_mesh);
      wrote("mesh.ply");
      write_text_atomically(dir / "paths.ply", paths_ply(plan));
      wrote("paths.ply");
    }
    if (output.svg) {
      const Mesh& region = context.wound_region ? *context.wound_region : mandrel_mesh;
      write_text_atomically(
          dir / "development.svg",
          development_svg(
              plan, Unrolling::make(plan, region, context.wound_face_map, context.revolution)));
      wrote("development.svg");
      write_text_atomically(dir / "axes.svg", axes_svg(r.motion, plan.job_name));
      wrote("axes.svg");
      write_text_atomically(dir / "stability.svg", stability_svg(plan));
      wrote("stability.svg");
      if (r.has_robot) {
        // The positioner's E1 and the arm's joints against time (export/plots/joints_svg.h).
        std::vector<double> t;
        std::vector<JointSeries> js = joints.series;
        for (JointSeries& j : js) j.values.clear();
        double time = 0.0;
        for (const RobotTarget& g : r.robot.targets) {
          time += g.duration;
          t.push_back(time);
          js[0].values.push_back(g.e1);
          for (int j = 0; j < 6; ++j) js[j + 1].values.push_back(g.q[j]);
        }
        write_text_atomically(dir / "joints.svg", joints_svg(t, js, plan.job_name));
        wrote("joints.svg");
      }
    }
    if (output.viewer) {
      write_text_atomically(
          dir / "viewer.html",
          viewer_page(plan, mandrel_mesh, r.motion, {}, joints.time.empty() ? nullptr : &joints)
              .html);
      wrote("viewer.html");
    }
  };
  parallel_for_index(2, [&](int i) {
    if (i == 0 && replay) run_replay();
    if (i == 1) write_files();
  });
  if (output.report) {
    write_text_atomically(dir / "report.json", report_json(plan, r));
    wrote("report.json");
    write_text_atomically(dir / "report.md", report_markdown(plan, r));
    wrote("report.md");
  }
  return r;
}

}  // namespace windplan
