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
  char buf[700];
  std::snprintf(buf, sizeof buf,
                "robot: %zu targets, cycle %.1f s (planned %.1f s, %d moves slowed for joint "
                "speeds, max ratio %.2f), joint margin %.1f deg (%s), wrist |A5| >= %.1f deg, %d "
                "configuration changes between passes, IK %.3f s; %s",
                targets.size(), cycle_time, planned_time, slowed_moves, max_joint_speed_ratio,
                min_joint_margin, min_joint_margin_joint.c_str(), min_wrist_angle,
                configuration_changes, ik_seconds, positioner.brief_report().c_str());
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

  // Layer starts: the tow is tied on again there (per circuit ordinal).
  const std::vector<char> starts_layer = layer_start_circuits(plan);
  auto layer_start = [&](int ordinal) {
    return ordinal >= 0 && ordinal < static_cast<int>(starts_layer.size()) && starts_layer[ordinal];
  };

  // E1 monotone and smooth within every circuit (export/robot/positioner_e1.h); the arm puts the
  // eye at E1 - A about the E1 axis, so the eye in the mandrel frame stays where the plan has it.
  m.positioner = fit_positioner_e1(motion, plan);
  Joints seed = ro.home;
  m.targets.reserve(motion.states.size());
  // Where E1 - A changes by more than kTurnStepDeg between two states (A swings where the eye
  // passes near the E1 axis, and at the links between circuits), the arm's straight move between
  // the two turned eyes would leave the planned eye path (in the mandrel frame, by the chord of
  // that turn): targets are inserted there on the planned eye path (the straight line between
  // the two states' eyes in the mandrel frame), E1 and B interpolated linearly, each with its
  // share of the move's time.
  constexpr double kTurnStepDeg = 2.0;
  const AxisFrame frame = make_axis_frame(plan.axis);
  struct Step {
    MachineState s;
    int state;
    double e1;
  };
  std::vector<Step> steps;
  steps.reserve(motion.states.size());
  for (std::size_t i = 0; i < motion.states.size(); ++i) {
    const MachineState& s = motion.states[i];
    const double e1 = m.positioner.e1[i];
    const bool tie =
        i == 0 || (s.ordinal != motion.states[i - 1].ordinal && layer_start(s.ordinal));
    int parts = 1;
    if (!tie) {
      const MachineState& p = motion.states[i - 1];
      const double pe1 = m.positioner.e1[i - 1];
      const double turn = std::fabs((e1 - s.a_deg) - (pe1 - p.a_deg));
      // The arm moves straight in the cell: a turn by d about the E1 axis at radius Y puts the
      // eye Y (1 - cos(d / 2)) inside the arc, which the eye's plan allows chord_tolerance for
      // (export/machine/kinematics.h, kRobotEyeChords): 4.3 deg at Y = 70 mm, so 2 deg rules on
      // the shipped cells.
      const double y = std::max(s.y_mm, p.y_mm);
      double step = kTurnStepDeg;
      if (y > machine.chord_tolerance) {
        step = std::min(step, 2.0 * std::acos(1.0 - machine.chord_tolerance / y) * kDeg);
      }
      parts = std::max(1, static_cast<int>(std::ceil(turn / step)));
      for (int k = 1; k < parts; ++k) {
        const double f = static_cast<double>(k) / parts;
        MachineState q = s;
        q.eye = p.eye + f * (s.eye - p.eye);
        const double a_lin = p.a_deg + f * (s.a_deg - p.a_deg);
        const double a_raw = -frame.angle(q.eye) * kDeg;
        q.a_deg = a_lin + std::remainder(a_raw - a_lin, 360.0);
        q.x_mm = frame.axial(q.eye);
        q.y_mm = frame.radius(q.eye);
        q.b_deg = p.b_deg + f * (s.b_deg - p.b_deg);
        q.duration = s.duration / parts;
        steps.push_back({q, static_cast<int>(i), pe1 + f * (e1 - pe1)});
      }
    }
    MachineState last = s;
    last.duration = s.duration / parts;
    steps.push_back({last, static_cast<int>(i), e1});
  }
  for (std::size_t n = 0; n < steps.size(); ++n) {
    const MachineState& s = steps[n].s;
    const std::size_t i = steps[n].state;
    const bool first_of_state = n == 0 || steps[n - 1].state != steps[n].state;
    RobotTarget t;
    t.state = static_cast<int>(i);
    t.tie_on = first_of_state &&
               (i == 0 || (s.ordinal != motion.states[i - 1].ordinal && layer_start(s.ordinal)));
    t.e1 = steps[n].e1;
    t.eye = eye_in_base(s, ro.offset, ro.eye == "roller");
    {
      // The eye's place turned by E1 - A about the E1 axis; a ring eye keeps its orientation in
      // the cell (it lays the fibre the same at any rotation, and the wrist need not turn), a
      // roller eye turns with it (its B is measured in the mandrel's frame).
      const Eigen::AngleAxisd turn((t.e1 - s.a_deg) / kDeg, Vec3::UnitX());
      t.eye.translation() = turn * t.eye.translation();
      if (ro.eye == "roller") t.eye.linear() = turn.toRotationMatrix() * t.eye.linear();
    }
    const Eigen::Isometry3d cell_eye = m.base * t.eye;
    const bool solved = n == 0 ? arm.inverse_near(cell_eye * tool_inv, ro.home, ro.joint_margin,
                                                  ro.wrist_margin, &t.q)
                               : arm.inverse(cell_eye * tool_inv, seed, &t.q);
    if (!solved) {
      throw InputError("machine.robot: the eye pose of " + point_name(s, cell_eye.translation()) +
                       " is out of reach of the " + ro.arm_name +
                       (n == 0 ? " (no inverse kinematics inside the joint limits"
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
