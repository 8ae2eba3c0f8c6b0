#pragma once
// G-code for lathe-type winding machines (machine.kind lathe2 or lathe4) in three dialects.
//
// Every resampled machine state (export/machine/kinematics.h) becomes exactly one motion line, in
// order: the first state of the plan a rapid G0, every other one a G1 with its feed. Axis words
// carry the machine value sign * v + offset of each axis (machine.axes), fixed to 4 decimals (mm
// and deg); a word is written only when its rounded value changes (at least one word per line). A
// header comment names the job, the windplan version, the units and the feed convention.
//
//  - linuxcnc (RS274NGC, toolpath.ngc): % ... %, G21 G90 and G93 (inverse time, F = 1 / move
//    time in minutes, on every G1) or G94 (F in combined axis units per minute, degrees counted
//    as mm), ends with M2.
//  - marlin (toolpath.gcode): G21, G90, G94 (F per minute as above), and after the move to the
//    first point of each circuit `G92 <A>0` re-zeroes the spindle axis so that the unwrapped
//    angle does not grow without bound (A words are then relative to that circuit's start; the
//    A offset is not applied); ends with M84.
//  - fanuc (toolpath.nc): main program O<program_number> with N line numbers, G21 G90 G93/G94,
//    calls one subprogram per circuit (O<program_number + 1 + k> for the k-th circuit) with
//    M98 P..., each ending with M99; the main program ends with M30. Comments are upper case.
//    N numbers restart at 1 in each program and wrap after 99999.
//
// Layups (Motion::layers not empty, planner/plan_layup.h): before the first circuit of each layer a
// comment names it (number, name, kind, its circuits); between two layers the program comments
// the end of the previous one ("tie off and cut the tow"), pauses with M0 (the operator ties off,
// cuts and ties the tow on at the next layer's start, then presses cycle start) and moves to the
// next layer's first point with a rapid G0 (the tow is cut: no fibre is laid on the way). Fanuc
// writes these in the main program before the layer's first M98 call. lathe2 (no cross-feed: its
// eye radius is set by hand per setup) winds each layer with the eye on its own cylinder
// (export/machine/kinematics.h): its M0 carries the comment eye_radius_comment(R), "eye radius
// R mm: set the eye by hand, then cycle start" (R with 4 decimals; upper case in Fanuc), which
// the reader turns into the eye radius of the moves that follow (export/program/gcode_reader.h).
#include <string>

#include "export/machine/kinematics.h"
#include "planner/job/machine_options.h"

namespace windplan {

/// ".ngc", ".gcode" or ".nc".
std::string gcode_extension(const std::string& dialect);

/// The whole program text for `motion` (from compute_motion with the same options).
/// \throw InputError for a robot machine (no G-code) or when Fanuc program numbers exceed 9999.
std::string gcode_program(const Motion& motion, const std::string& job_name,
                          const MachineOptions& opts);

/// Formats a value with 4 decimals, "-0.0000" written as "0.0000".
std::string format_fixed4(double v);

/// The comment of a lathe2 layup's operator stop that names the next layer's eye radius (mm).
std::string eye_radius_comment(double radius_mm);

}  // namespace windplan
