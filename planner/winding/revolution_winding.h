#pragma once
// Helical winding on a shape of revolution: geodesic passes from Clairaut's integral on the
// wound region's own meridian (planner/winding/clairaut_pass.h), a closing pattern (planner/
// winding_pattern.h), and K circuits that are copies of circuit 0 turned by the pattern's
// advance, placed on the mesh by closest point.
//
// A circuit: the out pass from the start end to the far end (phi from 0 to Phi), the far end's
// turnaround, the return pass (phi from Phi + delta_1 on, still increasing: the mandrel turns
// one way), the start end's turnaround. On a dome the turnaround is the geodesic's own tangent
// point on the parallel r = c: the two passes meet there with no arc between them. At a dwell
// end (a pipe or cone end, a station) the fibre is held by pins or a ring while the mandrel
// turns by delta: a dwell arc along the end circle (CircuitSegment::Kind::Turnaround).
// Circuit k is circuit 0 turned by k times the advance, so whatever the mesh's own asymmetry the
// circuits differ only by the projection onto the mesh (its tessellation error); the planned
// points carry the projected positions, the interpolated vertex normals and the faces of the
// full mesh (face_map), annotated like build_circuits (planner/winding/fibre_metrics.h).
// Units: mm, radians.
#include <array>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"
#include "planner/plan/plan.h"
#include "planner/winding/clairaut_pass.h"
#include "planner/winding/friction_winding.h"
#include "planner/winding/winding_options.h"
#include "planner/winding/winding_pattern.h"

namespace windplan {

struct RevolutionWinding {
  /// false: the job's turns are beyond the geodesic turn limit between dwell ends
  /// (problem.why); nothing else is planned.
  bool planned = false;
  std::vector<Vec2> meridian;  ///< the wound meridian (clipped to the stations), start end first
  PatternProblem problem;
  PatternCandidate pattern;
  ClairautPass pass;  ///< the out pass of circuit 0 in meridian coordinates
  std::vector<Circuit> circuits;
  /// Per end: true where the passes turn around geodesically (no dwell arc).
  std::array<bool, 2> geodesic_end = {false, false};
  /// winding.slippage > 0 at a pipe or cone end: friction turnarounds instead of dwells
  /// (planner/winding/friction_winding.h); `pass` and `pattern` are then friction_plan's.
  bool friction = false;
  FrictionWinding friction_plan;
  /// The largest distance from a planned point (before projection) to the mesh (mm): the
  /// tessellation error the circuits carry.
  double projection_max = 0.0;
};

/// The largest fibre length between the planned points of a pass (mm): an eighth of the band,
/// within [0.25, 2].
double fibre_step(const WindingOptions& options);

/// The meridian clipped to the axial range [x0, x1] (NaN: no clip at that end), the end points
/// interpolated.
std::vector<Vec2> clip_meridian(const std::vector<Vec2>& meridian, double x0, double x1);

/// The wound meridian of a job: the annulus's meridian clipped to winding.start_station /
/// end_station. \throw ConfigError naming the station key and its range for a station outside
/// the wound region (check_station, planner/winding/helix.h); as annulus_meridian.
std::vector<Vec2> wound_meridian(const Mesh& annulus, const SpindleAxis& axis,
                                 const WindingOptions& options);

/// The circuits of a pattern on the annulus (see the header comment).
/// \param face_map annulus face -> full-mesh face (empty: keep annulus faces)
/// \param turnarounds per end, a friction turnaround's samples (phi from 0; planner/
///        friction_winding.h) laid as a Pass segment instead of that end's dwell arc; null or
///        empty: the pattern's dwell
std::vector<Circuit> revolution_circuits(
    const Mesh& annulus, const std::vector<int>& face_map, const SpindleAxis& axis,
    const ClairautPass& pass, const PatternCandidate& pattern, const WindingOptions& options,
    double* projection_max = nullptr,
    const std::array<std::vector<PassSample>, 2>* turnarounds = nullptr);

/// Meridian, pattern and circuits of a job's winding on a shape of revolution.
/// \throw ConfigError naming the winding key for a turnaround, angle, turns or pattern that no
///        geodesic winding on this mandrel can give (planner/winding/winding_pattern.h);
///        TopologyError when the annulus has no meridian about the axis.
RevolutionWinding plan_revolution_winding(const Mesh& annulus, const std::vector<int>& face_map,
                                          const SpindleAxis& axis, const WindingOptions& options);

}  // namespace windplan
