#include "planner/mandrel/mandrel_mesh.h"

#include <unistd.h>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/mesh/mesh_io.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

namespace fs = std::filesystem;

class MandrelMesh : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("windplan_mandrel_mesh_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(MandrelMesh, ScalesUnitsToMillimetres) {
  // A tube of radius 0.05 m and length 0.2 m written in metres.
  write_mesh(dir_ / "tube.obj", test::open_cylinder(0.05, 0.2, 32, 4));
  MandrelOptions m;
  m.file = dir_ / "tube.obj";
  m.units = LengthUnit::Metre;
  MeshHealth h;
  const Mesh mesh = load_mandrel_mesh(m, &h);
  const BoundingBox box = mesh.bounding_box();
  EXPECT_NEAR(box.max.z() - box.min.z(), 200.0, 1e-9);
  EXPECT_NEAR(box.max.x(), 50.0, 1e-9);
  EXPECT_NEAR(h.bbox.max.z(), 200.0, 1e-9);
  m.units = LengthUnit::Inch;
  EXPECT_NEAR(load_mandrel_mesh(m).bounding_box().max.z(), 0.2 * 25.4, 1e-12);
}

TEST_F(MandrelMesh, RepairFollowsTheOption) {
  TriangleSoup s = test::octahedron();
  std::swap(s.triangles[3][0], s.triangles[3][1]);
  write_mesh(dir_ / "o.ply", s);
  MandrelOptions m;
  m.file = dir_ / "o.ply";
  std::vector<std::string> changes;
  EXPECT_EQ(load_mandrel_mesh(m, nullptr, &changes).genus(), 0);
  EXPECT_EQ(changes.size(), 1u);
  m.repair = false;
  try {
    load_mandrel_mesh(m);
    FAIL() << "no TopologyError";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("o.ply"), std::string::npos) << e.what();
  }
}

TEST_F(MandrelMesh, MissingFileIsAnIoErrorNamingIt) {
  MandrelOptions m;
  m.file = dir_ / "missing.stl";
  try {
    load_mandrel_mesh(m);
    FAIL() << "no IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.stl"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace windplan
