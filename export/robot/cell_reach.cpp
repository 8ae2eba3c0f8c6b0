#include "export/robot/cell_reach.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "export/robot/robot_motion.h"
#include "geometry/base/errors.h"
#include "geometry/region/winding_surface.h"

namespace windplan {

namespace {

double norm3(const std::array<double, 3>& a) { return std::hypot(a[0], a[1], a[2]); }

/// The eye's distance from the axis at a station (see the header comment).
double eye_distance(const EnvelopeOptions& env, double radius, double station) {
  const std::string mode = env.mode();
  if (mode == "profile") {
    RadiusProfile p;
    for (const auto& xr : env.profile) {
      p.axial.push_back(xr[0]);
      p.radius.push_back(xr[1]);
    }
    return p.at(station);
  }
  if (mode == "free_length") return std::hypot(radius, env.free_length);
  return radius + env.clearance;
}

}  // namespace

std::string CellReach::brief_report() const {
  char buf[160];
  std::snprintf(buf, sizeof buf, "cell reach: %zu eye points reachable (%.3f s)", points.size(),
                seconds);
  return buf;
}

namespace {

// The check at the stations of `wound`, the eye at `profile`'s radius there (see the header);
// `what` names the surface in the message ("mandrel", "laminate under layers[1] (outer)").
CellReach reach(const Mesh& wound, const SpindleAxis& axis, const RadiusProfile& profile,
                const MachineOptions& machine, const std::string& what) {
  const RobotOptions& ro = machine.robot;
  if (!ro.has_arm()) throw ConfigError("machine.robot.arm: a robot cell needs an arm profile");
  if (wound.points().empty()) throw InputError("cell reach: the wound region is empty");
  const auto t0 = std::chrono::steady_clock::now();
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Vec3& p : wound.points()) {
    const double x = axis.axial(p);
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  const RobotArm arm(ro);
  const Eigen::Isometry3d base = frame6_transform(ro.positioner);
  const Eigen::Isometry3d tool_inv = frame6_transform(ro.tool).inverse();
  // The arm's full stretch from its first joint: no point farther than that is reachable.
  const Vec3 first(ro.joints[0].origin[0], ro.joints[0].origin[1], ro.joints[0].origin[2]);
  double stretch = norm3(ro.flange) + norm3(ro.tool.xyz);
  for (std::size_t j = 1; j < ro.joints.size(); ++j) stretch += norm3(ro.joints[j].origin);
  const bool roller = ro.eye == "roller";
  const double mid = 0.5 * (lo + hi);

  CellReach out;
  for (double station : {lo, mid, hi}) {
    CellReachPoint p;
    p.station = station;
    p.distance = eye_distance(machine.envelope, profile.at(station), station);
    MachineState s;
    s.x_mm = station;
    s.y_mm = p.distance;
    bool solved = false;
    std::string why;
    for (double b : {90.0, 60.0, 120.0}) {
      s.b_deg = b;
      const Eigen::Isometry3d eye = base * eye_in_base(s, ro.offset, roller);
      p.cell = eye.translation();
      const double far = (p.cell - first).norm();
      if (far > stretch) {
        char buf[160];
        std::snprintf(buf, sizeof buf,
                      "is %.1f mm from A1's origin, beyond the arm's full stretch "
                      "%.1f mm",
                      far, stretch);
        why = buf;
        break;
      }
      if (arm.inverse_near(eye * tool_inv, ro.home, ro.joint_margin, ro.wrist_margin, &p.q, true)) {
        solved = true;
        break;
      }
      char buf[160];
      std::snprintf(buf, sizeof buf,
                    "has no inverse kinematics inside the joint limits less joint_margin %.1f deg "
                    "with |A5| >= wrist_margin %.1f deg",
                    ro.joint_margin, ro.wrist_margin);
      why = buf;
      if (!roller) break;
    }
    if (!solved) {
      const std::string where =
          ro.positioner_file.empty()
              ? std::string(
                    "machine.robot.positioner (none: the positioner frame is the robot's "
                    "base)")
              : ro.positioner_file + ": frame";
      char buf[400];
      std::snprintf(buf, sizeof buf,
                    " with machine.robot.offset %.1f mm puts the %s out of reach of the %s: "
                    "the eye at %.1f mm along the spindle axis, %.1f mm from it, at (%.1f, %.1f, "
                    "%.1f) mm in the cell, ",
                    ro.offset, what.c_str(), ro.arm_name.c_str(), station, p.distance, p.cell.x(),
                    p.cell.y(), p.cell.z());
      throw InputError(where + buf + why +
                       "; move the positioner's frame or machine.robot.offset (checked before "
                       "planning" +
                       (what == "mandrel" ? std::string() : " the layer") + ")");
    }
    out.points.push_back(p);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace

CellReach check_cell_reach(const Mesh& wound, const SpindleAxis& axis, const RadiusProfile& profile,
                           const MachineOptions& machine) {
  return reach(wound, axis, profile, machine, "mandrel");
}

CellReach check_cell_reach_over(const Mesh& wound, const SpindleAxis& axis, const Mesh& surface,
                                const MachineOptions& machine, const std::string& layer) {
  if (surface.points().empty())
    throw InputError("cell reach: the surface under " + layer + " is empty");
  // Its largest radius, never below the surface between stations (bound_between).
  const RadiusProfile profile = compute_radius_profile(surface, axis, 200, true);
  return reach(wound, axis, profile, machine, "laminate under " + layer);
}

}  // namespace windplan
