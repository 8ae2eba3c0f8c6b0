#pragma once
// Replay of a robot program (export/robot/robot_program_reader.h) through the job's robot cell:
// every target is solved to joints by inverse kinematics (seeded with the previous target's joints;
// the first: the solution nearest the arm's home), and forward kinematics of those joints with the
// program's TOOL gives the eye in the cell. The mandrel sits on the job's positioner
// (machine.robot.positioner, offset), turned by the target's E1; the eye in the mandrel frame then
// goes through the G-code replay's fibre model (export/program/replay.h: contact point, payout lag,
// pins), with each robot move (linear in the BASE frame and in E1) cut into pieces of at most 2 mm
// of eye travel, each an equivalent lathe4 block (A = E1 - the eye's angle about the E1 axis, X =
// its axial position less the offset, Y = its distance from the axis). PTP / MoveJ tie the tow on
// again (as a G0). Checked and reported: the largest deviation from the plan (and its file and
// line), the eye's and the flange's and last link's (wrist centre to flange) smallest distance to
// the mandrel (a layup: to the surface of the layer in work, circuit_surfaces below), joint margins
// and the smallest |A5|, joint and E1 speeds against their limits, configuration changes (Status)
// and the cycle time: KRL LIN max(TCP distance / $VEL.CP, |dE1| / (E1 max velocity x $VEL_EXTAX[1]
// / 100)), RAPID \T, PTP / MoveJ the slowest joint at its max_velocity. Errors (InputError naming
// the file and line): a target out of reach, a joint past its limit.
#include <string>
#include <vector>

#include "export/machine/kinematics.h"
#include "export/program/replay.h"
#include "export/robot/robot_program_reader.h"

namespace windplan {

struct RobotReplayResult {
  ReplayResult fibre;  ///< the fibre model's result (its lines: lines of the targets' files)
  int targets = 0;
  std::string max_deviation_at;    ///< "file:line" of the largest deviation
  double max_eye_deviation = 0.0;  ///< mm, target eye to the planned eye path (0: not measured)
  std::string max_eye_deviation_at;
  double min_link_clearance = 0.0;  ///< mm, flange and last link to the mandrel mesh
  std::string min_link_clearance_at;
  double min_joint_margin = 0.0;  ///< deg
  std::string min_joint_margin_joint;
  double min_wrist_angle = 0.0;        ///< deg, smallest |A5|
  double max_joint_speed_ratio = 0.0;  ///< joint or E1 speed over its max_velocity, largest
  std::string max_joint_speed_at;
  int configuration_changes = 0;
  double cycle_time = 0.0;       ///< s
  double seconds = 0.0;          ///< wall time
  std::string summary;           ///< one line
  std::string min_clearance_at;  ///< "file:line" of the eye's least clearance (fibre.min_clearance)

  /// The check of machine.replay_tolerance on the worst of the fibre's deviation and the eye's
  /// (the larger one; the fibre's on a tie): true when it is <= tolerance (mm) or the tolerance
  /// is <= 0 (report only); else false, with `excess` (when given) naming it and its file:line.
  bool within(double tolerance, ReplayExcess* excess = nullptr) const;

  /// The check of machine.envelope.clearance on the replayed eye: true when its least distance to
  /// the surface of the layer in work (fibre.min_clearance, every 2 mm of eye travel) is at least
  /// clearance - 1e-3 mm (rounding; no chord slack: the eye is planned beyond the clearance,
  /// export/machine/kinematics.h), or clearance <= 0 (not checked); else false, with `message`
  /// (when given) "FILE:LINE: the replay puts the eye D mm from the surface it winds on, less
  /// than machine.envelope.clearance C mm".
  bool keeps_clearance(double clearance, std::string* message = nullptr) const;
};

/// \throw InputError for an empty program or mesh, a target out of reach or past a joint limit
/// \param planned the planned motion (nullptr: the eye path is not measured)
/// \param circuit_surfaces per circuit of plan.circuits, the mesh of the surface it was wound on
///        (a layup: planner/plan_layup.h layup_circuit_surfaces), handed to the G-code replay's
///        fibre model as is (export/program/replay.h: each circuit walked, and the eye's
///        clearance measured, on its own surface); null, missing entries or an empty list: the
///        mandrel. The flange's and last link's clearance of a target is measured to the surface
///        of the layer in work: that of the circuit of the nearest planned eye (without
///        `planned`: the nearest of all the surfaces).
RobotReplayResult replay_robot_program(const RobotProgram& program, const WindingPlan& plan,
                                       const Mesh& mandrel, const MachineOptions& machine,
                                       const Motion* planned = nullptr,
                                       const ReplayOptions& options = {},
                                       const std::vector<const Mesh*>& circuit_surfaces = {});

}  // namespace windplan
