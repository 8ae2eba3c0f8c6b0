// libFuzzer harness: the G-code reader (export/program/gcode_reader.h) for each dialect and
// machine kind, chosen by the first byte; the rest is the program. Every input must be read or
// refused with an InputError naming the line; anything else (another exception, a crash, a
// sanitizer report, a hang) is a finding. Run: docs/bad_inputs.md, "Fuzzing".
#include <cstddef>
#include <cstdint>
#include <string>

#include "export/program/gcode_reader.h"
#include "geometry/base/errors.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kDialects[] = {"linuxcnc", "marlin", "fanuc"};
  windplan::MachineOptions m;
  m.kind = (data[0] & 1) ? "lathe4" : "lathe2";
  m.gcode.dialect = kDialects[(data[0] >> 1) % 3];
  if (data[0] & 0x80) {  // travel limits and an offset, as a shop's machine.axes
    m.x.min = -10;
    m.x.max = 900;
    m.x.sign = -1;
    m.x.offset = 5;
  }
  const std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    windplan::read_gcode(text, m, "fuzz.ngc");
  } catch (const windplan::InputError&) {
    // A clear refusal with the line.
  }
  return 0;
}
