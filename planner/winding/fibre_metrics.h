#pragma once
// Fibre-path differential geometry and the figures of a plan: turn spacing along meridians,
// coverage and winding pattern, fibre stability (slippage against friction, bridging).
//
// Curvatures are estimated robustly from the polyline and the mesh normals: the tangent at arc
// length s is the unit chord P(s + w/2) - P(s - w/2) projected onto the tangent plane, and
// t' = (T(s + w/2) - T(s - w/2)) / w, i.e. smoothed finite differences over a window w of about a
// band width (WindingOptions::curvature_window, default band_width). Then k_n = -t' . n (n the
// outward normal, so k_n > 0 where the fibre presses on a convex mandrel) and
// k_g = t' . (n x t) with n the interpolated (angle-weighted) vertex normal; slippage is
// |k_g / k_n|. The window filters the tessellation's kinks (edge-crossing scale); curvature
// radii well above w are resolved to O(w^2 / radius^2).
//
// Spacing: the out passes (one helix family) are cut with `meridians` lines of constant conformal
// angle theta (planner/winding/harmonic.h); along each meridian the crossings are ordered by height
// and the chord between successive ones is the turn spacing (mm), also divided by the local girth
// (the girth field's face value, or 2 pi r when no field is given). spacing_cv is the coefficient
// of variation of the girth-normalised spacing (0 for equally spaced helices, whatever the radius).
//
// Coverage (shapes of revolution): at the largest radius R with winding angle a there, full
// coverage needs ceil(2 pi R cos a / B) circuits; cover factor K B / (2 pi R cos a).
//
// Stability (slippage |k_g / k_n| against the friction coefficient mu; bridging where k_n <= 0)
// is evaluated on the passes and, separately, on the turnarounds; the pass figures
// (PlanMetrics::max_slippage, slip_fraction, bridging_length) do not include the turnarounds.
// A turnaround is a dwell arc along the boundary loop (polar opening or tube end) or a station
// circle; its figures (PlanMetrics::turnarounds, and per end turnaround_ends) come from the arc's
// own geometry: its points with the normal of the face each segment lies in, annotated on their
// own as build_circuits does before joining the arc to its passes. So the corner where a pass
// meets the arc (the pass's winding angle against the arc's hoop direction) counts in neither
// figure (in the circuit, i.e. fibre_path.csv, an arc's end points carry the adjoining passes'
// values; the figures take the arc's own). Near an arc's
// ends the window keeps its width, shifted inwards, as on the passes. An arc shorter than the
// window is one window (w cut to the arc's length): every point gets the arc's mean bend, the
// chords over its two halves split in the frame at its middle; on a parallel that bend points
// at the axis, so |k_g / k_n| is unchanged (tan b on a cone of half-angle b, 0 on a cylinder)
// while k_n and k_g are both low by sin(phi / 4) / (phi / 4) for an arc turning by phi. An arc of
// a single segment has no bend (k_n = k_g = 0: slippage 0, no bridging). A segment counts above
// mu (bridging) when the mean slippage (k_n) of its two ends is above mu (below -1e-5 / mm).
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/mesh/surface_path.h"
#include "geometry/region/axis.h"
#include "planner/plan/plan.h"
#include "planner/winding/helix.h"
#include "planner/winding/winding_options.h"

