#pragma once
// Options of the `machine:` and `output:` sections of a job (schema: docs/config.md). They live in
// planner/ because the Job struct holds them and planner/ must not include export/; export/
// (kinematics, G-code, files) reads them.
//
// Units: lengths in mm, angles in degrees, times in seconds, velocities in mm/s or deg/s.
#include <array>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "planner/job/robot_options.h"

namespace windplan {

/// The clearance envelope the payout eye moves on: a surface of revolution around the spindle
/// axis. Exactly one mode applies:
///  - "clearance" (default): the mandrel's radius profile plus `clearance`;
///  - "profile": the explicit (axial, radius) polyline `profile`;
///  - "free_length": no envelope, the eye is at a fixed free-fibre length along the tangent.
struct EnvelopeOptions {
  double clearance = 20.0;  ///< mm added to the mandrel radius profile, > 0
  std::vector<std::array<double, 2>>
      profile;               ///< [[x mm, r mm], ...], x strictly increasing, r > 0
  double free_length = 0.0;  ///< mm; > 0 selects the fixed-free-length mode
  /// mm: lathe2 eye cylinder radius; 0 = the largest mandrel radius + clearance. >= 0
  double radius = 0.0;

  /// "clearance", "profile" or "free_length", from which field is set.
  std::string mode() const;
  bool is_valid(std::string* why) const;
};

/// One machine axis: how the planner's value v maps to the G-code word (sign * v + offset),
/// its travel limits (on that machine value) and its velocity limit.
struct AxisOptions {
  std::string letter;   ///< G-code address letter (one of A B C U V W X Y Z)
  double sign = 1.0;    ///< +1 or -1
  double offset = 0.0;  ///< mm or deg added after the sign
  double min =
      -std::numeric_limits<double>::infinity();  ///< travel limit (mm or deg), machine value
  double max =
      std::numeric_limits<double>::infinity();  ///< travel limit (mm or deg), machine value
  double max_velocity = 100.0;                  ///< mm/s or deg/s, > 0
  double max_acceleration = 1000.0;             ///< mm/s^2 or deg/s^2, > 0

  bool is_valid(std::string* why) const;
};

/// G-code output.
struct GcodeOptions {
  /// "linuxcnc" (RS274NGC, toolpath.ngc), "marlin" (toolpath.gcode), "fanuc" (toolpath.nc).
  std::string dialect = "linuxcnc";
  /// Feed convention: "auto" (linuxcnc: inverse_time; marlin, fanuc: per_minute),
  /// "inverse_time" (G93, F = 1 / move time in minutes; not for marlin) or "per_minute" (G94,
  /// F = combined axis distance per minute, degrees counted as mm).
  std::string feed = "auto";
  int program_number = 1000;  ///< Fanuc main program O number; circuit c is O(number + 1 + c)

  bool is_valid(std::string* why) const;
};

/// The `machine:` section.
struct MachineOptions {
  /// "lathe2" (spindle A + carriage X), "lathe4" (+ cross-feed Y and eye rotation B) or
  /// "robot" (eye pose in the mandrel frame, eye_pose.csv, no G-code).
  std::string kind = "lathe2";
  EnvelopeOptions envelope;
  /// mm: resampled fibre and eye polylines stay within this distance of the dense ones, > 0.
  double chord_tolerance = 0.05;
  /// mm/s: upper bound on the fibre laying speed; 0 = no bound.
  double max_fibre_speed = 0.0;
  /// mm: largest half-width of the arc-length window of the local quadratic fit that gives the
  /// fibre tangents the eye is placed along (export/machine/tangent_smoothing.h); 0 = the plan's
  /// tangents.
  double tangent_window = 15.0;
  /// Each circuit's spindle A monotone, its carriage X monotone between its two turning points
  /// (export/machine/monotone_axes.h).
  bool monotone_axes = true;
  /// mm: a program whose replay (export/program/replay.h) lays the fibre farther than this from the
  /// planned path is not written by `windplan run`; 0 = replay and report only. >= 0
  double replay_tolerance = 0.5;
  /// The profile file the machine was read from (machine.profile), empty if none; for reports.
  std::string profile;
  /// A spindle (deg), X carriage (mm), Y cross-feed (mm), B eye rotation (deg).
  AxisOptions a{"A",
                1.0,
                0.0,
                -std::numeric_limits<double>::infinity(),
                std::numeric_limits<double>::infinity(),
                720.0,
                1440.0};
  AxisOptions x{"X",
                1.0,
                0.0,
                -std::numeric_limits<double>::infinity(),
                std::numeric_limits<double>::infinity(),
                500.0,
                2000.0};
  AxisOptions y{"Y",
                1.0,
                0.0,
                -std::numeric_limits<double>::infinity(),
                std::numeric_limits<double>::infinity(),
                200.0,
                1000.0};
  AxisOptions b{"B",
                1.0,
                0.0,
                -std::numeric_limits<double>::infinity(),
                std::numeric_limits<double>::infinity(),
                360.0,
                1440.0};
  GcodeOptions gcode;
  /// The robot cell (kind robot with an arm: KRL or RAPID programs; planner/job/robot_options.h).
  RobotOptions robot;

  bool is_valid(std::string* why) const;
};

/// The `output:` section: which files export_plan writes, and where.
struct OutputOptions {
  /// Output directory; relative paths resolve against the job file's directory. Empty: the CLI
  /// chooses ("<job name>.out" beside the job).
  std::filesystem::path directory;
  bool csv = true;     ///< fibre_path.csv, payout.csv, axes.csv (and eye_pose.csv for robots)
  bool gcode = true;   ///< toolpath.ngc / .gcode / .nc (not for robots)
  bool report = true;  ///< report.json, report.md
  bool ply = true;     ///< mesh.ply, paths.ply
  bool svg = true;     ///< development.svg, axes.svg
  bool viewer = true;  ///< viewer.html (export/plots/viewer.h)
  /// Stage timings in report.json/report.md. Off by default so that two runs of the same job
  /// give byte-identical files; the stdout summary always shows them.
  bool timings = false;

  bool is_valid(std::string* why) const;
};

}  // namespace windplan
