#include "export/files/csv.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"

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

TEST(Csv, NumbersMatchPrintfG) {
  // The fast formatter must print exactly what printf("%.*g") prints.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> mant(-10, 10), ex(-12, 12);
  for (int i = 0; i < 20000; ++i) {
    const double v = mant(rng) * std::pow(10.0, std::floor(ex(rng)));
    for (int digits : {4, 10, 17}) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.*g", digits, v);
      ASSERT_EQ(format_csv_number(v, digits), buf) << v;
    }
  }
  EXPECT_EQ(format_csv_number(-3, 10), "-3");
  EXPECT_EQ(format_csv_number(1e20, 10), "1e+20");
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
