#pragma once
// Machine kinematics of a winding plan: the payout eye and the machine axes.
//
// Payout eye (the convention of Cadfil's payout files): for a fibre point P with unit tangent t
// (the direction of travel), the eye is E = P + L t, the point where the tangent line first
// leaves the eye envelope; L >= 0 is the free fibre length between eye and mandrel. The
// envelope is a surface of revolution about the spindle axis, R_env(x) of the axial coordinate x,
// chosen per machine kind (export/machine/eye_envelope.h: a cylinder for lathe2, the true-distance
// clearance envelope for lathe4 and robots, or an explicit profile; or a fixed free length).
// A robot with the mandrel mesh (kind robot, envelope.clearance) has no envelope of revolution:
// its eye is the first point of the tangent line at the true clearance from the mesh (a layup's
// circuit: from the surface of its layer, circuit_surfaces below)
// (export/machine/clearance_eye.h), with eyes inserted where the tangent turns by more than 2 deg
// between two dense points and where a circuit goes on from the previous one's last point (link
// eyes, the tangent turned from that circuit's last tangent; not at a layer's start, where the
// tow is tied on again), its targets resampled in (X, Y, angle) as well (the cell's
// interpolation); its eyes are planned at the clearance plus kRobotEyeChords chord tolerances, so
// that the eye keeps the clearance between the targets too (one tolerance for the chords, one for
// the turn of the eye about the positioner's axis between two targets,
// export/robot/robot_motion.h). lathe4 on a layup (circuit_surfaces): each circuit's envelope is
// the clearance envelope of the surface it is wound on, and its clearance is checked on that
// surface; lathe2 (no cross-feed): each layer's eye cylinder is the largest radius of the surface
// it is wound on + the clearance, set by hand at the operator stop before the layer
// (export/program/gcode.h), unless envelope.radius (or a constant profile) fixes one cylinder for
// all, whose clearance is then checked on each layer's surface. The
// tangents t are the plan's, smoothed under machine.tangent_window
// (export/machine/tangent_smoothing.h). L solves f(L) = r(E(L)) - R_env(x(E(L))) = 0 for the first
// root: f is Lipschitz with constant 1 + S (S = the largest |dR_env/dx|), so marching by -f/(1+S)
// never steps over a root (sphere tracing); the last bracket is refined by bisection to 1e-10 mm.
//
// Axis frame: the spindle axis (origin o, unit d) with a fixed orthonormal pair (u, v), u the
// normalised projection of the world axis least aligned with d (ties: x before y before z), v =
// d x u. Angular position theta(p) = atan2((p-o).v, (p-o).u), counter-clockwise about d.
//
// Lathe axes, for each resampled point (machine frame: the mandrel turned by A about d; the eye
// moves in the half-plane through the axis spanned by d and u):
//   A [deg]: spindle angle = -theta(E), unwrapped (continuous over the whole plan), so that the
//            turned eye lies at angle 0, i.e. on +u;
//   X [mm]:  carriage = axial coordinate of E;
//   Y [mm]:  cross-feed = radial distance of E from the axis (lathe2: reported, not a machine
//   axis); B [deg]: eye rotation about its radial direction (lathe4; 0 for lathe2): with the fibre
//            direction t resolved at E into axial t_x = t.d and circumferential t_c = t.(d x r_E)
//            (r_E the unit radial direction of E), B = atan2(t_c, t_x), unwrapped: 0 when the
//            fibre runs along +d, +90 when it runs circumferentially counter-clockwise about d.
// Times: the feed plan of export/machine/feed_plan.h over the machine axes (lathe2: A, X; others A,
// X, Y, B), per-axis max_velocity and max_acceleration, and the fibre speed cap delta_s /
// max_fibre_speed when that is set; t_s accumulates durations from 0 at the first point; the move
// into the first point of a circuit (c > 0) links it to the previous one and counts in its time.
// Feed F (the G-code dialect's convention): inverse time F = 60 / duration (1/min, G93), or per
// minute F = 60 * |(delta of each machine axis)| / duration with degrees counted as mm (G94).
// The first point of the plan has duration 0 and F 0 (a rapid positioning move); a move without
// motion has duration 0 and keeps the previous F.
// Clearance (with a mandrel mesh): every dense eye point's distance to the surface its circuit is
// wound on (the mesh, or on a layup the layer in work: Motion::clearance_on_layers); below the
// required clearance minus chord_tolerance (a robot's true-distance eye: below the clearance) it is
// an error naming the point.
// Monotone axes (machine.monotone_axes, export/machine/monotone_axes.h): per circuit, A monotone
// and X monotone between its turning points; the eye is then recomputed from the axes (lathe4:
// first each eye whose A or X would go back is slid outward along its own fibre tangent, from the
// previous circuit's last state too where the circuit goes on from it: export/machine/
// monotone_by_payout.h; the fit then changes nothing there). Reversals: a
// reversal of an axis is a sign change between consecutive non-zero moves of its resampled values;
// a pass is a CircuitSegment of kind Pass.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "export/machine/eye_envelope.h"
#include "export/machine/feed_plan.h"
#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"
#include "planner/job/machine_options.h"
#include "planner/plan/plan.h"

