#pragma once
// axes.svg: the machine axes against time, one panel each, so that an engineer sees the motion
// the G-code asks for: A (spindle, deg), X (carriage, mm), Y (cross-feed, mm), B (eye rotation,
// deg) and the feed F (the dialect's unit) over t_s (s), on a shared time axis with the circuit
// boundaries as faint vertical lines. Each panel is scaled to its own range (a constant axis gets
// a +-1 band). Per pixel column the min and max of the samples in it are drawn (an envelope), so
// a plan of any length keeps its extremes and stays a few hundred kB. Deterministic text.
// Elements for readers: <g class="panel" data-axis="A|X|Y|B|F"> each with one <polyline>.
#include <string>

#include "export/machine/kinematics.h"

namespace windplan {

struct AxesSvgOptions {
  int width = 1100;        ///< px
  int panel_height = 110;  ///< px per axis
};

std::string axes_svg(const Motion& motion, const std::string& job_name,
                     const AxesSvgOptions& opts = {});

}  // namespace windplan
