#pragma once
// Reads a robot program back (KUKA KRL or ABB RAPID as export/robot/robot_program.h describes
// them, or one a person wrote or edited in that subset), written independently of the writer: it
// shares no code with robot_program.cpp.
//
// KRL: the main .src (its .dat beside it: DECL FRAME ... = {X, Y, Z, A, B, C}) sets $TOOL and $BASE
// to declared frames, may set $VEL_EXTAX[1] and $APO.CDIS, and calls parts NAME( ) whose NAME.src
// and NAME.dat are read from the same folder ($VEL_EXTAX[1] holds until set again); a part moves
// with PTP VAR or LIN VAR [C_DIS] to E6POS (or POS/E6AXIS-free) declarations of its .dat ({X, Y, Z,
// A, B, C[, S, T][, E1..E6]}), and sets $VEL.CP (m/s). Comments start with ';'; '&' lines are
// ignored. RAPID: the main module declares tooldata and wobjdata (PERS or CONST; the work object's
// user frame times its object frame is the BASE) and PROC main calls the parts; NAME.mod beside it
// holds MODULE NAME with PROC NAME() of MoveJ / MoveL to inline robtargets [[x, y, z], [q1..q4],
// [cf...], [E1, ...]] with speeddata (v<n> or v<n>\T:=seconds), a zone and the tool\WObj. Comments
// start with '!'. Anything else (an unknown statement, a variable never declared, a malformed
// aggregate, a missing part file, a tool or work object not declared): InputError naming the file
// and line. Also refused, naming the line: a part called twice, or calling itself or the main
// program (each part runs once); a name declared twice (in one .dat, or in the RAPID modules); a
// position beyond 100 m, an angle A, B or C beyond +-360 deg, an E1 beyond 1e9 deg; S or cfx not
// a whole number 0 to 7; $VEL.CP outside [1e-6, 10] m/s; \T over a day; a RAPID part that calls.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

struct RobotProgramTarget {
  std::string file;                                        ///< file name (no folder) of the move
  int line = 0;                                            ///< 1-based
  bool joint_move = false;                                 ///< PTP / MoveJ
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< TCP in the BASE frame (mm)
  double e1 = 0.0;                                         ///< deg
  int status = -1;                                         ///< KRL S / RAPID cfx; -1 not given
  double vel_cp = -1.0;      ///< KRL $VEL.CP at the move, m/s (-1: RAPID)
  double vel_extax = 100.0;  ///< KRL $VEL_EXTAX[1] at the move, % of E1's max velocity
  double time = -1.0;        ///< RAPID \T, s (-1: not given)
};

struct RobotProgram {
  std::string dialect;                                     ///< "krl" or "rapid"
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();  ///< TCP in the flange frame
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();  ///< BASE in the robot's base frame
  std::vector<RobotProgramTarget> targets;
  std::vector<std::string> files;  ///< files read, in order
};

/// Reads the program whose main file is `main` (.src: KRL, .mod: RAPID; `dialect` must match).
/// \throw IoError when a file cannot be read, InputError for a malformed program
RobotProgram read_robot_program(const std::filesystem::path& main, const std::string& dialect);
/// The same from files in memory (name -> text, names without folder); `main` names one of them.
RobotProgram read_robot_program(const std::map<std::string, std::string>& files,
                                const std::string& main, const std::string& dialect);

}  // namespace windplan
