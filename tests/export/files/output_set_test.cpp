// export/files/output_set.h and export/files/manifest.h in process: the lock, foreign folders, the
// swap that leaves exactly the new set, clean-up of an unfinished set. (The runs killed by a signal
// are in tests/cli/cli_output_set_test.cpp.)
#include "export/files/output_set.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "export/files/sha256.h"
#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

class OutputSetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("windplan_outset_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  std::set<std::string> names(const fs::path& d) const {
    std::set<std::string> s;
    for (const auto& e : fs::directory_iterator(d)) s.insert(e.path().filename().string());
    return s;
  }
  fs::path root_;
};

TEST_F(OutputSetTest, CommitLeavesExactlyTheNewSetAndItsManifest) {
  const fs::path dir = root_ / "job";
  {
    OutputSet set(dir);
    write_text_atomically(set.staging() / "toolpath.gcode", "G1 X1\n");
    write_text_atomically(set.staging() / "report.json", "{}\n");
    Manifest m;
    m.job = "first";
    set.commit(m, {"toolpath.gcode", "report.json"});
  }
  EXPECT_EQ(names(dir), (std::set<std::string>{"toolpath.gcode", "report.json", "manifest.json"}));
  {
    OutputSet set(dir);
    write_text_atomically(set.staging() / "toolpath.ngc", "G1 X2\n");
    Manifest m;
    m.job = "second";
    set.commit(m, {"toolpath.ngc"});
  }
  // The previous job's toolpath.gcode and report.json are gone with its set.
  EXPECT_EQ(names(dir), (std::set<std::string>{"toolpath.ngc", "manifest.json"}));
  const std::string man = read_text_file(dir / "manifest.json");
  EXPECT_NE(man.find("\"job\": \"second\""), std::string::npos) << man;
  EXPECT_NE(man.find(sha256_hex("G1 X2\n")), std::string::npos) << man;
  EXPECT_EQ(manifest_file_names(man), std::vector<std::string>{"toolpath.ngc"});
  // Beside the folder: only the lock file, no staging or old set.
  EXPECT_EQ(names(root_), (std::set<std::string>{"job", ".job.lock"}));
}

TEST_F(OutputSetTest, SecondSetOnAHeldFolderIsRefused) {
  const fs::path dir = root_ / "job";
  OutputSet first(dir);
  try {
    OutputSet second(dir);
    FAIL() << "a second writer was let in";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("another windplan run (pid " + std::to_string(::getpid())),
              std::string::npos)
        << e.what();
  }
  // Another spelling of the same folder is the same lock.
  EXPECT_THROW(OutputSet((root_ / "x" / ".." / "job" / "").string()), IoError);
}

TEST_F(OutputSetTest, UnfinishedSetIsRemovedAndThePreviousKept) {
  const fs::path dir = root_ / "job";
  fs::create_directories(dir);
  write_text_atomically(dir / "report.md", "old\n");
  {
    OutputSet set(dir);
    write_text_atomically(set.staging() / "report.md", "new\n");
    // No commit: an exception in the export.
  }
  EXPECT_EQ(read_text_file(dir / "report.md"), "old\n");
  EXPECT_EQ(names(root_), (std::set<std::string>{"job", ".job.lock"}));
}

TEST_F(OutputSetTest, AFolderWithFilesWindplanDidNotWriteIsNeverReplaced) {
  const fs::path dir = root_ / "docs";
  fs::create_directories(dir);
  write_text_atomically(dir / "thesis.tex", "mine\n");
  write_text_atomically(dir / "report.md", "old\n");
  try {
    OutputSet set(dir);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("thesis.tex: not written by windplan"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(read_text_file(dir / "thesis.tex"), "mine\n");
  const fs::path file = root_ / "plain_file";
  write_text_atomically(file, "x");
  EXPECT_THROW(OutputSet set(file), IoError);
}

TEST_F(OutputSetTest, LeftoversOfAKilledRunAreRemovedByTheNext) {
  const fs::path dir = root_ / "job";
  fs::create_directories(root_ / ".job.staging.999999");
  write_text_atomically(root_ / ".job.staging.999999" / "fibre_path.csv", "half");
  fs::create_directories(dir);
  write_text_atomically(dir / "payout.csv.tmp.999999", "half");  // from before staging folders
  {
    OutputSet set(dir);
    Manifest m;
    set.commit(m, {});
  }
  EXPECT_EQ(names(root_), (std::set<std::string>{"job", ".job.lock"}));
  EXPECT_EQ(names(dir), (std::set<std::string>{"manifest.json"}));
}

TEST(OutputNames, WindplanNamesAndTheirTemporaries) {
  EXPECT_TRUE(is_windplan_output_name("toolpath.gcode"));
  EXPECT_TRUE(is_windplan_output_name("fibre_path.csv.tmp.1234"));
  EXPECT_FALSE(is_windplan_output_name("fibre_path.csv.tmp."));
  EXPECT_FALSE(is_windplan_output_name("notes.txt.tmp.12"));
  EXPECT_FALSE(is_windplan_output_name("thesis.tex"));
}

}  // namespace
}  // namespace windplan
