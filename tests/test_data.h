#pragma once
// Access to the shared test meshes (../shared/data/meshes beside the repo). A user's clone has no
// ../shared: tests that need it call WINDPLAN_REQUIRE_SHARED_MESH, which skips with a message.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace windplan::test {

inline std::filesystem::path shared_mesh(const std::string& name) {
  return std::filesystem::path(WINDPLAN_SHARED_MESHES) / name;
}

inline std::filesystem::path source_dir() { return WINDPLAN_SOURCE_DIR; }

}  // namespace windplan::test

/// Declares `var` as the path of a shared mesh, or skips the test when it is absent.
#define WINDPLAN_REQUIRE_SHARED_MESH(var, name)                                            \
  const std::filesystem::path var = ::windplan::test::shared_mesh(name);                   \
  if (!std::filesystem::exists(var)) {                                                     \
    GTEST_SKIP() << "shared test mesh not found: " << var.string()                         \
                 << " (needs ../shared/data/meshes beside the repo)";                      \
  }
