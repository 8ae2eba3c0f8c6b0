#pragma once
// The winding plan: what the planner hands to export/ (kinematics, G-code, CSV, reports).
//
// Units: lengths in mm, angles in degrees unless a field says radians, curvatures in 1/mm.
// Frames: all positions and directions are in the mandrel frame (the frame of the mesh).
// The spindle axis is a line (origin, unit direction) in that frame; "axial position" of a point
// p is (p - origin) . direction, its "radius" the distance from the axis line.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"
#include "planner/plan/layer_summary.h"

namespace windplan {

/// One point of a fibre path with its differential geometry.
struct FibrePoint {
  Vec3 position = Vec3::Zero();  ///< on the mandrel surface (mm)
  Vec3 normal = Vec3::UnitX();   ///< unit outward surface normal
  Vec3 tangent = Vec3::UnitZ();  ///< unit fibre direction (direction of travel)
  double s = 0.0;                ///< arc length from the circuit start (mm)
  double winding_angle = 0.0;    ///< deg from the meridian: 0 axial, 90 hoop
  double k_n = 0.0;              ///< normal curvature along the fibre (1/mm), > 0 convex
  double k_g = 0.0;              ///< geodesic curvature (1/mm)
  double slippage = 0.0;         ///< |k_g / k_n| (tendency to slip; compare with friction mu)
  int face = -1;                 ///< mesh face containing the point (-1 if unknown)
};

/// A section of a circuit: a helical pass from one end to the other, or a turnaround (dwell) at
/// a polar opening or tube end.
struct CircuitSegment {
  enum class Kind { Pass, Turnaround };
  Kind kind = Kind::Pass;
  int first = 0;  ///< index of the first point in Circuit::points
  int last = 0;   ///< index of the last point (inclusive)
};

/// One continuous fibre circuit.
struct Circuit {
  int index = 0;
  std::vector<FibrePoint> points;
  std::vector<CircuitSegment> segments;
};

/// A planar cut-line (trim line) on the mandrel.
struct CutLine {
  std::string name;
  std::vector<Vec3> points;  ///< closed loop (last != first) or open curve
  bool closed = true;
  Vec3 plane_normal = Vec3::UnitZ();
  double plane_offset = 0.0;  ///< n . p = offset (mm)
  double length = 0.0;        ///< mm
  double residual = 0.0;      ///< max |n . p - offset| (mm)
};

/// Wall time of one pipeline stage (reported on stdout; in report.json/md only with
/// output.timings, so that files stay byte-identical between runs).
struct StageTiming {
  std::string stage;
  double seconds = 0.0;
};

/// Fibre stability on turnarounds (the dwell arcs; planner/winding/fibre_metrics.h): of the arcs at
/// one end of the passes, or of all of them. Kept apart from the passes' figures in PlanMetrics.
struct TurnaroundStability {
  double length = 0.0;           ///< mm: the dwell arcs summed over all circuits
  double max_slippage = 0.0;     ///< max |k_g/k_n| over their points
  double slip_length = 0.0;      ///< mm of dwell arc with |k_g/k_n| > mu
  double slip_fraction = 0.0;    ///< slip_length / length
  double bridging_length = 0.0;  ///< mm of dwell arc with k_n <= 0 (the fibre would bridge)
  /// Per end only: the station circle the arcs run along (mm along the spindle axis); NaN: the
  /// boundary loop (polar opening or tube end).
  double station = std::nan("");

