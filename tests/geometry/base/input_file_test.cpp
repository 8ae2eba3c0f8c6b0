// geometry/base/input_file.h: only regular files of bounded size are read (issue 28: /dev/zero
// grew to GBs, a FIFO blocked forever, a directory gave "Operation not supported").
#include "geometry/base/input_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

std::string error_of(const fs::path& p, std::uintmax_t cap) {
  try {
    read_input_file(p, cap, "a job file");
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

class InputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("windplan_input_file_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(InputFile, SpecialFilesAreRefusedAtOnceNamedAsSuch) {
  // A FIFO with no writer: the open does not block, the read is never tried.
  const fs::path fifo = dir_ / "job.yaml";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  EXPECT_EQ(error_of(fifo, kJobFileCap),
            fifo.string() + ": is a FIFO (named pipe), not a file; give a job file");
  EXPECT_EQ(error_of("/dev/zero", kJobFileCap),
            "/dev/zero: is a character device (like /dev/zero or a terminal), not a file; give "
            "a job file");
  EXPECT_EQ(error_of(dir_, kJobFileCap),
            dir_.string() + ": is a directory, not a file; give a job file");
  EXPECT_EQ(error_of(dir_ / "missing", kJobFileCap),
            (dir_ / "missing").string() + ": no such file");
  EXPECT_THROW(check_input_file("/dev/zero", kMeshFileCap, "a mesh file"), IoError);
}

TEST_F(InputFile, TheCapIsTheFilesSizeBoundAndContentIsReadWhole) {
  const fs::path f = dir_ / "a.csv";
  std::ofstream(f, std::ios::binary) << std::string(20000, 'x') << '\0' << "tail";
  EXPECT_EQ(read_input_file(f, 20005, "a CSV").size(), 20005u);
  EXPECT_EQ(read_input_file(f, 20005, "a CSV").substr(20001), "tail");
  EXPECT_EQ(error_of(f, 20004),
            f.string() + ": is 20005 bytes, above the bound of 20004 bytes for a job file");
  EXPECT_EQ(check_input_file(f, kCsvFileCap, "a CSV"), 20005u);
  // A link to a regular file is read; the bounds of windplan's readers are ordered.
  fs::create_symlink(f, dir_ / "link.csv");
  EXPECT_EQ(read_input_file(dir_ / "link.csv", kCsvFileCap, "a CSV").size(), 20005u);
  EXPECT_LT(kJobFileCap, kCsvFileCap);
  EXPECT_EQ(byte_size_text(512), "512 bytes");
  EXPECT_EQ(byte_size_text(16 * kMiB), "16.78 MB");
  EXPECT_EQ(byte_size_text(4096 * kMiB), "4.295 GB");
}

}  // namespace
}  // namespace windplan
