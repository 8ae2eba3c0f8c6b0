#pragma once
// Equally spaced geodesic helices on the wound region (an annulus) and the continuous circuits
// they form.
//
// 1. Initial helices (trace_helix): in the conformal coordinates (h, theta) of planner/harmonic.h
//    the helix with N turns is the level set theta - hand 2 pi N h = const (hand +1: the out pass
//    from loop 0 to loop 1, theta increasing; hand -1: the return pass from loop 1 to loop 0,
//    theta still increasing, so the mandrel keeps turning one way). It is traced face by face into
//    a SurfacePath: each crossed edge with lambda from linear interpolation of the level function
//    on that edge; start and end are edge points on the boundary loops.
// 2. Refinement: each pass is refined by the geodesic core (geometry/geodesic.h) under the density
//    rho (rho = (g / mean g)^(-beta), g the girth; empty = Euclidean), ends held fixed.
// 3. Circuits: a circuit is out pass, turnaround at loop 1, return pass, turnaround at loop 0. A
//    turnaround is a dwell arc along the boundary loop (polar opening or tube end) while the
//    mandrel advances by `dwell` radians of theta; both dwells are pi + pi p / K so that each
//    circuit advances the start by the pattern's 2 pi p / K (p coprime to K; p = 1) and the K
//    circuits close into one continuous fibre.
// Paper: the density idea (equally spaced helices as geodesics of rho = 1/g) follows the windplan
// design card; the geodesic refinement is Liu et al. (see geometry/geodesic.h).
#include <array>
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

/// Traces the level set of theta - hand 2 pi turns h through `start` (an edge point on a boundary
/// edge) until it reaches the other boundary loop.
/// \throw InputError if start is not on a boundary edge, turns < 1 or hand not +-1;
///        TopologyError if the level set returns to its start loop or does not end (h not
///        monotone along it), naming the face.
SurfacePath trace_helix(const Mesh& annulus, const HarmonicCoordinates& hc,
                        const SurfacePoint& start, int turns, int hand);

/// A dwell arc along a boundary loop, from `start` (edge point on the loop) on by `dwell`
/// radians of theta (increasing).
struct LoopArc {
  std::vector<Vec3> points;  ///< start, loop vertices passed, end
  std::vector<int> faces;    ///< per segment: the annulus face of the boundary edge
  SurfacePoint end;          ///< edge point at theta(start) + dwell
  double length = 0.0;       ///< mm
};
LoopArc loop_arc(const Mesh& annulus, const HarmonicCoordinates& hc, const SurfacePoint& start,
                 double dwell);

/// Lifted theta and height at an edge point of the annulus (h in [0, 1], theta in radians).
std::array<double, 2> edge_point_coordinates(const Mesh& annulus, const HarmonicCoordinates& hc,
                                             int halfedge, double t);

struct HelixPass {
  int circuit = 0;
  int hand = 1;         ///< +1 out pass (loop 0 -> 1), -1 return pass (loop 1 -> 0)
  SurfacePath initial;  ///< the traced level set
  SurfacePath path;     ///< refined
  GeodesicSummary summary;
};

struct Turnaround {
  int circuit = 0;
  int loop = 0;        ///< 0: start loop, 1: end loop
  double dwell = 0.0;  ///< radians of theta
  LoopArc arc;
};

struct HelixPlanSummary {
  int circuits = 0;      ///< K used
  int pattern_step = 1;  ///< p: circuit k starts at theta_0 + 2 pi p k / K
  bool circuits_auto = false;
  double auto_angle_deg = 0;  ///< winding angle at the largest radius (for K auto)
  double auto_radius = 0;     ///< mm
  int not_converged = 0;      ///< passes whose refinement did not converge
  double trace_ms = 0, refine_ms = 0, harmonic_ms = 0;
  std::vector<std::string> warnings;
};

/// K circuits with two passes and two turnarounds each, in winding order.
struct HelixPlan {
  HarmonicCoordinates coords;
  std::vector<HelixPass> passes;        ///< 2 per circuit: out, return
  std::vector<Turnaround> turnarounds;  ///< 2 per circuit: at loop 1 (after out), at loop 0
  HelixPlanSummary summary;
};

/// Plans the helices of a winding surface.
/// \param annulus the winding surface; loops its two boundary loops (start loop first)
/// \param rho per annulus face density (> 0), or empty for the Euclidean metric
/// \param axis spindle axis (for K auto: the winding angle at the largest radius)
/// \throw ConfigError for invalid options; as compute_harmonic_coordinates / trace_helix.
HelixPlan plan_helices(const Mesh& annulus, const std::array<std::vector<int>, 2>& loops,
                       const std::vector<double>& rho, const SpindleAxis& axis,
                       const WindingOptions& options = {}, const GeodesicOptions& geodesic = {});

/// The density of a girth field: rho_f = (g_f / mean g)^(-beta) (area-weighted mean).
/// \throw InputError for a non-positive girth or a size mismatch.
std::vector<double> density_from_girth(const Mesh& annulus, const std::vector<double>& face_girth,
                                       double beta);

}  // namespace windplan
