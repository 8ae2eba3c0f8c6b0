// The cell's targets for a planned helix: FK of the solved joints puts the eye where the lathe
// model does, in one configuration; a joint limit or wrist margin the path crosses is an error
// naming the circuit, point and joint.
#include "export/robot/robot_motion.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "geometry/base/errors.h"
#include "planner/job/robot_config.h"
#include "tests/export/plan_fixtures.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

MachineOptions cell() {
  MachineOptions m;
  m.kind = "robot";
  decode_robot(ConfigNode::load_string("arm: kuka_kr16_2.yaml\npositioner: positioner_1axis.yaml\n"
                                       "tool: {xyz: [250, 0, 0]}\noffset: -180\n",
                                       "cell.yaml"),
               std::filesystem::path(WINDPLAN_SOURCE_DIR) / "configs" / "machines", &m.robot);
  return m;
}

struct Fixture {
  WindingPlan plan = test::helix_plan(50, 60, 2, 2000);
  Mesh mesh{test::open_cylinder(50, 28.87 * 4 * M_PI + 100, 256, 100)};
};

TEST(RobotMotion, ForwardKinematicsPutsTheEyeWhereTheLatheModelDoes) {
  const Fixture f;
  const MachineOptions m = cell();
  const Motion mo = compute_motion(f.plan, m, &f.mesh);
  const RobotMotion rm = compute_robot_motion(mo, f.plan, m);
  // One target per state, and targets inserted on the planned eye path where E1 - A turns.
  ASSERT_GE(rm.targets.size(), mo.states.size());
  ASSERT_EQ(rm.targets.back().state + 1, static_cast<int>(mo.states.size()));
  const RobotArm arm(m.robot);
  const AxisFrame frame = make_axis_frame(f.plan.axis);
  for (const RobotTarget& t : rm.targets) {
    const MachineState& s = mo.states[t.state];
    const Vec3 eye_cell = (arm.flange(t.q) * rm.tool).translation();
    // Back to the mandrel frame: the positioner turned by E1 (positioner_e1.h).
    const Vec3 c = rm.base.inverse() * eye_cell;
    const double th = std::atan2(c.z(), c.y()) - t.e1 * M_PI / 180;
    const double r = std::hypot(c.y(), c.z());
    const Vec3 eye = frame.origin + (c.x() + 180) * frame.d +
                     r * (std::cos(th) * frame.u + std::sin(th) * frame.v);
    const bool last_of_state = &t == &rm.targets.back() || (&t + 1)->state != t.state;
    if (last_of_state) {
      ASSERT_LT((eye - s.eye).norm(), 1e-6) << t.state;
    } else {  // on the straight line from the previous state's eye to this state's
      ASSERT_GT(t.state, 0);
      const Vec3 a = mo.states[t.state - 1].eye, d = s.eye - a;
      const double f = std::clamp((eye - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      ASSERT_LT((eye - (a + f * d)).norm(), 1e-6) << t.state;
    }
    EXPECT_EQ(t.status, rm.targets.front().status);
  }
  EXPECT_EQ(rm.configuration_changes, 0);
  EXPECT_GE(rm.min_wrist_angle, m.robot.wrist_margin);
  EXPECT_GT(rm.min_joint_margin, m.robot.joint_margin);
  EXPECT_GE(rm.cycle_time, mo.wind_time - 1e-9);
}

TEST(RobotMotion, AJointLimitOnThePathIsNamed) {
  const Fixture f;
  MachineOptions m = cell();
  const Motion mo = compute_motion(f.plan, m, &f.mesh);
  const RobotMotion ok = compute_robot_motion(mo, f.plan, m);
  // A1 turns over the helix's length (the eye moves along the positioner axis): a limit inside
  // its range stops the path.
  double lo = 1e9, hi = -1e9;
  for (const RobotTarget& t : ok.targets) {
    lo = std::min(lo, t.q[0]);
    hi = std::max(hi, t.q[0]);
  }
  ASSERT_GT(hi - lo, 10.0);
  // The limit on the side the path moves to, so that the first target is inside it.
  const double mid = 0.5 * (lo + hi);
  if (ok.targets.front().q[0] < mid) {
    m.robot.joints[0].max = mid + m.robot.joint_margin;
  } else {
    m.robot.joints[0].min = mid - m.robot.joint_margin;
  }
  try {
    compute_robot_motion(mo, f.plan, m);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("circuit 0 point"), std::string::npos) << w;
    EXPECT_NE(w.find("joint A1 = "), std::string::npos) << w;
    EXPECT_NE(w.find("past its limit"), std::string::npos) << w;
  }
}

}  // namespace
}  // namespace windplan
