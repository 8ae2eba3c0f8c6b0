#pragma once
// Friction turnarounds on a shape of revolution: passes that turn around on the mandrel at an
// end whose radius is above the turnaround radius (a pipe or cone end, a station), held by
// friction instead of pins or a ring (winding.slippage > 0).
//
// Each such end gets a friction turnaround (planner/semi_geodesic.h): its apex (winding angle
// 90 deg) on the parallel half a band width in from the end, so the band stays on the wound
// region; from there the fibre runs back at the constant slippage lambda until r sin a falls to
// the pass's Clairaut constant c, where the geodesic pass takes over with the same angle. The
// pass is Clairaut's geodesic between the two joins (planner/clairaut_pass.h); at an end that
// narrows below c (a dome) it still turns around geodesically.
//
// The pattern. A circuit advances the mandrel by A = 2 Phi(c) + Theta_0 + Theta_1 (Phi the
// geodesic pass between the joins, Theta the turnarounds' turns). A lower lambda makes a longer
// turnaround that wraps more, so A grows as lambda falls (on a cylinder Theta / 2 =
// -ln(tan(a0/2)) / lambda against the geodesic's tan(a0) / R per mm it replaces). The pattern
// (K, p) closes when A = 2 pi (m + p / K) for a whole m; the pass's c is kept (the winding angle
// the job asked for) and lambda is lowered from winding.slippage to the largest value that
// closes it: the fibre never uses more friction than the job allows. lambda is searched down to
// winding.slippage / 4 (a grid in 1 / lambda, then bisection); the turnarounds must fit in the
// wound region at that lambda. Candidates (K, p) are tried in the order of
// planner/winding_pattern.h (full nominal cover first, fewest circuits), or the job's own.
// Units: mm, radians unless a field says deg.
#include <array>
#include <string>
#include <vector>

#include "geometry/mesh.h"
#include "planner/clairaut_pass.h"
#include "planner/plan.h"
#include "planner/semi_geodesic.h"
#include "planner/winding_options.h"
#include "planner/winding_pattern.h"

namespace windplan {

struct FrictionWinding {
  std::array<bool, 2> friction_end = {false, false};  ///< per end: a friction turnaround
  std::array<FrictionTurnaround, 2> turnarounds;      ///< valid where friction_end
  ClairautPass pass;         ///< the geodesic pass between the joins (or geodesic turnarounds)
  PatternCandidate pattern;  ///< dwell 0, advance 2 Phi + Theta_0 + Theta_1
  double slippage = 0.0;     ///< lambda used at every turnaround point (<= bound)
  double bound = 0.0;        ///< winding.slippage
};

/// True when the job asks for friction turnarounds and the problem has an end that would dwell.
bool wants_friction_turnarounds(const PatternProblem& problem, const WindingOptions& options);

/// Turnarounds, pass and closing pattern (see the header comment).
/// \throw ConfigError naming winding.slippage where friction cannot turn the fibre around at an
///        end (the end widens too steeply for the bound) or the turnarounds do not fit in the
///        wound region (the message gives the length they need and the region's), and naming
///        winding.pattern when no lambda in [bound / 4, bound] closes the job's (K, p).
FrictionWinding plan_friction_winding(const PatternProblem& problem, const WindingOptions& options);

/// The figures of a plan's friction turnarounds measured on its circuits (segments in the order
/// revolution_circuits lays them: out pass, far turnaround, return pass, start turnaround; a
/// turnaround only at a friction end): per end and for the passes, the largest measured
/// |k_g / k_n| and the fibre length.
FrictionFigures friction_figures(const FrictionWinding& winding,
                                 const std::vector<Circuit>& circuits, double mu);

}  // namespace windplan
