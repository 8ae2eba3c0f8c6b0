#pragma once
// stability.svg: does the fibre stay where it is laid? Along one circuit, against its fibre
// length: the winding angle (deg) and the measured slippage tendency |k_g / k_n| of the laid
// points, with the friction coefficient mu as a red line (above it the fibre slips unless pins or
// a ring hold it) and, where the plan leans on friction on purpose (winding.slippage), the planned
// lambda as a dashed line. The circuit drawn is the one with the largest measured |k_g / k_n| (on
// a shape of revolution the circuits are copies, so any one shows them all). Dwell arcs held by
// pins or a ring are shaded grey, points where k_n <= 0 (the fibre would bridge) marked orange.
// Every figure comes from the laid points (planner/winding/fibre_metrics.h), not from the planner's
// own numbers, except the planned lambda line. Per pixel column the envelope of the samples is
// drawn (export/plots/svg_util.h). Deterministic text. Elements for readers: <g class="panel"
// data-quantity="angle|slippage" data-lo data-hi> with one <rect> frame and one <polyline>; <line
// class="mu" data-value>, <line class="planned" data-value>; the root's data-circuit (the circuit
// drawn) and data-max (its largest value).
#include <string>

#include "planner/plan/plan.h"

namespace windplan {

struct StabilitySvgOptions {
  int width = 1100;        ///< px
  int panel_height = 150;  ///< px per panel
};

std::string stability_svg(const WindingPlan& plan, const StabilitySvgOptions& opts = {});

}  // namespace windplan
