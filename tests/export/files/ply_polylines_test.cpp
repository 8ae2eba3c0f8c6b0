// paths.ply (export/files/ply_polylines.h) read back line by line: the header's counts, every
// vertex's coordinates as printf("%.10g") prints them (the C library's formatting, not the
// writer's; negative zero as 0, magnitudes from 1e-7 to 1e8 and values needing all ten digits),
// its circuit or cut-line id, and every edge, a closed cut-line's closing edge included.
#include "export/files/ply_polylines.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace windplan {
namespace {

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

std::string printf_point(const Vec3& p, long id) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%.10g %.10g %.10g %ld", p.x() + 0.0, p.y() + 0.0, p.z() + 0.0,
                id);
  return buf;
}

TEST(PlyPolylines, CoordinatesAsPrintfPrintsThemAndEveryEdge) {
  WindingPlan plan;
  const std::vector<std::vector<Vec3>> circuits = {
      {Vec3(0.0, -0.0, 1.0 / 3.0), Vec3(-123.456789012345, 1e-7, 98765432.1),
       Vec3(2.5e-5, -7.0, 1e8)},
      {Vec3(1234567.891, -0.000123456789123, 42.0), Vec3(-1.0 / 7.0, 5.5, -9.999999999999)}};
  for (std::size_t k = 0; k < circuits.size(); ++k) {
    Circuit c;
    c.index = static_cast<int>(k) + 3;
    for (const Vec3& p : circuits[k]) {
      FibrePoint q;
      q.position = p;
      c.points.push_back(q);
    }
    plan.circuits.push_back(c);
  }
  CutLine loop;
  loop.points = {Vec3(1, 0, -2), Vec3(0, 1, -2.000000000001), Vec3(-1, 0, -2)};
  loop.closed = true;
  CutLine open;
  open.points = {Vec3(3, 3, 3), Vec3(4, 4, 4)};
  open.closed = false;
  plan.cutlines = {loop, open};

  const std::vector<std::string> l = lines(paths_ply(plan));
  std::size_t at = 0;
  while (at < l.size() && l[at] != "end_header") ++at;
  ASSERT_LT(at, l.size());
  const std::string text(paths_ply(plan));
  EXPECT_NE(text.find("element vertex 10\n"), std::string::npos);
  EXPECT_NE(text.find("element edge 7\n"), std::string::npos);  // 2 + 1 + 3 (closed) + 1
  std::vector<std::string> expect;
  for (std::size_t k = 0; k < circuits.size(); ++k) {
    for (const Vec3& p : circuits[k]) expect.push_back(printf_point(p, static_cast<long>(k) + 3));
  }
  for (const Vec3& p : loop.points) expect.push_back(printf_point(p, -1));
  for (const Vec3& p : open.points) expect.push_back(printf_point(p, -2));
  expect.insert(expect.end(), {"0 1 3", "1 2 3", "3 4 4", "5 6 -1", "6 7 -1", "7 5 -1", "8 9 -2"});
  const std::vector<std::string> body(l.begin() + at + 1, l.end());
  EXPECT_EQ(body, expect);
  // No "-0" anywhere.
  EXPECT_EQ(text.find(" -0 "), std::string::npos);
  EXPECT_EQ(body.front().rfind("0 0 0.3333333333 3", 0), 0u) << body.front();
}

}  // namespace
}  // namespace windplan