namespace windplan {

/// A robot's true-distance eye is planned this many machine.chord_tolerance beyond
/// envelope.clearance (see the header comment).
constexpr double kRobotEyeChords = 2.0;

/// The spindle axis with a fixed angular reference (see the header comment).
struct AxisFrame {
  Vec3 origin = Vec3::Zero();
  Vec3 d = Vec3::UnitZ();
  Vec3 u = Vec3::UnitX();
  Vec3 v = Vec3::UnitY();
  double axial(const Vec3& p) const { return (p - origin).dot(d); }
  double radius(const Vec3& p) const {
    const Vec3 q = p - origin;
    return (q - q.dot(d) * d).norm();
  }
  /// Angle about d in (-pi, pi] (radians); 0 on the axis.
  double angle(const Vec3& p) const;
};

AxisFrame make_axis_frame(const SpindleAxis& axis);

struct EyeSolution {
  Vec3 eye = Vec3::Zero();
  double free_length = 0.0;  ///< mm
  int iterations = 0;
};

/// Solves the payout eye of point p with unit tangent t.
/// \throw InputError when p is on or outside the envelope (envelope inside the mandrel) or the
///        tangent never leaves it (parallel to the axis); `where` names the point in the message.
EyeSolution solve_payout_eye(const AxisFrame& frame, const Envelope& env, const Vec3& p,
                             const Vec3& t, const std::string& where = "");

/// The machine's state at one resampled point of the plan.
struct MachineState {
  int circuit = 0;        ///< Circuit::index
  int ordinal = 0;        ///< position of the circuit in WindingPlan::circuits
  int index = 0;          ///< index into the circuit's dense points
  double t_s = 0.0;       ///< s since the first point
  double duration = 0.0;  ///< s, of the move into this point
  double a_deg = 0.0, x_mm = 0.0, y_mm = 0.0, b_deg = 0.0;
  double feed = 0.0;               ///< F in the dialect's convention
  Vec3 position = Vec3::Zero();    ///< fibre point (mandrel frame)
  Vec3 eye = Vec3::Zero();         ///< payout eye (mandrel frame)
  Vec3 direction = Vec3::UnitZ();  ///< unit fibre direction at the eye (mandrel frame)
  double free_length = 0.0;        ///< mm
  double paid_out = 0.0;        ///< mm of fibre through the eye: laid length so far + free length
  Vec3 radial = Vec3::UnitX();  ///< unit radial direction of the eye (robot pose; mandrel frame)
};

/// Min and max of one quantity.
struct Range {
  double min = 0.0, max = 0.0;
};

struct Motion {
  std::vector<MachineState> states;  ///< resampled points of all circuits, in order
  bool inverse_time = false;         ///< F convention: true G93 (1/min), false G94 (units/min)
  double wind_time = 0.0;            ///< s, final t_s
  int dense_points = 0;
  double max_chord_deviation = 0.0;  ///< mm (fibre and eye polylines)
  Range a, x, y, b, free_length;     ///< deg, mm, mm, deg, mm
  int max_eye_iterations = 0;
  /// Dense points whose free fibre to a robot's true-distance eye passes inside the mandrel
  /// (export/machine/clearance_eye.h); -1 for envelopes (not measured).
  int fibre_into_mandrel = -1;
  /// The plan's layers (WindingPlan::layers; empty for a one-layer job): the G-code comments
  /// each layer and pauses between layers (export/program/gcode.h).
  std::vector<LayerSummary> layers;

