// machine.robot: the shipped cell reads whole; an unknown dialect, an unknown key, a missing
// profile and an arm with 5 joints are one error naming the file, line and key.
#include "planner/job/robot_config.h"

#include <gtest/gtest.h>

#include <fstream>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

const std::filesystem::path kMachines =
    std::filesystem::path(WINDPLAN_SOURCE_DIR) / "configs" / "machines";

std::string error_of(const std::string& yaml, const std::filesystem::path& base = kMachines) {
  RobotOptions r;
  try {
    decode_robot(ConfigNode::load_string(yaml, "job.yaml"), base, &r);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(RobotConfig, ShippedCellReads) {
  RobotOptions r;
  decode_robot(ConfigNode::load_string("arm: kuka_kr16_2.yaml\npositioner: positioner_1axis.yaml\n"
                                       "dialect: rapid\ntool: {xyz: [250, 0, 0]}\neye: roller\n",
                                       "job.yaml"),
               kMachines, &r);
  EXPECT_EQ(r.arm_name, "KUKA KR 16-2");
  ASSERT_EQ(r.joints.size(), 6u);
  EXPECT_EQ(r.joints[3].origin[2], -35.0);
  EXPECT_EQ(r.joints[5].max_velocity, 615.0);
  EXPECT_EQ(r.flange[0], 158.0);
  EXPECT_EQ(r.positioner.xyz[0], 1300.0);
  EXPECT_EQ(r.positioner.abc[0], 90.0);
  EXPECT_EQ(r.dialect, "rapid");
  EXPECT_EQ(r.eye, "roller");
  EXPECT_EQ(r.tool.xyz[0], 250.0);
}

TEST(RobotConfig, BadInputIsOneLineNamingTheKey) {
  std::string e = error_of("dialect: fanuc\n");
  EXPECT_NE(e.find("job.yaml:1"), std::string::npos) << e;
  EXPECT_NE(e.find("dialect"), std::string::npos) << e;
  e = error_of("arm: kuka_kr16_2.yaml\nspeed: 3\n");
  EXPECT_NE(e.find("speed"), std::string::npos) << e;
  e = error_of("arm: no_such_arm.yaml\n");
  EXPECT_NE(e.find("no_such_arm.yaml does not exist"), std::string::npos) << e;
  // An arm profile with 5 joints names that file.
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "windplan_robot_cfg";
  std::filesystem::create_directories(dir);
  {
    std::ofstream f(dir / "arm5.yaml");
    f << "name: five\njoints:\n";
    for (int i = 0; i < 5; ++i) {
      f << "  - {name: A" << i + 1
        << ", origin: [0, 0, 100], axis: [0, 0, 1], min: -90, max: 90, max_velocity: 100}\n";
    }
    f << "flange: [0, 0, 50]\n";
  }
  e = error_of("arm: arm5.yaml\n", dir);
  EXPECT_NE(e.find("arm5.yaml"), std::string::npos) << e;
  EXPECT_NE(e.find("needs 6 revolute joints (got 5)"), std::string::npos) << e;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace windplan
