// windplan simulate and the machine section (profiles, limits) as subprocesses.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "tests/cli/cli_runner.h"
#include "tests/test_data.h"

namespace windplan::test {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

const char* const kJob =
    "name: small\n"
    "mandrel: {source: pipe, pipe: {radius: 50, length: 200}}\n"
    "winding: {turns: 1, circuits: 2}\n";

// Two helical layers on a pipe (lathe2, the default machine): each layer's stop names its eye
// radius.
const char* const kPipeLayupJob =
    "name: layup\n"
    "mandrel: {source: pipe, pipe: {radius: 50, length: 300}}\n"
    "material: {tex: 2400, fibre_density: 1.8, fibre_volume_fraction: 0.6, tows: 8}\n"
    "winding: {turns: 2, circuits: auto, band_width: 10}\n"
    "layers:\n  - {kind: helical, name: inner}\n  - {kind: helical, name: outer}\n"
    "machine: {replay_tolerance: 1}\n"
    "output: {ply: false, svg: false, viewer: false}\n";

class CliSimulate : public CliTest {};

TEST_F(CliSimulate, RunThenSimulateTheProgramWritesTheJson) {
  write(dir_ / "job.yaml", kJob);
  ASSERT_EQ(run({"run", (dir_ / "job.yaml").string(), "--out", (dir_ / "out").string()}).code, 0);
  const YAML::Node report = YAML::LoadFile((dir_ / "out" / "report.json").string());
  ASSERT_TRUE(report["motion"]["replay"]["max_deviation_mm"]);
  const RunResult r =
      run({"simulate", (dir_ / "job.yaml").string(), (dir_ / "out" / "toolpath.ngc").string(),
           "--json", (dir_ / "sim.json").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("replay:"), std::string::npos) << r.out;
  const YAML::Node j = YAML::LoadFile((dir_ / "sim.json").string());
  // The replay of the same program by the run and by simulate agree.
  EXPECT_DOUBLE_EQ(j["max_deviation_mm"].as<double>(),
                   report["motion"]["replay"]["max_deviation_mm"].as<double>());
  EXPECT_NEAR(j["wind_time_s"].as<double>(), report["summary"]["wind_time_s"].as<double>(), 1e-3);
  EXPECT_GT(j["blocks"].as<int>(), 10);
}

// A layup (two helical layers of thick tows on a pipe): simulate plans it as run does and walks
// each layer's circuits on the surface that layer was wound on, so both replays agree and stay
// within 1 mm (before: simulate replayed the layup's program against one layer on the bare
// mandrel and refused it).
TEST_F(CliSimulate, ALayupReplaysOnItsOwnSurfacesAsRunDoes) {
  write(dir_ / "layup.yaml", kPipeLayupJob);
  const RunResult w =
      run({"run", (dir_ / "layup.yaml").string(), "--out", (dir_ / "layup").string()});
  ASSERT_EQ(w.code, 0) << w.err;
  const YAML::Node report = YAML::LoadFile((dir_ / "layup" / "report.json").string());
  const double run_dev = report["motion"]["replay"]["max_deviation_mm"].as<double>();
  EXPECT_LT(run_dev, 1.0);
  const RunResult r =
      run({"simulate", (dir_ / "layup.yaml").string(), (dir_ / "layup" / "toolpath.ngc").string(),
           "--json", (dir_ / "layup.json").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const YAML::Node j = YAML::LoadFile((dir_ / "layup.json").string());
  EXPECT_DOUBLE_EQ(j["max_deviation_mm"].as<double>(), run_dev);
  // lathe2 (issue #26): the stop before the outer layer names its eye radius. Without it (an
  // older program, or a stop edited away) the outer layer is replayed on the mandrel's cylinder,
  // 16.32 mm from the surface it is wound on: exit 1, one line naming the program line (the
  // tolerance raised to 3 mm so that the clearance, not the 2.0 mm deviation, is what refuses it).
  std::ifstream in(dir_ / "layup" / "toolpath.ngc");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto stop = text.find("\nM0 (eye radius ");
  ASSERT_NE(stop, std::string::npos);
  text.erase(stop + 3, text.find('\n', stop + 1) - (stop + 3));
  write(dir_ / "old.ngc", text);
  std::ifstream job_in(dir_ / "layup.yaml");
  std::string job((std::istreambuf_iterator<char>(job_in)), std::istreambuf_iterator<char>());
  job.replace(job.find("replay_tolerance: 1"), 19, "replay_tolerance: 3");
  write(dir_ / "layup3.yaml", job);
  const RunResult old = run({"simulate", (dir_ / "layup3.yaml").string(),
                             (dir_ / "old.ngc").string(), "--json", (dir_ / "old.json").string()});
  EXPECT_EQ(old.code, 1);
  EXPECT_NE(old.err.find("old.ngc:"), std::string::npos) << old.err;
  EXPECT_NE(old.err.find(": the replay puts the eye 16.3"), std::string::npos) << old.err;
  EXPECT_NE(old.err.find("less than the clearance 20.000 mm"), std::string::npos) << old.err;
  EXPECT_EQ(std::count(old.err.begin(), old.err.end(), '\n'), 1) << old.err;
}

// A robot layup (two helical layers of thick tows on a pipe in the KR 16 cell): run writes a KRL
// program whose replay walks each layer on its own surface, and simulate plans the job as run does
// (before: it planned one layer on the bare mandrel, and the second layer's targets were refused
// as off the plan), so both replays agree.
TEST_F(CliSimulate, ARobotLayupReplaysOnItsOwnSurfacesAsRunDoes) {
  write(dir_ / "rlayup.yaml",
        "name: rlayup\n"
        "mandrel: {source: pipe, angular_deflection: 3, pipe: {radius: 50, length: 200}}\n"
        "material: {tex: 2400, fibre_density: 1.8, fibre_volume_fraction: 0.6, tows: 8}\n"
        "winding: {turns: 1, circuits: auto, band_width: 16}\n"
        "layers:\n  - {kind: helical, name: inner}\n  - {kind: helical, name: outer}\n"
        "machine: {profile: " +
            (source_dir() / "configs" / "machines" / "robot_cell_kr16.yaml").string() +
            ", replay_tolerance: 0.5}\n"
            "output: {ply: false, svg: false, viewer: false}\n");
  const RunResult w =
      run({"run", (dir_ / "rlayup.yaml").string(), "--out", (dir_ / "rlayup").string()});
  ASSERT_EQ(w.code, 0) << w.err;
  const YAML::Node report = YAML::LoadFile((dir_ / "rlayup" / "report.json").string());
  const double run_dev = report["motion"]["replay"]["max_deviation_mm"].as<double>();
  EXPECT_LT(run_dev, 0.5);
  const RunResult r = run({"simulate", (dir_ / "rlayup.yaml").string(),
                           (dir_ / "rlayup" / "wp_rlayup.src").string(), "--json",
                           (dir_ / "rlayup.json").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const YAML::Node j = YAML::LoadFile((dir_ / "rlayup.json").string());
  EXPECT_DOUBLE_EQ(j["max_deviation_mm"].as<double>(), run_dev);
  EXPECT_GT(j["min_eye_clearance_mm"].as<double>(), 19.0);  // 20 mm off the layer in work
}

TEST_F(CliSimulate, BadProgramsAreExitOneNamingTheLine) {
  write(dir_ / "job.yaml", kJob);
  write(dir_ / "unknown.ngc", "%\nG21 G90 G93\nG0 X0 A0\nG1 X1 A1 Q2 F10\nM2\n%\n");
  RunResult r = run({"simulate", (dir_ / "job.yaml").string(), (dir_ / "unknown.ngc").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("unknown.ngc:4: unknown word Q2"), std::string::npos) << r.err;
  write(dir_ / "marlin.gcode", "G21\nG90\nG94\nG0 X0 A0\nG92 A0\nG1 X1 A1 F100\nM84\n");
  r = run({"simulate", (dir_ / "job.yaml").string(), (dir_ / "marlin.gcode").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("marlin.gcode:5: G92 belongs to a marlin program"), std::string::npos)
      << r.err;
  write(dir_ / "limit.yaml", std::string(kJob) + "machine: {axes: {X: {min: -10, max: 100}}}\n");
  write(dir_ / "far.ngc", "G21 G90 G93\nG0 X0 A0\nG1 X120 A1 F10\nM2\n");
  r = run({"simulate", (dir_ / "limit.yaml").string(), (dir_ / "far.ngc").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("far.ngc:3: axis X moves to 120"), std::string::npos) << r.err;
}

TEST_F(CliSimulate, MachineProfilesAndTheirErrors) {
  // A shipped profile, with a job key overriding it.
  const fs::path machines = source_dir() / "configs" / "machines";
  write(dir_ / "job.yaml", std::string(kJob) +
                               "machine: {profile: " + (machines / "lathe4.yaml").string() +
                               ", gcode: {dialect: fanuc}}\n");
  ASSERT_EQ(run({"run", (dir_ / "job.yaml").string(), "--out", (dir_ / "out").string()}).code, 0);
  const YAML::Node report = YAML::LoadFile((dir_ / "out" / "report.json").string());
  EXPECT_EQ(report["machine"]["kind"].as<std::string>(), "lathe4");
  EXPECT_EQ(report["machine"]["dialect"].as<std::string>(), "fanuc");
  EXPECT_TRUE(fs::exists(dir_ / "out" / "toolpath.nc"));
  // Missing, malformed, and a bad acceleration: one line naming the file and key.
  write(dir_ / "missing.yaml", std::string(kJob) + "machine: {profile: nowhere.yaml}\n");
  RunResult r = run({"run", (dir_ / "missing.yaml").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("nowhere.yaml does not exist"), std::string::npos) << r.err;
  write(dir_ / "broken.yaml", "kind: [lathe2\n");
  write(dir_ / "uses_broken.yaml", std::string(kJob) + "machine: {profile: broken.yaml}\n");
  r = run({"run", (dir_ / "uses_broken.yaml").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("broken.yaml"), std::string::npos) << r.err;
  write(dir_ / "acc.yaml", "kind: lathe2\naxes: {X: {max_acceleration: 0}}\n");
  write(dir_ / "uses_acc.yaml", std::string(kJob) + "machine: {profile: acc.yaml}\n");
  r = run({"run", (dir_ / "uses_acc.yaml").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("acc.yaml"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("max_acceleration must be > 0"), std::string::npos) << r.err;
  write(dir_ / "unknown_key.yaml", "kind: lathe2\nspeed: 3\n");
  write(dir_ / "uses_unknown.yaml", std::string(kJob) + "machine: {profile: unknown_key.yaml}\n");
  r = run({"run", (dir_ / "uses_unknown.yaml").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("unknown_key.yaml:2"), std::string::npos) << r.err;
}

// Issue #26: lathe4 follows non-round sections. On a rounded-rectangle boom the eye sits in a flat
// face's plane while the fibre crosses the face: the fibre lies straight on the face to where it
// leaves it, and the pins turn it in the face's plane (before: the contact walk stayed behind the
// plan, 2.66 mm, refused). On an oval canister with screw tabs the eye is put on the dwell arcs'
// true tangents (the planner's dwell points carry interpolated normals; before: a facet's, 3 deg
// off, 2.62 mm, refused). Both are planned, written and replayed within 0.5 mm on lathe4 (the
// boom with the eye on the plan's own tangents, tangent_window: 0, as configs/boom.yaml). The
// canister with the circuits that cover it (auto: 21, none of a section bare, tangent_window: 0 as
// configs/canister.yaml): where a dwell arc meets its pass the eye slides out along the pass's
// tangent so that the spindle does not turn back (export/machine/monotone_by_payout.h; before,
// the least-squares fit moved it below the last pin's tangent plane and the fibre left the pins
// early: 0.773 mm, refused; 0.810 with the default tangent window).
TEST_F(CliSimulate, Lathe4LaysABoomAndAnOvalCanisterWithinTheReplayTolerance) {
  const std::string profile =
      "machine: {profile: " + (source_dir() / "configs" / "machines" / "lathe4.yaml").string();
  const std::string out_keys = "output: {ply: false, svg: false, viewer: false}\n";
  const std::pair<const char*, std::string> parts[] = {
      {"boom",
       "mandrel:\n  source: section\n"
       "  section: {shape: rounded_rectangle, width: 80, height: 50, corner_radius: 10, "
       "length: 300}\n  region: {start: 30, end: 270}\n"
       "winding: {turns: 1, circuits: 4, band_width: 10}\n" +
           profile + ", tangent_window: 0, replay_tolerance: 0.5}\n" + out_keys},
      {"canister",
       "mandrel:\n  source: section\n"
       "  section: {shape: ellipse, semi_axes: [80, 50], length: 300}\n"
       "  features:\n    bore: 20\n    tabs:\n"
       "      - {at: 10, count: 2, reach: 25, width: 20, thickness: 8, hole_radius: 4}\n"
       "      - {at: 282, count: 2, reach: 25, width: 20, thickness: 8, hole_radius: 4}\n"
       "  region: {start: 30, end: 270}\n"
       "winding: {turns: 1, band_width: 10}\n" +
           profile + ", tangent_window: 0, replay_tolerance: 0.5}\n" + out_keys}};
  for (const auto& [name, text] : parts) {
    SCOPED_TRACE(name);
    const fs::path job = dir_ / (std::string(name) + ".yaml");
    write(job, text);
    const fs::path out = dir_ / name;
    const RunResult r = run({"run", job.string(), "--out", out.string()});
    ASSERT_EQ(r.code, 0) << r.err;  // a replay beyond 0.5 mm is refused (exit 1)
    const YAML::Node report = YAML::LoadFile((out / "report.json").string());
    EXPECT_EQ(report["machine"]["kind"].as<std::string>(), "lathe4");
    const double dev = report["motion"]["replay"]["max_deviation_mm"].as<double>();
    std::printf("%s: replay %.3f mm\n", name, dev);
    EXPECT_LT(dev, 0.5);
    EXPECT_GT(report["motion"]["replay"]["blocks"].as<int>(), 100);
    EXPECT_GE(report["motion"]["replay"]["min_clearance_mm"].as<double>(),
              report["motion"]["required_clearance_mm"].as<double>() - 0.05);
    EXPECT_EQ(report["motion"]["spindle_reversals"].as<int>(), 0);
    if (std::string(name) == "canister") {
      // 0.123 mm as configs/canister.yaml; 0.404 without the replay's pin hold (the program's
      // rounding put the swung eye 3e-4 mm below the last pin's plane), 0.773 before the slide.
      EXPECT_LT(dev, 0.2);
      EXPECT_EQ(report["coverage"]["bare_fraction"].as<double>(), 0.0);  // covered
      EXPECT_GE(report["circuits"].size(), 21u);
    }
  }
}

// lathe2's operator stops (docs/bad_inputs.md, "Third round"): every bad eye radius named at the
// stop between a two-layer pipe's layers is one line naming the program line, exit 1, before the
// replay (no JSON written). Before: two radii took the first, 0x49 read as 73 mm, a radius inside
// the part was a deviation at a later line, 99999 mm replayed for more than 60 s.
TEST_F(CliSimulate, BadEyeRadiusStopsAreOneLineExitOne) {
  write(dir_ / "layup.yaml", kPipeLayupJob);
  ASSERT_EQ(run({"run", (dir_ / "layup.yaml").string(), "--out", (dir_ / "o").string()}).code, 0);
  std::ifstream in(dir_ / "o" / "toolpath.ngc");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t stop = text.find("\nM0 (eye radius ") + 1;
  ASSERT_NE(stop, 0u);
  const std::size_t stop_end = text.find('\n', stop);
  const std::string line = std::to_string(std::count(text.begin(), text.begin() + stop, '\n') + 1);
  struct Case {
    std::string stop, says;
  };
  const std::string bad_form = ": the comment names an eye radius but not as \"eye radius R mm\"";
  const std::vector<Case> cases = {
      {"M0 (eye radius -73 mm)", line + bad_form},
      {"M0 (eye radius 0 mm)", line + bad_form},
      {"M0 (eye radius nan mm)", line + bad_form},
      {"M0 (eye radius inf mm)", line + bad_form},
      {"M0 (eye radius 1e308 mm)", line + bad_form},
      {"M0 (eye radius 1" + std::string(400, '0') + " mm)", line + bad_form},
      {"M0 (eye radius 0x49 mm)", line + bad_form},
      {"M0 (eye radius 73.6774 mm eye radius 90 mm)", line + ": the comment names the eye radius "
                                                             "more than once"},
      {"M0 (eye radius 90 mm) (eye radius 73.6774 mm)", line + ": the comment names the eye "
                                                               "radius more than once"},
      {"M0 (eye radius 30 mm)", line + ": the stop sets the eye at radius 30 mm, inside the part: "
                                       "layer 2 (outer) is wound on a surface reaching radius "
                                       "53.68 mm"},
      {"M0 (eye radius 1e-9 mm)", line + ": the stop sets the eye at radius 1e-09 mm, inside"},
      {"M0 (eye radius 99999 mm)", ": the eye has travelled more than 10 km by this move"},
      {"(eye radius 73.6774 mm)", line + ": an eye radius is set by hand at an operator stop"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].stop);
    const fs::path prog = dir_ / ("stop" + std::to_string(i) + ".ngc");
    write(prog, text.substr(0, stop) + cases[i].stop + text.substr(stop_end));
    const fs::path json = dir_ / ("stop" + std::to_string(i) + ".json");
    const RunResult r =
        run({"simulate", (dir_ / "layup.yaml").string(), prog.string(), "--json", json.string()});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find(prog.string() + ":"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(cases[i].says), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(json));
  }
  // The same stop in a lathe4 job's program: only a lathe2 sets its eye by hand.
  write(dir_ / "l4.yaml", std::string(kJob) + "machine: {profile: " +
                              (source_dir() / "configs" / "machines" / "lathe4.yaml").string() +
                              "}\n");
  ASSERT_EQ(run({"run", (dir_ / "l4.yaml").string(), "--out", (dir_ / "l4").string()}).code, 0);
  std::ifstream in4(dir_ / "l4" / "toolpath.ngc");
  std::string t4((std::istreambuf_iterator<char>(in4)), std::istreambuf_iterator<char>());
  const std::size_t end4 = t4.rfind("\nM2");
  ASSERT_NE(end4, std::string::npos);
  t4.insert(end4 + 1, "M0 (eye radius 90 mm)\n");
  write(dir_ / "l4.ngc", t4);
  const RunResult r4 = run({"simulate", (dir_ / "l4.yaml").string(), (dir_ / "l4.ngc").string()});
  EXPECT_EQ(r4.code, 1);
  EXPECT_NE(r4.err.find("an eye radius set by hand: only a lathe2 (no cross-feed) sets its eye so; "
                        "a lathe4 moves it with its axes"),
            std::string::npos)
      << r4.err;
  EXPECT_EQ(std::count(r4.err.begin(), r4.err.end(), '\n'), 1) << r4.err;
}

TEST_F(CliSimulate, EveryShippedJobMovesAsAMachineShould) {
  // Issue #13's figures on every shipped job: at most 2 carriage reversals per circuit, none in
  // the middle half of a pass, the spindle never reversing, every block within the axes' velocity
  // and acceleration, and the eye at least the clearance (- 0.05 mm) from the mandrel mesh.
  int n = 0;
  for (const auto& e : fs::directory_iterator(source_dir() / "configs")) {
    if (e.path().extension() != ".yaml") continue;
    ++n;
    const fs::path out = dir_ / e.path().stem();
    const RunResult r = run({"run", e.path().string(), "--out", out.string()});
    ASSERT_EQ(r.code, 0) << e.path() << "\n" << r.err;
    EXPECT_NE(r.out.find("reversals        carriage"), std::string::npos) << r.out;
    const YAML::Node report = YAML::LoadFile((out / "report.json").string());
    const YAML::Node m = report["motion"];
    const bool robot = report["machine"]["kind"].as<std::string>() == "robot";
    SCOPED_TRACE(e.path().string());
    // A robot's eye follows the part at the true clearance (export/machine/clearance_eye.h) and
    // its cells keep no axis monotone: on a bent tube E1 and the lathe model's X, measured about
    // the principal axis, turn back and forth (bent_tube: 293 E1 reversals inside passes, X up to
    // 70 per circuit). The cell is held to its own checks instead (configuration, joint speeds,
    // the replay within replay_tolerance: tests/export/robot/robot_replay_test.cpp).
    if (!robot) {
      EXPECT_LE(m["max_carriage_reversals_per_circuit"].as<int>(), 2);
      EXPECT_EQ(m["mid_pass_carriage_reversals"].as<int>(), 0);
      EXPECT_EQ(m["spindle_reversals_in_passes"].as<int>(), 0);
    }
    EXPECT_LE(m["max_velocity_ratio"].as<double>(), 1 + 1e-9);
    EXPECT_LE(m["max_acceleration_ratio"].as<double>(), 1 + 1e-9);
    EXPECT_GE(m["min_clearance_mm"].as<double>(), m["required_clearance_mm"].as<double>() - 0.05);
    if (!robot) {  // robots have no G-code to replay; run refused any beyond replay_tolerance
      EXPECT_TRUE(m["replay"].IsMap());
    }
  }
  EXPECT_GE(n, 6);
}

}  // namespace
}  // namespace windplan::test
