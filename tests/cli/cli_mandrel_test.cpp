// `windplan mandrel` run as a subprocess (WINDPLAN_BINARY): the JSON report is pure JSON (no
// OpenCASCADE banner on stdout, even when reading STEP), files are written, errors exit 1 with
// one line naming the key or file, usage errors exit 2.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "geometry/cad/cad_import.h"
#include "geometry/mesh/mesh_io.h"
#include "tests/test_data.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int code = -1;
  std::string out, err;
};

class MandrelCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("windplan_mandrel_cli_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  static std::string q(const std::string& s) {
    std::string r = "'";
    for (char c : s) r += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return r + "'";
  }
  CliRun run(const std::vector<std::string>& args) const {
    std::string cmd = q(WINDPLAN_BINARY) + " mandrel";
    for (const auto& a : args) cmd += " " + q(a);
    cmd += " >" + q((dir_ / "out.txt").string()) + " 2>" + q((dir_ / "err.txt").string());
    const int status = std::system(cmd.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(dir_ / "out.txt"),
            slurp(dir_ / "err.txt")};
  }
  fs::path dir_;
};

std::string config(const std::string& name) {
  return (test::source_dir() / "configs" / name).string();
}

TEST_F(MandrelCli, JsonIsPureAndComplete) {
  for (const char* job : {"vessel.yaml", "vessel_step.yaml", "pipe.yaml"}) {
    const CliRun r = run({config(job), "--json"});
    ASSERT_EQ(r.code, 0) << job << ": " << r.err;
    ASSERT_FALSE(r.out.empty());
    EXPECT_EQ(r.out.front(), '{') << "stdout must start with the JSON object: "
                                  << r.out.substr(0, 200);
    EXPECT_EQ(r.out.substr(r.out.size() - 2), "}\n");
    const YAML::Node j = YAML::Load(r.out);  // JSON is YAML
    EXPECT_TRUE(j["mesh"]["closed"].as<bool>()) << job;
    EXPECT_TRUE(j["mesh"]["manifold"].as<bool>()) << job;
    EXPECT_TRUE(j["mesh"]["oriented"].as<bool>()) << job;
    ASSERT_EQ(j["winding_surface"]["loops"].size(), 2u);
    EXPECT_EQ(j["winding_surface"]["loops"][0]["role"].as<std::string>(), "start");
    EXPECT_GT(j["timings_ms"]["tessellation"].as<double>(), 0.0);
  }
}

