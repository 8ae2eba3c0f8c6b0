#pragma once
// Robot programs of a robot cell's motion (export/robot/robot_motion.h), in the dialect
// machine.robot.dialect:
//  - "krl" (KUKA KRL): a main module <base>.src + <base>.dat (the TOOL and BASE frames, set in the
//    .src with the external axis E1 at 100 % of its speed) calling parts <base>_pNN.src + .dat of
//    at most machine.robot.max_points targets each; a target is an E6POS (X, Y, Z in mm, A, B, C in
//    deg in the BASE frame, Status S and Turn T, E1 in deg) declared in the part's .dat; the first
//    target of the plan and of each layer is reached with PTP (the tow is tied on), every other
//    with LIN ... C_DIS after $VEL.CP (m/s) = TCP distance / the move's duration and
//    $VEL_EXTAX[1] (% of E1's max_velocity) = |dE1| / the move's duration (each written when it
//    changes);
//  - "rapid" (ABB RAPID): a main module <base>.mod (the tool data tEye and the work object
//    wPositioner, PROC main calling the parts) and parts <base>_pNN.mod whose procedures move with
//    MoveJ (tie-on) and MoveL to inline robtargets ([pos mm], [quaternion q1..q4], [cf1, cf4, cf6,
//    cfx], [E1 deg, 9E9 ...]) with speed v1000\T:= the move's duration (s) and zone z1.
// <base> is "wp_" and the job name in lower case letters, digits and '_' (at most 20 characters).
// Numbers: mm and deg with 4 decimals, quaternions and $VEL.CP (m/s) with 9.
#include <string>
#include <vector>

#include "export/robot/robot_motion.h"

namespace windplan {

struct ProgramFile {
  std::string name;  ///< file name (no directory)
  std::string text;
};

/// The module name of a job's program ("wp_" + the sanitised job name).
std::string robot_program_base(const std::string& job_name);
/// The file `windplan simulate` reads first: <base>.src (krl) or <base>.mod (rapid).
std::string robot_program_main(const std::string& job_name, const std::string& dialect);

/// The files of the program, main first. \throw ConfigError for an unknown dialect
std::vector<ProgramFile> robot_program(const RobotMotion& motion, const std::string& job_name,
                                       const MachineOptions& machine);

}  // namespace windplan
