// Robot cells through the command line: run writes a KRL or RAPID program and joints.csv, simulate
// reads the program back and replays it, an edited target is caught at its line, and bad input
// (an unknown dialect, a cell whose mandrel is out of reach, a malformed program) is one line,
// exit 1.
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "tests/cli/cli_runner.h"
#include "tests/test_data.h"

namespace windplan::test {
namespace {

namespace fs = std::filesystem;

std::string job(const std::string& robot_keys, double offset = -100) {
  return "name: cell\n"
         "mandrel: {source: pipe, pipe: {radius: 50, length: 200}}\n"
         "winding: {turns: 1, circuits: 2}\n"
         "machine:\n  profile: " +
         (source_dir() / "configs" / "machines" / "robot_cell_kr16.yaml").string() +
         "\n  robot: {offset: " + std::to_string(offset) + robot_keys + "}\n";
}

class CliRobot : public CliTest {
 protected:
  void write_job(const std::string& keys, double offset = -100) {
    std::ofstream(dir_ / "job.yaml") << job(keys, offset);
  }
};

TEST_F(CliRobot, RunWritesKrlThatSimulateReplays) {
  write_job("");
  const fs::path out = dir_ / "out";
  const RunResult r = run({"run", (dir_ / "job.yaml").string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* f : {"wp_cell.src", "wp_cell.dat", "wp_cell_p01.src", "wp_cell_p01.dat",
                        "joints.csv", "joints.svg"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }
  const YAML::Node robot = YAML::LoadFile((out / "report.json").string())["robot"];
  ASSERT_TRUE(robot.IsMap());
  EXPECT_LT(robot["replay"]["max_deviation_mm"].as<double>(), 0.5);
  EXPECT_EQ(robot["configuration_changes_between_passes"].as<int>(), 0);
  const fs::path json = dir_ / "sim.json";
  const RunResult s = run({"simulate", (dir_ / "job.yaml").string(), (out / "wp_cell.src").string(),
                           "--json", json.string()});
  ASSERT_EQ(s.code, 0) << s.err;
  const YAML::Node j = YAML::LoadFile(json.string());
  EXPECT_EQ(j["dialect"].as<std::string>(), "krl");
  EXPECT_NEAR(j["max_deviation_mm"].as<double>(), robot["replay"]["max_deviation_mm"].as<double>(),
              1e-9);
  EXPECT_LT(j["max_eye_deviation_mm"].as<double>(), 0.001);
  // One target moved 5 mm along X: simulate names its line, exit 1.
  std::ifstream in(out / "wp_cell_p01.dat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t p = text.find("DECL E6POS XP40={X ");
  ASSERT_NE(p, std::string::npos);
  const std::size_t a = p + 19, b = text.find(',', a);
  text.replace(a, b - a, std::to_string(std::stod(text.substr(a, b - a)) + 5.0));
  fs::create_directories(dir_ / "edited");
  for (const auto& e : fs::directory_iterator(out)) {
    fs::copy_file(e.path(), dir_ / "edited" / e.path().filename());
  }
  std::ofstream(dir_ / "edited" / "wp_cell_p01.dat", std::ios::trunc) << text;
  const RunResult bad =
      run({"simulate", (dir_ / "job.yaml").string(), (dir_ / "edited" / "wp_cell.src").string(),
           "--json", (dir_ / "bad.json").string()});
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("wp_cell_p01.src:"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("puts the eye"), std::string::npos) << bad.err;
}

TEST_F(CliRobot, RapidDialect) {
  write_job(", dialect: rapid");
  const fs::path out = dir_ / "out";
  ASSERT_EQ(run({"run", (dir_ / "job.yaml").string(), "--out", out.string()}).code, 0);
  EXPECT_TRUE(fs::exists(out / "wp_cell.mod"));
  EXPECT_TRUE(fs::exists(out / "wp_cell_p01.mod"));
  const RunResult s = run({"simulate", (dir_ / "job.yaml").string(), (out / "wp_cell.mod").string(),
                           "--json", (dir_ / "s.json").string()});
  EXPECT_EQ(s.code, 0) << s.err;
}

TEST_F(CliRobot, BadInputIsOneLineExitOne) {
  write_job(", dialect: fanuc");
  RunResult r = run({"run", (dir_ / "job.yaml").string(), "--out", (dir_ / "o").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("machine.robot.dialect"), std::string::npos) << r.err;
  write_job("", 3000);  // the mandrel 3 m along the positioner axis: out of reach
  r = run({"run", (dir_ / "job.yaml").string(), "--out", (dir_ / "o").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("out of reach of the KUKA KR 16-2"), std::string::npos) << r.err;
  // A positioner 5 m in front of the robot: refused once the mandrel is built, before any
  // planning stage (export/robot/cell_reach.h), naming the profile, its frame and the point.
  std::ofstream(dir_ / "far_positioner.yaml")
      << "name: far\nframe: {xyz: [5000, 0, 500], abc: [90, 0, 0]}\n";
  write_job(", positioner: " + (dir_ / "far_positioner.yaml").string(), 0);
  r = run({"run", (dir_ / "job.yaml").string(), "--out", (dir_ / "o").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("far_positioner.yaml: frame with machine.robot.offset 0.0 mm puts the "
                       "mandrel out of reach of the KUKA KR 16-2: the eye at"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("beyond the arm's full stretch"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("mandrel  done"), std::string::npos) << r.err;
  for (const char* stage : {"girth", "helices", "metrics", "export"})
    EXPECT_EQ(r.err.find(stage), std::string::npos) << stage << " ran: " << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "o" / "report.json"));
  write_job("");
  std::ofstream(dir_ / "p.src") << "DEF p( )\nLIN XP1\nEND\n";
  r = run({"simulate", (dir_ / "job.yaml").string(), (dir_ / "p.src").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("p.src:2"), std::string::npos) << r.err;
}

// Reach over the laminate: a cell whose positioner holds the pipe high (axis 1200 mm up, the eye
// above it) reaches the bare 50 mm pipe, but the helical layer's laminate (20 mm bands) puts the
// hoop layer's eye out of reach. Refused once that layer's surface is built, before it is
// planned: one line naming the layer, exit 1, no output.
TEST_F(CliRobot, ALaminateOutOfReachIsOneLineExitOne) {
  std::ofstream(dir_ / "high.yaml")
      << "name: high\nframe: {xyz: [900, 0, 1200], abc: [90, 0, 90]}\ne1_max_velocity: 180\n";
  std::ofstream(dir_ / "job.yaml")
      << "name: thick\n"
         "mandrel: {source: pipe, angular_deflection: 3, pipe: {radius: 50, length: 300}}\n"
         "material: {tex: 2400, fibre_density: 1.8, resin_density: 1.2,\n"
         "           fibre_volume_fraction: 0.6, band_thickness: 20}\n"
         "winding: {turns: 2, circuits: auto, band_width: 16}\n"
         "layers:\n  - {kind: helical, name: inner}\n  - {kind: hoop, name: outer}\n"
         "machine:\n  profile: "
      << (source_dir() / "configs" / "machines" / "robot_cell_kr16.yaml").string()
      << "\n  robot: {offset: -150, positioner: " << (dir_ / "high.yaml").string() << "}\n";
  const RunResult r = run({"run", (dir_ / "job.yaml").string(), "--out", (dir_ / "o").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("high.yaml: frame with machine.robot.offset -150.0 mm puts the laminate "
                       "under layers[1] (outer) out of reach of the KUKA KR 16-2: the eye at"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("inner    done"), std::string::npos) << r.err;  // the mandrel was reached
  EXPECT_EQ(r.err.find("outer    done"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("export"), std::string::npos) << r.err;
  std::size_t errors = 0;
  for (std::size_t p = r.err.find("error:"); p != std::string::npos;
       p = r.err.find("error:", p + 1))
    ++errors;
  EXPECT_EQ(errors, 1u) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "o" / "report.json"));
}

}  // namespace
}  // namespace windplan::test
