// windplan run and windplan helices as subprocesses: exit codes, files, byte-identical reruns,
// every shipped config end to end.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "tests/test_data.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

struct Proc {
  int code = -1;
  std::string out, err;
};

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string sh_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

class CliRun : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("windplan_run_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  Proc run(const std::vector<std::string>& args) const {
    std::string cmd = sh_quote(WINDPLAN_BINARY);
    for (const auto& a : args) cmd += " " + sh_quote(a);
    cmd += " >" + sh_quote((dir_ / "stdout.txt").string()) + " 2>" +
           sh_quote((dir_ / "stderr.txt").string());
    const int status = std::system(cmd.c_str());
    Proc r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read_all(dir_ / "stdout.txt");
    r.err = read_all(dir_ / "stderr.txt");
    return r;
  }
  fs::path dir_;
};

fs::path config(const std::string& name) { return test::source_dir() / "configs" / name; }

// Two runs, with 2 threads and with 1 (girth samples and pass refinements run in parallel).
TEST_F(CliRun, VesselRunsAndRunsWithTwoThreadsAndOneAreByteIdentical) {
  const fs::path a = dir_ / "a", b = dir_ / "b";
  const Proc r1 =
      run({"run", config("vessel.yaml").string(), "--out", a.string(), "--threads", "2"});
  ASSERT_EQ(r1.code, 0) << r1.err;
  const Proc r2 =
      run({"run", config("vessel.yaml").string(), "--out", b.string(), "--threads", "1"});
  ASSERT_EQ(r2.code, 0) << r2.err;
  EXPECT_NE(r1.out.find("vessel"), std::string::npos) << r1.out;
  // One progress line per stage on stderr.
  for (const char* stage : {"mandrel", "girth", "helices", "metrics", "export"}) {
    EXPECT_NE(r1.err.find(std::string("windplan run: ") + stage), std::string::npos) << r1.err;
  }
  int files = 0;
  for (const auto& e : fs::directory_iterator(a)) {
    ++files;
    const fs::path other = b / e.path().filename();
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_TRUE(read_all(e.path()) == read_all(other)) << e.path().filename() << " differs";
  }
  for (const char* f :
       {"fibre_path.csv", "payout.csv", "axes.csv", "toolpath.ngc", "report.json", "report.md",
        "mesh.ply", "paths.ply", "development.svg", "axes.svg", "stability.svg", "viewer.html"}) {
    EXPECT_TRUE(fs::exists(a / f)) << f;
  }
  EXPECT_GE(files, 11);
  EXPECT_LT(fs::file_size(a / "viewer.html"), 5000000u);
  // report.json is JSON (YAML reads it) with the plan's circuits.
  const YAML::Node rep = YAML::LoadFile((a / "report.json").string());
  EXPECT_TRUE(rep.IsMap());
  // The shipped vessel (isotensoid domes, 30 mm openings): geodesic passes that turn around on
  // the domes (issue 12), so they make more turns than the 0.6 that would reach the openings;
  // no bare band anywhere, no warning, and the summary says so.
  const double limit = rep["summary"]["geodesic_turn_limit"].as<double>();
  EXPECT_GT(limit, 0.5);
  EXPECT_LT(limit, 0.8);
  EXPECT_TRUE(rep["pattern"]["geodesic"].as<bool>());
  const double c = rep["pattern"]["turnaround_radius_mm"].as<double>();
  EXPECT_GE(c, rep["pattern"]["requested_radius_mm"].as<double>());
  EXPECT_GT(rep["summary"]["turns_per_pass"].as<double>(), limit);
  EXPECT_EQ(rep["coverage"]["bare_fraction"].as<double>(), 0.0);
  EXPECT_GE(rep["coverage"]["stations"].size(), 8u);
  EXPECT_EQ(r1.err.find("warning"), std::string::npos) << r1.err;
  EXPECT_NE(r1.out.find("coverage         bare 0.00%"), std::string::npos) << r1.out;
  EXPECT_NE(r1.out.find("(geodesic, turning around at r = "), std::string::npos) << r1.out;
}