  std::string envelope;  ///< the eye envelope of the machine kind, in words

  /// Clearance: the smallest distance of a dense eye point to the surface its circuit is wound
  /// on (the mandrel mesh, or on a layup the layer in work; NaN: no mesh given), the clearance
  /// required (mm) and where the minimum is.
  double min_clearance = std::nan("");
  double required_clearance = 0.0;
  int min_clearance_circuit = -1, min_clearance_index = -1;
  /// True when some circuit's clearance was measured on a surface other than the mandrel (a
  /// layup's layer in work, compute_motion's circuit_surfaces): min_clearance is then not an
  /// eye-mandrel distance.
  bool clearance_on_layers = false;

  /// Reversals of the carriage X and the spindle A (see the header comment).
  int carriage_reversals = 0;
  int max_carriage_reversals_per_circuit = 0;
  /// Carriage reversals whose fibre point is in the middle half (by arc length) of a pass.
  int mid_pass_carriage_reversals = 0;
  int spindle_reversals = 0;
  int spindle_reversals_in_passes = 0;  ///< at a point strictly inside a pass
  double max_tangent_change = 0.0;      ///< deg, largest change of the smoothed vs plan tangent
  double max_monotone_change_x = 0.0;   ///< mm, largest change of X by monotone_axes
  double max_monotone_change_a = 0.0;   ///< deg, largest change of A by monotone_axes
  /// lathe4: eyes slid outward along their fibre tangent so that A and X do not go back
  /// (export/machine/monotone_by_payout.h), and the largest extra free length given (mm).
  int payout_slid = 0;
  double max_payout_slide = 0.0;

  AxisLimitCheck limits;             ///< the feed plan measured against the axis limits
  std::vector<double> circuit_time;  ///< s per circuit (in order), the link move included
};

/// True when the G-code feed convention is inverse time (G93).
bool uses_inverse_time(const GcodeOptions& g);

/// The feed limits of the machine's axes, in the order A, X, Y, B.
std::array<FeedAxis, 4> feed_axes(const MachineOptions& opts);
/// Number of axes the machine drives (lathe2: 2, A and X; others 4).
int driven_axes(const MachineOptions& opts);

/// Computes eye, axes, times and feeds of a plan. Circuits with no points are skipped.
/// \param mandrel the mandrel mesh for the clearance check (nullptr: not checked)
/// \param circuit_surfaces per circuit of plan.circuits, the mesh of the surface it was wound on
///        (a layup: planner/plan_layup.h layup_circuit_surfaces, as export/program/replay.h takes
///        it); null, missing entries or an empty list: the mandrel. A robot's true-distance eye
///        (and its clearance check) is measured from the circuit's own surface, the layer in
///        work; lathe4 (and a robot without a mesh) takes the clearance envelope of that surface
///        and checks the clearance on it; lathe2 takes the cylinder of that surface's largest
///        radius + the clearance (its explicit envelope.radius or profile: that one cylinder)
///        and checks the clearance on it.
/// \throw InputError for an envelope inside the mandrel, a tangent that never leaves the
///        envelope, an eye closer to the mandrel than the clearance, or a machine value outside
///        an axis's travel limits (naming the axis, the value and the point as circuit/index).
Motion compute_motion(const WindingPlan& plan, const MachineOptions& opts,
                      const Mesh* mandrel = nullptr,
                      const std::vector<const Mesh*>& circuit_surfaces = {});

}  // namespace windplan
