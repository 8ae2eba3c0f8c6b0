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
  // Beside the folder: nothing, no staging or old set, no lock file.
  EXPECT_EQ(names(root_), (std::set<std::string>{"job"}));
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
  {
    OutputSet set(dir);
    write_text_atomically(set.staging() / "report.md", "old\n");
    set.commit(Manifest{}, {"report.md"});
  }
  {
    OutputSet set(dir);
    write_text_atomically(set.staging() / "report.md", "new\n");
    // No commit: an exception in the export.
  }
  EXPECT_EQ(read_text_file(dir / "report.md"), "old\n");
  EXPECT_EQ(names(root_), (std::set<std::string>{"job"}));
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
    EXPECT_NE(std::string(e.what()).find("holds 2 files windplan did not write: report.md, "
                                         "thesis.tex (no manifest.json)"),
              std::string::npos)
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
  // A user's file in a leftover folder is not windplan's to remove: it stays, with its folder.
  fs::create_directories(root_ / ".job.old.999998");
  write_text_atomically(root_ / ".job.old.999998" / "mine.txt", "mine");
  write_text_atomically(root_ / ".job.lock", "999999\n");  // left by a SIGKILL, not held
  {
    OutputSet set(dir);
    Manifest m;
    set.commit(m, {});
  }
  EXPECT_EQ(names(root_), (std::set<std::string>{"job", ".job.old.999998"}));
  EXPECT_EQ(read_text_file(root_ / ".job.old.999998" / "mine.txt"), "mine");
  EXPECT_EQ(names(dir), (std::set<std::string>{"manifest.json"}));
}

// Issue 28: a folder holding only a user's report.md and axes.csv (windplan's names, no
// manifest) was replaced and the files lost.
TEST_F(OutputSetTest, WindplanNamesWithoutAManifestAreNotReplaced) {
  const fs::path dir = root_ / "mine";
  fs::create_directories(dir);
  write_text_atomically(dir / "report.md", "my notes\n");
  write_text_atomically(dir / "axes.csv", "1,2\n");
  try {
    OutputSet set(dir);
    FAIL() << "a folder without a manifest was taken";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("axes.csv, report.md (no manifest.json)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(read_text_file(dir / "report.md"), "my notes\n");
  EXPECT_EQ(names(root_), (std::set<std::string>{"mine"}));  // no lock file left
}

// Issue 28: a manifest.json listing a user's thesis.docx made `run` delete it. Forged with the
// file's true size and hash: the name is not one windplan writes, so it is still refused.
TEST_F(OutputSetTest, AForgedManifestNeverMakesAUsersFileDeletable) {
  const fs::path dir = root_ / "docs";
  fs::create_directories(dir);
  write_text_atomically(dir / "thesis.docx", "chapter 1\n");
  Manifest m;
  m.job = "forged";
  m.files.push_back(manifest_entry(dir / "thesis.docx", "thesis.docx", false));
  write_text_atomically(dir / "manifest.json", manifest_json(m));
  try {
    OutputSet set(dir);
    FAIL() << "a forged manifest was trusted";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("did not write: thesis.docx (listed, but not a name "
                                         "windplan writes)"),
              std::string::npos)
        << e.what();
  }
  // Listing it under a name windplan writes, with a hash that is not the file's.
  write_text_atomically(dir / "report.md", "my report\n");
  m.files.clear();
  ManifestEntry e = manifest_entry(dir / "report.md", "report.md", false);
  e.sha256 = sha256_hex("something else");
  m.files.push_back(e);
  write_text_atomically(dir / "manifest.json", manifest_json(m));
  try {
    OutputSet set(dir);
    FAIL() << "a manifest with a wrong hash was trusted";
  } catch (const IoError& err) {
    EXPECT_NE(std::string(err.what())
                  .find("report.md, thesis.docx (changed since windplan wrote "
                        "it; not listed in manifest.json)"),
              std::string::npos)
        << err.what();
  }
  EXPECT_EQ(read_text_file(dir / "thesis.docx"), "chapter 1\n");
  EXPECT_EQ(read_text_file(dir / "report.md"), "my report\n");
  EXPECT_EQ(names(root_), (std::set<std::string>{"docs"}));
}

TEST_F(OutputSetTest, AnEditedOrIncompleteSetIsNotReplaced) {
  const fs::path dir = root_ / "job";
  for (int round = 0; round < 2; ++round) {
    {
      std::error_code ec;
      fs::remove_all(dir, ec);
      OutputSet set(dir);
      write_text_atomically(set.staging() / "report.md", "windplan's\n");
      write_text_atomically(set.staging() / "axes.csv", "t,x\n");
      set.commit(Manifest{}, {"report.md", "axes.csv"});
    }
    if (round == 0) {
      write_text_atomically(dir / "report.md", "my edits\n");
      EXPECT_THROW(OutputSet set(dir), IoError);
      EXPECT_EQ(read_text_file(dir / "report.md"), "my edits\n");
    } else {
      fs::remove(dir / "axes.csv");
      try {
        OutputSet set(dir);
        FAIL();
      } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("lists axes.csv, missing from the folder"),
                  std::string::npos)
            << e.what();
      }
    }
  }
  EXPECT_EQ(names(root_), (std::set<std::string>{"job"}));
}

