// libFuzzer harness: the pairs file of `windplan geodesic --pairs` (cli/pairs_reader.h) on a
// 10 x 10 grid: lines, tokens, vertex indices and x,y,z points snapped to the mesh. Every input
// must be read or refused with an InputError naming the line; anything else (another exception,
// a crash, a sanitizer report, a hang) is a finding. Run: docs/bad_inputs.md, "Fuzzing".
#include <cstddef>
#include <cstdint>
#include <string>

#include "cli/pairs_reader.h"
#include "geometry/base/errors.h"
#include "tests/mesh_fixtures.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const windplan::Mesh mesh(windplan::test::grid(10, 10));
  static const windplan::ClosestPointQuery query(mesh);
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    windplan::cli::read_pairs_of(text, "fuzz.txt", mesh, query, 0.5);
  } catch (const windplan::InputError&) {
    // A clear refusal with the line.
  }
  return 0;
}
