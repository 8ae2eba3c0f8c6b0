// Runs the built windplan binary (WINDPLAN_BINARY) and checks exit codes, stdout and stderr.
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "geometry/mesh/mesh_io.h"
#include "geometry/mesh/mesh_validation.h"
#include "tests/cli/cli_runner.h"
#include "tests/mesh_fixtures.h"
#include "tests/test_data.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

using test::RunResult;
using test::slurp;

class Cli : public test::CliTest {
 protected:
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
};

const std::string kTube = (test::source_dir() / "configs/meshes/tube.obj").string();

TEST_F(Cli, Help) {
  const RunResult r = run({"--help"});
  EXPECT_EQ(r.code, 0);
  EXPECT_NE(r.out.find("mesh"), std::string::npos) << r.out;
  const RunResult m = run({"mesh", "--help"});
  EXPECT_EQ(m.code, 0);
  EXPECT_NE(m.out.find("--repair"), std::string::npos) << m.out;
  EXPECT_NE(m.out.find("--json"), std::string::npos) << m.out;
}

TEST_F(Cli, Version) {
  const RunResult r = run({"--version"});
  EXPECT_EQ(r.code, 0);
  EXPECT_EQ(r.out.rfind("windplan ", 0), 0u) << r.out;
}

TEST_F(Cli, MeshJsonOnTheShippedTube) {
  const RunResult r = run({"mesh", kTube, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const YAML::Node j = YAML::Load(r.out);  // JSON is YAML
  ASSERT_TRUE(j.IsMap()) << r.out;
  // configs/meshes/make_tube.py: 48 around, 24 along, radius 50, length 200.
  EXPECT_EQ(j["vertices"].as<int>(), 48 * 25);
  EXPECT_EQ(j["faces"].as<int>(), 2 * 48 * 24);
  EXPECT_EQ(j["components"].as<int>(), 1);
  EXPECT_EQ(j["boundary_loops"].as<int>(), 2);
  EXPECT_EQ(j["boundary_edges"].as<int>(), 2 * 48);
  EXPECT_EQ(j["genus"].as<int>(), 0);
  EXPECT_FALSE(j["closed"].as<bool>());
  EXPECT_TRUE(j["manifold"].as<bool>());
  EXPECT_TRUE(j["oriented"].as<bool>());
  EXPECT_NEAR(j["bbox"]["max"][2].as<double>(), 200.0, 1e-9);
  EXPECT_NEAR(j["bbox"]["min"][0].as<double>(), -50.0, 1e-9);
  EXPECT_NEAR(j["edge_length"]["min"].as<double>(), 2 * 50 * std::sin(M_PI / 48), 1e-9);
  EXPECT_EQ(j["degenerate_triangles"].as<int>(), 0);
  EXPECT_FALSE(j["repair"]["requested"].as<bool>());
  EXPECT_TRUE(j["problems"].IsSequence());
}

TEST_F(Cli, MeshTextReportOfAJob) {
  const RunResult r = run({"mesh", (test::source_dir() / "configs/tube_mesh.yaml").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("boundary loops:  2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("repaired: nothing to repair"), std::string::npos) << r.out;
}

TEST_F(Cli, RepairAndWriteThenReadBack) {
  TriangleSoup s = test::torus(3, 1, 12, 8);
  std::swap(s.triangles[7][0], s.triangles[7][1]);
  write_mesh(dir_ / "in.obj", s);
  const fs::path out = dir_ / "fixed.ply";
  const RunResult r =
      run({"mesh", (dir_ / "in.obj").string(), "--repair", "-o", out.string(), "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const YAML::Node j = YAML::Load(r.out);
  EXPECT_TRUE(j["oriented"].as<bool>());
  EXPECT_FALSE(j["input"]["oriented"].as<bool>());
  EXPECT_EQ(j["input"]["inconsistent_edges"].as<int>(), 3);
  EXPECT_EQ(j["repair"]["changes"].size(), 1u);
  const TriangleSoup back = read_mesh(out);
  EXPECT_EQ(back.points, s.points);
  EXPECT_EQ(check_mesh(back).genus, 1);
  EXPECT_TRUE(check_mesh(back).oriented);
}

TEST_F(Cli, BrokenMeshGetsItsReportButCannotBeWritten) {
  // A fin: three triangles on one edge.
  write("fin.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  const RunResult report = run({"mesh", (dir_ / "fin.obj").string()});
  EXPECT_EQ(report.code, 0) << report.err;
  EXPECT_NE(report.out.find("non-manifold edge"), std::string::npos) << report.out;
  const RunResult w =
      run({"mesh", (dir_ / "fin.obj").string(), "--repair", "-o", (dir_ / "x.ply").string()});
  EXPECT_EQ(w.code, 1);
  EXPECT_NE(w.err.find("(0, 1)"), std::string::npos) << w.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.ply"));
}

TEST_F(Cli, MissingFileIsExit1NamingIt) {
  const RunResult r = run({"mesh", (dir_ / "no_such_mesh.stl").string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("no_such_mesh.stl"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
}

TEST_F(Cli, AJobWithAParametricMandrelIsRedirected) {
  const fs::path job =
      write("pipe.yaml", "mandrel:\n  source: pipe\n  pipe: {radius: 5, length: 20}\n");
  const RunResult r = run({"mesh", job.string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("'pipe'"), std::string::npos) << r.err;
}

TEST_F(Cli, UnknownFlagIsExit2) {
  const RunResult r = run({"mesh", kTube, "--frobnicate"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--frobnicate"), std::string::npos) << r.err;
  EXPECT_EQ(run({"mesh"}).code, 2);
  EXPECT_EQ(run({"mesh", kTube, "-o", (dir_ / "x.stl").string()}).code, 2);
}

TEST_F(Cli, JobWithUnknownKeyIsExit1NamingFileLineKey) {
  const fs::path job = write(
      "job.yaml", "name: t\nmandrel:\n  source: mesh\n  file: " + kTube + "\n  colour: red\n");
  const RunResult r = run({"mesh", job.string()});
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("job.yaml:5"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("colour"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace windplan
