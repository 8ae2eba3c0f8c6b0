// libFuzzer harness: the job loader (YAML parsing, every section's decoder, is_valid, the
// up-front bounds of planner/job/job_limits.h). Every input must load or be refused with an
// InputError (exit 1 in the CLI); anything else -- another exception, a crash, a sanitizer
// report, a hang -- is a finding. Paths in the job resolve against /nonexistent, so no input
// reaches a real file. Run: docs/bad_inputs.md, "Fuzzing".
#include <cstddef>
#include <cstdint>
#include <string>

#include "geometry/base/errors.h"
#include "planner/job/job.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    windplan::load_job_from_string(text, "/nonexistent/fuzz.yaml");
  } catch (const windplan::InputError&) {
    // A clear refusal: what the loader is for.
  }
  return 0;
}
