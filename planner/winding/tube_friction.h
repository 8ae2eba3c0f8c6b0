#pragma once
// Friction (semi-geodesic) winding of a tube that is no shape of revolution, on a TubeSurface
// (planner/winding/tube_surface.h: a bent tube or elbow's closed forms in
// planner/winding/tube_centre_line.h, or the smooth fit of any mesh, CAD or oval tube in
// planner/winding/mesh_tube_surface.h; formulas below for the circular tube): a layer at a constant
// winding angle a0 to the centre line (winding.angle, or the angle whose passes make
// winding.turns: tube_angle_for_turns), held by friction where the bend asks for it, turning
// around by friction inside the wound region.
//
// The fibre, state (s, theta, a) integrated in its length l (classical RK4, 1 mm steps, events
// located by bisection on the last step):
//   ds/dl = cos a / h,   dtheta/dl = sin a / r,
//   passes:       da/dl = 0                       (k_g = -geodesic_turn: friction holds a0),
//   turnarounds:  da/dl = geodesic_turn + sigma lambda k_n   (|k_g / k_n| = lambda exactly).
// A constant angle needs |k_g / k_n| = |h_theta cos a0| / (h r k_n) (constant_angle_slippage; on a
// torus the closed form of the header comment there): 0 on straight pieces, at most 0.179 at 55
// deg on a bend of 5 tube radii, 0.328 on one of 3. The planner refuses (ConfigError naming
// winding.angle and the slippage it would need) before tracing anything when that exceeds
// winding.slippage, or where k_n <= 0 (the fibre would bridge the inside of the bend).
//
// Turnarounds: the apex (a = pi / 2, the fibre's extreme station) half a band width inside each
// end of the wound region, so the band stays on it; the fibre never runs along the region's edge.
// sigma = +1 at the far end (a rises from a0 through pi / 2 to pi - a0), -1 at the start end. On a
// straight leg a turnaround half takes r (1 / sin a0 - 1) / lambda of centre line and turns the
// section by -ln(tan(a0 / 2)) / lambda (planner/winding/semi_geodesic.h's closed forms); where the
// pass leaves for it is found by shooting (the apex lands on its station to 1e-6 mm).
//
// The pattern: each circuit runs apex to apex (start end, far end, start end) and the next one
// starts where it ended, so the fibre is one continuous curve. In a bend a circuit's advance in
// theta depends on where it enters, so the circuits are no copies of one another. All run at
// lambda = winding.slippage (the shortest turnarounds; a lower lambda is no help: in a bend a
// turnaround needs at least the constant angle's demand). The advance A = 2 pi (m + p / K) is
// chosen a little below the least advance of a circuit (sampled at 48 entry angles), and circuit
// k, entering at theta_k = k A, has its far apex moved inward by the delta_k (>= 0, found by
// regula falsi) at which it advances by exactly A: the starts are spread exactly evenly,
// p k / K of a turn, and the chain closes after K circuits (theta_K = K A = 2 pi (K m + p)).
// p: winding's skip, or the largest advance's p coprime to K. Where the section is no circle
// (TubeSurface::even_is_theta false) advances are measured in the even angle (the fraction of
// the loop's length) of the outgoing pass at mid-region, so those passes lie evenly along the
// loop; the return passes follow the far turnarounds, which an oval spreads unevenly.
// Pins (winding.pins: {count N, diameter d, offset x}): a ring of N pins on the section circle
// at x (default B / 2 + d) inside each end instead of friction turnarounds. The passes run at a0
// between the pin circles and dwell along them (Turnaround segments, held by the pins; the pins'
// diameter is not in the path, which is laid on the circle through their feet). The start dwell
// is one pin pitch 2 pi / N (so it wraps at least one pin); the far dwell of circuit k (at least
// a pitch) is what makes it advance by exactly A, the least 2 pi q / K above every circuit's
// advance with one pitch of dwell. Pins that do not fit (2 N d > 2 pi r: each needs its own
// diameter of gap) or pin circles off the tube or past each other are refused.
// K: winding.circuits, or auto: ceil(2 pi r cos a0 / B), the nominal full cover of a straight
// tube.
// Units: mm, radians unless a field says deg.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"
#include "planner/plan/plan.h"
#include "planner/winding/tube_centre_line.h"
#include "planner/winding/tube_surface.h"
#include "planner/winding/winding_options.h"

