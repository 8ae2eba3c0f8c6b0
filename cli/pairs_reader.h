#pragma once
// The points and pairs files of `windplan geodesic` (cli/cmd_geodesic.cpp), read from their text
// so that the fuzz harness (tests/fuzz/fuzz_pairs.cpp) reaches the same code:
// - batch_lines_of: one entry per line that holds data (blank lines and '#' lines skipped),
//   tokens separated by spaces, tabs or ';'; a control character (NUL, ...) other than tab and
//   CR anywhere in a line is refused with the line (it was cut by the number parser and copied
//   whole into the CSV).
// - parse_point: a vertex index, or x,y,z snapped to the mesh within `tolerance` mm.
// - read_pairs_of: every line 'FROM TO', checked before anything is solved.
#include <string>
#include <vector>

#include "geometry/mesh/closest_point.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/surface_path.h"

namespace windplan::cli {

/// A line of a batch file that holds data: its 1-based number, its text and its tokens.
struct BatchLine {
  int number = 0;
  std::string text;
  std::vector<std::string> tokens;
};

/// One pair of `--pairs`, as given and as parsed.
struct BatchPair {
  int line = 0;
  std::string from, to;
  SurfacePoint a, b;
};

/// Strict number parsing: false unless all of `s` (NULs included) is one double.
bool parse_double(const std::string& s, double* out);

/// \throw InputError "FILE:LINE: ..." for a control character.
std::vector<BatchLine> batch_lines_of(const std::string& text, const std::string& file);

/// \throw UsageError for text that is no point, InputError for a point off the mesh.
SurfacePoint parse_point(const Mesh& mesh, const ClosestPointQuery& query, double tolerance,
                         const std::string& option, const std::string& text);

/// \throw InputError "FILE:LINE: ..." for the first bad line, or when there is no pair.
std::vector<BatchPair> read_pairs_of(const std::string& text, const std::string& file,
                                     const Mesh& mesh, const ClosestPointQuery& query,
                                     double tolerance);

}  // namespace windplan::cli
