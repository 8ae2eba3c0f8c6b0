#include "planner/job/job.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace windplan
