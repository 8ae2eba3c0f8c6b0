#pragma once
// Reads back a G-code program of one of the three dialects windplan writes
// (export/program/gcode.h), as written or as a user edited it, into the moves a lathe-type winder
// would make.
//
// Accepted, per dialect (anything else is an error naming the line):
//   all:      G0, G1 (modal), G21, G90, G94, F, M0 (the pause between layers; lathe2: its comment
//             "eye radius R mm", case-insensitive, R in decimal, 0 < R <= 100 m, sets the eye
//             radius of the moves after it, export/program/gcode.h; a comment naming an eye
//             radius anywhere else, twice, or in another kind's program, is an error), the
//             machine's axis
//   letters (lathe2: X and A;
//             lathe4: X, Y, A, B, as named in machine.axes), blank lines;
//   linuxcnc: "%" lines, ( ) and ; comments, G93, M2, M30;
//   marlin:   ; comments, G92 (re-zeroing; shifts are undone so values stay absolute), M84, M2;
//   fanuc:    "%" lines, ( ) comments, O program labels, N numbers, G93, M98 P.. / M99
//             subprogram calls and returns, M30.
// A program that uses another dialect's words (O, M98, M99 outside fanuc; G92, M84 outside
// marlin; G93 or "( )" comments in marlin) is reported as written for that dialect. Inch units
// (G20), incremental mode (G91), arcs (G2/G3) and other codes are errors. Axis values are turned
// back into the planner's values ((word - offset) / sign; Marlin's A without offset, see
// export/program/gcode.h), and each move is checked against the axes' travel limits.
#include <string>
#include <vector>

#include "planner/job/machine_options.h"

namespace windplan {

struct GcodeBlock {
  int line = 0;                               ///< 1-based line number in the program text
  bool rapid = false;                         ///< G0
  double a = 0.0, x = 0.0, y = 0.0, b = 0.0;  ///< planner values (deg, mm, mm, deg) after the move
  double feed = 0.0;                          ///< modal F at the move
  bool inverse_time = false;                  ///< G93 active at the move
  /// lathe2: mm, the eye radius named at the last operator stop before the move (M0 with "eye
  /// radius R mm"); 0: none yet, the machine's own (export/program/replay.h)
  double eye_radius = 0.0;
};

/// lathe2: an operator stop (M0) naming the eye radius of the layer after it.
struct GcodeEyeStop {
  int line = 0;         ///< 1-based line number of the M0
  double radius = 0.0;  ///< mm, > 0
};

struct GcodeProgram {
  std::vector<GcodeBlock> blocks;       ///< motion blocks in execution order
  std::vector<GcodeEyeStop> eye_stops;  ///< lathe2: the stops naming an eye radius, in order
  bool inverse_time = false;            ///< G93 seen
  bool ended = false;                   ///< reached its end code
};

/// \param text the program; \param name the file name for messages
/// \throw InputError naming `name:line` for an unknown word or code, another dialect's word, a
///        first move that leaves an axis undefined, a value beyond an axis's travel, a G1 without
///        a feed, or a missing end code.
GcodeProgram read_gcode(const std::string& text, const MachineOptions& machine,
                        const std::string& name = "program");

}  // namespace windplan
