#pragma once
// The motion figures of a plan (issue #13) for report.json, report.md and the run summary: the
// eye envelope, the eye's least distance from the surface it winds on (the mandrel; on a layup
// the layer in work, labelled so in report.md: Motion::clearance_on_layers), axis reversals, the
// feed plan against the axis limits, the wind time per circuit and the G-code replay.
// export/files/report.cpp calls these.
#include <string>

#include "export/machine/kinematics.h"
#include "export/program/replay.h"
#include "geometry/base/json.h"

namespace windplan {

/// The "motion" object of report.json (`replay` may be null: not replayed).
void motion_json(JsonWriter& j, const Motion& motion, const ReplayResult* replay);
/// The "## Motion" section of report.md.
std::string motion_markdown(const Motion& motion, const ReplayResult* replay);
/// The summary lines (two-space indent, as the rest of the run summary).
std::string motion_summary(const Motion& motion, const ReplayResult* replay);

}  // namespace windplan
