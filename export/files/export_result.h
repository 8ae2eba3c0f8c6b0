#pragma once
// What export_plan (export/export_plan.h) returns: the files written, the motion and the G-code
// replay, the machine options as used. The reports (export/files/report.h) are made from it.
#include <filesystem>
#include <string>
#include <vector>

#include "export/machine/kinematics.h"
#include "export/program/replay.h"
#include "export/robot/robot_motion.h"
#include "export/robot/robot_replay.h"
#include "planner/job/machine_options.h"

namespace windplan {

struct ExportResult {
  std::filesystem::path directory;
  std::vector<std::string> files;  ///< names written, in order (relative to directory)
  Motion motion;                   ///< eye, axes, times (from compute_motion)
  /// The replay of the G-code program (lathe kinds with a non-empty mandrel mesh); has_replay
  /// false otherwise.
  bool has_replay = false;
  ReplayResult replay;
  /// A robot cell with an arm (machine.robot.arm): its motion, the program's main file and the
  /// replay of the written program (export/robot/); `replay` then holds its fibre part.
  bool has_robot = false;
  RobotMotion robot;
  std::string robot_main;
  bool has_robot_replay = false;
  RobotReplayResult robot_replay;
  MachineOptions machine;  ///< as used
  bool timings = false;    ///< output.timings
};

}  // namespace windplan
