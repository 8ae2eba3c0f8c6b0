#include "planner/job/robot_config.h"

#include <cmath>

#include "geometry/base/format_number.h"

namespace windplan {

namespace {

// Bounds on the numbers of a cell (a value beyond them is a typo or the wrong unit: a tool 1e300 mm
// long, or a joint origin of 1e300 mm after 38 s of inverse kinematics, was refused as the
// positioner's frame putting the mandrel out of reach).
constexpr double kMaxCellLength = 1e5;    // mm: a frame in the cell, within 100 m
constexpr double kMaxLinkLength = 1e4;    // mm: an arm's link or flange, within 10 m
constexpr double kMaxAngle = 360.0;       // deg: KUKA's A, B, C
constexpr double kMaxJointAngle = 720.0;  // deg: a joint limit (two turns either way)
constexpr double kMaxE1Velocity = 3600;   // deg/s: ten turns a second

std::string deg(double v) { return format_shortest(v); }

void decode_frame(ConfigNode n, Frame6* f) {
  if (!n.present()) return;
  n.get("xyz", &f->xyz);
  n.get("abc", &f->abc);
  n.finish();
  for (double v : f->xyz) {
    if (!std::isfinite(v)) n.fail("xyz", "must be finite (mm)");
    if (std::fabs(v) > kMaxCellLength) {
      n.fail("xyz",
             deg(v) + " mm is beyond 100 m: no robot cell is so large (a value in microns?)");
    }
  }
  for (double v : f->abc) {
    if (!(std::fabs(v) <= kMaxAngle)) {
      n.fail("abc", deg(v) + " deg: an orientation angle lies within -360 to 360 deg");
    }
  }
}

ConfigNode load_profile(ConfigNode& n, const std::string& key, const std::filesystem::path& base,
                        std::string* file_out) {
  std::string name;
  n.require(key, &name);
  if (name.empty()) n.fail(key, "must name a profile file");
  const std::filesystem::path file = (base / name).lexically_normal();
  if (!std::filesystem::exists(file)) {
    n.fail(key, "the profile " + file.string() + " does not exist");
  }
  ConfigNode p = ConfigNode::load_file(file, key + " profile");
  if (!p.present() || !p.yaml().IsMap()) {
    throw ConfigError(file.string() + ": a " + key + " profile must be a map of keys");
  }
  *file_out = file.string();
  return p;
}

void decode_arm(ConfigNode a, RobotOptions* r) {
  a.require("name", &r->arm_name);
  std::string source;  // where the numbers come from: read (so it is no unknown key), not used
  a.get("source", &source);
  r->joints.clear();
  for (ConfigNode j : a.list("joints")) {
    RobotJoint joint;
    j.require("name", &joint.name);
    j.require("origin", &joint.origin);
    j.require("axis", &joint.axis);
    j.require("min", &joint.min);
    j.require("max", &joint.max);
    j.require("max_velocity", &joint.max_velocity);
    j.finish();
    const double n = std::hypot(joint.axis[0], joint.axis[1], joint.axis[2]);
    if (!(std::fabs(n - 1.0) < 1e-9)) j.fail("axis", "must be a unit vector");
    if (!(joint.min < joint.max)) j.fail("max", "must be > min");
    if (!(joint.max_velocity > 0.0)) j.fail("max_velocity", "must be > 0 deg/s");
    for (double v : joint.origin) {
      if (std::fabs(v) > kMaxLinkLength) {
        j.fail("origin", deg(v) + " mm is beyond 10 m: no arm's link is so long");
      }
    }
    if (std::fabs(joint.min) > kMaxJointAngle || std::fabs(joint.max) > kMaxJointAngle) {
      j.fail(std::fabs(joint.min) > kMaxJointAngle ? "min" : "max",
             "a joint limit lies within -720 to 720 deg (got " + deg(joint.min) + " to " +
                 deg(joint.max) + ")");
    }
    r->joints.push_back(joint);
  }
  if (r->joints.size() != 6) {
    a.fail("joints", "needs 6 revolute joints (got " + std::to_string(r->joints.size()) + ")");
  }
  a.require("flange", &r->flange);
  for (double v : r->flange) {
    if (std::fabs(v) > kMaxLinkLength) {
      a.fail("flange", deg(v) + " mm is beyond 10 m: no arm's flange is so far out");
    }
  }
  std::vector<double> home;
  if (a.get("home", &home)) {
    if (home.size() != 6) a.fail("home", "needs 6 joint values (deg)");
    for (int i = 0; i < 6; ++i) {
      // (A home outside its joint's limits was refused as the mandrel out of reach.)
      const RobotJoint& j = r->joints[i];
      if (!(home[i] >= j.min && home[i] <= j.max)) {
        a.fail("home", "element " + std::to_string(i) + " (" + deg(home[i]) + " deg) is outside " +
                           j.name + "'s limits [" + deg(j.min) + ", " + deg(j.max) + "] deg");
      }
      r->home[i] = home[i];
    }
  }
  a.finish();
}

void decode_positioner(ConfigNode p, RobotOptions* r) {
  p.require("name", &r->positioner_name);
  std::string source;
  p.get("source", &source);
  decode_frame(p.section("frame"), &r->positioner);
  p.get("e1_max_velocity", &r->e1_max_velocity);
  if (!(r->e1_max_velocity > 0.0)) p.fail("e1_max_velocity", "must be > 0 deg/s");
  if (r->e1_max_velocity > kMaxE1Velocity) {
    p.fail("e1_max_velocity", deg(r->e1_max_velocity) +
                                  " deg/s is beyond 3600 deg/s (ten turns a second): no "
                                  "positioner turns a mandrel so fast");
  }
  p.finish();
}

}  // namespace

void decode_robot(ConfigNode n, const std::filesystem::path& base, RobotOptions* r) {
  if (!n.present()) return;
  n.get_choice("dialect", {"krl", "rapid"}, &r->dialect);
  if (n.has("arm")) {
    ConfigNode a = load_profile(n, "arm", base, &r->arm_file);
    decode_arm(a, r);
  }
  if (n.has("positioner")) {
    ConfigNode p = load_profile(n, "positioner", base, &r->positioner_file);
    decode_positioner(p, r);
  }
  n.get("offset", &r->offset);
  n.get_choice("eye", {"ring", "roller"}, &r->eye);
  decode_frame(n.section("tool"), &r->tool);
  n.get("joint_margin", &r->joint_margin);
  n.get("wrist_margin", &r->wrist_margin);
  n.get("max_points", &r->max_points);
  n.finish();
  n.check(*r);
}

}  // namespace windplan
