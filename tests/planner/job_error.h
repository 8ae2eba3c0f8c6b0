#pragma once
// The message a job's YAML is refused with: the ConfigError's text, "" when it loads, and a
// marked text for any other exception (which a test then shows as the failure it is).
#include <string>

#include "geometry/base/errors.h"
#include "planner/job/job.h"

namespace windplan::test {

inline std::string job_load_error(const std::string& yaml,
                                  const std::string& file = "/jobs/j.yaml") {
  try {
    load_job_from_string(yaml, file);
  } catch (const ConfigError& e) {
    return e.what();
  } catch (const std::exception& e) {
    return std::string("NOT A ConfigError: ") + e.what();
  }
  return "";
}

}  // namespace windplan::test
