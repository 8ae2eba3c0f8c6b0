// libFuzzer harness: the STEP/IGES/BREP importer and the tessellation (geometry/cad), the format
// chosen by the first byte (0: STEP, 1: IGES, 2: BREP), the rest written to a file of that
// extension. Every input must import (and tessellate) or be refused with an InputError naming the
// file: a crash inside OpenCASCADE is turned into one (geometry/cad/occt_signals.h), anything else
// (another exception, an uncaught crash, a sanitizer report, a hang) is a finding. OCCT's static
// set-up leaks: run with -detect_leaks=0 (docs/bad_inputs.md, "Fuzzing").
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "geometry/base/errors.h"
#include "geometry/cad/cad_import.h"
#include "geometry/cad/tessellate.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kExt[] = {".step", ".igs", ".brep"};
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("windplan_fuzz_cad_" + std::to_string(::getpid()) + kExt[data[0] % 3]);
  {
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    const windplan::CadImport c = windplan::import_cad(file);
    windplan::TessellateOptions t;
    t.linear_deflection = 1.0;  // coarse: the fuzzer is after crashes, not accuracy
    windplan::tessellate(c.shape, t);
  } catch (const windplan::InputError&) {
    // A clear refusal with the file.
  }
  std::error_code ec;
  std::filesystem::remove(file, ec);
  return 0;
}