  bool at_station() const { return std::isfinite(station); }
};

// Coverage measured on the laid bands (planner/winding/coverage.h says how).
/// The figures at one station (see the header comment).
struct StationCoverage {
  /// mm along the spindle axis; with CoverageReport::centre_line mm along the tube's centre line
  /// (geometry/region/spine.h); off revolution without one, a level of the harmonic height
  double station = 0.0;
  double loop_length = 0.0;                        ///< mm: the section loop's length
  std::array<int, 2> bands = {0, 0};               ///< bands per family (+, -)
  std::array<double, 2> family_bare = {0.0, 0.0};  ///< bare fraction per family
  double bare_fraction = 0.0;                      ///< the worse family
  double widest_gap = 0.0;                         ///< mm along the loop
  double widest_overlap = 0.0;  ///< mm across the band (0 when no two neighbours share)
  int max_stack = 0;            ///< most bands of one family over one point
  double mean_plies = 0.0;      ///< band length of both families / loop length
  double cover_factor = 0.0;    ///< the smaller family's band length / loop length
  double spacing_cv = 0.0;      ///< CV of neighbouring band-centre distances (both families)
  double spacing_mean = 0.0;    ///< their mean (mm across the band)
};

/// The slippage |k_g / k_n| of a point where the fibre does not press on the mandrel (k_n = 0,
/// k_g != 0): no friction holds it. Stored as this sentinel, written as "unbounded" (JSON null),
/// never as a measured figure.
constexpr double kUnboundedSlippage = 1e12;
inline bool is_unbounded_slippage(double s) { return !(s < kUnboundedSlippage); }

struct CoverageReport {
  std::vector<StationCoverage> stations;
  int skipped = 0;  ///< stations without a section loop around the axis
  /// The stations are sections normal to a tube's centre line (StationCoverage::station: mm along
  /// it, of centre_line_length mm).
  bool centre_line = false;
  double centre_line_length = 0.0;  ///< mm (centre_line only)
  // Over the measured stations:
  double bare_fraction = 0.0;   ///< the largest
  double widest_gap = 0.0;      ///< the largest (mm)
  double widest_overlap = 0.0;  ///< the largest (mm)
  /// The largest at the stations whose loop is within 0.5% of the longest (the cylinder of a
  /// vessel or pipe: where the bands lie side by side; domes stack them by design) (mm).
  double widest_overlap_largest = 0.0;
  int max_stack = 0;
  double cover_factor = 0.0;  ///< the smallest
  double mean_plies = 0.0;    ///< the mean over the stations
  double spacing_cv = 0.0;    ///< the largest
  double spacing_mean = 0.0;  ///< the mean over the stations (mm)

