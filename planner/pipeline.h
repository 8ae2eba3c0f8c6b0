#pragma once
// The planning pipeline of a job: mandrel -> winding surface -> girth field -> density ->
// helices (planner/winding/helix.h) -> continuous circuits with their differential geometry and the
// plan metrics (planner/winding/fibre_metrics.h) -> cut-lines (planner/cutlines/cutlines.h) ->
// WindingPlan.
//
// On a shape of revolution the metrics stage also computes the geodesic turn limit N_max between
// the ends of the passes (the boundary loops, or the stations; planner/winding/clairaut.h) from the
// wound region's meridian, reports it (PlanMetrics::geodesic_turn_limit) and, when beta = 0 and
// winding.turns > N_max, warns that the passes cannot be geodesics and will wrap along the
// smaller end (with beta > 0 the density bends the passes: the figure is reported, no warning).
//
// Export (export/export_plan.h) is the last stage of `windplan run`; it lives in export/, which
// depends on planner/ (house style rule 1: no upward includes), so the CLI calls plan_job and
// then export_plan. Stage wall times go into plan.metrics.timings in stage order (the files show
// them only with output.timings, so two runs stay byte-identical).
#include <functional>
#include <string>
#include <vector>

#include "planner/girth/girth.h"
#include "planner/job/job.h"
#include "planner/mandrel/mandrel_builder.h"
#include "planner/mandrel/tube_spine.h"
#include "planner/plan/plan.h"
#include "planner/winding/clairaut.h"
#include "planner/winding/fibre_metrics.h"
#include "planner/winding/helix.h"
#include "planner/winding/revolution_winding.h"
#include "planner/winding/tube_friction.h"

namespace windplan {

struct PipelineOptions {
  /// Called after each stage with its name and wall time (e.g. a progress line on stderr).
  std::function<void(const StageTiming&)> on_stage;
  /// Called before each stage starts with its name.
  std::function<void(const std::string&)> on_stage_start;
  /// Called once the mandrel is built, before the winding stages: a check that needs the mandrel
  /// and lives above planner/ (the robot cell's reach, export/robot/cell_reach.h) refuses the job
  /// there by throwing, before the long work. plan_job and plan_layup call it.
  std::function<void(const Mandrel&)> on_mandrel;
  /// Called by plan_layup before each layer wound over others, with the surface it will be wound
  /// on (the laminate the layers under it built) and the layer as "layers[k] (name)": a check
  /// above planner/ (the robot cell's reach over the laminate, export/robot/cell_reach.h) refuses
  /// the job there by throwing, before that layer's winding stages.
  std::function<void(const Mesh&, const std::string&)> on_layer_surface;
};

/// Off shapes of revolution, the wound region as a tube: either a friction layer at a constant
/// angle to the exact centre line of a parametric bent tube (winding.slippage or winding.angle;
/// planner/winding/tube_friction.h), or geodesic / helix passes with coverage measured on the
/// sections normal to the region's centre line (planner/mandrel/tube_spine.h).
struct TubeResult {
  bool friction = false;      ///< a friction layer: `layer` holds its figures
  TubeFrictionWinding layer;  ///< (its circuits moved into the plan)
  /// The tube's centre line: the sections normal to it measure the passes' coverage (a friction
  /// layer plans and measures on its `exact` line); empty spine, with `why`, when the region is
  /// not a tube.
  TubeSpine centre_line;
  /// A friction layer's surface: centre_line.exact on a parametric bent tube, else the fit of
  /// the wound mesh around the centre line (planner/winding/mesh_tube_surface.h).
  std::shared_ptr<const TubeSurface> surface;
  std::string surface_report;  ///< the fit's brief_report (empty on a bent tube)
};

struct PipelineResult {
  Mandrel mandrel;
  bool has_girth = false;  ///< the girth field was computed (beta > 0 or no revolution)
  GirthField girth;
  std::vector<double> face_girth;  ///< per winding-surface face (mm): girth field or 2 pi r
  /// true: the circuits come from Clairaut's integral (a shape of revolution, beta = 0;
  /// planner/winding/revolution_winding.h) and `revolution` holds them (its circuits moved into the
  /// plan); false: from the geodesic core (`helices`).
  bool clairaut = false;
  RevolutionWinding revolution;
  HelixPlan helices;
  /// Off shapes of revolution: the wound region as a tube (see TubeResult).
  TubeResult tube;
  /// Off shapes of revolution with a centre line: the passes laid (docs/config.md, "Which paths
  /// off revolution"): "geodesic" (the core's refinement) or "helix" (the traced, evenly spread
  /// level sets, held by friction), and the figures of the one not laid, for the report.
  std::string laid = "geodesic";
  std::string laid_why;
  std::vector<PassReport> passes;
  bool has_turn_limit = false;  ///< turn_limit was computed (a shape of revolution)
  ClairautLimit turn_limit;     ///< N_max between the ends of the passes
  WindingPlan plan;
};

/// Runs a loaded job up to the WindingPlan.
/// \throw what the stages throw: IoError/InputError/TopologyError/ConfigError for bad input.
PipelineResult plan_job(const Job& job, const PipelineOptions& options = {});

/// The winding stages of plan_job (girth, helices, metrics and coverage, the turn limit; not the
/// mandrel, not the cut-lines) on a mandrel already built, with `winding` in place of
/// job.winding: the helical layers of a layup (planner/plan_layup.h) run it on the surfaces built
/// by the layers under them.
PipelineResult plan_winding(Mandrel mandrel, const Job& job, const WindingOptions& winding,
                            const PipelineOptions& options = {});

}  // namespace windplan
