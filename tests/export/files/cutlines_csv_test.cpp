// cutlines.csv (export/files/cutlines_csv.h): header, one row per point, names as strings.
#include "export/files/cutlines_csv.h"

#include <sstream>

#include <unistd.h>

#include <gtest/gtest.h>

#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"

namespace windplan {
namespace {

std::vector<CutLine> two_lines() {
  CutLine a;
  a.name = "trim_start";
  a.points = {Vec3(1, 0, 0), Vec3(0, 1, 0.5), Vec3(-1, 0, 0.25)};
  CutLine b;
  b.name = "odd, \"name\"";
  b.closed = false;
  b.points = {Vec3(0.1, 0.2, 0.3), Vec3(1e-12, -2.5, 1000)};
  return {a, b};
}

TEST(CutlinesCsv, OneRowPerPointWithTheNameAsAString) {
  std::ostringstream s;
  write_cutlines_csv(s, two_lines());
  EXPECT_EQ(s.str(),
            "name,index,x [mm],y [mm],z [mm]\n"
            "trim_start,0,1,0,0\n"
            "trim_start,1,0,1,0.5\n"
            "trim_start,2,-1,0,0.25\n"
            "\"odd, \"\"name\"\"\",0,0.1,0.2,0.3\n"
            "\"odd, \"\"name\"\"\",1,1e-12,-2.5,1000\n");
  std::ostringstream empty;
  write_cutlines_csv(empty, {});
  EXPECT_EQ(empty.str(), "name,index,x [mm],y [mm],z [mm]\n");
}

TEST(CutlinesCsv, FileIsWrittenAndUnwritablePathIsAnIoError) {
  const std::filesystem::path p = std::filesystem::temp_directory_path() /
                                  ("windplan_cutlines_csv_" + std::to_string(::getpid())) /
                                  "cutlines.csv";
  write_cutlines_csv(p, two_lines());
  std::ostringstream s;
  write_cutlines_csv(s, two_lines());
  EXPECT_EQ(read_text_file(p), s.str());
  std::filesystem::remove_all(p.parent_path());
  EXPECT_THROW(write_cutlines_csv("/proc/windplan/none/cutlines.csv", two_lines()), IoError);
}

}  // namespace
}  // namespace windplan