namespace windplan {

struct TubeFrictionSummary {
  bool closed = false;      ///< the chain of circuits closes (theta_K - theta_0 = 2 pi n)
  int evaluations = 0;      ///< circuits traced to choose the advance and the apex moves
  std::string termination;  ///< one line: how lambda was chosen
  std::string brief_report() const;
};

struct TubeFrictionWinding {
  std::vector<Circuit> circuits;    ///< apex to apex, segments Pass (split at the apexes)
  double angle_deg = 0.0;           ///< a0 (deg from the centre line)
  double required = 0.0;            ///< max |k_g / k_n| the constant angle needs (closed form)
  double required_s = 0.0;          ///< station of it (mm)
  double required_theta_deg = 0.0;  ///< its angle from the outside of the bend (deg)
  double slippage = 0.0;            ///< lambda of the turnarounds (= bound)
  double bound = 0.0;               ///< winding.slippage
  int K = 0, p = 0;                 ///< circuits and skip
  int n = 0;                        ///< whole turns of the chain: theta_K - theta_0 = 2 pi n
  std::array<double, 2> apex_s = {0.0, 0.0};  ///< apex stations before any move (mm)
  /// Least and most the far apex moved inward over the circuits (mm).
  std::array<double, 2> apex_moved = {0.0, 0.0};
  std::vector<double> starts_deg;  ///< theta of each circuit's start apex (deg, unwrapped)
  std::array<double, 2> turnaround_span = {0.0,
                                           0.0};  ///< centre line per end, both halves (mm, mean)
  double turnaround_length = 0.0;                 ///< fibre in turnarounds over all circuits (mm)
  double fibre_length = 0.0;                      ///< all circuits (mm)
  double turns_per_pass = 0.0;                    ///< mean theta turns per pass, apex to apex
  double spread_deg = 0.0;  ///< largest offset of a circuit's start from p k / K of a turn (deg)
  double projection_max = 0.0;  ///< largest move of a planned point onto the mesh (mm)
  int pins = 0;                 ///< pins per end ring (0: friction turnarounds)
  std::array<double, 2> dwell_deg = {0.0, 0.0};  ///< pins: least and most far dwell (deg)
  /// Max |k_g / k_n| measured on the laid points and its station (mm), filled by
  /// planner/winding/tube_friction_within_mu.h (0 when planned without it).
  double measured = 0.0, measured_s = 0.0;
  TubeFrictionSummary summary;
};

/// Mean turns of the section per pass (apex to apex, both apexes on their unmoved stations) of
/// circuits at angle a0 (rad) entering at 8 evenly spread angles.
/// \throw ConfigError when the turnarounds do not fit
double tube_turns_per_pass(const TubeSurface& line, double s0, double s1, double a0, double lambda,
                           double band_width);

/// The angle a0 (rad) whose passes make winding.turns: the highest such angle in [5, 80] deg
/// (turns are not monotone: at low angles the turnarounds wrap more), scanned down in 5 deg
/// steps and refined by regula falsi on tube_turns_per_pass at lambda = winding.slippage. The
/// closing apex moves then shorten passes a little: the plan reports the turns it made.
/// \throw ConfigError naming winding.turns with the range that can be made
double tube_angle_for_turns(const TubeSurface& line, double s0, double s1,
                            const WindingOptions& options);

/// The planned layer (see the header comment) on the stations [s0, s1] of `line`. Points are
/// placed on `annulus` (closest point; faces through face_map, empty: annulus faces) and
/// annotated (k_n, k_g, slippage) from their positions by planner/winding/fibre_metrics.h.
/// \throw ConfigError naming winding.angle when it and winding.turns are missing (or both given),
/// when holding it needs more
///        slippage than winding.slippage (with the figure and where) or the fibre would bridge;
///        naming winding.slippage when the turnarounds do not fit in [s0, s1] (with the lengths)
///        or a circuit would need its far apex more than a quarter of the region inward.
/// \param turnaround_slippage lambda of the friction turnarounds (NaN: winding.slippage; below
///        it when the laid turnarounds measure above mu, planner/winding/tube_friction_within_mu.h)
TubeFrictionWinding plan_tube_friction(const TubeSurface& line, double s0, double s1,
                                       const Mesh& annulus, const std::vector<int>& face_map,
                                       const SpindleAxis& axis, const WindingOptions& options,
                                       double turnaround_slippage = std::nan(""));

}  // namespace windplan
