// Robot cells through the command line: run writes a KRL or RAPID program and joints.csv, simulate
// reads the program back and replays it, an edited target is caught at its line, and bad input
// (an unknown dialect, a cell whose mandrel is out of reach, a malformed program) is one line,
// exit 1.
#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

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

std::string slurp_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// `text` with the first `from` replaced by `to` (the test fails when `from` is absent).
std::string edit(std::string text, const std::string& from, const std::string& to) {
  const std::size_t p = text.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  if (p != std::string::npos) text.replace(p, from.size(), to);
  return text;
}

void expect_one_line(const RunResult& r, const std::string& says) {
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// Edited KRL and RAPID programs (docs/bad_inputs.md, "Third round"): one line naming the file and
// line, exit 1, and no JSON report. Before: a part called 3000 times read and replayed it for
// more than 60 s; a second declaration of a name silently replaced the first (TOOL_EYE: exit 0);
// S or cfx 1e300 went through an undefined int cast; A 1e300, \T 1e300, $VEL.CP 1e300 were taken.
TEST_F(CliRobot, BadRobotProgramsAreOneLineExitOne) {
  for (const std::string dialect : {"krl", "rapid"}) {
    SCOPED_TRACE(dialect);
    write_job(", dialect: " + dialect);
    const fs::path out = dir_ / ("out_" + dialect);
    ASSERT_EQ(run({"run", (dir_ / "job.yaml").string(), "--out", out.string()}).code, 0);
    const bool krl = dialect == "krl";
    const std::string main = krl ? "wp_cell.src" : "wp_cell.mod";
    const std::string part = krl ? "wp_cell_p01.src" : "wp_cell_p01.mod";
    const std::string data = krl ? "wp_cell_p01.dat" : "wp_cell_p01.mod";
    struct Case {
      std::string file, from, to, says;
    };
    const std::string call = krl ? "wp_cell_p01( )\n" : "    wp_cell_p01;\n";
    std::vector<Case> cases = {
        {main, call, call + call,
         main + ":" + (krl ? "11" : "8") + ": calls wp_cell_p01, which runs already (called on " +
             main + ":" + (krl ? "10" : "7") + ")"},
    };
    std::string many;
    for (int i = 0; i < 3000; ++i) many += call;
    cases.push_back({main, call, many, "calls wp_cell_p01, which runs already"});
    if (krl) {
      const std::string xp5 = "DECL E6POS XP5={X -62.4991,Y 3.6861,Z -69.9980,A -90.0000";
      cases.push_back({part, "PTP XP1\n", "PTP XP1\nwp_cell_p01( )\n",
                       part + ":6: calls wp_cell_p01, which runs already"});
      cases.push_back({part, "PTP XP1\n", "PTP XP1\nwp_cell( )\n",
                       part + ":6: calls wp_cell, which runs already (the main program)"});
      cases.push_back({data, "DECL E6POS XP6=", "DECL E6POS XP5=",
                       data + ":9: 'XP5' is declared a second time (first on " + data + ":8)"});
      cases.push_back({"wp_cell.dat", "ENDDAT",
                       "DECL FRAME TOOL_EYE={X 0,Y 0,Z 0,A 0,B 0,C 0}\nENDDAT",
                       "'TOOL_EYE' is declared a second time (first on wp_cell.dat:4)"});
      cases.push_back({data, xp5 + ",B 0.0000,C 0.0000,S 6", xp5 + ",B 0.0000,C 0.0000,S 1e300",
                       "XP5's S = 1e+300: a status is"});
      cases.push_back({data, xp5, "DECL E6POS XP5={X -62.4991,Y 3.6861,Z -69.9980,A 1e300",
                       "component A = 1e+300 deg: an orientation angle lies within"});
      cases.push_back(
          {data, "XP5={X -62.4991", "XP5={X 1e300", "component X = 1e+300 mm is beyond 100 m"});
      cases.push_back(
          {data, "XP5={X -62.4991", "XP5={X nan", data + ":8: component X: 'nan' is not a number"});
      cases.push_back({data, ",E1 -142.4199", "", "XP5 has no E1 (the positioner)"});
      cases.push_back({part, "$VEL.CP = 0.048941403", "$VEL.CP = 1e300",
                       part + ":6: $VEL.CP = 1e300 m/s: a path speed lies within"});
      cases.push_back({main, "$VEL_EXTAX[1] = 100", "$VEL_EXTAX[1] = 0",
                       main + ":8: $VEL_EXTAX[1] must be in (0, 100]"});
      cases.push_back({main, "$VEL_EXTAX[1] = 100", "$VEL_EXTAX[1] = -5",
                       main + ":8: $VEL_EXTAX[1] must be in (0, 100]"});
    } else {
      cases.push_back({main, "  PROC main",
                       "  PERS tooldata tEye := [TRUE,[[0,0,0],[1,0,0,0]],[1,[0,0,50],[1,0,0,0],"
                       "0,0,0]];\n  PROC main",
                       main + ":6: 'tEye' is declared a second time (first on " + main + ":4)"});
      cases.push_back({part, "[0,0,-1,6],[-142.4199", "[0,0,-1,1e300],[-142.4199",
                       "cfx = 1e+300: a status is a whole number 0 to 7"});
      cases.push_back({part, "T:=0.044756", "T:=1e300", "\\T = 1e+300 s: one move of more"});
      cases.push_back({part, "[[-62.4991", "[[1e300", "robtarget pos[0] = 1e+300 mm is beyond"});
      cases.push_back({part, "PROC wp_cell_p01()\n", "PROC wp_cell_p01()\n    wp_cell_p01;\n",
                       part + ":4: 'wp_cell_p01': a part calls no other module"});
    }
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const Case& c = cases[i];
      SCOPED_TRACE(c.says);
      const fs::path d = dir_ / (dialect + "_case" + std::to_string(i));
      fs::create_directories(d);
      for (const auto& e : fs::directory_iterator(out)) {
        if (e.path().filename().string().rfind("wp_cell", 0) == 0)
          fs::copy_file(e.path(), d / e.path().filename());
      }
      const std::string edited = edit(slurp_text(d / c.file), c.from, c.to);
      std::ofstream(d / c.file, std::ios::trunc) << edited;
      const RunResult r = run({"simulate", (dir_ / "job.yaml").string(), (d / main).string(),
                               "--json", (d / "sim.json").string()});
      expect_one_line(r, c.says);
      EXPECT_FALSE(fs::exists(d / "sim.json"));
    }
    // A part that is missing, a directory or a link to /dev/zero.
    const fs::path d = dir_ / (dialect + "_files");
    fs::create_directories(d);
    fs::copy_file(out / main, d / main);
    if (krl) fs::copy_file(out / "wp_cell.dat", d / "wp_cell.dat");
    RunResult r = run({"simulate", (dir_ / "job.yaml").string(), (d / main).string()});
    expect_one_line(r, main + ":" + (krl ? "10" : "7") + ": calls wp_cell_p01, but " +
                           (d / part).string() + " is missing");
    fs::create_directories(d / part);
    r = run({"simulate", (dir_ / "job.yaml").string(), (d / main).string()});
    expect_one_line(r, (d / part).string() + ": is a directory, not a file");
    fs::remove(d / part);
    fs::create_symlink("/dev/zero", d / part);
    r = run({"simulate", (dir_ / "job.yaml").string(), (d / main).string()});
    expect_one_line(r, (d / part).string() + ": is a character device");
  }
}

