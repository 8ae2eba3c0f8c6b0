#pragma once
// development.svg: the plan unrolled onto a plane so that an engineer sees the winding pattern,
// its coverage, gaps and overlaps at a glance.
//
// Coordinates (export/plots/unroll.h): horizontal "along" (mm: the axial position on a shape of
// revolution, the height between the two ends on other tubes), vertical "around" (deg, 0 at the
// top, 360 at the bottom).
// Bands: each circuit is a polygon of the plan's band width: its edges are the fibre points moved
// by +-w/2 across the fibre in the tangent plane (p +- w/2 (n x t)), unrolled with the same map,
// so the band is as wide on the plot as on the mandrel. Bands are filled translucent (opacity
// 0.45): bare surface stays white, one band shows its colour, overlaps show darker. A polygon is
// drawn with its angle unwrapped along the circuit and repeated every 360 deg, clipped to the plot.
// Colours: by layer when the plan has more than one (export/plots/viewer.h circuit_layers), else by
// circuit (golden-angle hues); a legend on the right names them and the coverage shades.
// Lines: the cut-lines black dashed; the mandrel ends solid grey and the turnaround zones dashed
// grey (axis unrolling only); the conformal unrolling marks its two ends. Labels of these lines sit
// in lanes above the plot, a label moving to the next lane when it would overlap another.
// Points closer than 0.7 px to the previous drawn one are skipped. Deterministic text.
// Elements for readers: <g id="bands"> with one <polygon class="band" data-circuit="k"> per
// circuit (in <defs>, placed by <use>), <g id="legend">, <g id="cutlines">, <g id="labels">.
#include <string>

#include "export/plots/unroll.h"
#include "planner/plan/plan.h"

namespace windplan {

struct SvgOptions {
  int width = 1200;            ///< px
  int height = 680;            ///< px
  double band_opacity = 0.45;  ///< fill opacity of one band (0..1)
};

std::string development_svg(const WindingPlan& plan, const Unrolling& unrolling,
                            const SvgOptions& opts = {});

}  // namespace windplan
