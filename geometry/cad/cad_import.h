#pragma once
// Reading CAD models (STEP, IGES, BREP) into one B-rep solid or shell, in millimetres.
//
// The format is chosen by the extension (.step/.stp, .iges/.igs, .brep/.brp, case-insensitive).
// STEP and IGES files carry their length unit and are converted to mm by the reader; BREP files
// have none, so `brep_unit_to_mm` scales them. IGES models saved as loose faces are sewn
// (BRepBuilderAPI_Sewing) into shells; a closed sewn shell becomes a solid.
//
// A file with several solids (or, lacking solids, several shells) yields the one named by
// `solid` (its name in the file, or its 1-based index "2"), otherwise the largest (by volume for
// solids, by area for shells) with a warning naming the others.
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/cad/cad_shape.h"

namespace windplan {

struct CadImportOptions {
  /// Which solid/shell to take: "" = the largest, a name from the file, or a 1-based index.
  std::string solid;
  /// Scale of a BREP file's coordinates to mm (STEP/IGES carry their unit): mm/unit, > 0.
  double brep_unit_to_mm = 1.0;
  /// Sewing tolerance for loose faces (mm, > 0).
  double sewing_tolerance = 1e-3;
  /// Refuse an open shell (InputError) instead of returning it with a warning.
  bool require_closed = false;

  bool is_valid(std::string* why) const;
};

struct CadImport {
  CadShape shape;                   ///< the selected solid or shell (mm)
  std::string format;               ///< "step", "iges" or "brep"
  std::string selected;             ///< name of the selected body ("solid 1" when unnamed)
  std::vector<std::string> bodies;  ///< names of all candidate bodies, in file order
  bool is_solid = false;            ///< a solid (else a shell)
  bool closed = false;              ///< no free edges
  bool sewn = false;                ///< loose faces were sewn
  std::vector<std::string> warnings;
};

/// Reads `file`.
/// \throw IoError naming the file when it is missing, empty, not a STEP/IGES/BREP file of the
///        kind its extension says, or unreadable; InputError naming the file when it has no
///        surfaces (only wires or points), when `solid` names no body, or when a closed body is
///        required and the selected one is open; ConfigError for invalid options.
CadImport import_cad(const std::filesystem::path& file, const CadImportOptions& options = {});

/// True for the extensions import_cad reads.
bool is_cad_file(const std::filesystem::path& file);

}  // namespace windplan
