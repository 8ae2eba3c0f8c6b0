#pragma once
// One number formatted with a printf conversion, for reports and messages:
// format_number("%.3f", 1.5) == "1.500", format_fixed(1.5, 3) == "1.500". Negative zero
// prints as 0 (v + 0.0).
#include <cstdio>
#include <cstdlib>
#include <string>

namespace windplan {

/// \param format a printf format with exactly one double conversion (e.g. "%.2f", "%g")
inline std::string format_number(const char* format, double v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, format, v + 0.0);
  return buf;
}

/// v with `digits` decimals ("%.*f"): format_fixed(38.114, 2) == "38.11".
inline std::string format_fixed(double v, int digits) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v + 0.0);
  return buf;
}

/// The shortest "%g" form that reads back as v exactly, for messages quoting a user's value:
/// format_shortest(1.0000001) == "1.0000001" (std::to_string gave "1.000000", hiding why 1.0000001
/// is not in [0, 1]).
inline std::string format_shortest(double v) {
  char buf[64];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v + 0.0);
    if (std::strtod(buf, nullptr) == v + 0.0) break;
  }
  return buf;
}

}  // namespace windplan
