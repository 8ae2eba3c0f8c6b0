// windplan geodesic / windplan loop (cli/cmd_geodesic.cpp), run as the built binary
// (WINDPLAN_BINARY): closed-form lengths on planes and cylinders, metrics, outputs, bad input.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/stat.h>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "geometry/mesh/mesh_io.h"
#include "tests/cli/cli_runner.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_data.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

using test::RunResult;
using test::slurp;

std::string has(const std::string& text, const std::string& what) {
  return text.find(what) != std::string::npos ? "" : "'" + what + "' not in: " + text;
}

class CliGeodesic : public test::CliTest {
 protected:
  void SetUp() override {
    test::CliTest::SetUp();
    plane_ = (dir_ / "plane.obj").string();
    write_mesh(plane_, test::grid(10, 10));  // 121 vertices, 200 faces, [0, 10]^2
  }

  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  /// `count` copies of `value`, one per line.
  std::string per_face(const std::string& name, int count, const std::string& value) const {
    std::string text;
    for (int i = 0; i < count; ++i) text += value + "\n";
    return write(name, text);
  }
  std::string plane_;
};

double json_length(const RunResult& r) { return YAML::Load(r.out)["length"].as<double>(); }

TEST_F(CliGeodesic, Help) {
  const RunResult g = run({"geodesic", "--help"});
  EXPECT_EQ(g.code, 0);
  EXPECT_EQ(has(g.out, "--from"), "");
  EXPECT_EQ(has(g.out, "--density"), "");
  const RunResult l = run({"loop", "--help"});
  EXPECT_EQ(l.code, 0);
  EXPECT_EQ(has(l.out, "--init"), "");
  const RunResult all = run({"--help"});
  EXPECT_EQ(has(all.out, "geodesic"), "");
  EXPECT_EQ(has(all.out, "loop"), "");
}

TEST_F(CliGeodesic, PlaneBetweenVerticesIsTheStraightSegment) {
  // Vertex j * 11 + i sits at (i, j, 0).
  for (const char* solver : {"newton", "lbfgs"}) {
    const RunResult r =
        run({"geodesic", plane_, "--from", "2", "--to", "119", "--json", "--solver", solver});
    ASSERT_EQ(r.code, 0) << r.err;
    const YAML::Node j = YAML::Load(r.out);
    EXPECT_NEAR(j["length"].as<double>(), std::hypot(7.0, 10.0), 1e-9) << solver;
    EXPECT_NEAR(j["euclidean_length"].as<double>(), std::hypot(7.0, 10.0), 1e-9);
    EXPECT_GE(j["initial_length"].as<double>(), j["length"].as<double>() - 1e-12);
    EXPECT_EQ(j["solver"].as<std::string>(), solver);
    EXPECT_EQ(j["termination"].as<std::string>().empty(), false);
    for (const char* key : {"iterations", "reroutes", "time_ms", "init_ms", "refine_ms"})
      EXPECT_TRUE(j[key].IsDefined()) << key;
    EXPECT_NEAR(j["time_ms"].as<double>(), j["init_ms"].as<double>() + j["refine_ms"].as<double>(),
                1e-6);
    const YAML::Node pts = j["points"];
    ASSERT_GE(pts.size(), 2u);
    EXPECT_NEAR(pts[0][0].as<double>(), 2.0, 1e-12);
    EXPECT_NEAR(pts[0][1].as<double>(), 0.0, 1e-12);
    EXPECT_NEAR(pts[pts.size() - 1][0].as<double>(), 9.0, 1e-12);
    EXPECT_NEAR(pts[pts.size() - 1][1].as<double>(), 10.0, 1e-12);
    // Every point lies on the segment.
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const double x = pts[k][0].as<double>(), y = pts[k][1].as<double>();
      EXPECT_NEAR(10.0 * (x - 2.0) - 7.0 * y, 0.0, 1e-9) << k;
    }
  }
}