TEST_F(MandrelCli, WritesMeshesAndStep) {
  const fs::path mesh = dir_ / "vessel.ply", annulus = dir_ / "annulus.obj",
                 step = dir_ / "vessel.step";
  const CliRun r = run({config("pipe.yaml"), "-o", mesh.string(), "--winding", annulus.string(),
                        "--step", step.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("start loop"), std::string::npos) << r.out;
  EXPECT_EQ(read_mesh(mesh).triangles.size() > read_mesh(annulus).triangles.size(), true);
  const CadImport back = import_cad(step);
  EXPECT_TRUE(back.is_solid && back.closed);
}

TEST_F(MandrelCli, ErrorsNameTheKeyOrFile) {
  std::ofstream(dir_ / "bad.yaml")
      << "mandrel:\n  source: bent_tube\n  bent_tube: {radius: 25, segments: [100, 100], "
         "bends: [{angle: 90, radius: 20}]}\n";
  const CliRun r = run({(dir_ / "bad.yaml").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("bends[0].radius"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(r.out.empty());

  std::ofstream(dir_ / "text.step") << "just text\n";
  std::ofstream(dir_ / "cad.yaml") << "mandrel: {source: cad, file: text.step}\n";
  const CliRun c = run({(dir_ / "cad.yaml").string(), "--json"});
  EXPECT_EQ(c.code, 1);
  EXPECT_NE(c.err.find("text.step"), std::string::npos) << c.err;
  EXPECT_TRUE(c.out.empty()) << c.out;

  EXPECT_EQ(run({}).code, 2);
  EXPECT_EQ(run({config("pipe.yaml"), "--nope"}).code, 2);
}

// A mandrel whose wound region is not an annulus (an elliptical canister with a bore and screw
// tabs): the candidate table on stdout, one error line naming mandrel.region on stderr, exit 1.
TEST_F(MandrelCli, NonAnnulusPrintsTheRegionTableAndTheSuggestedKeys) {
  std::ofstream(dir_ / "canister.yaml")
      << "mandrel:\n  source: section\n  section: {shape: ellipse, semi_axes: [80, 50], "
         "length: 300}\n  features:\n    bore: 20\n    tabs:\n"
         "      - {at: 10, count: 2, reach: 25, width: 20, thickness: 8, hole_radius: 4}\n"
         "      - {at: 282, count: 2, reach: 25, width: 20, thickness: 8, hole_radius: 4}\n";
  const CliRun r = run({(dir_ / "canister.yaml").string(), "-o", (dir_ / "canister.ply").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.out.find("loops  around  genus"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("suggested (under mandrel:): region: {start: "), std::string::npos) << r.out;
  // Six candidates: the wall with its tabs, the bore, four tab undersides.
  for (const char* row : {"\n    1 ", "\n    2 ", "\n    6 "}) {
    EXPECT_NE(r.out.find(row), std::string::npos) << row << "\n" << r.out;
  }
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("Candidate regions: #1"), std::string::npos) << r.err;
  const std::size_t k = r.err.find("Set mandrel.region: {start: ");
  ASSERT_NE(k, std::string::npos) << r.err;
  // The story: the same canister as a closed mesh file (written by -o even though it
  // cannot be wound) fails the same way, and winds with the suggested keys.
  ASSERT_TRUE(fs::exists(dir_ / "canister.ply"));
  const std::string mesh_job =
      "mandrel:\n  source: mesh\n  file: canister.ply\n"
      "  axis: {origin: [0, 0, 0], direction: [0, 0, 1]}\n";
  std::ofstream(dir_ / "mesh.yaml") << mesh_job;
  const CliRun m = run({(dir_ / "mesh.yaml").string()});
  EXPECT_EQ(m.code, 1);
  EXPECT_NE(m.err.find(r.err.substr(k, r.err.find('}', k) - k)), std::string::npos) << m.err;
  double a = 0, b = 0;
  ASSERT_EQ(std::sscanf(r.err.c_str() + k, "Set mandrel.region: {start: %lf, end: %lf}", &a, &b),
            2);
  std::ofstream(dir_ / "mesh.yaml")
      << mesh_job << "  region: {start: " << a << ", end: " << b << "}\n";
  const CliRun w = run({(dir_ / "mesh.yaml").string()});
  EXPECT_EQ(w.code, 0) << w.err;
  EXPECT_NE(w.out.find("annulus"), std::string::npos) << w.out;
}

TEST_F(MandrelCli, RegionIsReportedInJson) {
  const CliRun r = run({config("flanged_pipe.yaml"), "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const YAML::Node j = YAML::Load(r.out);
  EXPECT_EQ(j["region"]["start"].as<double>(), 20.0);
  EXPECT_EQ(j["region"]["end"].as<double>(), 480.0);
  ASSERT_EQ(j["regions"].size(), 2u) << "the wall and the bore between the planes";
  EXPECT_TRUE(j["regions"][0]["wound"].as<bool>());
  EXPECT_NEAR(j["regions"][0]["radius_min"].as<double>(), 50.0, 0.01);
  EXPECT_NEAR(j["profile"]["max_radius"].as<double>(), 90.0, 0.01) << "the flanges count";
}

TEST_F(MandrelCli, RegionAndSectionErrorsAreOneLineNamingTheKey) {
  struct Case {
    const char* yaml;
    const char* key;
  };
  for (const Case& c :
       {Case{"mandrel:\n  source: pipe\n  pipe: {radius: 50, length: 500}\n"
             "  region: {start: 600, end: 700}\n",
             "mandrel.region: the range [600, 700] mm misses the mandrel"},
        Case{"mandrel:\n  source: pipe\n  pipe: {radius: 50, length: 500}\n"
             "  axis: {origin: [300, 0, 0], direction: [0, 0, 1]}\n"
             "  region: {start: 100, end: 400}\n",
             "goes around the spindle axis"},
        Case{"mandrel:\n  source: section\n  section: {shape: rounded_rectangle, width: 100, "
             "height: 200, corner_radius: 60, length: 300}\n",
             "corner_radius (60 mm) must be at most half"},
        Case{"mandrel:\n  source: pipe\n  pipe: {radius: 50, length: 500}\n"
             "  region: {start: 100, end: 400, component: 3}\n",
             "mandrel.region.component: 3 is out of range"}}) {
    std::ofstream(dir_ / "bad.yaml") << c.yaml;
    const CliRun r = run({(dir_ / "bad.yaml").string()});
    EXPECT_EQ(r.code, 1) << c.yaml;
    EXPECT_NE(r.err.find(c.key), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

// Two open tubes one after the other along the axis (a mesh file): a range over both holds two
// surfaces around the axis and neither nests in the other; the error asks for
// mandrel.region.component, and the component chosen winds.
TEST_F(MandrelCli, RegionOverTwoTubesNeedsAComponent) {
  std::ofstream obj(dir_ / "two_tubes.obj");
  const int n = 48;
  for (int tube = 0; tube < 2; ++tube) {
    for (int ring = 0; ring < 2; ++ring) {
      for (int k = 0; k < n; ++k) {
        const double a = 2.0 * M_PI * k / n;
        obj << "v " << 40.0 * std::cos(a) << " " << 40.0 * std::sin(a) << " "
            << 300.0 * tube + 200.0 * ring << "\n";
      }
    }
  }
  for (int tube = 0; tube < 2; ++tube) {
    const int b = 1 + 2 * n * tube;  // OBJ indices are 1-based
    for (int k = 0; k < n; ++k) {
      const int k1 = (k + 1) % n;
      obj << "f " << b + k << " " << b + k1 << " " << b + n + k1 << "\n";
      obj << "f " << b + k << " " << b + n + k1 << " " << b + n + k << "\n";
    }
  }
  obj.close();
  const std::string job =
      "mandrel:\n  source: mesh\n  file: two_tubes.obj\n"
      "  axis: {origin: [0, 0, 0], direction: [0, 0, 1]}\n";
  std::ofstream(dir_ / "two.yaml") << job << "  region: {start: 100, end: 400}\n";
  const CliRun r = run({(dir_ / "two.yaml").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("choose one with mandrel.region.component"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  std::ofstream(dir_ / "two.yaml") << job << "  region: {start: 100, end: 400, component: 2}\n";
  const CliRun ok = run({(dir_ / "two.yaml").string(), "--json"});
  ASSERT_EQ(ok.code, 0) << ok.err;
  const YAML::Node j = YAML::Load(ok.out);
  EXPECT_TRUE(j["regions"][1]["wound"].as<bool>());
}

}  // namespace
}  // namespace windplan
