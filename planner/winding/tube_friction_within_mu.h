#pragma once
// A friction layer on a tube (planner/winding/tube_friction.h, any tube_surface) whose laid points, measured
// as an independent reader measures them (planner/winding/fibre_metrics.h: finite differences
// over the curvature window on the points placed on the mesh), stay within winding.mu.
//
// Why: the layer is planned on the exact tube, its turnarounds at |k_g / k_n| = winding.slippage
// exactly, and laid on the tessellated mandrel. Where a turnaround reaches into a bend the laid
// points measure higher than planned: configs/elbow.yaml with its region ending on the stations
// 60 and 530 mm (both turnarounds 24-26 mm into the bend) measures 0.208 at 104.8 mm, 4.8 mm past
// the bend's start, against 0.19 planned; on the exact torus the same fibre measures 0.193 (the
// window across the bend's start, where the curvature jumps), on a 2 deg tessellation 0.194. The
// excess is the facets along the bend (about 24 mm long at linear_deflection 0.25 on a 300 mm
// outer radius, against a 12 mm window), which the passes' 0.179 absorbs and the turnarounds'
// 0.19 does not.
//
// So: plan at lambda = winding.slippage; measure the laid points; while the largest is above mu
// and lies on a turnaround (its angle to the centre line more than 0.5 deg off a0), plan the
// turnarounds again at lambda mu / measured (x 0.99) of the last (at most 4 times; lambda may go
// below the constant angle's demand: a turnaround in a bend then turns back a little where the
// bend pulls harder, and still turns). A largest value on a
// pass (held at a0, no lambda to lower) or one that stays above mu: ConfigError, one line naming
// winding.slippage, the figure and the station, and what to change. Pins: the passes only (the
// dwells are held by the pins).
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"
#include "planner/winding/tube_surface.h"
#include "planner/winding/tube_friction.h"
#include "planner/winding/winding_options.h"

namespace windplan {

/// plan_tube_friction with the turnarounds' lambda lowered until the laid points measure within
/// options.mu (see the header comment); the result's `measured`, `measured_s`, `slippage` (the
/// lambda laid) and summary say what was done.
/// \throw ConfigError naming winding.slippage with the measured figure and its station when no
///        lambda keeps the laid points within mu; whatever plan_tube_friction throws
TubeFrictionWinding plan_tube_friction_within_mu(const TubeSurface& line, double s0, double s1,
                                                 const Mesh& annulus,
                                                 const std::vector<int>& face_map,
                                                 const SpindleAxis& axis,
                                                 const WindingOptions& options);

}  // namespace windplan
