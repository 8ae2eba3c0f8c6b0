#include "geometry/base/atomic_file.h"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("windplan_test_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

TEST(AtomicFile, WritesAndReadsBack) {
  const fs::path d = temp_dir("atomic1");
  write_text_atomically(d / "sub" / "a.txt", "hello\n");
  EXPECT_EQ(read_text_file(d / "sub" / "a.txt"), "hello\n");
  // No temporary file is left beside it.
  int n = 0;
  for (const auto& e : fs::directory_iterator(d / "sub")) n += e.is_regular_file();
  EXPECT_EQ(n, 1);
}

TEST(AtomicFile, FailureInWriterLeavesOldFileIntact) {
  const fs::path d = temp_dir("atomic2");
  write_text_atomically(d / "a.txt", "old");
  EXPECT_THROW(write_file_atomically(d / "a.txt",
                                     [](std::ostream& out) {
                                       out << "partial";
                                       throw IoError("simulated failure");
                                     }),
               IoError);
  EXPECT_EQ(read_text_file(d / "a.txt"), "old");
  int n = 0;
  for (const auto& e : fs::directory_iterator(d)) n += e.is_regular_file();
  EXPECT_EQ(n, 1);
}

TEST(AtomicFile, MissingFileIsAnIoErrorNamingIt) {
  try {
    read_text_file("/nonexistent/windplan/file.obj");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/windplan/file.obj"), std::string::npos);
  }
}

}  // namespace
}  // namespace windplan
