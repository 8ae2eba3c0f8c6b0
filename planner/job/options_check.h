#pragma once
// The "set why and fail" step the options validators of planner/job share
// (MachineOptions::is_valid, RobotOptions::is_valid and the structs beside them).
#include <string>

namespace windplan::options_check {

/// Sets *why (when given) to `msg` and returns false: `return fail(why, "...");`.
inline bool fail(std::string* why, const std::string& msg) {
  if (why) *why = msg;
  return false;
}

}  // namespace windplan::options_check
