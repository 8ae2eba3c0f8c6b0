#include "planner/job/robot_options.h"

#include <cmath>

#include "planner/job/options_check.h"

namespace windplan {

using options_check::fail;

bool RobotOptions::is_valid(std::string* why) const {
  if (dialect != "krl" && dialect != "rapid") {
    return fail(why, "dialect must be krl or rapid (got '" + dialect + "')");
  }
  if (eye != "ring" && eye != "roller") return fail(why, "eye must be ring or roller");
  if (!joints.empty() && joints.size() != 6) {
    return fail(why, "the arm must have 6 joints (got " + std::to_string(joints.size()) + ")");
  }
  for (const RobotJoint& j : joints) {
    const double n = std::hypot(j.axis[0], j.axis[1], j.axis[2]);
    if (!(std::fabs(n - 1.0) < 1e-9))
      return fail(why, "joint " + j.name + ": axis must be a unit vector");
    if (!(j.min < j.max)) return fail(why, "joint " + j.name + ": min must be < max");
    if (!(j.max_velocity > 0.0)) return fail(why, "joint " + j.name + ": max_velocity must be > 0");
  }
  if (!(e1_max_velocity > 0.0)) return fail(why, "e1_max_velocity must be > 0 deg/s");
  if (!std::isfinite(offset)) return fail(why, "offset must be finite");
  if (!(joint_margin >= 0.0) || !(wrist_margin >= 0.0)) {
    return fail(why, "joint_margin and wrist_margin must be >= 0 deg");
  }
  if (max_points < 10) return fail(why, "max_points must be >= 10");
  return true;
}

}  // namespace windplan