// A file put into the folder while the run plans: checked again before the swap.
TEST_F(OutputSetTest, AFileAddedDuringTheRunIsNeverRemoved) {
  const fs::path dir = root_ / "job";
  {
    OutputSet set(dir);
    write_text_atomically(set.staging() / "report.md", "1\n");
    set.commit(Manifest{}, {"report.md"});
  }
  {
    OutputSet set(dir);
    write_text_atomically(set.staging() / "report.md", "2\n");
    write_text_atomically(dir / "notes.txt", "mine\n");
    EXPECT_THROW(set.commit(Manifest{}, {"report.md"}), IoError);
  }
  EXPECT_EQ(read_text_file(dir / "notes.txt"), "mine\n");
  EXPECT_EQ(read_text_file(dir / "report.md"), "1\n");
  EXPECT_EQ(names(root_), (std::set<std::string>{"job"}));
}

TEST_F(OutputSetTest, LinksAndMountPointsAreRefusedBeforeAnythingIsCreated) {
  fs::create_symlink(root_ / "nowhere", root_ / "dangling");
  try {
    OutputSet set(root_ / "dangling");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("is a symbolic link to nothing"), std::string::npos)
        << e.what();
  }
  fs::create_directories(root_ / "real");
  fs::create_symlink(root_ / "real", root_ / "link");
  EXPECT_THROW(OutputSet set(root_ / "link"), IoError);
  EXPECT_EQ(names(root_), (std::set<std::string>{"dangling", "link", "real"}));
  EXPECT_THROW(OutputSet set(""), IoError);
  if (fs::is_directory("/proc/self")) {
    try {
      OutputSet set("/proc");
      FAIL();
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find("/proc: is a mount point"), std::string::npos)
          << e.what();
    }
    EXPECT_FALSE(fs::exists("/.proc.lock"));
  }
}

TEST(ManifestFiles, ReadsWhatManifestJsonWritesAndNothingElse) {
  Manifest m;
  m.job = "j";
  m.files.push_back({"report.md", "", 12, std::string(64, 'a')});
  m.files.push_back({"odd \"name\"\x01", "", 0, std::string(64, '0')});
  std::vector<ManifestEntry> f;
  ASSERT_TRUE(parse_manifest_files(manifest_json(m), &f));
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[1].name, "odd \"name\"\x01");
  EXPECT_EQ(f[0].size, 12u);
  EXPECT_TRUE(parse_manifest_files(manifest_json(Manifest{}), &f));
  EXPECT_TRUE(f.empty());
  m.files.push_back(m.files[0]);  // a name twice
  EXPECT_FALSE(parse_manifest_files(manifest_json(m), &f));
  m.files.pop_back();
  m.files[0].sha256 = "abc";
  EXPECT_FALSE(parse_manifest_files(manifest_json(m), &f));
  m.files[0].sha256 = std::string(64, 'a');
  m.files[0].name = "../x";
  EXPECT_FALSE(parse_manifest_files(manifest_json(m), &f));
  EXPECT_FALSE(parse_manifest_files("{\"windplan_manifest\": 1, \"files\": []}", &f));
  EXPECT_FALSE(parse_manifest_files(manifest_json(Manifest{}) + "x", &f));
}

TEST(OutputNames, WindplanNamesAndTheirTemporaries) {
  EXPECT_TRUE(is_windplan_output_name("toolpath.gcode"));
  EXPECT_TRUE(is_windplan_output_name("fibre_path.csv.tmp.1234"));
  EXPECT_FALSE(is_windplan_output_name("fibre_path.csv.tmp."));
  EXPECT_FALSE(is_windplan_output_name("notes.txt.tmp.12"));
  EXPECT_FALSE(is_windplan_output_name("thesis.tex"));
}

// The files of robot cells (export/robot) and of design: jobs (export/files/fea_deck.h) are
// windplan's: a second run of such a job into its own folder replaces them.
TEST(OutputNames, RobotProgramsAndDesignFiles) {
  for (const char* n : {"wp_bent_tube.src", "wp_bent_tube_p03.dat", "wp_elbow_robot_p01.mod",
                        "joints.csv", "joints.svg", "model.inp", "model_plies.csv", "design.md"}) {
    EXPECT_TRUE(is_windplan_output_name(n)) << n;
  }
  for (const char* n : {"wp_.src", "wp_a b.src", "wp_job.txt", "xp_job.src", "wp_../x.mod"}) {
    EXPECT_FALSE(is_windplan_output_name(n)) << n;
  }
}

}  // namespace
}  // namespace windplan
