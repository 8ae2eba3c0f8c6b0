#pragma once
// The per-layer sections of a layup's reports (WindingPlan::layers, planner/plan_layup.h): in
// report.json a "layers" array (one object per layer: name, kind, circuits, angle, Clairaut
// constant or pitch, coverage, band thickness, thickness on the cylinder / at the turnarounds /
// maximum, slippage of passes and turnarounds, band and fibre length, fibre and resin mass, wind
// time) and a "laminate" object with the totals; in report.md a "Layers" table and one section
// per layer; on stdout one line per layer. Wind time per layer: the machine states' durations
// summed over the layer's circuits. Nothing is written for a plan without layers.
#include <string>
#include <vector>

#include "export/machine/kinematics.h"
#include "geometry/base/json.h"
#include "planner/plan/plan.h"

namespace windplan {

/// Wind time (s) of each layer of plan.layers, from the motion's states.
std::vector<double> layer_wind_times(const WindingPlan& plan, const Motion& motion);

/// Writes the "layers" and "laminate" keys into the current JSON object.
void layers_json(JsonWriter& j, const WindingPlan& plan, const Motion& motion);
/// The "## Layers" section of report.md ("" without layers).
std::string layers_markdown(const WindingPlan& plan, const Motion& motion);
/// The stdout lines ("" without layers).
std::string layers_summary(const WindingPlan& plan, const Motion& motion);

}  // namespace windplan
