#pragma once
// Replay of a G-code program through the job's machine model: where the fibre lands.
//
// Each block's axis values (export/program/gcode_reader.h) put the eye, in the mandrel frame, at
//   E = o + X d + Y (cos(-A) u + sin(-A) v)
// (export/machine/kinematics.h: the axis frame, A = -theta(E)); lathe2 programs have no Y, the eye
// runs on the cylinder named at the last operator stop (GcodeBlock::eye_radius: a layup's layers
// each on their own), before any on the kind's eye cylinder of the mandrel
// (export/machine/eye_envelope.h). Within a block the axes move
// linearly, and the move is cut into sub-steps of at most `step` mm of eye travel in the mandrel
// frame.
//
// The fibre runs from its contact point P on the mandrel straight to the eye, tangent to the
// surface at P. When the eye moves to E', the straight fibre from P would cut into the surface
// ((E' - P) . n(P) < 0): the fibre wraps on and P advances along the surface towards E' (the
// tangent-plane direction of E' - P) until the free fibre is tangent again ((E' - P) . n = 0,
// found by bracketing and regula falsi on straight steps projected back onto the mesh, at most
// 4 `step` per sub-step (a contact that finds no tangency, e.g. pulled over a tube's open end,
// does not run away along the rim), with normals
// interpolated from face-corner normals that do not average across creases). When the free fibre
// lifts off, P stays: laid fibre does not come off. This is the payout lag of a real winder; on a
// cylinder it lays z_P' = (z_E - z_P) / tan(beta) per radian (beta = acos(r / R_eye)), whose steady
// state is the planned helix. The fibre starts at the planned path's first point (where it is tied
// on); a rapid G0 after that (between layers: the tow is cut) ties it on again at the first point
// of the next layer after the last tie-on (a plan without layers: of the circuit after the
// contact's; not after the contact's in a layup: a layer's last pins can release the contact onto
// the next layer's first point, and the circuit after it was that layer's second).
// On the plan's turnarounds (CircuitSegment::Kind::Turnaround: dwell arcs on
// pin rings, stations or a boss) the pins or the boss hold the fibre: once the contact comes within
// catch_distance (10 mm, along the plan) of one, it moves along the planned arc to the first
// planned point whose free fibre to the eye is tangent ((E - P) . n >= 0 with the plan's normal),
// and no deviation is counted (held_substeps counts those sub-steps); it leaves the arc at its end,
// free again. Flat faces (issue #26: a rounded rectangle's sides; a facet with a vertex all of
// whose faces are coplanar, so not a coarse pipe's facet strips): a fibre is straight there, and
// with the eye in the face's plane every point of it is "tangent". The contact keeps an anchor, the
// last point that holds the fibre (pins, or a curved surface); beyond it the fibre runs straight
// over the face (probed every 4 `step`: a point within `touch` of the face lies on it) towards the
// eye (the eye in or above the plane) or along the tangent-plane direction of the eye (below it),
// and the contact is where it leaves the face. With the eye in the plane the stretch swings with
// the eye and only the anchor counts as laid; when its far end is held (the eye drops below the
// plane and the fibre wraps on where the surface curves, or pins catch it) the stretch is laid and
// its points are compared with the plan. There the pins turn the fibre in the face's plane: it
// wraps on to the next pin while that pin stands outside the straight fibre (away from the arc's
// bend), and leaves the arc's last pin when the fibre no longer bends round it. Elsewhere the
// tangency on an arc is judged with the plan's normal (the planner's dwell points carry the
// surface's interpolated normal, a flat face's own) and the contact leaves the arc at its end, at
// the pass's first point. The catch distance is measured along the plan from the foot of the
// contact on its planned segment (a straight pass on a flat face is one long segment).
// On a curved surface's arc an eye less than `hold` below a pin's tangent plane counts as on it.
// A layup's circuits are walked on the surface each layer was wound on
// (circuit_surfaces below), not on the bare mandrel.
//
// Deviation: the distance of every sub-step's contact point to the planned fibre polyline (all
// circuits in order), searched in a window of arc length that moves along it. With layers
// (WindingPlan::layers) the window, the pins that catch the fibre and the contact stay within the
// layer being laid, from its first point (reached by the rapid that ties the tow on; that of its
// first circuit with points) to its last: the step from one layer's last point to the next one's
// first is no fibre.
// Time: G93 blocks take 60 / F s; G94 blocks take distance / (F / 60) with the distance of the
// driven axes (degrees counted as mm); a G0 takes the slowest axis at max_velocity.
#include <string>
#include <vector>

#include "export/machine/feed_plan.h"
#include "export/program/gcode_reader.h"
#include "geometry/mesh/mesh.h"
#include "planner/job/machine_options.h"
#include "planner/plan/plan.h"

