#pragma once
// Options of a robot cell (`machine.robot:`, schema: docs/config.md): the arm (a URDF-like joint
// list read from an arm profile), the positioner whose rotary axis E1 turns the mandrel, the tool
// frame of the payout eye, and the program dialect. They live in planner/ because the Job holds
// them; export/robot (kinematics, KRL and RAPID, replay) reads them.
//
// Frames: the cell frame is the robot's base frame (KUKA $ROBROOT, ABB base). A Frame6 is a
// position (mm) and KUKA angles A, B, C (deg): R = Rz(A) Ry(B) Rx(C).
// Arm: joint i sits at `origin` (mm, in the frame of joint i-1 at zero, the base for the first)
// and turns about the unit `axis` by q_i (deg); all joint frames are parallel to the base at
// q = 0 (the URDF convention of ROS-Industrial's support packages). The flange ($FLANGE / tool0)
// is `flange` mm from the last joint, parallel to it: x points out of the flange.
// Positioner: the mandrel's spindle axis lies on the x axis of `frame` (in the cell frame), its
// axis origin `offset` mm along it; the mandrel's reference direction u (export/machine/
// kinematics.h) is the frame's y axis at E1 = 0; E1 = the spindle angle A of the lathe model.
#include <array>
#include <limits>
#include <string>
#include <vector>

namespace windplan {

/// A position (mm) and KUKA A, B, C angles (deg): R = Rz(A) Ry(B) Rx(C).
struct Frame6 {
  std::array<double, 3> xyz{0.0, 0.0, 0.0};  ///< mm
  std::array<double, 3> abc{0.0, 0.0, 0.0};  ///< deg
};

/// One revolute joint of the arm.
struct RobotJoint {
  std::string name;                             ///< e.g. A1
  std::array<double, 3> origin{0.0, 0.0, 0.0};  ///< mm from the previous joint (at q = 0)
  std::array<double, 3> axis{0.0, 0.0, 1.0};    ///< unit rotation axis (previous frame)
  double min = -180.0, max = 180.0;             ///< deg, travel limits
  double max_velocity = 100.0;                  ///< deg/s, > 0
};

/// The `machine.robot:` section.
struct RobotOptions {
  /// "krl" (KUKA: .src + .dat) or "rapid" (ABB: .mod).
  std::string dialect = "krl";
  std::string arm_file;            ///< the arm profile (machine.robot.arm), empty: no arm
  std::string arm_name;            ///< from the arm profile, for reports and program headers
  std::vector<RobotJoint> joints;  ///< 6 revolute joints, base to wrist
  std::array<double, 3> flange{0.0, 0.0, 0.0};  ///< mm from the last joint to the flange
  std::array<double, 6> home{0.0, -90.0, 90.0, 0.0, 45.0, 0.0};  ///< deg, IK seed of a pass
  std::string positioner_file;  ///< the positioner profile (machine.robot.positioner)
  std::string positioner_name;
  Frame6 positioner;               ///< the positioner's frame in the cell (x = the E1 axis)
  double e1_max_velocity = 180.0;  ///< deg/s of E1, > 0
  double offset = 0.0;  ///< mm along E1 from the positioner frame to the mandrel axis origin
  Frame6 tool;          ///< the eye in the flange frame (x: towards the mandrel axis)
  /// "ring" (a round orifice: the eye's rotation about its axis is held) or "roller" (a roller or
  /// slot eye turned to the fibre direction, lathe4's B; export/robot/robot_motion.h).
  std::string eye = "ring";
  double joint_margin = 5.0;  ///< deg: required distance of every joint to its limits, >= 0
  double wrist_margin = 5.0;  ///< deg: required |A5| (distance to the wrist singularity), >= 0
  int max_points = 3000;      ///< targets per program file (longer programs split), >= 10

  bool has_arm() const { return !joints.empty(); }
  bool is_valid(std::string* why) const;
};

}  // namespace windplan