  bool measured() const { return !stations.empty(); }
  /// One line: "bare 0.00% (widest gap 0.0 mm), overlap <= 0.3 mm, up to 3 bands, ...".
  std::string brief_report() const;
};

/// How the circuits were planned on a shape of revolution (planner/winding/revolution_winding.h).
struct PatternInfo {
  bool geodesic = false;  ///< planned from Clairaut's integral (false: the geodesic core's route)
  int circuits = 0;       ///< K
  int skip = 0;           ///< p
  double turnaround_radius = std::nan("");  ///< c (mm): the parallel the passes turn around on
  double requested_radius = std::nan("");   ///< the c the job asked for (mm)
  std::string requested_by;                 ///< the key that asked ("winding.turnaround", ...)
  double largest_radius = std::nan("");     ///< R (mm)
  double angle_deg = std::nan("");          ///< winding angle on the largest parallel (deg)
  std::array<bool, 2> geodesic_end = {false, false};  ///< per end: geodesic turnaround (no dwell)
  std::array<double, 2> dwell_deg = {0.0, 0.0};       ///< per end: dwell (deg; 0 geodesic)
  double advance_deg = 0.0;     ///< mandrel advance per circuit, modulo 360 (deg)
  double projection_max = 0.0;  ///< largest distance of a planned point from the mesh (mm)
};

/// Friction turnarounds (winding.slippage > 0, planner/winding/friction_winding.h): the slippage
/// lambda planned and measured per end and on the passes, and the fibre friction carries.
struct FrictionFigures {
  bool planned = false;        ///< the plan has friction turnarounds
  double bound = 0.0;          ///< winding.slippage
  double mu = 0.0;             ///< winding.mu
  double pass_lambda = 0.0;    ///< planned on the passes (0: geodesic)
  double pass_measured = 0.0;  ///< largest measured |k_g/k_n| on the passes' points
  double pass_length = 0.0;    ///< mm of pass fibre, all circuits
  std::array<bool, 2> at_end = {false, false};   ///< per end: a friction turnaround
  std::array<double, 2> lambda = {0.0, 0.0};     ///< planned lambda per end
  std::array<double, 2> measured = {0.0, 0.0};   ///< largest measured |k_g/k_n| per end
  std::array<double, 2> length = {0.0, 0.0};     ///< mm of fibre friction carries, one turnaround
  std::array<double, 2> axial = {0.0, 0.0};      ///< mm along the axis from the join to the apex
  std::array<double, 2> angle_deg = {0.0, 0.0};  ///< mandrel turn over one turnaround (deg)
  std::array<double, 2> pass_angle_deg = {0.0, 0.0};  ///< winding angle where the pass joins
  /// A friction transition on the passes (a vessel with unequal openings): r sin a goes from one
  /// dome's turnaround radius to the other's at |k_g/k_n| = pass_lambda.
  bool transition = false;
  std::array<double, 2> transition_c = {0.0, 0.0};  ///< the two geodesics' c (mm), start first
  double transition_length = 0.0;                   ///< mm of each pass's fibre friction carries
  double transition_axial = 0.0;                    ///< mm along the axis
  double transition_angle_deg = 0.0;                ///< mandrel turn over it (deg)
};

/// Figures of a plan, reported in the summary, report.json and report.md.
struct PlanMetrics {
  double fibre_length = 0.0;  ///< mm, all circuits
  int circuits = 0;
  double turns_per_pass = 0.0;    ///< N (turns, > 0, need not be whole)
  double band_width = 0.0;        ///< mm
  int circuits_for_coverage = 0;  ///< circuits needed for full coverage
  /// Band length laid per unit of circumference, the smaller pass family, measured on the laid
  /// bands (coverage.cover_factor; >= 1: enough band for full cover).
  double cover_factor = 0.0;
  CoverageReport coverage;  ///< measured on the laid bands (planner/winding/coverage.h)
  PatternInfo pattern_info;
  FrictionFigures friction_turnarounds;  ///< planned with winding.slippage > 0
  std::string pattern;           ///< e.g. "K=12, advance 1/12, coprime" (shapes of revolution)
  double spacing_cv = 0.0;       ///< coefficient of variation of turn spacing along meridians
  double spacing_mean = 0.0;     ///< mm
  double max_slippage = 0.0;     ///< max |k_g/k_n|
  double friction = 0.0;         ///< mu from the job
  double slip_fraction = 0.0;    ///< fraction of path length with slippage > mu
  double bridging_length = 0.0;  ///< mm of path with k_n <= 0 (fibre would bridge)
  // max_slippage, slip_fraction and bridging_length are of the passes; the turnarounds have
  // their own figures:
  TurnaroundStability turnarounds;  ///< all dwell arcs (station unused)
  /// Per end of the passes: [0] the start (loop 0 or winding.start_station), [1] the end.
  std::array<TurnaroundStability, 2> turnaround_ends;
  /// Shapes of revolution: N_max, the most turns a geodesic can make between the ends of the
  /// passes (Clairaut, planner/winding/clairaut.h; turns). +inf: no limit (a cylinder); NaN: not a
  /// shape of revolution (not reported).
  double geodesic_turn_limit = std::nan("");
  double geodesic_min_radius = std::nan("");  ///< mm: r_min, the largest Clairaut constant; NaN
  std::vector<std::string> warnings;
  std::vector<StageTiming> timings;  ///< filled by the pipeline, in stage order
};

/// The complete plan handed to export/.
struct WindingPlan {
  std::string job_name;
  SpindleAxis axis;
  RadiusProfile profile;
  std::vector<Circuit> circuits;
  std::vector<CutLine> cutlines;
  PlanMetrics metrics;
  /// A layup (planner/plan_layup.h): its layers in winding order, each naming its circuits; empty
  /// for a job without `layers:`.
  std::vector<LayerSummary> layers;
};

/// Per circuit of a layup's plan, 1 at the circuit where a layer starts (the tow is tied on
/// there): the layer's first circuit that has points; a layer whose first circuits have none
/// starts at the next one that has, and a layer with no circuit that has points starts nowhere.
/// All 0 for a plan without layers.
inline std::vector<char> layer_start_circuits(const WindingPlan& plan) {
  const int n = static_cast<int>(plan.circuits.size());
  std::vector<char> starts(plan.circuits.size(), 0);
  for (const LayerSummary& l : plan.layers) {
    const int end = std::min(n, l.first_circuit + l.circuit_count);
    for (int c = std::max(0, l.first_circuit); c < end; ++c) {
      if (plan.circuits[c].points.empty()) continue;
      starts[c] = 1;
      break;
    }
  }
  return starts;
}

}  // namespace windplan
