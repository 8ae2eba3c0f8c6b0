#pragma once
// A layup: the layers of a job (`layers:`, planner/layup/layers.h) wound in order, each on the
// surface built by the layers under it, into one plan for the part.
//
// Shapes of revolution. The mandrel's meridian (planner/winding/clairaut.h meridian_profile,
// between the two boundary loops, resampled every quarter of the narrowest band) is the first
// surface. Each layer is planned on the current surface:
//   hoop:    planner/layup/hoop.h on the surface's radius profile (range default: the mandrel's
//            cylindrical part), thickness (3) of planner/layup/laminate_thickness.h;
//   helical: the winding stages of a one-layer job (plan_winding, planner/pipeline.h: the
//            Clairaut route with its pattern on shapes of revolution, else the geodesic core)
//            with the layer's winding keys, on the mandrel for the innermost layer, else on the
//            surface of revolution of the current meridian (rings about a mesh edge apart); its
//            thickness is (2) of planner/layup/laminate_thickness.h from its own circuits: K, and
//            the Clairaut constant c of its pattern (the geodesic core's route: the median of r sin
//            a measured on its passes).
// design.dome_thickness: spline replaces (2) by planner/layup/dome_thickness.h; with
// design.turnaround_stagger f, helical layer h (0 the innermost helical) is wound with its
// turnaround radius moved outward by h f B (from its `turnaround`, from its `angle` on the
// surface's largest radius, else from the default: the larger polar opening + B / 2).
// The current meridian is then offset by the layer's thickness (offset_meridian: a thickness
// that would close a polar opening is an InputError naming the layer).
// Other mandrels (helical layers only): a layer's thickness on each face of the current surface
// is measured from its paths: the band volume t B L_f of the band centre line in a face (length
// L_f) is spread over the faces within B/2 of it in proportion to their area, and the next surface
// is the current one with every vertex moved along its normal by the area-weighted mean thickness
// of its faces.
//
// The plan (WindingPlan) holds every layer's circuits in winding order, numbered on through the
// layers, and WindingPlan::layers their figures (planner/plan/layer_summary.h). Its metrics are the
// innermost helical layer's (coverage, pattern, stability) with fibre_length and circuits
// summed over all layers, and every layer's warnings prefixed with its name; its profile is the
// outer surface's on the mandrel profile's stations (the machine clears the finished part). Points
// of layers wound on a built surface have face -1 (they do not lie on the mandrel's mesh).
#include <memory>
#include <string>
#include <vector>

#include "planner/job/job.h"
#include "planner/layup/laminate_thickness.h"
#include "planner/layup/material.h"
#include "planner/layup/netting.h"
#include "planner/mandrel/mandrel_builder.h"
#include "planner/pipeline.h"
#include "planner/plan/plan.h"

namespace windplan {

struct LayupLayer {
  LayerOptions options;
  std::vector<Circuit> circuits;       ///< as wound (on the surface under it)
  LayerSummary summary;                ///< its figures (also in WindingPlan::layers)
  std::vector<double> face_thickness;  ///< per face of the mandrel's winding surface (mm)
  MaterialEstimate material;
  /// The surface it was wound on when that is not the mandrel (a layer over others: the revolved
  /// current meridian, or the offset mesh off revolution); null: the mandrel's mesh. The G-code
  /// replay walks this layer's circuits on it (layup_circuit_surfaces).
  std::shared_ptr<const Mesh> surface;
};

struct LayupResult {
  Mandrel mandrel;
  bool revolution = false;
  LaminateProfiles profiles;  ///< shapes of revolution only (empty mandrel meridian otherwise)
  std::vector<LayupLayer> layers;
  MaterialEstimate total;
  WindingPlan plan;
  /// design: with a pressure: the netting burst pressure of the wound laminate by layer, from
  /// each layer's measured angle and cylinder thickness on the mandrel's largest radius.
  bool has_netting = false;
  double netting_radius = 0.0;  ///< mm
  NettingBurst netting;
};

/// A surface of revolution meshed from a meridian: rings about `edge` mm apart along it (the
/// ends kept; no farther apart than the spacing around when `edge` needs fewer than 48 per ring:
/// a pipe's mesh edges run end to end), `edge` mm apart around it (48 to 512 per ring), each
/// quad split in two, outward
/// normals. The winding surface is the whole mesh (an annulus).
/// \throw InputError for edge <= 0.
Mesh revolve_meridian(const MeridianPolyline& meridian, const SpindleAxis& axis, double edge);

/// The largest-axial-so-far points of a meridian as a radius profile (a built surface whose
/// offset runs back along the axis near an opening keeps its forward-running part).
RadiusProfile forward_profile(const MeridianPolyline& meridian);

/// Per circuit of result.plan (in order), the mesh of the surface it was wound on: a layer's
/// LayupLayer::surface, null for layers wound on the mandrel (export/program/replay.h).
std::vector<const Mesh*> layup_circuit_surfaces(const LayupResult& result);

/// Plans every layer of `job` (its `layers:`, or one helical layer of `winding:`).
/// \throw what the stages throw; InputError naming layers[k] for a hoop range outside the
///        mandrel, a thickness that would close a polar opening, or a hoop layer on a mandrel that
///        is not a shape of revolution.
LayupResult plan_layup(const Job& job, const PipelineOptions& options = {});

}  // namespace windplan