namespace windplan {

/// Curvature below which a fibre counts as straight for its slippage (1/mm: a radius of 10 m):
/// its |k_g / k_n| is 0, not the ratio of two tiny numbers.
inline constexpr double kStraightFibreCurvature = 1e-4;

/// Unit vertex normals of a mesh (angle-weighted).
std::vector<Vec3> vertex_normals(const Mesh& mesh);

/// Fills s (starting at s0), tangent, winding angle, k_n, k_g and slippage of `points` from their
/// positions and normals (see the header comment). \param window mm, > 0
void annotate_fibre_points(std::vector<FibrePoint>* points, const SpindleAxis& axis, double window,
                           double s0 = 0.0);

/// Winding angle (deg, 0 axial, 90 hoop) of direction t at a point with normal n.
double winding_angle_deg(const SpindleAxis& axis, const Vec3& n, const Vec3& t);

/// The unit normal at a surface point: the vertex normals `vn` interpolated (vertex, edge or
/// barycentric weights) and normalised.
Vec3 point_normal(const Mesh& mesh, const std::vector<Vec3>& vn, const SurfacePoint& p);

/// Appends a segment to a circuit: `pts` annotated on their own (annotate_fibre_points with
/// `window`) with arc length continuing the circuit's; the first point, which repeats the
/// circuit's last one, is kept once (with a pass's annotation when `kind` is Pass).
void append_circuit_segment(Circuit* circuit, std::vector<FibrePoint> pts,
                            CircuitSegment::Kind kind, const SpindleAxis& axis, double window);

/// Polyline points of a path with interpolated normals and annulus faces (not yet annotated).
std::vector<FibrePoint> path_points(const Mesh& annulus, const SurfacePath& path,
                                    const std::vector<Vec3>& normals);

/// The K continuous circuits of a helix plan as dense FibrePoints (passes and turnarounds,
/// each annotated separately, arc length continuous). face_map maps annulus faces to the full
/// mesh (empty: keep annulus faces). A turnaround's points carry the surface's interpolated
/// vertex normal (on a flat face, the face's own), not the facet normal its figures use: the eye
/// is put on their tangents (issue #26: a facet's normal, 3 deg off on an oval canister's 60
/// facets, put the eye below the true tangent plane at the arc's end).
std::vector<Circuit> build_circuits(const Mesh& annulus, const HelixPlan& plan,
                                    const std::vector<int>& face_map, const SpindleAxis& axis,
                                    const WindingOptions& options);

struct SpacingStats {
  int samples = 0;               ///< spacings measured
  double mean = 0.0;             ///< mm
  double cv = 0.0;               ///< coefficient of variation of the mm spacing
  double mean_normalised = 0.0;  ///< spacing / girth (dimensionless)
  double cv_normalised = 0.0;    ///< coefficient of variation of spacing / girth
};

/// Turn spacing of the out passes along `meridians` lines of constant theta.
/// \param face_girth per annulus face (mm), or empty for 2 pi r
SpacingStats turn_spacing(const Mesh& annulus, const HelixPlan& plan,
                          const std::vector<double>& face_girth, const SpindleAxis& axis,
                          int meridians);

/// Per pass figures for reports.
struct PassReport {
  int circuit = 0;
  int hand = 1;
  double length = 0.0;       ///< mm
  double angle_start = 0.0;  ///< winding angle where the pass starts (opening or station, deg)
  double angle_end = 0.0;    ///< where it ends (deg)
  double radius_start = 0.0, radius_end = 0.0;  ///< mm
  double max_slippage = 0.0;
  int iterations = 0;
  double time_ms = 0.0;  ///< refinement wall time
  std::string termination;
};
std::vector<PassReport> pass_reports(const HelixPlan& plan, const std::vector<Circuit>& circuits,
                                     const SpindleAxis& axis);

/// Spacing, coverage/pattern and stability of a plan (fills every PlanMetrics field except
/// timings and the geodesic turn limit), with warnings: slippage and bridging on the passes, and
/// on the turnarounds per end ("turnaround slippage: ...", naming the start or end loop or
/// station circle, the max |k_g/k_n|, by how much it exceeds mu, and the length above mu).
/// The turnaround figures are computed from plan.turnarounds on `annulus` (see the header comment).
PlanMetrics compute_plan_metrics(const Mesh& annulus, const HelixPlan& plan,
                                 const std::vector<Circuit>& circuits,
                                 const std::vector<double>& face_girth, const SpindleAxis& axis,
                                 bool revolution, const WindingOptions& options);

/// Per pass figures read off the circuits' Pass segments (out pass hand +1, return -1), with no
/// refinement figures (iterations 0) and `how` as the termination.
std::vector<PassReport> circuit_pass_reports(const std::vector<Circuit>& circuits,
                                             const SpindleAxis& axis, const std::string& how);

/// The stability figures and warnings of circuits planned without a HelixPlan (the Clairaut
/// route, planner/winding/revolution_winding.h): fibre length, circuits, band width, mu, the
/// passes' stability and, per end, the dwell arcs' (each re-annotated on its own points, as
/// compute_plan_metrics does), with the same warnings. Coverage, pattern and turn limit are
/// filled by the pipeline.
PlanMetrics circuit_plan_metrics(const std::vector<Circuit>& circuits, const SpindleAxis& axis,
                                 const WindingOptions& options);

}  // namespace windplan
