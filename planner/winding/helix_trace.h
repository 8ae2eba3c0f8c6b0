#pragma once
// Tracing on the wound region (an annulus) in the conformal coordinates (h, theta) of
// planner/winding/harmonic.h: the initial helices of plan_helices (planner/winding/helix.h, step 1
// of its header), arcs along the boundary loops and along station circles (the turnarounds),
// and the coordinates of surface points.
#include <array>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/mesh/surface_path.h"
#include "geometry/region/axis.h"
#include "planner/winding/harmonic.h"

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
/// mandrel (the longest if several do), via plane_sections() of planner/cutlines/cutlines.h.
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

}  // namespace windplan
