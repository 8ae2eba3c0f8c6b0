#pragma once
// Equally spaced geodesic helices on the wound region (an annulus) and the continuous circuits
// they form.
//
// 1. Initial helices (trace_helix): in the conformal coordinates (h, theta) of planner/harmonic.h
//    the helix with N turns is the level set theta - hand 2 pi N h / (h1 - h0) = const (hand +1:
//    the out pass from loop 0 to loop 1, theta increasing; hand -1: the return pass from loop 1
//    to loop 0, theta still increasing, so the mandrel keeps turning one way), with [h0, h1] the
//    heights of its two ends ([0, 1] from loop to loop). It is traced face by face into a
//    SurfacePath: each crossed edge with lambda from linear interpolation of the level function
//    on that edge; it ends on the other boundary loop (an edge point) or, with an axial station,
//    where the axial coordinate reaches the station (a face point).
// 2. Refinement: each pass is refined by the geodesic core (geometry/geodesic.h) under the density
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
// design card; the geodesic refinement is Liu et al. (see geometry/geodesic.h).
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/axis.h"
#include "geometry/geodesic.h"
#include "geometry/mesh.h"
#include "geometry/surface_path.h"
#include "planner/harmonic.h"
#include "planner/winding_options.h"

namespace windplan {

/// A point on a boundary loop of the annulus, at lifted angle `theta` (radians).
SurfacePoint loop_point_at_theta(const Mesh& annulus, const HarmonicCoordinates& hc,
                                 const std::vector<int>& loop, double theta);

/// Where a traced helix stops and over which height span it makes its turns.
struct HelixTraceOptions {
  /// h1 - h0 (dimensionless, > 0): the turns are made over this span of the harmonic height,
  /// i.e. the level function is theta - hand 2 pi turns h / height_span. 1: loop to loop.
  double height_span = 1.0;
  /// Axial station (mm along `axis`) where the trace stops instead of at the boundary loop: the
  /// first point where the axial coordinate reaches it (from below on the way to loop 1, from
  /// above on the way to loop 0). NaN: the trace runs to the boundary loop.
  double stop_station = std::nan("");
  /// The spindle axis of stop_station (origin mm, unit direction).
  SpindleAxis axis;
};

/// Traces the level set of theta - hand 2 pi turns h / height_span through `start` until it
/// reaches the other boundary loop or options.stop_station.
/// \param start an edge point on a boundary edge (the trace runs away from that loop), or a point
///        inside the annulus (a face point or an edge point on an interior edge; hand +1 runs
///        towards loop 1, hand -1 towards loop 0)
/// \param turns N (turns, finite, > 0; need not be whole)
/// \return a SurfacePath from `start`; its end is an edge point on the boundary loop, or a face
///         point (barycentric in the last strip face) on the stop station
/// \throw InputError if start is a vertex or not a point of the mesh, turns not finite or <= 0,
///        hand not +-1 or height_span not > 0; TopologyError if the level set returns to the loop
///        it left, reaches a boundary loop before the stop station, or does not end (h not monotone
///        along it), naming the face.
SurfacePath trace_helix(const Mesh& annulus, const HarmonicCoordinates& hc,
                        const SurfacePoint& start, double turns, int hand,
                        const HelixTraceOptions& options = {});

/// A dwell arc along a boundary loop or a station circle, from `start` on by `dwell` radians of
/// theta (increasing).
struct LoopArc {
  std::vector<Vec3> points;  ///< start, loop vertices (or station crossings) passed, end
  std::vector<int> faces;    ///< per segment: the annulus face it lies in
  SurfacePoint end;          ///< at theta(start) + dwell: an edge point on the loop, or a face
                             ///< point on the station circle
  double length = 0.0;       ///< mm
};
/// The dwell arc along the boundary loop of `start` (an edge point on the loop).
LoopArc loop_arc(const Mesh& annulus, const HarmonicCoordinates& hc, const SurfacePoint& start,
                 double dwell);

/// A station circle: the closed section of the annulus by the plane normal to the spindle axis
/// at an axial station (a parallel on a shape of revolution), as the chain of its edge crossings
/// ordered so that theta increases. Segment i runs from crossings[i] to crossings[(i + 1) % n]
/// inside faces[i].
struct StationCircle {
  double station = 0.0;                 ///< mm along the spindle axis
  std::vector<SurfacePoint> crossings;  ///< edge points (halfedge, t) on the plane
  std::vector<Vec3> points;             ///< their positions (mm)
  std::vector<int> faces;               ///< per segment: the annulus face
  /// Lifted theta at crossings[i] (radians, non-decreasing; one lift continued along the chain);
  /// n + 1 values: theta.back() is crossings[0] again, theta.front() + 2 pi up to rounding.
  std::vector<double> theta;
  double height = 0.0;  ///< length-weighted mean of h along the circle (dimensionless)
  double length = 0.0;  ///< mm
};

/// The station circle at axial position `station` (mm): the section loop that goes around the
/// mandrel (the longest if several do), via plane_sections() of planner/cutlines.h.
/// \param key the job key for messages (e.g. "winding.start_station")
/// \throw ConfigError naming `key` when the plane's section has no loop around the mandrel.
StationCircle station_circle(const Mesh& annulus, const HarmonicCoordinates& hc,
                             const SpindleAxis& axis, double station, const std::string& key);

/// The dwell arc along `circle` from `start` (a point on the circle, to rounding: the nearest
/// segment is taken) on by `dwell` radians of theta. The end is a face point strictly inside its
/// segment (off the crossings and so off the mesh edges).
/// \throw TopologyError if start is farther than 1e-6 of the circle's length from it.
LoopArc station_arc(const Mesh& annulus, const StationCircle& circle, const SurfacePoint& start,
                    double dwell);

/// The open interval of axial stations (mm) strictly between the two boundary loops: (largest
/// axial coordinate on loops[0], smallest on loops[1]). Empty (lo >= hi) when they overlap.
std::array<double, 2> station_range(const Mesh& annulus,
                                    const std::array<std::vector<int>, 2>& loops,
                                    const SpindleAxis& axis);

/// \throw ConfigError naming `key` (winding.start_station / end_station) and the open range
///        (mm) when `station` is not strictly inside `range` (station_range()).
void check_station(const std::string& key, double station, const std::array<double, 2>& range);

/// Lifted theta and height at an edge point of the annulus (h in [0, 1], theta in radians).
std::array<double, 2> edge_point_coordinates(const Mesh& annulus, const HarmonicCoordinates& hc,
                                             int halfedge, double t);
/// The same for any surface point: edge points as edge_point_coordinates, face points in their
/// face's lift, vertices in the lift of one of their faces.
std::array<double, 2> surface_point_coordinates(const Mesh& annulus, const HarmonicCoordinates& hc,
                                                const SurfacePoint& p);

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
/// \throw ConfigError for invalid options, naming winding.start_station / winding.end_station
///        and the valid range (mm) for a station outside station_range() or whose plane does not
///        cut the wound region around the mandrel; as compute_harmonic_coordinates / trace_helix.
HelixPlan plan_helices(const Mesh& annulus, const std::array<std::vector<int>, 2>& loops,
                       const std::vector<double>& rho, const SpindleAxis& axis,
                       const WindingOptions& options = {}, const GeodesicOptions& geodesic = {});

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
