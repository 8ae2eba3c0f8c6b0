// KRL and RAPID programs of a planned helix read back by the independent reader: every target's
// pose, E1 and Status as written (to the 4 decimals of mm and deg), split into parts of
// max_points targets, the same text twice.
#include "export/robot/robot_program.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "export/robot/robot_program_reader.h"
#include "planner/job/robot_config.h"
#include "tests/export/plan_fixtures.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

TEST(RobotProgram, WrittenProgramsReadBackTargetForTarget) {
  for (const char* dialect : {"krl", "rapid"}) {
    MachineOptions m;
    m.kind = "robot";
    decode_robot(
        ConfigNode::load_string("arm: kuka_kr16_2.yaml\npositioner: positioner_1axis.yaml\n"
                                "tool: {xyz: [250, 0, 0], abc: [0, 0, 0]}\noffset: -180\n"
                                "max_points: 200\ndialect: " +
                                    std::string(dialect) + "\n",
                                "cell.yaml"),
        std::filesystem::path(WINDPLAN_SOURCE_DIR) / "configs" / "machines", &m.robot);
    const WindingPlan plan = test::helix_plan(50, 60, 2, 2000);
    const Mesh mesh(test::open_cylinder(50, 28.87 * 4 * M_PI + 100, 256, 100));
    const Motion mo = compute_motion(plan, m, &mesh);
    const RobotMotion rm = compute_robot_motion(mo, plan, m);
    const std::vector<ProgramFile> files = robot_program(rm, "Helix test", m);
    const std::size_t parts = (rm.targets.size() + 199) / 200;
    EXPECT_EQ(files.size(), (std::string(dialect) == "krl" ? 2 : 1) * (parts + 1)) << dialect;
    EXPECT_EQ(files.front().name, robot_program_main("Helix test", dialect));
    EXPECT_EQ(files.front().name,
              std::string(dialect) == "krl" ? "wp_helix_test.src" : "wp_helix_test.mod");
    std::map<std::string, std::string> texts;
    for (const ProgramFile& f : files) texts[f.name] = f.text;
    const RobotProgram p = read_robot_program(texts, files.front().name, dialect);
    ASSERT_EQ(p.targets.size(), rm.targets.size()) << dialect;
    EXPECT_LT((p.tool.matrix() - rm.tool.matrix()).norm(), 1e-6);
    EXPECT_LT((p.base.matrix() - rm.base.matrix()).norm(), 1e-4);
    for (std::size_t i = 0; i < p.targets.size(); ++i) {
      const RobotTarget& w = rm.targets[i];
      const RobotProgramTarget& r = p.targets[i];
      ASSERT_LT((r.pose.translation() - w.eye.translation()).norm(), 1e-4) << dialect << " " << i;
      ASSERT_LT((r.pose.linear() - w.eye.linear()).norm(), 1e-6) << dialect << " " << i;
      ASSERT_NEAR(r.e1, w.e1, 5e-5) << dialect << " " << i;
      ASSERT_EQ(r.status, w.status);
      EXPECT_EQ(r.joint_move, i == 0);
    }
    // Deterministic.
    const std::vector<ProgramFile> again = robot_program(rm, "Helix test", m);
    for (std::size_t k = 0; k < files.size(); ++k) EXPECT_EQ(files[k].text, again[k].text);
  }
}

// $VEL_EXTAX[1] is a system variable: it holds from one KRL part file to the next. Targets 1 mm
// apart, 0.01 s each, E1 at 50 % of its 180 deg/s except the last move of the first part (E1
// still: 0.000001 %) and the first of the second (1.8 deg: 100 %). Read back, every LIN's time
// max(distance / $VEL.CP, |dE1| / (E1 max x $VEL_EXTAX / 100)) is the written 0.01 s (before: the
// second part assumed 100 % without writing it, and its first move took 1e6 s).
TEST(RobotProgram, KrlExternalAxisSpeedHoldsAcrossPartFiles) {
  MachineOptions m;
  m.kind = "robot";
  decode_robot(ConfigNode::load_string("arm: kuka_kr16_2.yaml\npositioner: positioner_1axis.yaml\n"
                                       "tool: {xyz: [250, 0, 0]}\nmax_points: 10\ndialect: krl\n",
                                       "cell.yaml"),
               std::filesystem::path(WINDPLAN_SOURCE_DIR) / "configs" / "machines", &m.robot);
  RobotMotion rm;
  double e1 = 0.0;
  for (int i = 0; i < 25; ++i) {
    RobotTarget t;
    t.tie_on = i == 0;
    t.eye.translation() = Vec3(i, 70, 0);
    e1 += i == 0 ? 0.0 : i == 9 ? 0.0 : i == 10 ? 1.8 : 0.9;
    t.e1 = e1;
    t.duration = i == 0 ? 0.0 : 0.01;
    rm.targets.push_back(t);
  }
  std::map<std::string, std::string> texts;
  for (const ProgramFile& f : robot_program(rm, "extax", m)) texts[f.name] = f.text;
  ASSERT_EQ(texts.size(), 8u);  // main and three parts, .src and .dat each
  const RobotProgram p = read_robot_program(texts, "wp_extax.src", "krl");
  ASSERT_EQ(p.targets.size(), 25u);
  EXPECT_EQ(p.targets[10].file, "wp_extax_p02.src");
  EXPECT_DOUBLE_EQ(p.targets[9].vel_extax, 1e-6);
  EXPECT_DOUBLE_EQ(p.targets[10].vel_extax, 100.0);
  for (int i = 1; i < 25; ++i) {
    const RobotProgramTarget& a = p.targets[i - 1];
    const RobotProgramTarget& b = p.targets[i];
    const double move = (b.pose.translation() - a.pose.translation()).norm() / 1000.0 / b.vel_cp;
    const double axis = std::fabs(b.e1 - a.e1) / (m.robot.e1_max_velocity * b.vel_extax / 100.0);
    EXPECT_NEAR(std::max(move, axis), 0.01, 1e-6) << i;
  }
}

}  // namespace
}  // namespace windplan