// Cell profiles (docs/bad_inputs.md, "Third round"): one line naming the profile file and key, or
// the job's key, exit 1, before planning. Before: a tool or arm origin of 1e300 mm and a home pose
// outside its joint's limits were blamed on the positioner's frame (after 38 s for the origin);
// joint limits of +-1e300 deg and e1_max_velocity 1e300 deg/s were taken; an arm profile that is a
// mesh was "the job file".
TEST_F(CliRobot, BadCellProfilesAreOneLineExitOne) {
  const std::string arm = slurp_text(source_dir() / "configs" / "machines" / "kuka_kr16_2.yaml");
  const std::string pos =
      slurp_text(source_dir() / "configs" / "machines" / "positioner_1axis.yaml");
  auto profile = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  };
  struct Case {
    std::string keys, says;
  };
  const std::vector<Case> cases = {
      {", tool: {xyz: [1e300, 0, 0], abc: [0, 0, 0]}",
       "job.yaml:6: key 'machine.robot.tool.xyz': 1e+300 mm is beyond 100 m"},
      {", tool: {xyz: [250, 0, 0], abc: [1e300, 0, 0]}",
       "job.yaml:6: key 'machine.robot.tool.abc': 1e+300 deg: an orientation angle"},
      {", tool: {xyz: [.nan, 0, 0], abc: [0, 0, 0]}", "key 'machine.robot.tool.xyz'"},
      {", arm: " +
           profile("origin.yaml", edit(arm, "origin: [260, 0, 0]", "origin: [1e300, 0, 0]")),
       "origin.yaml:11: key 'joints[1].origin': 1e+300 mm is beyond 10 m"},
      {", arm: " + profile("limits.yaml", edit(arm, "min: -350, max: 350, max_velocity: 615",
                                               "min: -1e300, max: 1e300, max_velocity: 615")),
       "limits.yaml:15: key 'joints[5].min': a joint limit lies within -720 to 720 deg"},
      {", arm: " + profile("home.yaml", edit(arm, "home: [0, -90, 90, 0, 45, 0]",
                                             "home: [0, -90, 90, 0, 45, 900]")),
       "home.yaml:17: key 'home': element 5 (900 deg) is outside A6's limits [-350, 350] deg"},
      {", arm: " + profile("zero.yaml", edit(arm, "min: -130, max: 130", "min: 0, max: 0")),
       "zero.yaml:14: key 'joints[4].max': must be > min"},
      {", arm: " + (source_dir() / "configs" / "meshes" / "tube.obj").string(),
       "tube.obj: the arm profile must be a YAML map of keys"},
      {", arm: " + (source_dir() / "configs" / "machines" / "positioner_1axis.yaml").string(),
       "key 'joints': needs 6 revolute joints (got 0)"},
      {", positioner: " +
           profile("fast.yaml", edit(pos, "e1_max_velocity: 180", "e1_max_velocity: 1e300")),
       "fast.yaml:9: key 'e1_max_velocity': 1e+300 deg/s is beyond 3600 deg/s"},
      {", positioner: " +
           profile("still.yaml", edit(pos, "e1_max_velocity: 180", "e1_max_velocity: 0")),
       "still.yaml:9: key 'e1_max_velocity': must be > 0 deg/s"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.says);
    write_job(c.keys);
    const RunResult r = run({"run", (dir_ / "job.yaml").string(), "--out", (dir_ / "o").string()});
    expect_one_line(r, c.says);
    EXPECT_FALSE(fs::exists(dir_ / "o"));
  }
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
