#include "planner/job/job.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

std::string error_of(const std::string& yaml) {
  try {
    load_job_from_string(yaml, "/jobs/test.yaml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(Job, LoadsMeshMandrelAndResolvesPathRelativeToJob) {
  const Job job = load_job_from_string(
      "name: tube\nmandrel:\n  source: mesh\n  file: meshes/tube.stl\n  units: in\n"
      "  repair: false\n",
      "/jobs/test.yaml");
  EXPECT_EQ(job.name, "tube");
  EXPECT_EQ(job.mandrel.file, std::filesystem::path("/jobs/meshes/tube.stl"));
  EXPECT_EQ(job.mandrel.units, LengthUnit::Inch);
  EXPECT_DOUBLE_EQ(to_millimetres(job.mandrel.units), 25.4);
  EXPECT_FALSE(job.mandrel.repair);
}

TEST(Job, NameDefaultsToFileStem) {
  const Job job = load_job_from_string("mandrel:\n  file: a.obj\n", "/x/my-job.yaml");
  EXPECT_EQ(job.name, "my-job");
  EXPECT_TRUE(job.mandrel.repair);
}

TEST(Job, UnknownKeyNamesFileLineAndKey) {
  const std::string e = error_of("mandrel:\n  file: a.obj\n  repiar: true\n");
  EXPECT_NE(e.find("/jobs/test.yaml:3"), std::string::npos) << e;
  EXPECT_NE(e.find("mandrel.repiar"), std::string::npos) << e;
}

TEST(Job, UnknownTopLevelSectionIsRejected) {
  const std::string e = error_of("mandrel:\n  file: a.obj\nwindings:\n  turns: 3\n");
  EXPECT_NE(e.find(":3"), std::string::npos) << e;
  EXPECT_NE(e.find("windings"), std::string::npos) << e;
}

TEST(Job, WrongTypeIsRejected) {
  const std::string e = error_of("mandrel:\n  file: a.obj\n  repair: maybe\n");
  EXPECT_NE(e.find("mandrel.repair"), std::string::npos) << e;
  EXPECT_NE(e.find("boolean"), std::string::npos) << e;
}

TEST(Job, MissingFileKeyIsRejected) {
  const std::string e = error_of("mandrel:\n  source: mesh\n");
  EXPECT_NE(e.find("mandrel.file"), std::string::npos) << e;
}

TEST(Job, BadUnitAndSyntaxErrors) {
  EXPECT_NE(error_of("mandrel:\n  file: a.obj\n  units: cm\n").find("units"), std::string::npos);
  EXPECT_NE(error_of("mandrel: [\n").find("YAML syntax"), std::string::npos);
  EXPECT_NE(error_of("").find("empty"), std::string::npos);
  EXPECT_NE(error_of("name: x\n").find("mandrel"), std::string::npos);
}

TEST(Job, MissingJobFileIsAnIoError) { EXPECT_THROW(load_job("/nonexistent/job.yaml"), IoError); }

}  // namespace
}  // namespace windplan

