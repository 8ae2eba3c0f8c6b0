#pragma once
// cutlines.csv: the points of every cut-line, one row per point, in the mandrel frame (mm).
//
//   name,index,x [mm],y [mm],z [mm]
//   trim_start,0,100,0,-12.5
//
// `name` is the cut-line's name as a string (quoted when it contains a comma, a quote or a line
// break), `index` the point's 0-based position along it. A closed loop's first point is not
// repeated at the end. Numbers are printed like export/files/csv.h (deterministic, 10 significant
// digits), the file is written through write_file_atomically.
#include <filesystem>
#include <ostream>
#include <vector>

#include "planner/plan/plan.h"

namespace windplan {

/// Writes the cut-lines as CSV text (header line first, even when there are none).
void write_cutlines_csv(std::ostream& out, const std::vector<CutLine>& cutlines, int digits = 10);

/// Writes the cut-lines to a file atomically. \throw IoError naming the path
void write_cutlines_csv(const std::filesystem::path& path, const std::vector<CutLine>& cutlines,
                        int digits = 10);

}  // namespace windplan