TEST_F(CliGeodesic, PointsGivenAsCoordinatesAreProjected) {
  // 1e-3 above the plane: within the default tolerance (1e-3 x diagonal = 0.014 mm).
  const RunResult r =
      run({"geodesic", plane_, "--from", "0.5,0.25,0.001", "--to", "9.5,7.75,-0.001", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(json_length(r), std::hypot(9.0, 7.5), 1e-9);
  // Text output too.
  const RunResult t = run({"geodesic", plane_, "--from", "0.5,0.25,0", "--to", "3,3,0"});
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_EQ(has(t.out, "length"), "");
  EXPECT_EQ(has(t.out, "termination"), "");
}

TEST_F(CliGeodesic, CsvOutputHoldsThePolyline) {
  const std::string csv = (dir_ / "sub" / "path.csv").string();
  const RunResult r = run({"geodesic", plane_, "--from", "0", "--to", "120", "-o", csv, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const YAML::Node pts = YAML::Load(r.out)["points"];
  std::istringstream in(slurp(csv));
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(has(line, "x [mm]"), "");
  std::size_t rows = 0;
  double last_x = -1.0, last_y = -1.0;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream ls(line);
    double x = 0, y = 0, z = 0;
    ASSERT_TRUE(static_cast<bool>(ls >> x >> y >> z)) << line;
    EXPECT_NEAR(x, y, 1e-9);  // the diagonal of the grid
    EXPECT_NEAR(z, 0.0, 1e-12);
    last_x = x;
    last_y = y;
    ++rows;
  }
  EXPECT_EQ(rows, pts.size());
  EXPECT_NEAR(last_x, 10.0, 1e-9);
  EXPECT_NEAR(last_y, 10.0, 1e-9);
}

TEST_F(CliGeodesic, CylinderUnrolls) {
  const int n = 32, m = 12;
  const double r = 3.0, len = 6.0;
  const std::string tube = (dir_ / "tube.obj").string();
  write_mesh(tube, test::open_cylinder(r, len, n, m));
  // Vertex (i, j) = j * n + i; from (0, 0) to (9, 12): the developed strip gives the length.
  const double chord = 2.0 * r * std::sin(M_PI / n);
  const RunResult res =
      run({"geodesic", tube, "--from", "0", "--to", std::to_string(12 * n + 9), "--json"});
  ASSERT_EQ(res.code, 0) << res.err;
  EXPECT_NEAR(json_length(res), std::hypot(9 * chord, len), 1e-9);
}

TEST_F(CliGeodesic, JobFileUsesTheMandrel) {
  // configs/pipe.yaml: a parametric pipe. The geodesic is at least the chord between its ends
  // and at most the initial edge path.
  const std::string job = (test::source_dir() / "configs/pipe.yaml").string();
  const RunResult r = run({"geodesic", job, "--from", "0", "--to", "100", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const YAML::Node j = YAML::Load(r.out);
  const YAML::Node pts = j["points"];
  ASSERT_GE(pts.size(), 2u);
  Vec3 a, b;
  for (int k = 0; k < 3; ++k) {
    a[k] = pts[0][k].as<double>();
    b[k] = pts[pts.size() - 1][k].as<double>();
  }
  EXPECT_GE(j["length"].as<double>(), (b - a).norm() - 1e-9);
  EXPECT_LE(j["length"].as<double>(), j["initial_length"].as<double>() + 1e-9);
  EXPECT_EQ(run({"geodesic", job, "--from", "0", "--to", "100000"}).code, 1);
}

TEST_F(CliGeodesic, ExactReferenceOnTheCylinder) {
  const int n = 32, m = 12;
  const double r = 3.0, len = 6.0;
  const std::string tube = (dir_ / "tube.obj").string();
  write_mesh(tube, test::open_cylinder(r, len, n, m));
  const double expected = std::hypot(9 * 2.0 * r * std::sin(M_PI / n), len);
  const RunResult res = run(
      {"geodesic", tube, "--from", "0", "--to", std::to_string(12 * n + 9), "--json", "--exact"});
  ASSERT_EQ(res.code, 0) << res.err;
  const YAML::Node j = YAML::Load(res.out);
  EXPECT_NEAR(j["exact_length"].as<double>(), expected, 1e-9);
  EXPECT_NEAR(j["excess"].as<double>(), 0.0, 1e-9);
  EXPECT_EQ(run({"geodesic", tube, "--from", "0", "--to", "5", "--exact", "--density",
                 per_face("rho.txt", 2 * n * m, "1")})
                .code,
            2);
}

TEST_F(CliGeodesic, DensityAndAnisotropicMetricsScaleTheLength) {
  const double straight = std::hypot(7.0, 10.0);
  const RunResult d = run({"geodesic", plane_, "--from", "2", "--to", "119", "--json", "--density",
                           per_face("rho.txt", 200, "2.5")});
  ASSERT_EQ(d.code, 0) << d.err;
  EXPECT_NEAR(json_length(d), 2.5 * straight, 1e-9);
  EXPECT_EQ(YAML::Load(d.out)["metric"].as<std::string>(), "density");
  // T = 3 I in every face frame: every length triples.
  const RunResult a = run({"geodesic", plane_, "--from", "2", "--to", "119", "--json", "--metric",
                           per_face("abc.txt", 200, "3 0 3")});
  ASSERT_EQ(a.code, 0) << a.err;
  EXPECT_NEAR(json_length(a), 3.0 * straight, 1e-9);
  EXPECT_EQ(YAML::Load(a.out)["metric"].as<std::string>(), "anisotropic");
}

TEST_F(CliGeodesic, BadDensityFilesNameTheLine) {
  // Wrong count.
  RunResult r = run({"geodesic", plane_, "--from", "0", "--to", "5", "--density",
                     per_face("short.txt", 199, "1")});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(has(r.err, "short.txt"), "");
  EXPECT_EQ(has(r.err, "200 faces"), "");
  r = run({"geodesic", plane_, "--from", "0", "--to", "5", "--density",
           per_face("long.txt", 201, "1")});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(has(r.err, "long.txt:201"), "");
  // Zero, negative, NaN and garbage, on line 8 (face 7).
  for (const std::string bad : {"0", "-1", "nan", "abc"}) {
    std::string text;
    for (int i = 0; i < 200; ++i) text += (i == 7 ? bad : "1.5") + "\n";
    r = run({"geodesic", plane_, "--from", "0", "--to", "5", "--density", write("bad.txt", text)});
    EXPECT_EQ(r.code, 1) << bad;
    EXPECT_EQ(has(r.err, "bad.txt:8"), "") << bad;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
  }
  // Missing file.
  r = run(
      {"geodesic", plane_, "--from", "0", "--to", "5", "--density", (dir_ / "none.txt").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(has(r.err, "none.txt"), "");
}

TEST_F(CliGeodesic, MetricMustBePositiveDefinite) {
  std::string text;
  for (int i = 0; i < 200; ++i) text += i == 12 ? "1 2 1\n" : "1 0 1\n";
  RunResult r =
      run({"geodesic", plane_, "--from", "0", "--to", "5", "--metric", write("abc.txt", text)});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(has(r.err, "abc.txt:13"), "");
  EXPECT_EQ(has(r.err, "face 12"), "");
  EXPECT_EQ(has(r.err, "positive definite"), "");
  r = run({"geodesic", plane_, "--from", "0", "--to", "5", "--metric",
           per_face("two.txt", 200, "1 1")});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(has(r.err, "three values"), "");
}

/// Two n x n unit grids side by side, `gap` apart: a mesh of two components.
TriangleSoup two_grids(int n, double gap) {
  TriangleSoup two = test::grid(n, n);
  const TriangleSoup other = test::grid(n, n);
  const int shift = static_cast<int>(other.points.size());
  for (const Vec3& p : other.points) two.points.push_back(p + Vec3(n + gap, 0, 0));
  for (const Tri& t : other.triangles)
    two.triangles.push_back({t[0] + shift, t[1] + shift, t[2] + shift});
  return two;
}

TEST_F(CliGeodesic, BadEndpoints) {
  RunResult r = run({"geodesic", plane_, "--from", "0", "--to", "121"});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(has(r.err, "--to 121"), "");
  EXPECT_EQ(has(r.err, "out of range"), "");
  r = run({"geodesic", plane_, "--from", "-3", "--to", "5"});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(has(r.err, "--from -3"), "");
  r = run({"geodesic", plane_, "--from", "5,5,1", "--to", "5"});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(has(r.err, "from the mesh"), "");
  // Two components: a second grid beside the first.
  const std::string file = (dir_ / "two.obj").string();
  write_mesh(file, two_grids(2, 3.0));
  r = run({"geodesic", file, "--from", "0", "--to", "12"});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("internal"), std::string::npos) << r.err;
  // Missing mesh.
  r = run({"geodesic", (dir_ / "nothing.obj").string(), "--from", "0", "--to", "1"});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(has(r.err, "nothing.obj"), "");
}

// A pair without a path among pairs from the same vertex (answered together): the error names
// its line, the first such line of the file (here in the second group), and nothing is written.
TEST_F(CliGeodesic, PairsFromOneVertexNameTheFirstPairWithoutAPath) {
  const std::string mesh = (dir_ / "two.obj").string();
  write_mesh(mesh, two_grids(4, 5.0));
  const fs::path out = dir_ / "batch.csv";
  const RunResult r = run({"geodesic", mesh, "--pairs",
                           write("p.txt", "0 24\n3 7\n3 30\n0 40\n0 12\n"), "-o", out.string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(has(r.err, "p.txt:3:"), "") << r.err;
  EXPECT_EQ(r.err.find("p.txt:4:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(CliGeodesic, UsageErrors) {
  EXPECT_EQ(run({"geodesic", plane_, "--from", "0"}).code, 2);
  EXPECT_EQ(run({"geodesic", plane_, "--from", "0", "--to", "1", "--solver", "gauss"}).code, 2);
  EXPECT_EQ(run({"geodesic", plane_, "--from", "0", "--to", "1,2"}).code, 2);
  EXPECT_EQ(run({"geodesic", plane_, "--from", "zero", "--to", "1"}).code, 2);
  EXPECT_EQ(
      run({"geodesic", plane_, "--from", "0", "--to", "1", "--density", "a", "--metric", "b"}).code,
      2);
  EXPECT_EQ(run({"geodesic", "--from", "0", "--to", "1"}).code, 2);
  EXPECT_EQ(run({"loop", plane_}).code, 2);
}

std::string oblique_ring_csv(double r, double z, double tilt, int n) {
  std::string text = "x,y,z\n";
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * (i + 0.5) / n;
    std::ostringstream s;
    s.precision(17);
    s << r * std::cos(t) << "," << r * std::sin(t) << "," << z + tilt * std::cos(t) << "\n";
    text += s.str();
  }
  return text;
}

TEST_F(CliGeodesic, LoopOnACylinderBecomesARing) {
  // The closed geodesics around a polyhedral cylinder are its horizontal sections: n chords.
  const int n = 24, m = 10;
  const double r = 2.0, len = 8.0;
  const std::string tube = (dir_ / "tube.obj").string();
  write_mesh(tube, test::open_cylinder(r, len, n, m));
  const double chord = 2.0 * r * std::sin(M_PI / n);
  // The curve: an oblique ring near the polyhedral surface (the chords sag by r (1 - cos(pi/n))).
  const std::string curve =
      write("curve.csv", oblique_ring_csv(r * std::cos(M_PI / n), 4.0, 1.0, 40));
  for (const char* solver : {"newton", "lbfgs"}) {
    const std::string out = (dir_ / "loop.csv").string();
    const RunResult res = run({"loop", tube, "--init", curve, "--solver", solver, "--json", "-o",
                               out, "--snap-tolerance", "0.1"});
    ASSERT_EQ(res.code, 0) << res.err;
    const YAML::Node j = YAML::Load(res.out);
    EXPECT_TRUE(j["closed"].as<bool>());
    EXPECT_NEAR(j["length"].as<double>(), n * chord, 1e-7) << solver;
    EXPECT_GT(j["initial_length"].as<double>(), j["length"].as<double>());
    // All points at one height.
    const YAML::Node pts = j["points"];
    ASSERT_GE(pts.size(), static_cast<std::size_t>(n));
    for (std::size_t k = 1; k < pts.size(); ++k)
      EXPECT_NEAR(pts[k][2].as<double>(), pts[0][2].as<double>(), 1e-6) << k;
    EXPECT_TRUE(fs::exists(out));
  }
}

TEST_F(CliGeodesic, BadCurves) {
  const std::string tube = (dir_ / "tube.obj").string();
  write_mesh(tube, test::open_cylinder(2.0, 8.0, 24, 10));
  RunResult r = run({"loop", tube, "--init", write("c.csv", "x,y,z\n2,0,4\n0,2,4\n-2,0,abc\n")});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(has(r.err, "c.csv:4"), "");
  r = run({"loop", tube, "--init", write("two.csv", "2,0,4\n0,2,4\n")});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(has(r.err, "at least 3"), "");
  r = run({"loop", tube, "--init", write("far.csv", "2,0,4\n0,2,4\n-2,0,4\n0,-9,4\n")});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(has(r.err, "far.csv"), "");
  r = run({"loop", tube, "--init", (dir_ / "none.csv").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(has(r.err, "none.csv"), "");
}

// ---- batch queries (--pairs) ----

namespace batch {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

}  // namespace batch

// Landmarks only bound the window search: the same lengths (to round-off of the refined
// corridor), whatever the thread count that built them. Bad counts are usage errors.
TEST_F(CliGeodesic, LandmarksGiveTheSameLengths) {
  const std::string torus = (dir_ / "torus.obj").string();
  write_mesh(torus, test::torus(3.0, 1.0, 40, 16));
  std::string text;
  for (const auto& p : std::vector<std::pair<int, int>>{{0, 300}, {7, 455}, {120, 610}, {33, 34}})
    text += std::to_string(p.first) + " " + std::to_string(p.second) + "\n";
  const std::string file = write("torus_pairs.txt", text);
  const RunResult plain = run({"geodesic", torus, "--pairs", file});
  ASSERT_EQ(plain.code, 0) << plain.err;
  const RunResult one =
      run({"geodesic", torus, "--pairs", file, "--landmarks", "6", "--threads", "1"});
  ASSERT_EQ(one.code, 0) << one.err;
  const RunResult two =
      run({"geodesic", torus, "--pairs", file, "--landmarks", "6", "--threads", "2"});
  ASSERT_EQ(two.code, 0) << two.err;
  const std::vector<std::string> r0 = batch::lines_of(plain.out), r1 = batch::lines_of(one.out),
                                 r2 = batch::lines_of(two.out);
  ASSERT_EQ(r0.size(), 5u);
  ASSERT_EQ(r1.size(), r0.size());
  ASSERT_EQ(r2.size(), r0.size());
  for (std::size_t i = 1; i < r0.size(); ++i) {
    const double l0 = std::stod(batch::csv_fields(r0[i])[3]);
    const double l1 = std::stod(batch::csv_fields(r1[i])[3]);
    EXPECT_NEAR(l1, l0, 1e-12 * l0) << r1[i];
    std::vector<std::string> f1 = batch::csv_fields(r1[i]), f2 = batch::csv_fields(r2[i]);
    f1.pop_back();  // time_ms
    f2.pop_back();
    EXPECT_EQ(f1, f2) << "landmarks built on 1 and 2 threads differ";
  }
  const RunResult single =
      run({"geodesic", torus, "--from", "7", "--to", "455", "--landmarks", "3", "--json"});
  ASSERT_EQ(single.code, 0) << single.err;
  EXPECT_NEAR(json_length(single), std::stod(batch::csv_fields(r0[2])[3]), 1e-12);
  for (const char* bad : {"-1", "65", "2.5", "many"}) {
    const RunResult r = run({"geodesic", torus, "--pairs", file, "--landmarks", bad});
    EXPECT_EQ(r.code, 2) << bad;
    EXPECT_NE(r.err.find("--landmarks"), std::string::npos) << r.err;
  }
  std::string rho;
  for (int f = 0; f < 40 * 16 * 2; ++f) rho += "1.5\n";
  write("rho.txt", rho);
  const RunResult r = run({"geodesic", torus, "--pairs", file, "--landmarks", "2", "--density",
                           (dir_ / "rho.txt").string()});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("Euclidean"), std::string::npos) << r.err;
}

// A batch gives, pair for pair, the length of single runs, in file order, the same whatever the
// thread count; comments and blank lines are skipped and rows name their line. Pairs from one
// vertex are answered together by one resumed window search: their lengths equal single runs'
// to 1e-12 (where shortest paths tie, as on a flat grid, the corridor can differ and so the
// refined length's last digits; found in review).
TEST_F(CliGeodesic, PairsBatchEqualsSingleRuns) {
  const std::string cyl = (dir_ / "cylinder.obj").string();
  write_mesh(cyl, test::open_cylinder(5.0, 20.0, 24, 10));
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {"0", "200"},   {"3", "150"},     {"5,0,0", "0,5,20"}, {"17", "0,-5,10"},
      {"100", "101"}, {"0", "150"},     {"3", "263"},        {"0", "3"},
      {"0", "7"},     {"0", "0,-5,10"}, {"100", "57"},       {"100", "200"}};
  std::string text = "# from to\n\n";
  for (const auto& p : pairs) text += p.first + " " + p.second + "\n";
  const std::string file = write("pairs.txt", text);
  const RunResult one = run({"geodesic", cyl, "--pairs", file, "--threads", "1"});
  ASSERT_EQ(one.code, 0) << one.err;
  const RunResult two = run(
      {"geodesic", cyl, "--pairs", file, "--threads", "2", "-o", (dir_ / "batch.csv").string()});
  ASSERT_EQ(two.code, 0) << two.err;
  const std::vector<std::string> rows1 = batch::lines_of(one.out);
  const std::vector<std::string> rows2 = batch::lines_of(slurp(dir_ / "batch.csv"));
  ASSERT_EQ(rows1.size(), pairs.size() + 1);
  ASSERT_EQ(rows2.size(), rows1.size());
  EXPECT_EQ(rows1[0].rfind("line,from,to,length,", 0), 0u) << rows1[0];
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    std::vector<std::string> f1 = batch::csv_fields(rows1[i + 1]);
    std::vector<std::string> f2 = batch::csv_fields(rows2[i + 1]);
    ASSERT_EQ(f1.size(), 12u) << rows1[i + 1];
    EXPECT_EQ(f1[0], std::to_string(i + 3));  // two skipped lines
    EXPECT_EQ(f1[1], pairs[i].first);
    EXPECT_EQ(f1[2], pairs[i].second);
    f1.pop_back();  // time_ms differs between runs
    f2.pop_back();
    EXPECT_EQ(f1, f2) << "1 thread and 2 threads differ on pair " << i;
    const RunResult single =
        run({"geodesic", cyl, "--from", pairs[i].first, "--to", pairs[i].second, "--json"});
    ASSERT_EQ(single.code, 0) << single.err;
    EXPECT_NEAR(std::stod(f1[3]), json_length(single), 1e-12 * json_length(single)) << "pair " << i;
    EXPECT_EQ(f1[5], "true");
  }
  // JSON lines: one object per pair with the same lengths.
  const RunResult js = run({"geodesic", cyl, "--pairs", file, "--json"});
  ASSERT_EQ(js.code, 0) << js.err;
  const std::vector<std::string> objs = batch::lines_of(js.out);
  ASSERT_EQ(objs.size(), pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const YAML::Node n = YAML::Load(objs[i]);
    EXPECT_EQ(n["length"].as<double>(), std::stod(batch::csv_fields(rows1[i + 1])[3]));
    EXPECT_EQ(n["line"].as<int>(), static_cast<int>(i + 3));
  }
}

// A bad line names the file and line, exits 1 and writes nothing (no partial table).
TEST_F(CliGeodesic, PairsBadLineIsExitOneWithTheLineAndNoOutput) {
  const fs::path out = dir_ / "batch.csv";
  for (const char* bad_line : {"0 9999", "zero 5", "3 50,50,50", "1 2 3", "-1 4"}) {
    const std::string bad = bad_line;
    const std::string file = write("bad.txt", "0 120\n# ok so far\n" + bad + "\n5 6\n");
    const RunResult r = run({"geodesic", plane_, "--pairs", file, "-o", out.string()});
    EXPECT_EQ(r.code, 1) << bad << ": " << r.err;
    EXPECT_EQ(has(r.err, "bad.txt:3:"), "") << bad;
    EXPECT_FALSE(fs::exists(out)) << bad;
    EXPECT_EQ(r.out, "") << bad;
  }
  const RunResult empty = run({"geodesic", plane_, "--pairs", write("empty.txt", "# none\n")});
  EXPECT_EQ(empty.code, 1);
  const RunResult both =
      run({"geodesic", plane_, "--pairs", write("p.txt", "0 1\n"), "--from", "0"});
  EXPECT_EQ(both.code, 2);
  const RunResult threads =
      run({"geodesic", plane_, "--pairs", write("p.txt", "0 1\n"), "--threads", "0"});
  EXPECT_EQ(threads.code, 2);
}

// Issue 28: a NUL inside a token was cut by the number parser and copied whole into the CSV;
// a FIFO or /dev/zero as the pairs file blocked or grew without bound.
TEST_F(CliGeodesic, PairsFileIsPlainTextInARegularFile) {
  const std::string nul = write("nul.txt", std::string("0 120\n5\0junk 6\n", 16));
  RunResult r = run({"geodesic", plane_, "--pairs", nul});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(has(r.err, "nul.txt:2: a control character (NUL) in the line"), "") << r.err;
  EXPECT_EQ(r.out, "");
  r = run({"geodesic", plane_, "--pairs", "/dev/zero"});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(has(r.err, "/dev/zero: is a character device"), "") << r.err;
  const fs::path fifo = dir_ / "pairs.fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  r = run({"geodesic", plane_, "--pairs", fifo.string()});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(has(r.err, "pairs.fifo: is a FIFO (named pipe)"), "") << r.err;
}

// A long batch says how far it is (1e6 pairs ran for minutes without a word): in a log, a line
// every 10 % and one at the end; a short batch prints nothing. (The pairs from one vertex are
// answered together, so a line may count a few pairs past its 10 %.)
TEST_F(CliGeodesic, LongPairsBatchesShowProgress) {
  std::string text;
  for (int i = 0; i < 1000; ++i)
    text += std::to_string(i % 121) + " " + std::to_string(120 - i % 121) + "\n";
  const RunResult r = run(
      {"geodesic", plane_, "--pairs", write("many.txt", text), "-o", (dir_ / "many.csv").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(has(r.err, " of 1000 pairs (10 %)"), "") << r.err;
  EXPECT_EQ(has(r.err, " of 1000 pairs (90 %)"), "") << r.err;
  EXPECT_EQ(has(r.err, "(1000 pairs)"), "") << r.err;
  const RunResult few = run({"geodesic", plane_, "--pairs", write("few.txt", "0 120\n")});
  EXPECT_EQ(few.err.find("pairs ("), std::string::npos) << few.err;
  // All from one vertex (answered in groups of a few pairs, so progress still shows).
  std::string one;
  for (int i = 0; i < 1000; ++i) one += "60 " + std::to_string(i % 121) + "\n";
  const RunResult same = run(
      {"geodesic", plane_, "--pairs", write("one.txt", one), "-o", (dir_ / "one.csv").string()});
  ASSERT_EQ(same.code, 0) << same.err;
  int lines = 0;
  for (std::size_t at = 0; (at = same.err.find(" of 1000 pairs (", at)) != std::string::npos; ++at)
    ++lines;
  EXPECT_GE(lines, 8) << same.err;
  EXPECT_LE(lines, 9) << same.err;
}

// Loops in a batch: each row equals the single run of the same curve, whatever the thread count;
// a bad curve line names the line and writes nothing.
TEST_F(CliGeodesic, CurvesBatchEqualsSingleLoops) {
  const int n = 24, m = 10;
  const double r = 2.0, len = 8.0;
  const std::string tube = (dir_ / "tube.obj").string();
  write_mesh(tube, test::open_cylinder(r, len, n, m));
  std::string batch_text = "# one closed curve per line\n";
  std::vector<std::string> singles;
  for (int k = 0; k < 3; ++k) {
    const std::string csv = oblique_ring_csv(r * std::cos(M_PI / n), 3.0 + k, 0.5 + 0.25 * k, 30);
    singles.push_back(write("curve" + std::to_string(k) + ".csv", csv));
    std::istringstream in(csv);
    std::string line, joined;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#' || line[0] == 'x') continue;
      std::string pt;
      std::istringstream ls(line);
      std::vector<std::string> parts;
      for (std::string tok; std::getline(ls, tok, ',');) parts.push_back(tok);
      if (parts.size() != 3) continue;
      joined += (joined.empty() ? "" : " ") + parts[0] + "," + parts[1] + "," + parts[2];
    }
    batch_text += joined + "\n";
  }
  const std::string file = write("curves.txt", batch_text);
  const RunResult one =
      run({"loop", tube, "--curves", file, "--snap-tolerance", "0.1", "--threads", "1"});
  ASSERT_EQ(one.code, 0) << one.err;
  const RunResult two =
      run({"loop", tube, "--curves", file, "--snap-tolerance", "0.1", "--threads", "2", "--json"});
  ASSERT_EQ(two.code, 0) << two.err;
  const std::vector<std::string> rows = batch::lines_of(one.out);
  const std::vector<std::string> objs = batch::lines_of(two.out);
  ASSERT_EQ(rows.size(), 4u);
  ASSERT_EQ(objs.size(), 3u);
  EXPECT_EQ(rows[0].rfind("line,points,length,", 0), 0u) << rows[0];
  for (int k = 0; k < 3; ++k) {
    const std::vector<std::string> f = batch::csv_fields(rows[k + 1]);
    EXPECT_EQ(f[0], std::to_string(k + 2));
    EXPECT_EQ(f[1], "30");
    const RunResult single =
        run({"loop", tube, "--init", singles[k], "--snap-tolerance", "0.1", "--json"});
    ASSERT_EQ(single.code, 0) << single.err;
    EXPECT_EQ(std::stod(f[2]), json_length(single)) << "curve " << k;
    EXPECT_EQ(YAML::Load(objs[k])["length"].as<double>(), std::stod(f[2])) << "curve " << k;
    EXPECT_NEAR(std::stod(f[2]), n * 2.0 * r * std::sin(M_PI / n), 1e-7);
  }
  const fs::path out = dir_ / "loops.csv";
  const std::string bad = write("bad.txt", batch::lines_of(batch_text)[1] + "\n1,2 3,4,5\n");
  const RunResult r1 =
      run({"loop", tube, "--curves", bad, "-o", out.string(), "--snap-tolerance", "0.1"});
  EXPECT_EQ(r1.code, 1);
  EXPECT_EQ(has(r1.err, "bad.txt:2:"), "");
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace windplan
