// The cell's reach before planning (export/robot/cell_reach.h): the shipped KR 16-2 cell reaches
// a tube on its positioner (and forward kinematics of the joints found puts the eye at the point
// checked, with the joints inside their limits), a positioner placed 5 m away is refused naming
// the positioner profile, its frame, the job's offset and the point, and a cell whose eye points
// are inside the arm's stretch but past its joint limits is refused by the inverse kinematics.
#include "export/robot/cell_reach.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "export/robot/robot_motion.h"
#include "geometry/base/errors.h"
#include "geometry/region/winding_surface.h"
#include "planner/job/robot_config.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

MachineOptions kr16_cell(const std::string& extra) {
  MachineOptions m;
  m.kind = "robot";
  decode_robot(ConfigNode::load_string("arm: kuka_kr16_2.yaml\npositioner: positioner_1axis.yaml\n"
                                       "tool: {xyz: [250, 0, 0]}\n" +
                                           extra,
                                       "cell.yaml"),
               std::filesystem::path(WINDPLAN_SOURCE_DIR) / "configs" / "machines", &m.robot);
  return m;
}

struct Tube {
  Mesh mesh;
  SpindleAxis axis;  // z through the origin: the fixture's axis
  RadiusProfile profile;
};

Tube tube(double r, double len) {
  Tube t{Mesh(test::open_cylinder(r, len, 64, 40)), SpindleAxis{}, RadiusProfile{}};
  t.profile = compute_radius_profile(t.mesh, t.axis);
  return t;
}

TEST(CellReach, ShippedCellReachesATubeAndTheJointsPutTheEyeThere) {
  const MachineOptions m = kr16_cell("offset: -200\n");
  const Tube t = tube(25, 400);
  const CellReach r = check_cell_reach(t.mesh, t.axis, t.profile, m);
  std::printf("%s\n", r.brief_report().c_str());
  ASSERT_EQ(r.points.size(), 3u);
  const RobotArm arm(m.robot);
  const Eigen::Isometry3d tool = frame6_transform(m.robot.tool);
  const double stations[3] = {0.0, 200.0, 400.0};
  for (int i = 0; i < 3; ++i) {
    const CellReachPoint& p = r.points[i];
    EXPECT_NEAR(p.station, stations[i], 1e-9);
    EXPECT_NEAR(p.distance, 25.0 + m.envelope.clearance, 0.05);  // radius + clearance
    // The positioner frame: x = E1 axis along the cell's +y, 1300 mm ahead, 500 mm up; the eye
    // is `distance` towards the robot (-x of the cell) from the axis, at station + offset.
    EXPECT_NEAR(p.cell.x(), 1300.0 - p.distance, 1e-6);
    EXPECT_NEAR(p.cell.y(), stations[i] - 200.0, 1e-6);
    EXPECT_NEAR(p.cell.z(), 500.0, 1e-6);
    EXPECT_LT(((arm.flange(p.q) * tool).translation() - p.cell).norm(), 1e-6);
    EXPECT_TRUE(joint_limit_violation(m.robot, p.q, m.robot.joint_margin).empty());
    EXPECT_GE(std::fabs(p.q[4]), m.robot.wrist_margin);
  }
}

TEST(CellReach, PositionerFiveMetresAwayIsRefusedNamingItsFrameAndThePoint) {
  MachineOptions m = kr16_cell("offset: 0\n");
  m.robot.positioner.xyz = {5000, 0, 500};
  const Tube t = tube(25, 400);
  try {
    check_cell_reach(t.mesh, t.axis, t.profile, m);
    FAIL() << "not refused";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    std::printf("%s\n", msg.c_str());
    EXPECT_NE(msg.find("positioner_1axis.yaml: frame with machine.robot.offset 0.0 mm"),
              std::string::npos)
        << msg;
    EXPECT_NE(msg.find("out of reach of the KUKA KR 16-2"), std::string::npos) << msg;
    // The first station's eye: 45 mm towards the robot from the axis at x = 5000 mm.
    EXPECT_NE(msg.find("at (4955.0, 0.0, 500.0) mm in the cell"), std::string::npos) << msg;
    EXPECT_NE(msg.find("beyond the arm's full stretch"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(CellReach, InsideTheStretchButPastTheJointLimitsIsRefusedByTheInverseKinematics) {
  // The positioner right above the robot's base, 200 mm over A2: the eye points lie within the
  // arm's stretch, but reaching them would fold the forearm past A3's limits.
  MachineOptions m = kr16_cell("offset: -200\n");
  m.robot.positioner.xyz = {0, 0, 900};
  const Tube t = tube(25, 400);
  try {
    check_cell_reach(t.mesh, t.axis, t.profile, m);
    FAIL() << "not refused";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    std::printf("%s\n", msg.c_str());
    EXPECT_NE(msg.find("has no inverse kinematics inside the joint limits"), std::string::npos)
        << msg;
  }
}

// A layup's outer layers put the eye further from the axis than the bare mandrel: a cell with the
// positioner above the robot's reach (its axis 1200 mm up, the eye above it) reaches a 50 mm
// tube's eye (70 mm from the axis, up to 1270 mm high) but not that of a laminate 45 mm thick on
// it (115 mm, 1315 mm high): refused naming the layer; the bare mandrel's check cannot see it.
TEST(CellReach, ALaminateOutOfReachIsRefusedNamingTheLayer) {
  MachineOptions m = kr16_cell("offset: -150\n");
  m.robot.positioner.xyz = {900, 0, 1200};
  m.robot.positioner.abc = {90, 0, 90};  // x = E1 along the cell's +y, y (the eye's side) up
  const Tube t = tube(50, 300);
  const Mesh laminate(test::open_cylinder(95, 300, 64, 40));
  const CellReach r = check_cell_reach(t.mesh, t.axis, t.profile, m);
  ASSERT_EQ(r.points.size(), 3u);
  EXPECT_NEAR(r.points[1].cell.z(), 1200.0 + 70.0, 0.05);
  try {
    check_cell_reach_over(t.mesh, t.axis, laminate, m, "layers[1] (outer)");
    FAIL() << "not refused";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    std::printf("%s\n", msg.c_str());
    EXPECT_NE(msg.find("positioner_1axis.yaml: frame with machine.robot.offset -150.0 mm puts the "
                       "laminate under layers[1] (outer) out of reach of the KUKA KR 16-2"),
              std::string::npos)
        << msg;
    EXPECT_NE(msg.find(", 115.0 mm from it,"), std::string::npos) << msg;
    EXPECT_NE(msg.find("(checked before planning the layer)"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  // The mandrel itself as the surface: the same eye points as check_cell_reach.
  const CellReach same = check_cell_reach_over(t.mesh, t.axis, t.mesh, m, "layers[1] (outer)");
  ASSERT_EQ(same.points.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(same.points[i].distance, r.points[i].distance, 0.05);
  }
}

}  // namespace
}  // namespace windplan
