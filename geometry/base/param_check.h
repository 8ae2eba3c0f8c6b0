#pragma once
// Internal to geometry/: the small helpers the parametric-mandrel validators share (number
// formatting for messages, "set why and fail", finite positive check). Not a public header.
#include <cmath>
#include <sstream>
#include <string>

namespace windplan::param_check {

inline std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

inline bool fail(std::string* why, const std::string& msg) {
  if (why) *why = msg;
  return false;
}

inline bool positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace windplan::param_check