namespace windplan {
namespace {

// Issue 18: `name: "../../escape"` or an absolute name wrote 9 files outside out/.
TEST(Job, NameIsCheckedBeforeItBecomesAFolderName) {
  const std::string pipe = "mandrel: {source: pipe, pipe: {radius: 50, length: 500}}\n";
  for (const char* bad : {"\"../../escape\"", "/tmp/abs", "a/b", "\"a\\\\b\"", "..", "\".hidden\"",
                          "\"\"", "\"x\\ty\""}) {
    const std::string e = error_of(pipe + "name: " + bad + "\n");
    EXPECT_NE(e.find("/jobs/test.yaml:2: key 'name'"), std::string::npos) << bad << " -> " << e;
  }
  EXPECT_EQ(load_job_from_string(pipe + "name: tank-7 rev.B\n", "/jobs/test.yaml").name,
            "tank-7 rev.B");
}

TEST(Job, MandrelFileThatIsAFolderSaysSo) {
  // Once "unknown mesh format" (a folder has no extension).
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "windplan_job_dir_mesh";
  std::filesystem::create_directories(dir / "tube");
  const std::string e = [&] {
    try {
      load_job_from_string("mandrel: {source: mesh, file: tube}\n", dir / "j.yaml");
    } catch (const ConfigError& x) {
      return std::string(x.what());
    }
    return std::string();
  }();
  std::filesystem::remove_all(dir);
  EXPECT_NE(e.find("key 'mandrel.file'"), std::string::npos) << e;
  EXPECT_NE(e.find("is a directory"), std::string::npos) << e;
}

// design: (planner/layup/design.h): the bad inputs of issue #27, each one line naming the key.
const char* const kDesignVessel =
    "mandrel:\n  source: vessel\n  vessel: {radius: 100, length: 300, dome: {polar_opening: "
    "30}}\nwinding: {band_width: 16}\nmaterial: {tows: 4}\n";

TEST(Job, DesignBadInputNamesTheKey) {
  std::string e = error_of(std::string(kDesignVessel) + "design:\n  pressure: 10\n");
  EXPECT_NE(e.find("design.fibre_strength"), std::string::npos) << e;
  EXPECT_NE(e.find("test.yaml:"), std::string::npos) << e;
  e = error_of(std::string(kDesignVessel) +
               "design:\n  pressure: 10\n  fibre_strength: 4900\n  fibre_volume_fraction: 1.2\n");
  EXPECT_NE(e.find("design.fibre_volume_fraction"), std::string::npos) << e;
  e = error_of(std::string(kDesignVessel) +
               "design:\n  pressure: 10\n  fibre_strength: 4900\n  burst_factor: 0.8\n");
  EXPECT_NE(e.find("design.burst_factor"), std::string::npos) << e;
  e = error_of(
      "mandrel:\n  source: cone\n  cone: {radius_start: 60, radius_end: 40, length: "
      "400}\ndesign:\n  pressure: 10\n  fibre_strength: 4900\n");
  EXPECT_NE(e.find("design"), std::string::npos) << e;
  EXPECT_NE(e.find("vessel or pipe"), std::string::npos) << e;
  e = error_of(std::string(kDesignVessel) + "design:\n  dome_thickness: cubic\n");
  EXPECT_NE(e.find("dome_thickness"), std::string::npos) << e;
  e = error_of(
      "mandrel:\n  source: pipe\n  pipe: {radius: 50, length: 500}\ndesign:\n  pressure: 10\n  "
      "fibre_strength: 4900\n");
  EXPECT_NE(e.find("winding.angle"), std::string::npos) << e;
  for (const std::string& m : {std::string("design.fibre_strength")}) {
    EXPECT_EQ(std::count(e.begin(), e.end(), '\n'), 0) << m;  // one line
  }
}

TEST(Job, DesignSizesTheLayersFromThePressure) {
  const Job job = load_job_from_string(
      std::string(kDesignVessel) +
          "design:\n  pressure: 10\n  burst_factor: 2.25\n  fibre_strength: 4900\n",
      "/jobs/test.yaml");
  ASSERT_TRUE(job.sized);
  // c = 30 + 8 mm: a = asin(0.38); sigma = 4900 x 0.6; 2.25 x 10 MPa.
  EXPECT_NEAR(job.sizing.angle_deg, std::asin(0.38) * 180.0 / M_PI, 1e-12);
  const double a = std::asin(0.38), sigma = 4900.0 * 0.6;
  EXPECT_NEAR(job.sizing.required.helical_thickness,
              22.5 * 100.0 / (2.0 * sigma * std::cos(a) * std::cos(a)), 1e-12);
  EXPECT_EQ(job.sizing.helical_layers, 2);
  EXPECT_EQ(job.sizing.hoop_layers, 2);
  ASSERT_EQ(job.layers.size(), 4u);
  EXPECT_EQ(job.layers[0].kind, LayerKind::Hoop);
  // A given layup is not sized.
  const Job given = load_job_from_string(
      std::string(kDesignVessel) +
          "layers:\n  - kind: helical\ndesign:\n  pressure: 10\n  fibre_strength: 4900\n",
      "/jobs/test.yaml");
  EXPECT_FALSE(given.sized);
  EXPECT_EQ(given.layers.size(), 1u);
}

}  // namespace
}  // namespace windplan
