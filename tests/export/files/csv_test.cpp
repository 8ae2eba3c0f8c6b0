#include "export/files/csv.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/base/parallel.h"

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

// Rows are formatted in chunks in parallel: a table of several batches of chunks (and a partial
// one) reads back the same at 1 and 2 threads, row by row as format_csv_number prints them.
TEST(Csv, ManyRowsAreTheSameOnOneThreadAndOnTwoAndInOrder) {
  CsvTable t;
  t.header = {"i", "x", "y"};
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-500.0, 500.0);
  for (int i = 0; i < 150001; ++i) t.rows.push_back({double(i), u(rng), u(rng) * 1e-6});
  std::string text[2];
  for (int threads : {1, 2}) {
    const ThreadLimit limit(threads);
    std::ostringstream out;
    write_csv(out, t);
    text[threads - 1] = out.str();
  }
  EXPECT_EQ(text[0], text[1]);
  std::istringstream in(text[1]);
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(line, "i,x,y");
  for (const std::vector<double>& row : t.rows) {
    ASSERT_TRUE(std::getline(in, line));
    ASSERT_EQ(line, format_csv_number(row[0], 10) + "," + format_csv_number(row[1], 10) + "," +
                        format_csv_number(row[2], 10));
  }
  EXPECT_FALSE(std::getline(in, line));
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
