#include "export/robot/robot_motion.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

constexpr double kDeg = 180.0 / M_PI;

std::string point_name(const MachineState& s, const Vec3& cell) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "circuit %d point %d (eye at %.1f, %.1f, %.1f mm in the cell)",
                s.circuit, s.index, cell.x(), cell.y(), cell.z());
  return buf;
}

/// True when the state is strictly inside a Pass segment of its circuit.
bool inside_pass(const WindingPlan& plan, const MachineState& s) {
  if (s.ordinal < 0 || s.ordinal >= static_cast<int>(plan.circuits.size())) return false;
  for (const CircuitSegment& seg : plan.circuits[s.ordinal].segments) {
    if (seg.kind == CircuitSegment::Kind::Pass && s.index > seg.first && s.index <= seg.last) {
      return true;
    }
  }
  return false;
}

}  // namespace

Eigen::Isometry3d eye_in_base(const MachineState& s, double offset, bool roller) {
  const double b = (roller ? s.b_deg : 90.0) / kDeg;
  const Vec3 x(0.0, -1.0, 0.0);
  const Vec3 z(std::cos(b), 0.0, std::sin(b));
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear().col(0) = x;
  t.linear().col(1) = z.cross(x);
  t.linear().col(2) = z;
  t.translation() = Vec3(s.x_mm + offset, s.y_mm, 0.0);
  return t;
}

std::string RobotMotion::brief_report() const {
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "robot: %zu targets, cycle %.1f s (planned %.1f s, %d moves slowed for joint "
                "speeds, max ratio %.2f), joint margin %.1f deg (%s), wrist |A5| >= %.1f deg, %d "
                "configuration changes between passes, IK %.3f s",
                targets.size(), cycle_time, planned_time, slowed_moves, max_joint_speed_ratio,
                min_joint_margin, min_joint_margin_joint.c_str(), min_wrist_angle,
                configuration_changes, ik_seconds);
  return buf;
}

RobotMotion compute_robot_motion(const Motion& motion, const WindingPlan& plan,
                                 const MachineOptions& machine) {
  const RobotOptions& ro = machine.robot;
  if (!ro.has_arm()) throw ConfigError("machine.robot.arm: a robot program needs an arm profile");
  const auto t0 = std::chrono::steady_clock::now();
  const RobotArm arm(ro);
  RobotMotion m;
  m.base = frame6_transform(ro.positioner);
  m.tool = frame6_transform(ro.tool);
  m.planned_time = motion.wind_time;
  m.min_joint_margin = std::numeric_limits<double>::infinity();
  m.min_wrist_angle = std::numeric_limits<double>::infinity();
  const Eigen::Isometry3d tool_inv = m.tool.inverse();

  // Layer starts: the tow is tied on again there.
  auto layer_start = [&](int ordinal) {
    for (const LayerSummary& l : motion.layers) {
      if (l.first_circuit == ordinal) return true;
    }
    return false;
  };

  Joints seed = ro.home;
  m.targets.reserve(motion.states.size());
  for (std::size_t i = 0; i < motion.states.size(); ++i) {
    const MachineState& s = motion.states[i];
    RobotTarget t;
    t.state = static_cast<int>(i);
    t.tie_on = i == 0 || (s.ordinal != motion.states[i - 1].ordinal && layer_start(s.ordinal));
    t.eye = eye_in_base(s, ro.offset, ro.eye == "roller");
    t.e1 = s.a_deg;
    const Eigen::Isometry3d cell_eye = m.base * t.eye;
    const bool solved = i == 0 ? arm.inverse_near(cell_eye * tool_inv, ro.home, ro.joint_margin,
                                                  ro.wrist_margin, &t.q)
                               : arm.inverse(cell_eye * tool_inv, seed, &t.q);
    if (!solved) {
      throw InputError("machine.robot: the eye pose of " + point_name(s, cell_eye.translation()) +
                       " is out of reach of the " + ro.arm_name +
                       (i == 0 ? " (no inverse kinematics inside the joint limits"
                               : " (no inverse kinematics from the previous joints") +
                       "; move machine.robot.offset or the positioner's frame)");
    }
    const std::string bad = joint_limit_violation(ro, t.q, ro.joint_margin);
    if (!bad.empty()) {
      throw InputError("machine.robot: at " + point_name(s, cell_eye.translation()) + " joint " +
                       bad);
    }
    if (std::fabs(t.q[4]) < ro.wrist_margin) {
      char buf[120];
      std::snprintf(buf, sizeof buf, " has |A5| = %.3f deg, within wrist_margin %.1f deg",
                    std::fabs(t.q[4]), ro.wrist_margin);
      throw InputError(
          "machine.robot: the wrist is singular: " + point_name(s, cell_eye.translation()) + buf);
    }
    t.status = arm.status(t.q);
    t.turn = RobotArm::turn(t.q);
    for (int j = 0; j < 6; ++j) {
      const double margin = std::min(t.q[j] - ro.joints[j].min, ro.joints[j].max - t.q[j]);
      if (margin < m.min_joint_margin) {
        m.min_joint_margin = margin;
        m.min_joint_margin_joint = ro.joints[j].name;
      }
    }
    m.min_wrist_angle = std::min(m.min_wrist_angle, std::fabs(t.q[4]));
    t.duration = s.duration;
    if (!m.targets.empty()) {
      const RobotTarget& p = m.targets.back();
      if (p.status != t.status) {
        if (inside_pass(plan, s) && s.ordinal == motion.states[i - 1].ordinal) {
          char buf[120];
          std::snprintf(buf, sizeof buf, " (Status %d -> %d)", p.status, t.status);
          throw InputError("machine.robot: the arm changes configuration inside a pass at " +
                           point_name(s, cell_eye.translation()) + buf);
        }
        ++m.configuration_changes;
      }
      double need = std::fabs(t.e1 - p.e1) / ro.e1_max_velocity;
      for (int j = 0; j < 6; ++j) {
        need = std::max(need, std::fabs(t.q[j] - p.q[j]) / ro.joints[j].max_velocity);
      }
      if (need > 0.0) {
        const double ratio =
            s.duration > 0.0 ? need / s.duration : std::numeric_limits<double>::infinity();
        if (ratio > 1.0) {
          ++m.slowed_moves;
          t.duration = need;
        }
        if (std::isfinite(ratio))
          m.max_joint_speed_ratio = std::max(m.max_joint_speed_ratio, ratio);
      }
    }
    m.cycle_time += t.duration;
    seed = t.q;
    m.targets.push_back(t);
  }
  m.ik_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return m;
}

}  // namespace windplan
