#pragma once
// Writing B-rep shapes to STEP (AP214), IGES (5.3, B-rep faces) or BREP, in millimetres, through
// write_file_atomically (OCCT writes a temporary file that is then copied into place atomically).
#include <filesystem>

#include "geometry/cad/cad_shape.h"

namespace windplan {

struct CadExportOptions {
  /// IGES only: write loose trimmed faces (IGES 144, mode 0) instead of B-rep solids (186,
  /// mode 1), as many CAD systems do; import_cad sews them back.
  bool iges_loose_faces = false;
};

/// Writes `shape` to `file`; the format follows the extension (.step/.stp, .iges/.igs,
/// .brep/.brp). \throw IoError naming the file when the extension is unknown or writing fails.
void export_cad(const CadShape& shape, const std::filesystem::path& file,
                const CadExportOptions& options = {});

}  // namespace windplan
