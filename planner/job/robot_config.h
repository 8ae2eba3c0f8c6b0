#pragma once
// Reads the `machine.robot:` section of a job and the arm and positioner profiles it names
// (planner/job/robot_options.h; docs/config.md). Unknown keys, a missing or malformed profile,
// a joint list that is not 6 revolute joints: ConfigError naming the file, line and key.
#include <filesystem>

#include "planner/job/config_node.h"
#include "planner/job/robot_options.h"

namespace windplan {

/// \param base the directory the profile paths are relative to (the job's or its machine
///        profile's directory)
void decode_robot(ConfigNode n, const std::filesystem::path& base, RobotOptions* r);

}  // namespace windplan
