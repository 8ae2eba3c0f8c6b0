#pragma once
// Winding patterns on a shape of revolution: which circuits close, and where they turn around.
//
// A circuit is an out pass, the turnaround at the far end, a return pass and the turnaround at
// the start. With geodesic passes (planner/winding/clairaut_pass.h) each pass turns the mandrel by
// Phi(c), c the Clairaut constant; a dwell at an end held by pins or a ring adds its own angle
// delta. So a circuit advances the mandrel by 2 Phi(c) + delta_0 + delta_1, and K circuits close
// into one continuous pattern when that advance is 2 pi p / K modulo 2 pi with p coprime to K
// (p, the "skip", is how many band positions each circuit moves on; K = 1 needs p = 0).
//
// Ends: an end where the wound region narrows below c (a dome towards its polar opening) is a
// geodesic turnaround: no dwell, the pass turns around by itself on the parallel r = c. An end
// whose radius is at least c (a pipe or cone end, a station) is a dwell end. Then:
// - with a dwell end the dwell angles close any (K, p) exactly and c is what the job asks;
// - with geodesic turnarounds at both ends (a vessel) only c can close the pattern: for each
//   (K, p) the turnaround radius nearest the requested one where 2 Phi(c) = 2 pi (m + p / K)
//   for a whole m, searched in a window of radii (WindingOptions::turnaround_window). The fibre
//   stays a geodesic; the turnaround moves by a fraction of a band.
// Coverage: on the largest parallel (radius R, winding angle a = asin(c / R)) one pass family
// lays K bands of width B, each B / cos(a) along the circumference, so a family needs
// K >= 2 pi R cos(a) / B; nominal cover factor K B / (2 pi R cos a), nominal overlap between
// neighbours B - 2 pi R cos(a) / K (mm across the band). These nominal figures only rank the
// candidates: the plan's coverage is measured on its laid bands (planner/winding/coverage.h).
// Units: mm, radians unless a field says deg.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "planner/winding/winding_options.h"

namespace windplan {

/// The geometry a pattern is chosen on: the wound meridian ((axial, radius) from the start end)
/// and what the job asks for.
struct PatternProblem {
  std::vector<Vec2> meridian;
  double band_width = 10.0;                       ///< B (mm)
  double largest_radius = 0.0;                    ///< R (mm), the largest radius of the meridian
  std::array<double, 2> end_radius = {0.0, 0.0};  ///< radius at each end of the meridian (mm)
  /// true: both ends narrow below the turnaround (a vessel's domes): geodesic turnarounds.
  bool domes = false;
  double requested_c = 0.0;       ///< the Clairaut constant the job asks for (mm)
  std::string requested_by;       ///< the key that asked: "winding.turnaround", ".angle", ".turns"
  double c_lo = 0.0, c_hi = 0.0;  ///< window of turnaround radii searched (mm)
  /// false: between dwell ends the job asks for more turns than a geodesic can make (`why`
  /// says how many it can); the passes cannot be Clairaut geodesics.
  bool reachable = true;
  std::string why;
  /// Both ends narrow (a vessel's domes), whatever c is asked.
  bool narrows = false;
  /// With winding.slippage > 0 on a vessel: per dome, the parallel its passes turn around on
  /// (winding.turnaround, default that end's opening + B / 2): the passes' c on the cylinder
  /// (requested_c) reaches it by friction on the dome (planner/winding/friction_winding.h). NaN
  /// otherwise.
  std::array<double, 2> apex_c = {std::nan(""), std::nan("")};
  /// winding.turns with winding.slippage > 0 on a vessel: the turns per pass the friction plan
  /// solves its c for (requested_c is then only a start); NaN otherwise.
  double turns = std::nan("");
};

/// Sets up the problem from the meridian and the job's winding options: the requested c from
/// winding.turnaround (default on domes: the larger end radius + B / 2), winding.angle (on the
/// largest parallel) or winding.turns (Phi(c) = 2 pi N), and its window.
/// \throw ConfigError naming the key for a turnaround below the opening or at/above the largest
///        radius, an angle or turns no geodesic can make on this mandrel.
PatternProblem pattern_problem(const std::vector<Vec2>& meridian, const WindingOptions& options);

/// One closing pattern.
struct PatternCandidate {
  int circuits = 0;                          ///< K
  int skip = 0;                              ///< p, coprime to K
  double c = 0.0;                            ///< turnaround radius / Clairaut constant (mm)
  double moved = 0.0;                        ///< c - requested c (mm)
  double angle_deg = 0.0;                    ///< winding angle on the largest parallel (deg)
  double turns_per_pass = 0.0;               ///< Phi / 2 pi
  std::array<double, 2> dwell = {0.0, 0.0};  ///< dwell at the start and far end (radians)
  double advance = 0.0;                      ///< per circuit: 2 Phi + dwells (radians, unreduced)
  double cover_factor = 0.0;                 ///< nominal, per pass family
  double overlap = 0.0;                      ///< nominal, mm across the band (< 0: a gap)

  bool full_cover() const { return overlap >= 0.0; }
  /// "K=37, p=5"
  std::string name() const;
};

/// The candidate patterns with K near the coverage count (from K_cov - 2 to K_cov + 3, K_cov
/// the fewest circuits with full nominal coverage at the requested c) and every p coprime to K,
/// each with its own c (domes) or dwells (dwell ends); on domes a (K, p) with no closing c in
/// the window is left out. Sorted: full cover first, then K, then |moved|, then p.
std::vector<PatternCandidate> pattern_candidates(const PatternProblem& problem);

/// The pattern a job winds: winding.circuits / winding.skip when given, else `auto` (the first
/// candidate: full nominal cover with the fewest circuits, nearest the requested turnaround).
/// \throw ConfigError naming winding.pattern (or winding.circuits / winding.skip) for K and p
///        that are not coprime, or a pattern that no turnaround in the window closes (the
///        message gives the nearest c that would).
PatternCandidate choose_pattern(const PatternProblem& problem, const WindingOptions& options);

/// The pattern for a given (K, p) at a fixed c when at least one end dwells; on domes the c in
/// [lo, hi] nearest `near` that closes it (NaN c when none).
PatternCandidate pattern_for(const PatternProblem& problem, int circuits, int skip, double lo,
                             double hi, double near);

}  // namespace windplan
