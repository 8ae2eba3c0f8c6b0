#pragma once
// The robot cell's part of the reports (report.json "robot", report.md "Robot cell"): the arm and
// positioner, the program files, the planned joint margins, wrist angle and speeds
// (export/robot/robot_motion.h) and the replay of the written program
// (export/robot/robot_replay.h). Wall times are left out so that the files stay byte-identical
// between runs.
#include <string>

#include "export/files/export_result.h"
#include "geometry/base/json.h"

namespace windplan {

/// The robot replay's figures as fields of the open JSON object (report.json's robot.replay and
/// `windplan simulate`'s report share them).
void robot_replay_fields(JsonWriter& j, const RobotReplayResult& rp);
void robot_json(JsonWriter& j, const ExportResult& r);
std::string robot_markdown(const ExportResult& r);

}  // namespace windplan
