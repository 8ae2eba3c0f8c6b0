#pragma once
// The robot cell's motion for a plan: every resampled eye state of export/machine/kinematics.h
// becomes a target of the arm (the eye's pose in the positioner's BASE frame) and an E1 angle of
// the positioner, solved to joint values through the arm's inverse kinematics.
//
// The cell (planner/job/robot_options.h): the positioner turns the mandrel by E1, monotone and
// smooth within every circuit (export/robot/positioner_e1.h: a fit of the lathe model's spindle
// angle A, which would put the turned eye in the half-plane of the axis d and u but turns back and
// forth on a bent tube). With E1 = A the eye is at (X + offset, Y, 0) in the positioner frame
// (X, Y the carriage and cross-feed of the lathe model); the target is that pose turned by
// E1 - A about the positioner's x axis (the E1 axis), so the eye in the mandrel frame is the
// plan's whatever E1 is. The pose before that turn is: x towards the mandrel axis (-u), z the fibre
// direction resolved in the d-v plane (cos B, 0, sin B) with B the eye rotation of lathe4 for a
// roller eye (machine.robot.eye: roller), or B = 90 deg (z along the mandrel's turning direction)
// for a ring eye (eye: ring, the default), whose orifice lays the fibre the same at any rotation, y
// = z x x. The flange target is BASE * eye * TOOL^-1 (BASE the positioner frame in the cell).
//
// Where E1 - A turns between two states, targets are inserted on the planned eye path (the
// straight line between the two eyes in the mandrel frame) in steps of at most 2 deg, and small
// enough that the arm's straight move between two of them, Y (1 - cos(step / 2)) inside the arc at
// the eye's distance Y from the E1 axis, stays within chord_tolerance (the eye is planned that far
// beyond the clearance for it: export/machine/kinematics.h, kRobotEyeChords).
// IK: the first target of the plan takes the solution nearest the arm's home joints
// (RobotArm::inverse_near), every other is seeded from the previous solution (one continuous
// configuration). Errors (InputError, naming the circuit and
// point and the pose in the cell): a target out of reach; a joint past its limit less
// joint_margin; |A5| below wrist_margin (the wrist singularity); a change of configuration
// (Status) inside a pass of the plan (CircuitSegment::Kind::Pass).
// Speeds: a move's duration is the plan's (export/machine/feed_plan.h) or longer when a joint or
// E1 would move faster than its max_velocity: duration = max(planned, |dq_i| / v_i, |dE1| / v_E1).
#include <string>
#include <vector>

#include "export/machine/kinematics.h"
#include "export/robot/positioner_e1.h"
#include "export/robot/robot_kinematics.h"

namespace windplan {

struct RobotTarget {
  int state = 0;        ///< index into Motion::states
  bool tie_on = false;  ///< first point of the plan or of a layer (the tow is tied on)
  Eigen::Isometry3d eye = Eigen::Isometry3d::Identity();  ///< eye pose in the BASE frame (mm)
  double e1 = 0.0;                                        ///< deg
  Joints q{};                                             ///< deg
  int status = 0, turn = 0;                               ///< robot_kinematics.h
  double duration = 0.0;                                  ///< s, of the move into this target
};

struct RobotMotion {
  std::vector<RobotTarget> targets;
  Eigen::Isometry3d base = Eigen::Isometry3d::Identity();  ///< positioner frame in the cell
  Eigen::Isometry3d tool = Eigen::Isometry3d::Identity();  ///< eye in the flange frame
  double cycle_time = 0.0;                                 ///< s, sum of the durations
  double planned_time = 0.0;                               ///< s, Motion::wind_time
  double min_joint_margin = 0.0;  ///< deg, smallest distance of a joint to a limit
  std::string min_joint_margin_joint;
  double min_wrist_angle = 0.0;        ///< deg, smallest |A5|
  double max_joint_speed_ratio = 0.0;  ///< at the planned durations (> 1: the move was slowed)
  int slowed_moves = 0;
  int configuration_changes = 0;  ///< between passes (at turnarounds or circuit links)
  double ik_seconds = 0.0;        ///< wall time of the IK
  PositionerE1 positioner;        ///< E1 per state (positioner_e1.h), its reversals and offsets
  std::string brief_report() const;
};

/// \throw InputError as in the header comment; ConfigError for a cell without an arm
RobotMotion compute_robot_motion(const Motion& motion, const WindingPlan& plan,
                                 const MachineOptions& machine);

/// The eye pose in the positioner frame for a lathe-model state (see the header comment); a ring
/// eye (roller false) keeps B = 90 deg.
Eigen::Isometry3d eye_in_base(const MachineState& s, double offset, bool roller);

}  // namespace windplan
