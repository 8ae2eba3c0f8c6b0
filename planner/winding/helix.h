#pragma once
// Equally spaced geodesic helices on the wound region (an annulus) and the continuous circuits
// they form.
//
// 1. Initial helices (trace_helix): in the conformal coordinates (h, theta) of
// planner/winding/harmonic.h
//    the helix with N turns is the level set theta - hand 2 pi N h / (h1 - h0) = const (hand +1:
//    the out pass from loop 0 to loop 1, theta increasing; hand -1: the return pass from loop 1
//    to loop 0, theta still increasing, so the mandrel keeps turning one way), with [h0, h1] the
//    heights of its two ends ([0, 1] from loop to loop). It is traced face by face into a
//    SurfacePath: each crossed edge with lambda from linear interpolation of the level function
//    on that edge; it ends on the other boundary loop (an edge point) or, with an axial station,
//    where the axial coordinate reaches the station (a face point).
// 2. Refinement: each pass is refined by the geodesic core (geometry/geodesic/geodesic.h) under the
// density
//    rho (rho = (g / mean g)^(-beta), g the girth; empty = Euclidean), ends held fixed.
// 3. Circuits: a circuit is out pass, turnaround at the end, return pass, turnaround at the start.
//    A turnaround is a dwell arc along the boundary loop (polar opening or tube end), or along
//    the station circle when the job gives `start_station` / `end_station` (the section of the
//    wound region by the plane normal to the spindle axis there: a parallel on a shape of
//    revolution), while the mandrel advances by `dwell` radians of theta. Each pass advances
//    theta by 2 pi N, so a circuit advances it by 4 pi N + 2 dwell, which must be the pattern's
//    2 pi p / K modulo 2 pi (p coprime to K; p = 1) for the K circuits to close into one
//    continuous fibre: both dwells are pi + pi p / K + c with c = -2 pi N reduced modulo pi into
//    [-pi/2, pi/2] (c = 0 for whole and half turns, N need not be whole). With stations, the N
//    turns of a pass are made between the two stations (h0, h1 the mean heights of their
//    circles); h varies slightly along a station circle, so the dwell at the start end is
//    corrected to start circuit k exactly 2 pi p k / K after circuit 0.
// Paper: the density idea (equally spaced helices as geodesics of rho = 1/g) follows the windplan
// design card; the geodesic refinement is Liu et al. (see geometry/geodesic/geodesic.h).
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/geodesic/geodesic.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/surface_path.h"
#include "geometry/region/axis.h"
#include "planner/winding/harmonic.h"
#include "planner/winding/helix_trace.h"
#include "planner/winding/winding_options.h"

namespace windplan {

struct HelixPass {
  int circuit = 0;
  int hand = 1;  ///< +1 out pass (start -> end: loop 0 or start station -> loop 1 or end station),
                 ///< -1 return pass
  SurfacePath initial;  ///< the traced level set
  SurfacePath path;     ///< refined
  GeodesicSummary summary;
};

struct Turnaround {
  int circuit = 0;
  int loop = 0;  ///< 0: at the start (loop 0 or start station), 1: at the end
  /// Radians of theta: turnaround_dwell(N, K, p) (pi + pi p / K for whole and half turns);
  /// corrected at the start with stations.
  double dwell = 0.0;
  /// mm: the station circle the arc runs along; NaN: the boundary loop.
  double station = std::nan("");
  LoopArc arc;

  bool at_station() const { return std::isfinite(station); }
};

struct HelixPlanSummary {
  int circuits = 0;      ///< K used
  int pattern_step = 1;  ///< p: circuit k starts at theta_0 + 2 pi p k / K
  bool circuits_auto = false;
  double auto_angle_deg = 0;  ///< winding angle at the largest radius (for K auto)
  double auto_radius = 0;     ///< mm
  int not_converged = 0;      ///< passes whose refinement did not converge
  /// h at the two ends of the passes: 0 / 1 at the loops, the station circle's mean height at a
  /// station (dimensionless); the N turns of a pass are made over heights[1] - heights[0].
  std::array<double, 2> heights = {0.0, 1.0};
  double trace_ms = 0, refine_ms = 0, harmonic_ms = 0;
  std::vector<std::string> warnings;
};

/// K circuits with two passes and two turnarounds each, in winding order.
struct HelixPlan {
  HarmonicCoordinates coords;
  std::vector<HelixPass> passes;        ///< 2 per circuit: out, return
  std::vector<Turnaround> turnarounds;  ///< 2 per circuit: at the end (after out), at the start
  HelixPlanSummary summary;
};

/// Plans the helices of a winding surface.
/// \param annulus the winding surface; loops its two boundary loops (start loop first)
/// \param rho per annulus face density (> 0), or empty for the Euclidean metric
/// \param axis spindle axis (for K auto: the winding angle at the largest radius; the stations)
/// \param options with start_station / end_station the passes run between those axial stations
///        (mm) and turn around on their circles; a missing one is the boundary loop
/// A pass whose refinement comes back with non-finite crossings (seen from the core's funnel
/// start) is refined again from its traced level set without it; if that fails too the level set
/// is kept and the pass counts as not converged. Both are named in summary.warnings.
/// \param refine_passes false: no pass is refined, each keeps its traced level set (path = initial;
///        K auto from the traced first pass), for trials that only measure where the traced
///        helices lie (the circuits and turnarounds do not depend on the refinement)
/// \throw ConfigError for invalid options, naming winding.start_station / winding.end_station
///        and the valid range (mm) for a station outside station_range() or whose plane does not
///        cut the wound region around the mandrel; as compute_harmonic_coordinates / trace_helix.
HelixPlan plan_helices(const Mesh& annulus, const std::array<std::vector<int>, 2>& loops,
                       const std::vector<double>& rho, const SpindleAxis& axis,
                       const WindingOptions& options = {}, const GeodesicOptions& geodesic = {},
                       bool refine_passes = true);

/// The dwell (radians of theta, in [pi/2, 3 pi/2] + pi p / K) of both turnarounds of a circuit
/// whose passes make `turns` turns each, so that each circuit advances theta by 2 pi p / K modulo
/// 2 pi: pi + pi p / K + c with c = -2 pi N reduced modulo pi into [-pi/2, pi/2]. Exactly
/// pi + pi p / K when N is a whole or half number.
double turnaround_dwell(double turns, int circuits, int pattern_step);

/// The density of a girth field: rho_f = (g_f / mean g)^(-beta) (area-weighted mean).
/// \throw InputError for a non-positive girth or a size mismatch.
std::vector<double> density_from_girth(const Mesh& annulus, const std::vector<double>& face_girth,
                                       double beta);

}  // namespace windplan
