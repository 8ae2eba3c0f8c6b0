// libFuzzer harness: the OFF mesh reader (geometry/mesh/mesh_io.h, read_mesh_data on ".off").
// Every input must give a triangle soup or an IoError naming the element; anything else -- another
// exception, a crash, a sanitizer report, a hang -- is a finding. Run: docs/bad_inputs.md.
#include <cstddef>
#include <cstdint>
#include <string>

#include "geometry/base/errors.h"
#include "geometry/mesh/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    windplan::read_mesh_data(bytes, "fuzz.off");
  } catch (const windplan::InputError&) {
    // A clear refusal.
  }
  return 0;
}
