// The shipped KUKA KR 16-2 through KDL: forward kinematics against poses computed by hand from the
// data-sheet dimensions, FK(IK(pose)) over the workspace, and the errors of a pose out of reach and
// of a joint past its limit.
#include "export/robot/robot_kinematics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "geometry/base/errors.h"
#include "planner/job/robot_config.h"

namespace windplan {
namespace {

RobotOptions kr16() {
  RobotOptions r;
  decode_robot(ConfigNode::load_string("arm: kuka_kr16_2.yaml\n", "test.yaml"),
               std::filesystem::path(WINDPLAN_SOURCE_DIR) / "configs" / "machines", &r);
  return r;
}

void expect_pose(const Eigen::Isometry3d& f, const Vec3& p, const Eigen::Matrix3d& r) {
  EXPECT_LT((f.translation() - p).norm(), 1e-9) << f.translation().transpose();
  EXPECT_LT((f.linear() - r).norm(), 1e-12) << f.linear();
}

TEST(RobotKinematics, ForwardMatchesHandComputedPoses) {
  const RobotArm arm(kr16());
  // Zero: the arm stretched forward, flange at a1 + a2 + d4 + flange, 675 - 35 high.
  expect_pose(arm.flange({0, 0, 0, 0, 0, 0}), Vec3(260 + 680 + 670 + 158, 0, 675 - 35),
              Eigen::Matrix3d::Identity());
  // A1 = 90 turns about -z: the stretched arm points to -y.
  Eigen::Matrix3d rz;
  rz << 0, 1, 0, -1, 0, 0, 0, 0, 1;
  expect_pose(arm.flange({90, 0, 0, 0, 0, 0}), Vec3(0, -1768, 640), rz);
  // KUKA home (A2 -90, A3 90): lower arm up, forearm level: A4 at (260 + 670, 1355 - 35).
  expect_pose(arm.flange({0, -90, 90, 0, 0, 0}), Vec3(930 + 158, 0, 1320),
              Eigen::Matrix3d::Identity());
  // A2 = -90 alone: all of it upright; Ry(-90) maps x to +z, the 35 mm offset to +x.
  Eigen::Matrix3d ry;
  ry << 0, 0, -1, 0, 1, 0, 1, 0, 0;
  expect_pose(arm.flange({0, -90, 0, 0, 0, 0}), Vec3(260 + 35, 0, 675 + 680 + 670 + 158), ry);
  // Home with A5 = 90 (about +y): the flange points down, 158 mm below the wrist centre.
  Eigen::Matrix3d down;
  down << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  expect_pose(arm.flange({0, -90, 90, 0, 90, 0}), Vec3(930, 0, 1320 - 158), down);
  EXPECT_LT((arm.wrist_centre({0, -90, 90, 0, 90, 0}) - Vec3(930, 0, 1320)).norm(), 1e-9);
}

TEST(RobotKinematics, ShippedAbbArmAtHandComputedPoses) {
  RobotOptions r;
  decode_robot(ConfigNode::load_string("arm: abb_irb4600_60_205.yaml\n", "test.yaml"),
               std::filesystem::path(WINDPLAN_SOURCE_DIR) / "configs" / "machines", &r);
  const RobotArm arm(r);
  // Zero (ABB's calibration pose): lower arm up, forearm level.
  expect_pose(arm.flange({0, 0, 0, 0, 0, 0}), Vec3(175 + 960 + 135, 0, 495 + 900 + 175),
              Eigen::Matrix3d::Identity());
  // Axis 3 at -90 (about +y): the forearm points up from 495 + 900, and its 175 mm offset
  // (+z at zero) turns to -x, back over axis 1's offset.
  Eigen::Matrix3d up;
  up << 0, 0, -1, 0, 1, 0, 1, 0, 0;
  expect_pose(arm.flange({0, 0, -90, 0, 0, 0}), Vec3(175 - 175, 0, 495 + 900 + 960 + 135), up);
  Joints q;
  ASSERT_TRUE(arm.inverse(arm.flange({10, 20, -30, 40, 50, 60}), {12, 18, -28, 38, 52, 58}, &q));
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(q[i], (Joints{10, 20, -30, 40, 50, 60})[i], 1e-6);
}

TEST(RobotKinematics, RoundTripOverTheWorkspace) {
  const RobotOptions r = kr16();
  const RobotArm arm(r);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int solved = 0;
  for (int k = 0; k < 300; ++k) {
    // A random reachable pose: FK of random joints inside the limits, away from A5 = 0.
    Joints q;
    for (int j = 0; j < 6; ++j) {
      const double mid = 0.5 * (r.joints[j].min + r.joints[j].max);
      const double half = 0.45 * (r.joints[j].max - r.joints[j].min);
      q[j] = mid + half * u(rng);
    }
    if (std::fabs(q[4]) < 10.0) q[4] = 10.0;
    const Eigen::Isometry3d pose = arm.flange(q);
    // Seed a few degrees away (as the previous point of a path is).
    Joints seed = q;
    for (double& s : seed) s += 3.0 * u(rng);
    Joints got;
    ASSERT_TRUE(arm.inverse(pose, seed, &got)) << "pose " << k;
    const Eigen::Isometry3d back = arm.flange(got);
    EXPECT_LT((back.translation() - pose.translation()).norm(), 1e-6) << "pose " << k;
    EXPECT_LT((back.linear() - pose.linear()).norm(), 1e-8);
    ++solved;
  }
  EXPECT_EQ(solved, 300);
}

// Along a path (each target seeded with the previous solution, as the robot motion and the replay
// solve them), Newton's steps stop only once the pose is down to rounding: FK of every solution
// within 1e-10 mm and 1e-13 rad of its target, four orders below what inverse accepts, and the
// joints those of the path within 1e-9 deg.
TEST(RobotKinematics, AlongAPathEverySolutionIsPolishedToRounding) {
  const RobotArm arm(kr16());
  Joints seed{10, -80, 95, 20, 60, -30};
  for (int k = 1; k <= 200; ++k) {
    // About 2 mm of eye travel between targets, every joint moving.
    const double s = 0.0015 * k;
    const Joints q{10 + 30 * s, -80 + 20 * s, 95 - 25 * s, 20 + 60 * s, 60 - 15 * s, -30 + 90 * s};
    const Eigen::Isometry3d pose = arm.flange(q);
    Joints got;
    ASSERT_TRUE(arm.inverse(pose, seed, &got)) << "target " << k;
    const Eigen::Isometry3d back = arm.flange(got);
    EXPECT_LT((back.translation() - pose.translation()).norm(), 1e-10) << "target " << k;
    EXPECT_LT((back.linear() - pose.linear()).norm(), 1e-13) << "target " << k;
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(got[i], q[i], 1e-9) << "target " << k << " A" << i + 1;
    seed = got;
  }
}

TEST(RobotKinematics, OutOfReachAndPastALimitAreNamed) {
  const RobotOptions r = kr16();
  const RobotArm arm(r);
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation() = Vec3(2500, 0, 700);  // 1611 mm reach to the wrist + 158 mm flange
  Joints q;
  EXPECT_FALSE(arm.inverse(far, r.home, &q));
  EXPECT_EQ(joint_limit_violation(r, {0, -90, 90, 0, 45, 0}), "");
  const std::string bad = joint_limit_violation(r, {0, -90, -140, 0, 45, 0});
  EXPECT_NE(bad.find("A3 = -140.000 deg past its limit -130 deg"), std::string::npos) << bad;
  EXPECT_NE(joint_limit_violation(r, {0, -90, 90, 0, 128, 0}, 5.0).find("A5"), std::string::npos);
}

TEST(RobotKinematics, FrameAnglesRoundTrip) {
  for (const std::array<double, 3> abc :
       {std::array<double, 3>{10, 20, 30}, {-170, 80, -5}, {90, 0, 0}, {0, -45, 179}}) {
    Frame6 f;
    f.abc = abc;
    const std::array<double, 3> back = rotation_abc(frame6_transform(f).linear());
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(back[i], abc[i], 1e-9);
  }
}

TEST(RobotKinematics, MalformedArmProfileNamesTheFile) {
  RobotOptions r;
  try {
    decode_robot(ConfigNode::load_string("arm: positioner_1axis.yaml\n", "test.yaml"),
                 std::filesystem::path(WINDPLAN_SOURCE_DIR) / "configs" / "machines", &r);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("positioner_1axis.yaml"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace windplan
