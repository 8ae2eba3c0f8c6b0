#pragma once
// The robot cell's reach, checked before planning: can the arm bring the payout eye to the
// mandrel where the winding will need it? A conservative screen from the mandrel's radius profile
// and the cell's geometry only (no plan), so that a cell that cannot wind the mandrel at all (a
// positioner placed metres away, an offset that puts the mandrel behind the robot) is refused in
// well under a second instead of after the planning stages; compute_robot_motion
// (export/robot/robot_motion.h) still checks every target of the plan afterwards.
//
// Points: at three stations along the spindle axis (the wound region's two ends and its middle),
// the eye at its distance from the axis there: the largest mandrel radius of the station (the
// radius profile, the largest over all angles: the positioner turns each side of the section to
// the eye) plus envelope.clearance ("clearance" mode), the envelope profile's radius ("profile")
// or hypot(radius, free_length) ("free_length"). The eye's pose is the one robot_motion gives a
// state there (eye_in_base: in the positioner's x-y half-plane, x towards the axis; the arm's
// target does not depend on E1); a roller eye (eye: roller) may be turned, so it counts as
// reachable at B = 90, 60 or 120 deg. A point is reachable when the arm has an inverse
// kinematics solution inside the joint limits less joint_margin with |A5| >= wrist_margin
// (RobotArm::inverse_near), and is rejected at once when it lies beyond the arm's full stretch
// (the sum of its link lengths, flange and tool) from the first joint.
//
// Errors: InputError, one line naming the positioner profile file and its `frame`, the job's
// machine.robot.offset, the arm and the unreachable point (station, distance from the axis, the
// point in the cell).
#include <string>
#include <vector>

#include "export/robot/robot_kinematics.h"
#include "geometry/region/axis.h"
#include "planner/job/machine_options.h"

namespace windplan {

struct CellReachPoint {
  double station = 0.0;      ///< mm along the spindle axis
  double distance = 0.0;     ///< mm, the eye from the axis
  Vec3 cell = Vec3::Zero();  ///< mm, the eye in the cell (robot base) frame
  Joints q{};                ///< deg, the solution found
};

struct CellReach {
  std::vector<CellReachPoint> points;  ///< every point checked (all reachable on return)
  double seconds = 0.0;                ///< wall time
  std::string brief_report() const;
};

/// Checks the cell's reach for a mandrel before planning (see the header comment).
/// \param wound the wound region (Mandrel::winding.mesh): its extent along the axis gives the
///        stations
/// \param axis the spindle axis (Mandrel::axis; stations are mm along it from its origin, the
///        lathe model's X)
/// \param profile the mandrel's largest radius along the axis (Mandrel::profile)
/// \throw InputError naming the unreachable point, or for an empty wound region; ConfigError for
///        a cell without an arm
CellReach check_cell_reach(const Mesh& wound, const SpindleAxis& axis, const RadiusProfile& profile,
                           const MachineOptions& machine);

/// The same over the surface a layup winds a layer on (the laminate the layers under it built,
/// planner/pipeline.h PipelineOptions::on_layer_surface): a layup's outer layers put the eye
/// further from the axis than the bare mandrel does. The stations are the mandrel's wound
/// region's (`wound`), the eye at `surface`'s largest radius there (its radius profile,
/// geometry/region/winding_surface.h, never below it between stations) plus the clearance, as
/// above. \param layer the layer wound on it, as "layers[1] (outer)"
/// \throw InputError as above, naming "the laminate under <layer>" instead of the mandrel
CellReach check_cell_reach_over(const Mesh& wound, const SpindleAxis& axis, const Mesh& surface,
                                const MachineOptions& machine, const std::string& layer);

}  // namespace windplan