// Between dwell ends more turns than a geodesic can make are warned about with a suggestion:
// the cone 60 -> 40 mm over 400 mm allows arccos(40 / 60) / sin(b) / 2 pi = 2.68 turns.
TEST_F(CliRun, ConeBeyondTheTurnLimitIsWarnedWithASuggestion) {
  std::string yaml = read_all(config("cone.yaml"));
  const std::string from = "\n  turns: 2\n";
  const std::size_t at = yaml.find(from);
  ASSERT_NE(at, std::string::npos);
  yaml.replace(at, from.size(), "\n  turns: 5\n");
  ASSERT_NE(yaml.find("\n  beta: 0 "), std::string::npos);
  const fs::path job = dir_ / "cone_n5.yaml";
  std::ofstream(job) << yaml;
  const Proc r = run({"helices", job.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("warning: winding.turns = 5 exceeds the 2.68 turns"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("use turns <= 2.68, beta > 0"), std::string::npos) << r.out;
}

// windplan patterns: the table's first row is what `pattern: auto` winds, every row measured
// on its own laid bands; off a shape of revolution it is refused.
TEST_F(CliRun, PatternsTableStartsWithWhatAutoWinds) {
  const fs::path job = dir_ / "hemi.yaml";
  std::ofstream(job) << "name: hemi\nmandrel:\n  source: vessel\n  vessel:\n    radius: 100\n"
                        "    length: 300\n    dome: {type: hemispherical, polar_opening: 30}\n"
                        "winding:\n  band_width: 16\n";
  const Proc t = run({"patterns", job.string(), "--json", "--top", "4"});
  ASSERT_EQ(t.code, 0) << t.err;
  const YAML::Node table = YAML::Load(t.out);
  ASSERT_GE(table["patterns"].size(), 2u);
  ASSERT_LE(table["patterns"].size(), 4u);
  const YAML::Node first = table["patterns"][0];
  const Proc h = run({"helices", job.string(), "--json"});
  ASSERT_EQ(h.code, 0) << h.err;
  const YAML::Node plan = YAML::Load(h.out);
  EXPECT_EQ(plan["metrics"]["pattern_info"]["circuits"].as<int>(), first["circuits"].as<int>());
  EXPECT_EQ(plan["metrics"]["pattern_info"]["skip"].as<int>(), first["skip"].as<int>());
  EXPECT_NEAR(plan["metrics"]["pattern_info"]["turnaround_radius"].as<double>(),
              first["turnaround_radius"].as<double>(), 1e-9);
  EXPECT_EQ(plan["metrics"]["coverage"]["bare_fraction"].as<double>(),
            first["bare_fraction"].as<double>());
  for (const YAML::Node& row : table["patterns"]) {
    EXPECT_GE(row["turnaround_radius"].as<double>(), table["window_lo"].as<double>());
    EXPECT_LE(row["turnaround_radius"].as<double>(), table["window_hi"].as<double>());
  }
  // A tube that is not a shape of revolution: K circuits near what the run winds, each planned
  // as the run plans it; the starred row (circuits: auto) covers every section.
  const Proc bent = run({"patterns", config("bent_tube.yaml").string(), "--json", "--top", "3"});
  ASSERT_EQ(bent.code, 0) << bent.err;
  const YAML::Node tube = YAML::Load(bent.out);
  EXPECT_EQ(tube["tube"].as<std::string>(), "bent_tube centre line");
  ASSERT_EQ(tube["patterns"].size(), 3u);
  EXPECT_EQ(tube["patterns"][0]["bare_fraction"].as<double>(), 0.0);
  EXPECT_LE(tube["patterns"][0]["max_slippage"].as<double>(), 0.2);
  EXPECT_GT(tube["patterns"][1]["bare_fraction"].as<double>(), 0.0);  // one circuit fewer
}

// Every shipped job runs end to end: one test per configs/*.yaml (each its own ctest, with its
// own time limit).
std::vector<std::string> shipped_configs() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(test::source_dir() / "configs")) {
    if (e.path().extension() == ".yaml") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

class ShippedConfig : public CliRun, public ::testing::WithParamInterface<std::string> {};

TEST_P(ShippedConfig, RunsEndToEnd) {
  const fs::path job = config(GetParam() + ".yaml");
  const fs::path out = dir_ / "out";
  const Proc r = run({"run", job.string(), "--out", out.string()});
  EXPECT_EQ(r.code, 0) << job << "\n" << r.err;
  EXPECT_TRUE(fs::exists(out / "fibre_path.csv")) << job;
  EXPECT_FALSE(r.out.empty()) << job;
}

INSTANTIATE_TEST_SUITE_P(Configs, ShippedConfig, ::testing::ValuesIn(shipped_configs()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

TEST(ShippedConfigs, AtLeastTheSixJobs) { EXPECT_GE(shipped_configs().size(), 6u); }

TEST_F(CliRun, DefaultOutputDirectoryIsOutJobName) {
  const fs::path job = dir_ / "j.yaml";
  std::ofstream(job) << "name: tiny\nmandrel:\n  source: pipe\n  pipe: {radius: 30, length: 100}\n"
                        "winding: {turns: 1, circuits: 2, band_width: 10}\n";
  const std::string cmd = "cd " + sh_quote(dir_.string()) + " && " + sh_quote(WINDPLAN_BINARY) +
                          " run j.yaml >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_TRUE(fs::exists(dir_ / "out" / "tiny" / "fibre_path.csv"));
}

TEST_F(CliRun, BadWindingInputIsExitOneWithTheKey) {
  const fs::path job = dir_ / "bad.yaml";
  std::ofstream(job) << "mandrel:\n  source: pipe\n  pipe: {radius: 30, length: 100}\n"
                        "winding:\n  turns: 0\n";
  const Proc r = run({"run", job.string(), "--out", (dir_ / "o").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("turns"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("bad.yaml"), std::string::npos) << r.err;
  // Patterns and turnarounds on a vessel (issue 12): one line naming the key, exit 1.
  for (const auto& [winding, key] :
       {std::pair<std::string, std::string>{"turnaround: 10", "winding.turnaround = 10.00 mm"},
        {"turnaround: 150", "winding.turnaround = 150.00 mm"},
        {"pattern: {circuits: 12, skip: 4}", "coprime"},
        {"pattern: {circuits: 7, skip: 3}\n  turnaround_window: 0", "winding.pattern: K=7, p=3"}}) {
    std::ofstream(job) << "mandrel:\n  source: vessel\n  vessel:\n    radius: 100\n"
                          "    length: 300\n    dome: {type: hemispherical, polar_opening: 30}\n"
                          "winding:\n  band_width: 16\n  "
                       << winding << "\n";
    const Proc v = run({"run", job.string(), "--out", (dir_ / "o").string()});
    EXPECT_EQ(v.code, 1) << winding;
    EXPECT_NE(v.err.find(key), std::string::npos) << v.err;
    std::istringstream lines(v.err);  // one error line (besides the stage progress lines)
    int errors = 0;
    for (std::string l; std::getline(lines, l);) errors += l.find("error:") != std::string::npos;
    EXPECT_EQ(errors, 1) << v.err;
  }
  const Proc u = run({"run"});
  EXPECT_EQ(u.code, 2) << u.err;
  const Proc h = run({"helices"});
  EXPECT_EQ(h.code, 2) << h.err;
}

// A job with axial stations: the fibre stays between them (passes from station to station,
// turnarounds on the station circles); a station off the mandrel is exit 1 naming the key.
TEST_F(CliRun, StationsBoundTheFibrePath) {
  const fs::path job = dir_ / "stations.yaml";
  std::ofstream(job) << "name: stations\nmandrel:\n  source: pipe\n"
                        "  pipe: {radius: 30, length: 200}\n"
                        "winding: {turns: 1, circuits: 3, band_width: 10, start_station: 40, "
                        "end_station: 160}\n";
  const fs::path out = dir_ / "o";
  const Proc r = run({"run", job.string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream csv(out / "fibre_path.csv");
  std::string line;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line.rfind("circuit,index,x [mm],y [mm],z [mm]", 0), 0u) << line;
  double zmin = 1e9, zmax = -1e9;
  int rows = 0;
  while (std::getline(csv, line)) {
    std::istringstream s(line);
    std::string cell;
    for (int i = 0; i < 5; ++i) std::getline(s, cell, ',');
    const double z = std::stod(cell);
    zmin = std::min(zmin, z);
    zmax = std::max(zmax, z);
    ++rows;
  }
  EXPECT_GT(rows, 10);
  EXPECT_NEAR(zmin, 40.0, 1e-4);
  EXPECT_NEAR(zmax, 160.0, 1e-4);
  for (const char* f : {"toolpath.ngc", "axes.csv", "report.json", "development.svg"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }

  const fs::path bad = dir_ / "bad_station.yaml";
  std::ofstream(bad) << "mandrel:\n  source: pipe\n  pipe: {radius: 30, length: 200}\n"
                        "winding: {turns: 1, circuits: 2, end_station: 300}\n";
  const Proc b = run({"run", bad.string(), "--out", (dir_ / "b").string()});
  EXPECT_EQ(b.code, 1) << b.err;
  EXPECT_NE(b.err.find("winding.end_station"), std::string::npos) << b.err;
  EXPECT_NE(b.err.find("(0, 200) mm"), std::string::npos) << b.err;
}

TEST_F(CliRun, HelicesJsonReportsEveryPass) {
  const Proc r = run({"helices", config("pipe.yaml").string(), "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const YAML::Node j = YAML::Load(r.out);
  const int K = j["circuits"].as<int>();
  EXPECT_GE(K, 1);
  EXPECT_EQ(static_cast<int>(j["passes"].size()), 2 * K);
  EXPECT_TRUE(j["metrics"]["spacing_cv"].IsScalar());
  EXPECT_LT(j["metrics"]["max_slippage"].as<double>(), 0.2);  // geodesics on a cylinder
  // A cylinder has no geodesic turn limit.
  EXPECT_FALSE(j["geodesic_turn_limit"]["bounded"].as<bool>());
  EXPECT_TRUE(j["geodesic_turn_limit"]["turns"].IsNull());
  EXPECT_NEAR(j["geodesic_turn_limit"]["min_radius_mm"].as<double>(), 50.0, 1e-9);
}

// Shop mandrels made in code, wound end to end: the region is cut out of the whole mandrel, the
// plan is exported and its coverage reported.
TEST_F(CliRun, ShopMandrelsWindWithCoverageReported) {
  const std::string winding = "winding: {turns: 1, circuits: 8, band_width: 10}\n";
  const std::vector<std::pair<std::string, std::string>> jobs{
      {"shop_pipe",
       "mandrel:\n  source: pipe\n  pipe: {radius: 50, length: 500}\n  features:\n"
       "    bore: 20\n    shaft_start: {radius: 25, length: 100}\n"
       "    shaft_end: {radius: 25, length: 100}\n    flanges:\n"
       "      - {at: 0, radius: 90, thickness: 12, bolts: 8, bolt_radius: 5, pitch_radius: 75}\n"
       "      - {at: 488, radius: 90, thickness: 12, bolts: 8, bolt_radius: 5, pitch_radius: 75}\n"
       "  region: {start: 20, end: 480}\n"},
      {"canister",
       "mandrel:\n  source: section\n  section: {shape: ellipse, semi_axes: [80, 50], "
       "length: 300}\n  features:\n    bore: 20\n    tabs:\n"
       "      - {at: 10, count: 2, reach: 25, width: 20, thickness: 8, hole_radius: 4}\n"
       "      - {at: 282, count: 2, reach: 25, width: 20, thickness: 8, hole_radius: 4}\n"
       "  region: {start: 30, end: 270}\n"
       // Not round: a lathe lays the fibre 1.4 mm off the plan (the G-code replay), over the
       // default machine.replay_tolerance; this test is about the winding, so it reports only.
       "machine: {replay_tolerance: 0}\n"},
      {"boom",
       "mandrel:\n  source: section\n  section: {shape: rounded_rectangle, width: 120, "
       "height: 80, corner_radius: 15, length: 600}\n  region: {start: 50, end: 550}\n"
       "machine: {replay_tolerance: 0}\n"}};  // not round either (see the canister)
  for (const auto& [name, yaml] : jobs) {
    SCOPED_TRACE(name);
    const fs::path job = dir_ / (name + ".yaml");
    std::ofstream(job) << yaml << winding;
    const fs::path out = dir_ / ("out_" + name);
    const Proc r = run({"run", job.string(), "--out", out.string()});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("cover factor"), std::string::npos) << r.out;
    const YAML::Node rep = YAML::LoadFile((out / "report.json").string());
    EXPECT_GT(rep["summary"]["cover_factor"].as<double>(), 0.0);
    EXPECT_TRUE(fs::exists(out / "toolpath.ngc"));
  }
}

// The shared meshes that are real mandrels: each either winds as given, or fails naming what to
// change (mandrel.region with suggested keys), and winds with that change.
TEST_F(CliRun, SharedMandrelMeshesWindOrSayWhatToChange) {
  for (const char* name : {"aerobar-brake-mandrel.stl", "bent-pipe.stl"}) {
    SCOPED_TRACE(name);
    const fs::path mesh = test::shared_mesh(name);
    if (!fs::exists(mesh)) {
      GTEST_SKIP() << mesh << " is absent (../shared not checked out)";
    }
    const std::string base = "mandrel:\n  source: mesh\n  file: " + mesh.string() + "\n";
    // A robot carries the eye: these mandrels are not round, and a lathe's eye cannot follow
    // the fibre round them (the G-code replay laid the aerobar's 16.9 mm off the plan).
    // bent-pipe.stl is 0.23 units in radius (1.457 around): the default 10 mm band is wider
    // than its circumference, refused since issue 28; a 1 mm band fits both meshes.
    const std::string winding =
        "winding: {turns: 1, circuits: 4, band_width: 1}\nmachine: {kind: robot}\n";
    const fs::path job = dir_ / "shared.yaml";
    std::ofstream(job) << base << winding;
    const Proc r = run({"run", job.string(), "--out", (dir_ / "o1").string()});
    if (r.code == 0) continue;
    EXPECT_EQ(r.code, 1) << r.err;
    const std::size_t k = r.err.find("Set mandrel.region: {start: ");
    ASSERT_NE(k, std::string::npos) << r.err;
    double a = 0, b = 0;
    ASSERT_EQ(std::sscanf(r.err.c_str() + k, "Set mandrel.region: {start: %lf, end: %lf}", &a, &b),
              2);
    std::ofstream(job) << base << "  region: {start: " << a << ", end: " << b << "}\n" << winding;
    const Proc r2 = run({"run", job.string(), "--out", (dir_ / "o2").string()});
    // The aerobar mandrel is a 10 mm slab with square edges: refused before the long work (it
    // ran 116 s to lay 45% bare with |k_g/k_n| unbounded), saying what to change.
    if (std::string(name) == "aerobar-brake-mandrel.stl") {
      EXPECT_EQ(r2.code, 1) << r2.err;
      EXPECT_NE(r2.err.find("the wound surface has sharp edges"), std::string::npos) << r2.err;
      EXPECT_NE(r2.err.find("give the mandrel rounded edges"), std::string::npos) << r2.err;
      // One error line (the warnings before it are the mesh repair's).
      const std::size_t e = r2.err.find("error: mandrel");
      ASSERT_NE(e, std::string::npos) << r2.err;
      EXPECT_EQ(r2.err.find('\n', e), r2.err.size() - 1) << r2.err;
      continue;
    }
    EXPECT_EQ(r2.code, 0) << r2.err;
    EXPECT_NE(r2.out.find("cover factor"), std::string::npos) << r2.out;
  }
}

// The shared bent-pipe.stl (units m): a closed tube whose flat end caps are normal to its legs
// winds without a region (its two planar end caps dropped), and between two sections normal to
// its centre line (mandrel.region.centre_line): remeshed at 25 mm, 8 turns, a full layer (no
// section of 24 bare) with every laid point within mu, read back from report.json and
// fibre_path.csv; a station past the centre line is one line.
TEST_F(CliRun, SharedBentPipeWindsBetweenCentreLineStations) {
  const fs::path mesh = test::shared_mesh("bent-pipe.stl");
  if (!fs::exists(mesh)) GTEST_SKIP() << mesh << " is absent (../shared not checked out)";
  const std::string head = "mandrel:\n  source: mesh\n  file: " + mesh.string() +
                           "\n  units: m\n  repair: true\n  remesh: 25\n";
  const std::string tail =
      "winding: {turns: 8, pattern: auto, band_width: 20, mu: 0.2, coverage_stations: 24}\n"
      "machine: {kind: robot}\n";
  const fs::path job = dir_ / "bent_pipe.yaml";
  std::ofstream(job) << head << "  region: {centre_line: {from: 50, to: 970}}\n" << tail;
  const Proc r = run({"run", job.string(), "--out", (dir_ / "bp").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const YAML::Node rep = YAML::LoadFile((dir_ / "bp" / "report.json").string());
  EXPECT_TRUE(rep["coverage"]["measured"].as<bool>());
  EXPECT_EQ(rep["coverage"]["stations"].size(), 24u);
  EXPECT_EQ(rep["coverage"]["bare_fraction"].as<double>(), 0.0);
  EXPECT_LE(rep["summary"]["max_slippage"].as<double>(), 0.2);
  // pattern: auto on a mesh never lays fewer circuits than its measured coverage needs.
  EXPECT_GE(rep["summary"]["circuits"].as<int>(),
            rep["summary"]["circuits_for_coverage"].as<int>());
  // Every laid point's |k_g/k_n| column within mu (the last column of fibre_path.csv).
  std::ifstream csv(dir_ / "bp" / "fibre_path.csv");
  std::string line;
  std::getline(csv, line);
  ASSERT_NE(line.find(",slippage"), std::string::npos) << line;
  int rows = 0;
  double worst = 0.0;
  while (std::getline(csv, line)) {
    worst = std::max(worst, std::stod(line.substr(line.rfind(',') + 1)));
    ++rows;
  }
  EXPECT_GT(rows, 1000);
  EXPECT_LE(worst, 0.2);
  const Proc m = run({"mandrel", job.string()});
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_NE(m.out.find("50 .. 970 mm along the tube's centre line (1020.45 mm long)"),
            std::string::npos)
      << m.out;
  std::ofstream(job) << head << "  region: {centre_line: {from: 50, to: 1100}}\n" << tail;
  const Proc bad = run({"run", job.string(), "--out", (dir_ / "bp2").string()});
  EXPECT_EQ(bad.code, 1);
  EXPECT_NE(bad.err.find("mandrel.region.centre_line.to: 1100.00 mm is outside the tube's "
                         "centre line (0 .. 1020.45 mm"),
            std::string::npos)
      << bad.err;
}

// As shipped, bent-pipe.stl's 700 faces are long flat facets under a 20 mm band (k_n ~ 0 along
// them): the helices would need |k_g/k_n| in the thousands, the geodesics are laid and leave most
// sections bare, and the warning says what to change (remesh, not more turns); remeshed at the
// band width as it says, the same job is a full layer within mu.
TEST_F(CliRun, SharedBentPipeAsShippedIsToldToRemeshAndThenWinds) {
  const fs::path mesh = test::shared_mesh("bent-pipe.stl");
  if (!fs::exists(mesh)) GTEST_SKIP() << mesh << " is absent (../shared not checked out)";
  const std::string head = "mandrel:\n  source: mesh\n  file: " + mesh.string() +
                           "\n  units: m\n  repair: true\n"
                           "  region: {centre_line: {from: 50, to: 970}}\n";
  const std::string tail =
      "winding: {turns: 8, pattern: auto, band_width: 20, mu: 0.2, coverage_stations: 24}\n"
      "machine: {kind: robot}\n";
  const fs::path job = dir_ / "bent_pipe_coarse.yaml";
  std::ofstream(job) << head << tail;
  const Proc r = run({"run", job.string(), "--out", (dir_ / "coarse").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("the mesh is coarse for the band"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("remesh it (mandrel.remesh of about the band width)"), std::string::npos)
      << r.err;
  const YAML::Node coarse = YAML::LoadFile((dir_ / "coarse" / "report.json").string());
  EXPECT_GT(coarse["coverage"]["bare_fraction"].as<double>(), 0.5);
  std::ofstream(job) << head << "  remesh: 20\n" << tail;
  const Proc f = run({"run", job.string(), "--out", (dir_ / "fine").string()});
  ASSERT_EQ(f.code, 0) << f.err;
  EXPECT_EQ(f.err.find("the mesh is coarse"), std::string::npos) << f.err;
  const YAML::Node fine = YAML::LoadFile((dir_ / "fine" / "report.json").string());
  EXPECT_EQ(fine["coverage"]["bare_fraction"].as<double>(), 0.0);
  EXPECT_LE(fine["summary"]["max_slippage"].as<double>(), 0.2);
}

// ---- layups (planner/plan_layup.h): the shipped vessel_layup.yaml and bad layer input ----

TEST_F(CliRun, VesselLayupEveryLayerInTheReportAndInOrderInTheProgram) {
  const fs::path out = dir_ / "layup";
  const Proc r = run({"run", config("vessel_layup.yaml").string(), "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const YAML::Node report = YAML::LoadFile((out / "report.json").string());
  const YAML::Node layers = report["layers"];
  ASSERT_EQ(layers.size(), 4u);
  const char* names[4] = {"hoop1", "helical1", "hoop2", "helical2"};
  const char* kinds[4] = {"hoop", "helical", "hoop", "helical"};
  double total_fibre = 0.0;
  for (std::size_t l = 0; l < 4; ++l) {
    const YAML::Node L = layers[l];
    EXPECT_EQ(L["name"].as<std::string>(), names[l]);
    EXPECT_EQ(L["kind"].as<std::string>(), kinds[l]);
    EXPECT_GT(L["thickness_cylinder_mm"].as<double>(), 0.0) << names[l];
    EXPECT_GE(L["thickness_max_mm"].as<double>(), L["thickness_cylinder_mm"].as<double>());
    EXPECT_GT(L["fibre_mass_g"].as<double>(), 0.0) << names[l];
    EXPECT_GT(L["resin_mass_g"].as<double>(), 0.0) << names[l];
    EXPECT_GT(L["wind_time_s"].as<double>(), 0.0) << names[l];
    total_fibre += L["fibre_mass_g"].as<double>();
  }
  // Hoop layers at about 89 deg, the two helical layers at two different angles.
  EXPECT_GT(layers[0]["angle_deg"].as<double>(), 85.0);
  EXPECT_GT(layers[2]["angle_deg"].as<double>(), 85.0);
  EXPECT_GT(std::abs(layers[3]["angle_deg"].as<double>() - layers[1]["angle_deg"].as<double>()),
            5.0);
  // Each layer is wound on the one under it: the surface radius grows by the thickness below.
  for (std::size_t l = 1; l < 4; ++l) {
    EXPECT_NEAR(layers[l]["surface_radius_mm"].as<double>(),
                layers[l - 1]["surface_radius_mm"].as<double>() +
                    layers[l - 1]["thickness_cylinder_mm"].as<double>(),
                0.02)
        << names[l];
  }
  EXPECT_NEAR(report["laminate"]["fibre_mass_g"].as<double>(), total_fibre, 1e-6 * total_fibre);
  // The program: every layer in order, a pause between layers.
  const std::string ngc = read_all(out / "toolpath.ngc");
  std::size_t at = 0;
  for (int l = 1; l <= 4; ++l) {
    const std::size_t p = ngc.find("(layer " + std::to_string(l) + " of 4: " + names[l - 1], at);
    ASSERT_NE(p, std::string::npos) << "layer " << l;
    at = p;
  }
  // lathe2 (issue #26): each pause names the next layer's eye radius, the largest radius of the
  // surface it is wound on + the clearance (20 mm), set by hand.
  std::size_t pauses = 0;
  const std::string stop = "\nM0 (eye radius ";
  for (std::size_t p = ngc.find(stop); p != std::string::npos; p = ngc.find(stop, p + 1)) {
    ++pauses;
    if (pauses > 3) break;
    EXPECT_NEAR(std::stod(ngc.substr(p + stop.size(), 12)),
                layers[pauses]["surface_radius_mm"].as<double>() + 20.0, 2e-3)
        << "layer " << pauses + 1;
  }
  EXPECT_EQ(pauses, 3u);
  for (const char* f :
       {"laminate.csv", "laminate.vtu", "layer_profiles.csv", "layer_profiles.svg"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }
  EXPECT_NE(read_all(out / "report.md").find("### Layer 4: helical2 (helical)"), std::string::npos);
  EXPECT_NE(r.out.find("laminate"), std::string::npos) << r.out;
}

// Bad input for a friction layer on a bent tube (issue 25's "Shown by"): a slippage above mu,
// an angle friction cannot hold on a 3r bend (with the figure), pins that do not fit or sit off
// the tube, a region end that is no section of the tube, a pass that measures above mu once laid:
// each one error line naming the key and the figure, exit 1, no fibre path written.
TEST_F(CliRun, BadTubeFrictionInputIsOneLineExitOne) {
  const fs::path job = dir_ / "elbow.yaml";
  struct Case {
    std::string region, bend_radius, winding, says;
  };
  const std::vector<Case> cases = {
      {"", "250", "  angle: 55\n  slippage: 0.25\n", "slippage 0.25 exceeds mu 0.2"},
      {"", "150", "  angle: 55\n  slippage: 0.19\n",
       "winding.angle 55 deg needs |k_g/k_n| up to 0.328"},
      {"", "250", "  angle: 55\n  slippage: 0.19\n  pins: {count: 60, diameter: 4}\n",
       "winding.pins: 60 pins of 4.0 mm do not fit around the 314.2 mm section (at most 39"},
      {"", "250", "  angle: 55\n  slippage: 0.19\n  pins: {count: 24, diameter: 4, offset: 1}\n",
       "winding.pins: offset 1.0 mm puts the pin circles off the tube's ends"},
      {"  region: {start: -200, end: 200}\n", "250", "  angle: 55\n  slippage: 0.19\n",
       "mandrel.region: the wound region's start edge is no section of the tube"},
      {"", "250", "  angle: 53.2\n  slippage: 0.2\n  circuits: 23\n",
       "on a pass held at 53.20 deg"}};
  for (const Case& c : cases) {
    std::ofstream(job) << "name: elbow\nmandrel:\n  source: bent_tube\n"
                          "  linear_deflection: 0.25\n  angular_deflection: 5\n"
                       << c.region
                       << "  bent_tube:\n    radius: 50\n    segments: [100, 100]\n"
                          "    bends:\n      - {angle: 90, radius: "
                       << c.bend_radius << ", plane_angle: 0}\nwinding:\n  mu: 0.2\n"
                       << "  band_width: 12\n"
                       << c.winding;
    const fs::path out = dir_ / "o";
    const Proc v = run({"run", job.string(), "--out", out.string()});
    EXPECT_EQ(v.code, 1) << c.winding << v.err;
    EXPECT_NE(v.err.find(c.says), std::string::npos) << v.err;
    std::istringstream lines(v.err);
    int errors = 0;
    for (std::string l; std::getline(lines, l);) errors += l.find("error:") != std::string::npos;
    EXPECT_EQ(errors, 1) << v.err;
    EXPECT_FALSE(fs::exists(out / "fibre_path.csv")) << c.says;
  }
}

TEST_F(CliRun, BadLayerInputIsExitOneWithTheKey) {
  const std::string pipe = "mandrel:\n  source: pipe\n  pipe: {radius: 30, length: 100}\n";
  const std::string vessel =
      "mandrel:\n  source: vessel\n  remesh: 6\n"
      "  vessel: {radius: 100, length: 300, dome: {type: isotensoid, polar_opening: 30}}\n"
      "winding: {turns: 0.59, band_width: 16}\n";
  struct Case {
    std::string yaml, key;
  };
  const std::vector<Case> cases = {
      {pipe + "layers: []\n", "'layers'"},
      {pipe + "layers:\n  - kind: polar\n", "layers[0].kind"},
      {pipe + "layers:\n  - kind: hoop\n    range: [-20, 50]\n", "layers[0].range"},
      {pipe + "material:\n  fibre_volume_fraction: 0\n", "fibre_volume_fraction"},
      {pipe + "material:\n  tex: -800\n", "tex"},
      {vessel + "material: {band_thickness: 6}\nlayers:\n  - kind: helical\n  - kind: hoop\n",
       "close the start polar opening"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const fs::path job = dir_ / ("bad_layers_" + std::to_string(i) + ".yaml");
    std::ofstream(job) << cases[i].yaml;
    const Proc r = run({"run", job.string(), "--out", (dir_ / "o").string()});
    EXPECT_EQ(r.code, 1) << cases[i].yaml << r.err;
    EXPECT_NE(r.err.find(cases[i].key), std::string::npos) << r.err;
    // One line: the error (warnings and stage lines aside).
    std::size_t errors = 0;
    for (std::size_t p = r.err.find("error"); p != std::string::npos;
         p = r.err.find("error", p + 1)) {
      ++errors;
    }
    EXPECT_EQ(errors, 1u) << r.err;
  }
}

// Screw tabs and flanges on the canister's ellipse, envelope.radius off a lathe2, and turns beside
// angle (docs/bad_inputs.md, "Third round"): one line naming the key, exit 1, before planning.
// Before: count 1e9 and a tab or flange off the body were exit 3 ("internal error", OpenCASCADE's
// fuse), 40 tabs fused into a collar planned for 29 s (exit 0), two rings of tabs overlapping and
// envelope.radius on a lathe4 or turns beside angle on a mesh tube were taken silently (unused).
TEST_F(CliRun, BadTabsEnvelopeRadiusAndTurnsAreOneLineExitOne) {
  const std::string canister =
      "name: c\nmandrel:\n  source: section\n"
      "  section: {shape: ellipse, semi_axes: [80, 50], length: 300}\n"
      "  region: {start: 30, end: 270}\n  features:\n";
  // A ring of tabs as the canister's, with the keys in `keys` changed.
  auto tab = [](const std::string& at, const std::string& keys = "") {
    std::string t = "{at: " + at + ", width: 20, thickness: 8";
    for (const char* k : {"count: 2", "reach: 25", "hole_radius: 4"}) {
      const std::string name = std::string(k).substr(0, std::string(k).find(':') + 1);
      if (keys.find(name) == std::string::npos) t += std::string(", ") + k;
    }
    return t + (keys.empty() ? "" : ", " + keys) + "}";
  };
  const std::string tail =
      "winding: {turns: 1, circuits: 4, band_width: 10}\n"
      "machine: {profile: " +
      config("machines/lathe4.yaml").string() + "}\n";
  struct Case {
    std::string yaml, says;
  };
  const std::vector<Case> cases = {
      {canister + "    tabs:\n      - " + tab("10", "count: 1000000000") + "\n" + tail,
       "features.tabs[0].count must be <= 360"},
      {canister + "    tabs:\n      - " + tab("10", "count: 40") + "\n" + tail,
       "mandrel.features.tabs[0]: its 40 tabs overlap one another where they leave the wall (9 "
       "deg apart, 14.4 deg needed"},
      {canister + "    tabs:\n      - " + tab("1000") + "\n" + tail,
       "mandrel.features.tabs[0].at = 1000 mm puts the tabs (1000 to 1008 mm along the axis) off "
       "the body's wall, which spans 0 to 300 mm"},
      {canister + "    tabs:\n      - " + tab("-100") + "\n" + tail,
       "mandrel.features.tabs[0].at = -100 mm puts the tabs"},
      {canister + "    tabs:\n      - " + tab("10") + "\n      - " + tab("12", "angle: 5") + "\n" +
           tail,
       "mandrel.features.tabs[0] and mandrel.features.tabs[1] overlap where they leave the wall "
       "(5 deg apart"},
      {canister + "    tabs:\n      - " + tab("10", "reach: 0") + "\n" + tail,
       "features.tabs[0]: reach, width and thickness must be > 0 mm"},
      {canister + "    tabs:\n      - " + tab("10", "hole_radius: 30") + "\n" + tail,
       "features.tabs[0].hole_radius (30 mm) must be >= 0 and below half the tab's width and "
       "reach"},
      {canister + "    flanges:\n      - {at: 1000, radius: 90, thickness: 12}\n" + tail,
       "mandrel.features.flanges[0].at = 1000 mm puts the flange (1000 to 1012 mm along the axis) "
       "off the mandrel"},
      {"name: p\nmandrel: {source: pipe, pipe: {radius: 50, length: 300}}\n"
       "winding: {turns: 2, circuits: 4, band_width: 10}\n"
       "machine: {profile: " +
           config("machines/lathe4.yaml").string() + ", envelope: {radius: 90}}\n",
       "envelope.radius is the eye cylinder of a lathe2 (no cross-feed); a lathe4 follows the "
       "clearance envelope"},
      {"name: t\nmandrel: {source: mesh, file: " + config("meshes/tube.obj").string() +
           ", units: mm, repair: true}\nwinding: {angle: 40, turns: 2, circuits: 4, band_width: "
           "10}\n",
       ":3: key 'winding.turns': give one of turns, angle or turnaround: each fixes the turnaround "
       "radius c, and angle would leave turns unused"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE(cases[i].says);
    const fs::path job = dir_ / ("bad_tabs_" + std::to_string(i) + ".yaml");
    std::ofstream(job) << cases[i].yaml;
    const Proc r = run({"run", job.string(), "--out", (dir_ / "o").string()});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find(cases[i].says), std::string::npos) << r.err;
    std::size_t errors = 0;
    for (std::size_t p = r.err.find("error"); p != std::string::npos;
         p = r.err.find("error", p + 1)) {
      ++errors;
    }
    EXPECT_EQ(errors, 1u) << r.err;
    EXPECT_EQ(r.err.find("girth"), std::string::npos) << r.err;  // refused before planning
    EXPECT_FALSE(fs::exists(dir_ / "o"));
  }
}

}  // namespace
}  // namespace windplan
