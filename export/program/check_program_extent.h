#pragma once
// Checks a G-code program read back (export/program/gcode_reader.h) against the plan it claims to
// wind, before the replay (export/program/replay.h) walks it sub-step by sub-step:
//  - lathe2: each operator stop's eye radius lies outside the surface of the layer after it (the
//    k-th stop naming a radius comes before layer k + 1, gcode.h); an eye inside the part is no
//    setting an operator can make (a stop naming 30 mm on a 50 mm pipe was replayed as a fibre
//    139 mm off the plan, the line named that of a later move);
//  - the eye's whole travel in the mandrel frame (the replay's measure: the chord and the arc of
//    each move, rapid moves excluded) is at most `max_travel_mm`: each block was already bounded
//    (100 m), but a stop naming an eye radius of 99999 mm made a two-layer pipe's 15489 blocks
//    a replay of hours without a word.
#include <string>

#include "export/program/gcode_reader.h"
#include "geometry/mesh/mesh.h"
#include "planner/job/machine_options.h"
#include "planner/plan/plan.h"

namespace windplan {

struct ProgramExtentOptions {
  /// mm of eye travel over the whole program: 2e7 replay sub-steps of 0.5 mm (10 km, the bound
  /// on the fibre a plan lays, planner/job/job_limits.h), > 0
  double max_travel_mm = 1e7;
  bool is_valid(std::string* why) const;
};

struct ProgramExtent {
  double eye_travel_mm = 0.0;  ///< the eye's travel over the program's feed moves (mm)
};

/// \param program as read; \param plan the plan it winds (its layers' surface radii);
/// \param mandrel the mandrel mesh (for lathe2's eye cylinder before the first stop);
/// \param name the program file for messages
/// \throw InputError naming `name:line`: a stop's radius at or inside the surface of the layer
///        after it; the eye's travel beyond the bound (the line where it passes it).
ProgramExtent check_program_extent(const GcodeProgram& program, const WindingPlan& plan,
                                   const Mesh& mandrel, const MachineOptions& machine,
                                   const std::string& name,
                                   const ProgramExtentOptions& options = {});

}  // namespace windplan
