#pragma once
// development.svg: the plan unrolled onto the (axial position, angle) plane so that an engineer
// sees the winding pattern at a glance.
//
// Horizontal axis: axial position x [mm] along the spindle axis; vertical axis: angular position
// of the fibre point about the spindle axis, theta in [0, 360) deg (the angle of
// export/kinematics.h's AxisFrame, counter-clockwise about the axis direction), 0 at the top.
// Each circuit is one colour (golden-angle hues); a path crossing the 0/360 seam is split there
// (both pieces run to the seam). Cut-lines are black dashed, the mandrel ends (the radius
// profile's ends) are solid grey vertical lines, the turnaround zones (axial extent of the
// Turnaround segments, or the fibre's axial extremes) dashed grey with labels. Points closer than
// half a pixel to the previous drawn one are skipped. Deterministic text (fixed decimals).
#include <string>

#include "planner/plan.h"

namespace windplan {

struct SvgOptions {
  int width = 1100;  ///< px
  int height = 640;  ///< px
};

std::string development_svg(const WindingPlan& plan, const SvgOptions& opts = {});

}  // namespace windplan
