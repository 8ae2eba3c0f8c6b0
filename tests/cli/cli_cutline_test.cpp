// windplan cutline as a subprocess (WINDPLAN_BINARY): exit codes, stdout, stderr, the CSV file.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/test_data.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

class CutlineCli : public ::testing::Test {
 protected:
  struct Result {
    int code = -1;
    std::string out, err;
  };
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("windplan_cutline_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  static std::string sh(const std::string& s) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  }
  Result run(const std::vector<std::string>& args) const {
    std::string cmd = sh(WINDPLAN_BINARY) + " cutline";
    for (const std::string& a : args) cmd += " " + sh(a);
    cmd += " >" + sh((dir_ / "out").string()) + " 2>" + sh((dir_ / "err").string());
    const int status = std::system(cmd.c_str());
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read(dir_ / "out");
    r.err = read(dir_ / "err");
    return r;
  }
  fs::path dir_;
};

const std::string kVessel = (test::source_dir() / "configs/vessel.yaml").string();

TEST_F(CutlineCli, JobCutlinesAsJsonAndCsv) {
  const fs::path csv = dir_ / "cut.csv";
  const Result r = run({kVessel, "--json", "-o", csv.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.front(), '{') << r.out;  // pure JSON on stdout
  EXPECT_NE(r.out.find("\"name\": \"split\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"name\": \"trim_oblique\""), std::string::npos) << r.out;
  const std::string text = read(csv);
  EXPECT_EQ(text.rfind("name,index,x [mm],y [mm],z [mm]\nsplit,0,", 0), 0u) << text.substr(0, 200);
  EXPECT_NE(text.find("\ntrim_oblique,0,"), std::string::npos);
}

TEST_F(CutlineCli, OneCutFromTheFlagsOnAMeshFile) {
  const std::string tube = (test::source_dir() / "configs/meshes/tube.obj").string();
  const Result r = run({tube, "--station", "0", "--name", "mid"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("cut-line mid: closed loop"), std::string::npos) << r.out;
}

TEST_F(CutlineCli, BadInputAndUsage) {
  Result r = run({kVessel, "--station", "900"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("misses the mandrel"), std::string::npos) << r.err;
  r = run({kVessel, "--plane", "0,0,0,1"});
  EXPECT_EQ(r.code, 2) << r.err;
  r = run({kVessel, "--plane", "0,0,1"});
  EXPECT_EQ(r.code, 2) << r.err;
  r = run({kVessel, "--name", "nope"});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("split, trim_oblique"), std::string::npos) << r.err;
  std::ofstream(dir_ / "bad.yaml")
      << "mandrel:\n  source: pipe\n  pipe: {radius: 50, length: 200}\n"
         "cutlines:\n  - {name: a, station: 10, colour: red}\n";
  r = run({(dir_ / "bad.yaml").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("bad.yaml:5: unknown key 'cutlines[0].colour'"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace windplan
