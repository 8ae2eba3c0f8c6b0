#include "export/csv.h"

#include <sstream>

#include <gtest/gtest.h>

#include "geometry/errors.h"

namespace windplan {
namespace {

TEST(Csv, FormatsDeterministically) {
  CsvTable t;
  t.header = {"i", "x [mm]"};
  t.rows = {{0, 1.5}, {1, -0.0}, {2, 1.0 / 3.0}};
  t.digits = 6;
  std::ostringstream out;
  write_csv(out, t);
  EXPECT_EQ(out.str(), "i,x [mm]\n0,1.5\n1,0\n2,0.333333\n");
}

TEST(Csv, RowWidthMismatchIsAnError) {
  CsvTable t;
  t.header = {"a", "b"};
  t.rows = {{1.0}};
  std::ostringstream out;
  EXPECT_THROW(write_csv(out, t), InvariantError);
}

}  // namespace
}  // namespace windplan
