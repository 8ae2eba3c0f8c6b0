// windplan check-fea: what it refuses before any long work (exit 1, one line), and the whole
// round trip on a small design job when ccx is installed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/cli/cli_runner.h"

namespace windplan::test {
namespace {

namespace fs = std::filesystem;

bool have_ccx() { return std::system("command -v ccx > /dev/null 2>&1") == 0; }

// A short pipe sized for 2 MPa at +-45 deg: one helical layer, no hoop (above 54.74 deg: none;
// at 45 deg t_hoop / t_hel = 3 cos^2 - 1 = 0.5).
const char* const kPipe =
    "name: pipe_design\nmandrel:\n  source: pipe\n  pipe: {radius: 40, length: 200}\n"
    "winding: {circuits: 6, band_width: 10, angle: 60}\nmaterial: {tows: 2}\n";

class CliCheckFea : public CliTest {};

TEST_F(CliCheckFea, RefusesAJobWithoutDesignOrWithoutItsModel) {
  std::ofstream(dir_ / "plain.yaml") << "mandrel:\n  source: pipe\n  pipe: {radius: 40, length: "
                                        "200}\nwinding: {turns: 1, circuits: 4, band_width: 10}\n";
  RunResult r = run({"check-fea", (dir_ / "plain.yaml").string(), "--out", (dir_ / "o").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("design:"), std::string::npos) << r.err;
  std::ofstream(dir_ / "d.yaml") << kPipe << "design: {pressure: 2, fibre_strength: 4000}\n";
  r = run({"check-fea", (dir_ / "d.yaml").string(), "--out", (dir_ / "none").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("model.inp is missing"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST_F(CliCheckFea, RunThenCheck) {
  if (!have_ccx()) GTEST_SKIP() << "ccx (calculix-ccx) is not installed";
  std::ofstream(dir_ / "d.yaml") << kPipe
                                 << "design: {pressure: 2, fibre_strength: 4000, fea_edge: 8}\n";
  const fs::path out = dir_ / "o";
  RunResult r = run({"run", (dir_ / "d.yaml").string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "model.inp"));
  EXPECT_TRUE(fs::exists(out / "design.md"));
  r = run({"check-fea", (dir_ / "d.yaml").string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("first-ply failure factor"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(fs::path(out.string() + ".fea") / "fea_check.md"));
  // A folder holding a file check-fea did not write is refused.
  std::ofstream(fs::path(out.string() + ".fea") / "mine.txt") << "x";
  r = run({"check-fea", (dir_ / "d.yaml").string(), "--out", out.string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("mine.txt"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace windplan::test
