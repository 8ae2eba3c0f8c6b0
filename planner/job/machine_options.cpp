#include "planner/job/machine_options.h"

#include <cmath>

#include "geometry/base/format_number.h"
#include "planner/job/options_check.h"

namespace windplan {

using options_check::fail;

std::string EnvelopeOptions::mode() const {
  if (!profile.empty()) return "profile";
  if (free_length > 0.0) return "free_length";
  return "clearance";
}

bool EnvelopeOptions::is_valid(std::string* why) const {
  if (!std::isfinite(clearance) || clearance <= 0.0) {
    return fail(why, "clearance must be > 0 mm (got " + format_shortest(clearance) + ")");
  }
  if (!std::isfinite(free_length) || free_length < 0.0) {
    return fail(why, "free_length must be >= 0 mm (got " + format_shortest(free_length) + ")");
  }
  if (!std::isfinite(radius) || radius < 0.0) {
    return fail(why, "radius must be >= 0 mm (got " + format_shortest(radius) + ")");
  }
  if (radius > 0.0 && (!profile.empty() || free_length > 0.0)) {
    return fail(why,
                "radius is the lathe2 cylinder of the clearance mode; not with profile or "
                "free_length");
  }
  if (!profile.empty() && free_length > 0.0) {
    return fail(why, "give either profile or free_length, not both");
  }
  if (profile.size() == 1) return fail(why, "profile needs at least two [x, r] points");
  for (std::size_t i = 0; i < profile.size(); ++i) {
    if (!(profile[i][1] > 0.0)) {
      return fail(why, "profile point " + std::to_string(i) + ": radius must be > 0");
    }
    if (i > 0 && !(profile[i][0] > profile[i - 1][0])) {
      return fail(why, "profile point " + std::to_string(i) + ": x must increase strictly");
    }
  }
  return true;
}

bool AxisOptions::is_valid(std::string* why) const {
  if (letter.size() != 1 || std::string("ABCUVWXYZ").find(letter[0]) == std::string::npos) {
    return fail(why, "letter must be one of A B C U V W X Y Z (got '" + letter + "')");
  }
  if (sign != 1.0 && sign != -1.0) return fail(why, "sign must be 1 or -1");
  if (!std::isfinite(offset)) return fail(why, "offset must be finite");
  if (!(min < max)) return fail(why, "min must be < max");
  if (!std::isfinite(max_velocity) || max_velocity <= 0.0) {
    return fail(why, "max_velocity must be > 0");
  }
  if (!std::isfinite(max_acceleration) || max_acceleration <= 0.0) {
    return fail(why, "max_acceleration must be > 0 (got " + std::to_string(max_acceleration) + ")");
  }
  return true;
}

bool GcodeOptions::is_valid(std::string* why) const {
  if (dialect != "linuxcnc" && dialect != "marlin" && dialect != "fanuc") {
    return fail(why, "dialect must be linuxcnc, marlin or fanuc (got '" + dialect + "')");
  }
  if (feed != "auto" && feed != "inverse_time" && feed != "per_minute") {
    return fail(why, "feed must be auto, inverse_time or per_minute (got '" + feed + "')");
  }
  if (dialect == "marlin" && feed == "inverse_time") {
    return fail(why, "marlin has no inverse-time feed (G93); use feed: per_minute");
  }
  if (program_number < 1 || program_number > 8999) {
    return fail(why, "program_number must be in 1..8999");
  }
  return true;
}

bool MachineOptions::is_valid(std::string* why) const {
  if (kind != "lathe2" && kind != "lathe4" && kind != "robot") {
    return fail(why, "kind must be lathe2, lathe4 or robot (got '" + kind + "')");
  }
  if (robot.has_arm() && kind != "robot") return fail(why, "robot.arm is for kind: robot");
  if (envelope.radius > 0.0 && kind != "lathe2") {
    // (A lathe4 job with envelope.radius: 90 was planned on its clearance envelope, the key
    // silently unused.)
    return fail(why, "envelope.radius is the eye cylinder of a lathe2 (no cross-feed); a " + kind +
                         " follows the clearance envelope: give envelope.clearance instead");
  }
  if (!std::isfinite(chord_tolerance) || chord_tolerance <= 0.0) {
    return fail(why, "chord_tolerance must be > 0 mm");
  }
  if (!std::isfinite(max_fibre_speed) || max_fibre_speed < 0.0) {
    return fail(why, "max_fibre_speed must be >= 0 mm/s");
  }
  if (!std::isfinite(tangent_window) || tangent_window < 0.0) {
    return fail(why, "tangent_window must be >= 0 mm");
  }
  if (!std::isfinite(replay_tolerance) || replay_tolerance < 0.0) {
    return fail(why, "replay_tolerance must be >= 0 mm (0: report only)");
  }
  std::string w;
  if (!envelope.is_valid(&w)) return fail(why, "envelope: " + w);
  const AxisOptions* axes[4] = {&a, &x, &y, &b};
  const char* names[4] = {"A", "X", "Y", "B"};
  for (int i = 0; i < 4; ++i) {
    if (!axes[i]->is_valid(&w)) return fail(why, std::string("axes.") + names[i] + ": " + w);
    for (int j = 0; j < i; ++j) {
      const bool used_i = kind == "lathe4" || i < 2;
      const bool used_j = kind == "lathe4" || j < 2;
      if (used_i && used_j && axes[i]->letter == axes[j]->letter) {
        return fail(why, std::string("axes.") + names[i] + " and axes." + names[j] +
                             " share the letter " + axes[i]->letter);
      }
    }
  }
  if (!gcode.is_valid(&w)) return fail(why, "gcode: " + w);
  return true;
}

bool OutputOptions::is_valid(std::string*) const { return true; }

}  // namespace windplan
