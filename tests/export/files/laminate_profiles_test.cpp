#include "export/files/laminate_profiles.h"

#include <gtest/gtest.h>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

LaminateProfiles two_layers() {
  LaminateProfiles p;
  p.mandrel = MeridianPolyline::from_points({Vec2(0, 50), Vec2(100, 50)}).resampled(10.0);
  MeridianPolyline surface = p.mandrel;
  for (double t : {1.0, 0.5}) {
    LayerThickness th;
    th.s = surface.s;
    th.thickness.assign(surface.s.size(), t);
    MeridianPolyline next = offset_meridian(surface, th, "test");
    p.names.push_back(t == 1.0 ? "hoop1" : "helical1");
    p.thickness.push_back(th);
    p.surfaces.push_back(next);
    surface = next;
  }
  return p;
}

TEST(LaminateProfiles, CsvRowsPerSurfaceWithTheRunningTotal) {
  const LaminateProfiles p = two_layers();
  const CsvTable t = laminate_profiles_table(p);
  const std::size_t n = p.mandrel.points.size();
  ASSERT_EQ(t.rows.size(), 3 * n);
  EXPECT_EQ(t.header[4], "radius [mm]");
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(t.rows[i][0], 0.0);
    EXPECT_DOUBLE_EQ(t.rows[i][4], 50.0);
    EXPECT_NEAR(t.rows[n + i][4], 51.0, 1e-12);
    EXPECT_NEAR(t.rows[2 * n + i][4], 51.5, 1e-12);
    EXPECT_DOUBLE_EQ(t.rows[2 * n + i][5], 0.5);  // layer 2's thickness
    EXPECT_DOUBLE_EQ(t.rows[2 * n + i][6], 1.5);  // total
    EXPECT_DOUBLE_EQ(t.rows[2 * n + i][2], p.mandrel.s[i]);
  }
  LaminateProfiles bad = p;
  bad.surfaces[1].points.pop_back();
  EXPECT_THROW(laminate_profiles_table(bad), InputError);
}

TEST(LaminateProfiles, SvgPlotsEverySurfaceAndTheStack) {
  const LaminateProfiles p = two_layers();
  const std::string svg = laminate_profiles_svg(p);
  EXPECT_EQ(svg, laminate_profiles_svg(p));  // deterministic
  std::size_t lines = 0;
  for (std::size_t at = svg.find("<polyline"); at != std::string::npos;
       at = svg.find("<polyline", at + 1)) {
    ++lines;
  }
  EXPECT_EQ(lines, 5u);  // the mandrel, two surfaces, two cumulative thickness lines
  EXPECT_NE(svg.find("1: hoop1"), std::string::npos);
  EXPECT_NE(svg.find("2: helical1"), std::string::npos);
  EXPECT_NE(svg.find("0 to 1.500"), std::string::npos);
  EXPECT_EQ(svg.rfind("</svg>\n"), svg.size() - 7);
}

// With the spline dome model the profiles carry the other model too: a column, dashed lines.
TEST(LaminateProfiles, ShowsTheAlternativeModel) {
  LaminateProfiles p = two_layers();
  EXPECT_EQ(laminate_profiles_table(p).header.size(), 7u);  // none: the columns as before
  EXPECT_EQ(laminate_profiles_svg(p).find("stroke-dasharray"), std::string::npos);
  p.alternative_name = "continuity";
  for (const LayerThickness& t : p.thickness) {
    LayerThickness a = t;
    for (double& v : a.thickness) v *= 2.0;
    p.alternative.push_back(a);
  }
  const CsvTable t = laminate_profiles_table(p);
  ASSERT_EQ(t.header.size(), 8u);
  EXPECT_EQ(t.header[7], "thickness continuity [mm]");
  const std::size_t n = p.mandrel.points.size();
  EXPECT_DOUBLE_EQ(t.rows[0][7], 0.0);                         // the mandrel
  EXPECT_DOUBLE_EQ(t.rows[2 * n][7], 2.0 * t.rows[2 * n][5]);  // layer 2
  const std::string svg = laminate_profiles_svg(p);
  EXPECT_NE(svg.find("dashed: continuity"), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
}

}  // namespace
}  // namespace windplan
