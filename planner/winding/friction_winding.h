#pragma once
// Friction-limited winding on a shape of revolution (winding.slippage > 0): passes that lean on
// friction where a geodesic cannot do what the job asks.
//
// Turnarounds by friction (planner/winding/semi_geodesic.h): the fibre's winding angle rises to 90
// deg at an apex and falls back at the constant slippage lambda until r sin a reaches the passes'
// Clairaut constant c, where Clairaut's geodesic pass (planner/winding/clairaut_pass.h) takes over
// with the same angle.
// - Pipe and cone ends, stations (an end at least as wide as c): the apex half a band width in
//   from the end, so the band stays on the wound region; no pins or ring.
// - Domes (a vessel): the apex on the parallel the job's turnaround names (winding.turnaround,
//   default that end's polar opening + B / 2, PatternProblem::apex_c), while c is what
//   winding.angle or winding.turns asks: friction on the dome lowers r sin a from the apex to a
//   c below it (a lower angle than the geodesic turning around there) or raises it to a c
//   above (a higher angle, more turns per pass). A dome whose apex is c turns around
//   geodesically. winding.turns is met by solving c for the turns of the whole pass
//   (turnarounds included) at lambda = winding.slippage.
// A friction transition on the cylinder (a vessel whose openings differ, with no angle or turns
// asked): each dome turns around geodesically on its own parallel c_0, c_1 and the pass joins
// them on the largest-radius part of the mandrel, where friction carries r sin a from c_0 to
// c_1 (on a cylinder of radius R over R |1 / sin a_0 - 1 / sin a_1| / lambda of axis),
// centred on it.
//
// The pattern. A circuit advances the mandrel by A = 2 (Phi + the friction parts' turns) (+ the
// turnarounds' Theta at pipe ends), and closes as (K, p) when A = 2 pi (m + p / K) for a whole m.
// lambda is lowered from winding.slippage (down to a quarter of it, or to what fills the
// cylinder for a transition) to the largest value that closes it: the fibre never uses more
// friction than the job allows, and a lower lambda makes a longer friction part that wraps
// more. When no lambda closes it, at lambda = winding.slippage c moves within
// winding.turnaround_window (the domes' turnarounds outward for a transition). Candidates
// (K, p) are tried in the order of planner/winding/winding_pattern.h (full nominal cover first,
// fewest circuits), or the job's own. Where friction cannot do it at the bound, the error names
// winding.slippage, what it reached or the length it needs, and the slippage that would do it.
// Units: mm, radians unless a field says deg.
#include <array>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "planner/plan/plan.h"
#include "planner/winding/clairaut_pass.h"
#include "planner/winding/semi_geodesic.h"
#include "planner/winding/winding_options.h"
#include "planner/winding/winding_pattern.h"

namespace windplan {

struct FrictionWinding {
  std::array<bool, 2> friction_end = {false, false};  ///< per end: a friction turnaround
  std::array<FrictionTurnaround, 2> turnarounds;      ///< valid where friction_end
  /// The pass between the joins: a geodesic, or with a transition geodesic - transition -
  /// geodesic (samples continuous in phi and length; `c` the start dome's).
  ClairautPass pass;
  bool transition = false;             ///< a friction transition on the passes
  FrictionTransition transition_path;  ///< valid where transition
  PatternCandidate pattern;            ///< dwell 0, advance 2 Phi + Theta_0 + Theta_1
  double requested_c = 0.0;  ///< the passes' c the job asks (winding.turns: solved here; mm)
  double slippage = 0.0;     ///< lambda used at every turnaround point (<= bound)
  double bound = 0.0;        ///< winding.slippage
};

/// True when winding.slippage > 0 and friction has something to do: an end that would dwell,
/// domes wound at a c other than their turnarounds', or domes whose turnarounds differ.
bool wants_friction_turnarounds(const PatternProblem& problem, const WindingOptions& options);

/// Turnarounds, pass and closing pattern (see the header comment).
/// \throw ConfigError naming winding.slippage where friction cannot turn the fibre around at an
///        end (the end widens too steeply for the bound, a dome too far from c), the friction
///        parts do not fit in the wound region (the message gives the length they need and the
///        region's) or winding.turns is out of reach (the range at the bound); each with the
///        slippage that would do it where one <= 1 does; naming winding.slippage when no lambda
///        closes the job's (K, p).
FrictionWinding plan_friction_winding(const PatternProblem& problem, const WindingOptions& options);

/// The figures of a plan's friction turnarounds measured on its circuits (segments in the order
/// revolution_circuits lays them: out pass, far turnaround, return pass, start turnaround; a
/// turnaround only at a friction end): per end and for the passes, the largest measured
/// |k_g / k_n| and the fibre length.
FrictionFigures friction_figures(const FrictionWinding& winding,
                                 const std::vector<Circuit>& circuits, double mu);

}  // namespace windplan