namespace windplan {

struct ReplayOptions {
  double step = 0.5;  ///< mm: largest eye travel (mandrel frame) per sub-step, > 0
  /// mm of planned path searched behind and ahead of the last match for the deviation.
  double search_back = 10.0;
  double search_ahead = 40.0;
  /// mm: a contact this close (along the plan) to a turnaround is caught by its pins or boss.
  double catch_distance = 10.0;
  /// mm: a point of a straight fibre this close to the surface lies on it (a flat face: the eye in
  /// its plane, or below it): the contact moves on to where the fibre leaves the face; 0: never.
  double touch = 1e-3;
  /// mm: on a curved surface's turnaround, an eye this close below a pin's tangent plane is on
  /// it and the pin holds the fibre (an eye swung in that plane, from a dwell arc's last eye to
  /// its pass's first, is put a few 1e-4 mm below it by the program's 4 decimals and the plan's
  /// tangent, normal to its normal to ~1e-6: 0.0003 mm at most over the oval canister's swings;
  /// judged exactly, the fibre left the pin at the pass's next point, 0.4 mm off there).
  double hold = 1e-3;
};

struct ReplayExcess;

struct ReplayResult {
  int blocks = 0;
  int substeps = 0;
  int held_substeps = 0;       ///< sub-steps on turnarounds (pins or boss lay the fibre)
  int straight_substeps = 0;   ///< sub-steps that laid a straight fibre on a flat face (touch)
  double max_deviation = 0.0;  ///< mm, contact point to the planned path
  int max_deviation_line = 0;  ///< program line of the block where it is largest
  Vec3 max_deviation_point = Vec3::Zero();
  double mean_deviation = 0.0;  ///< mm, over sub-steps
  /// mm, the eye at each block's end to the surface walked there (the mandrel, or on a layup the
  /// surface of the layer in work), and the program line of the least.
  double min_clearance = 0.0;
  int min_clearance_line = 0;
  /// lathe2: the eye's radius is set by hand at the operator stops (clearance_short says so).
  bool eye_radius_by_hand = false;
  double wind_time = 0.0;  ///< s, from the feed words
  int carriage_reversals = 0;
  int spindle_reversals = 0;
  double a_min = 0, a_max = 0, x_min = 0, x_max = 0, y_min = 0, y_max = 0, b_min = 0, b_max = 0;
  AxisLimitCheck limits;  ///< block velocities and accelerations from the feed words
  double seconds = 0.0;   ///< wall time of the replay
  std::string summary;    ///< one line

  /// The check of machine.replay_tolerance: true when max_deviation <= tolerance (mm) or the
  /// tolerance is <= 0 (report only); else false, with `excess` (when given) naming it.
  bool within(double tolerance, ReplayExcess* excess = nullptr) const;

  /// The eye's clearance in the replay (from the surface of the layer in work): "" when
  /// min_clearance >= clearance - slack (mm), else one line naming `program`, the line, the
  /// distance and the clearance ("machine.envelope.clearance: the replay of PROGRAM puts the eye
  /// D mm from ... at line N ..."; `located`: "PROGRAM:N: the replay puts the eye ..."; on a
  /// lathe2, eye_radius_by_hand, it asks whether each layer's stop names its eye radius).
  std::string clearance_short(const std::string& program, double clearance, double slack,
                              bool located) const;
};

/// A replay's worst deviation beyond machine.replay_tolerance (ReplayResult::within, and
/// RobotReplayResult::within in export/robot/robot_replay.h), and the two messages that refuse it.
struct ReplayExcess {
  bool eye = false;        ///< the eye of a robot target is off (else: the laid fibre)
  double deviation = 0.0;  ///< mm
  double tolerance = 0.0;  ///< mm
  std::string at;          ///< "file:line" of a robot program's target; "": a G-code `line`
  int line = 0;            ///< G-code program line (when `at` is empty)

  /// windplan run's: "machine.replay_tolerance: the replay of PROGRAM lays the fibre D mm from
  /// the plan at line N (or: at FILE:LINE), more than T mm; no program written".
  std::string refused(const std::string& program) const;
  /// windplan simulate's: "PROGRAM:N (or: FILE:LINE): the replay lays the fibre D mm from the
  /// plan, more than machine.replay_tolerance T mm" ("puts the eye" for an eye excess).
  std::string located(const std::string& program) const;
};

/// \param program from read_gcode with the same machine options
/// \param plan the planned fibre path (and the spindle axis and mandrel radius profile)
/// \param mandrel the mandrel mesh
/// \param circuit_surfaces per circuit of plan.circuits, the mesh of the surface it was wound on
///        (a layup's layers over others: planner/plan_layup.h layup_circuit_surfaces); null
///        entries, missing entries or an empty list: the mandrel. The contact walks a circuit on
///        its own surface (the clearance is measured to it too); when the plan moves on to a
///        circuit on another surface (a rapid G0 between layers ties the tow on again), the
///        contact is projected onto that surface.
/// \throw InputError for an empty program or mesh, or a kind with no G-code (robot)
ReplayResult replay_program(const GcodeProgram& program, const WindingPlan& plan,
                            const Mesh& mandrel, const MachineOptions& machine,
                            const ReplayOptions& options = {},
                            const std::vector<const Mesh*>& circuit_surfaces = {});

}  // namespace windplan
