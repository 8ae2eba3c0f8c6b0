// select_region / candidate_regions / suggest_region on mandrels made in code: a flanged pipe
// with shafts, bolt holes and a bore; two pipes in a row; a pipe seen from an axis beside it.
#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/cad/parametric_mandrel.h"
#include "geometry/cad/section_mandrel.h"
#include "geometry/cad/tessellate.h"
#include "geometry/region/mandrel_region.h"

namespace windplan {
namespace {

Mesh flanged_pipe() {
  MandrelFeatures f;
  f.bore = 20;
  f.shaft_start = {25, 100};
  f.shaft_end = {25, 100};
  f.flanges = {FlangeParams{0, 90, 12, 8, 5, 75}, FlangeParams{488, 90, 12, 8, 5, 75}};
  const CadShape s =
      add_mandrel_features(make_pipe(PipeParams{50, 500}), f, [](double) { return 50.0; });
  return Mesh(tessellate(s).soup);
}

RegionOptions range(double a, double b) {
  RegionOptions o;
  o.enabled = true;
  o.start = a;
  o.end = b;
  return o;
}

std::string error_of(const Mesh& m, const SpindleAxis& axis, const RegionOptions& o) {
  try {
    select_region(m, axis, o);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(MandrelRegion, FlangedPipeWallBetweenTheFlanges) {
  const Mesh m = flanged_pipe();
  const RegionSelection sel = select_region(m, SpindleAxis{}, range(20, 480));
  const CandidateRegion& c = sel.candidates[sel.chosen];
  EXPECT_TRUE(c.annulus);
  EXPECT_EQ(c.loops, 2);
  EXPECT_NEAR(c.axial_min, 20.0, 1e-9);
  EXPECT_NEAR(c.axial_max, 480.0, 1e-9);
  // The outer wall (r = 50) and the bore (r = 20) both go around the axis: outer is the wall.
  EXPECT_NEAR(c.mean_radius, 50.0, 0.1);
  ASSERT_EQ(sel.candidates.size(), 2u);
  RegionOptions inner = range(20, 480);
  inner.surface = "inner";
  const RegionSelection bore = select_region(m, SpindleAxis{}, inner);
  EXPECT_NEAR(bore.candidates[bore.chosen].mean_radius, 20.0, 0.1);
}

TEST(MandrelRegion, TheFullMeshKeepsEverything) {
  const Mesh m = flanged_pipe();
  const RegionSelection sel = select_region(m, SpindleAxis{}, range(20, 480));
  EXPECT_TRUE(sel.mesh.is_closed());
  EXPECT_NEAR(sel.mesh.total_area(), m.total_area(), 1e-9 * m.total_area());
}

TEST(MandrelRegion, RangeThroughAFlangeIsNotAnAnnulus) {
  const Mesh m = flanged_pipe();
  const std::string e = error_of(m, SpindleAxis{}, range(-50, 300));
  EXPECT_NE(e.find("not an annulus"), std::string::npos) << e;
  EXPECT_NE(e.find("mandrel.region"), std::string::npos) << e;
  EXPECT_NE(e.find("suggested: region: {start:"), std::string::npos) << e;
}

TEST(MandrelRegion, SuggestionIsTheWallBetweenTheFlanges) {
  const Mesh m = flanged_pipe();
  const RegionSuggestion s = suggest_region(m, SpindleAxis{});
  ASSERT_TRUE(s.found);
  EXPECT_GT(s.start, 12.0);
  EXPECT_LT(s.start, 20.0);
  EXPECT_LT(s.end, 488.0);
  EXPECT_GT(s.end, 480.0);
  EXPECT_NEAR(s.radius, 50.0, 0.1);
  EXPECT_NO_THROW(select_region(m, SpindleAxis{}, range(s.start, s.end)));
}

TEST(MandrelRegion, BadRanges) {
  const Mesh m = flanged_pipe();
  std::string e = error_of(m, SpindleAxis{}, range(700, 800));
  EXPECT_NE(e.find("misses the mandrel"), std::string::npos) << e;
  SpindleAxis beside;
  beside.origin = Vec3(300, 0, 0);
  e = error_of(m, beside, range(20, 480));
  EXPECT_NE(e.find("goes around the spindle axis"), std::string::npos) << e;
  RegionOptions o = range(20, 480);
  o.component = 7;
  e = error_of(m, SpindleAxis{}, o);
  EXPECT_NE(e.find("mandrel.region.component"), std::string::npos) << e;
  // Past the ends: the closed mandrel (no loop) or a cup (one loop), each said so.
  e = error_of(m, SpindleAxis{}, range(-200, 700));
  EXPECT_NE(e.find("keep region.start and region.end inside its axial extent [-100, 600] mm"),
            std::string::npos)
      << e;
  e = error_of(m, SpindleAxis{}, range(20, 700));
  EXPECT_NE(e.find("the range runs past an end of the mandrel"), std::string::npos) << e;
  o = range(480, 20);
  e = error_of(m, SpindleAxis{}, o);
  EXPECT_NE(e.find("region.start"), std::string::npos) << e;
}

TEST(MandrelRegion, TwoPipesInARowNeedAChoice) {
  // Two open pipes (the caps dropped), one after the other along the axis.
  TriangleSoup soup = tessellate(make_pipe(PipeParams{50, 200})).soup;
  {
    const Mesh closed(soup);
    std::vector<Tri> side;
    for (int f = 0; f < closed.num_faces(); ++f) {
      if (std::abs(closed.face_normal(f).z()) < 0.5) side.push_back(closed.triangle(f));
    }
    soup.triangles = side;
  }
  const std::size_t n = soup.points.size(), t = soup.triangles.size();
  for (std::size_t i = 0; i < n; ++i) soup.points.push_back(soup.points[i] + Vec3(0, 0, 300));
  for (std::size_t i = 0; i < t; ++i) {
    Tri tri = soup.triangles[i];
    for (int& v : tri) v += static_cast<int>(n);
    soup.triangles.push_back(tri);
  }
  const Mesh m(soup);
  const std::string e = error_of(m, SpindleAxis{}, range(100, 400));
  EXPECT_NE(e.find("mandrel.region.component"), std::string::npos) << e;
  RegionOptions o = range(100, 400);
  o.component = 2;
  const RegionSelection sel = select_region(m, SpindleAxis{}, o);
  EXPECT_TRUE(sel.candidates[1].annulus);
}

TEST(MandrelRegion, CandidateTableListsEveryPart) {
  const Mesh m = flanged_pipe();
  std::vector<char> all(m.num_faces(), 1);
  const auto c = candidate_regions(m, all, SpindleAxis{});
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].loops, 0);
  EXPECT_EQ(c[0].genus, 17) << "8 bolt holes in each of two flanges and the through bore";
  const std::string table = region_table(c);
  EXPECT_NE(table.find("genus"), std::string::npos);
}

// A rounded-rectangle boom with lofted domes, shafts at the openings and screw tabs near the
// start: the suggestion runs from above the tabs (z 50..56) onto the end dome, up to its opening
// (z = 440, where the flat cap and the shaft begin), not beyond.
TEST(MandrelRegion, SuggestionFollowsADomeToItsOpening) {
  SectionParams p = SectionParams::rounded_rectangle(120, 80, 15, 400);
  p.end_start = p.end_end = SectionEndParams{true, 40.0, 20.0};
  MandrelFeatures f;
  f.shaft_start = {12, 60};
  f.shaft_end = {12, 60};
  f.tabs = {TabParams{50, 4, 45, 20, 16, 6, 3}};
  const CadShape s = add_mandrel_features(make_section_mandrel(p), f,
                                          [&p](double th) { return section_radius(p, th); });
  const Mesh m(tessellate(s).soup);
  const RegionSuggestion g = suggest_region(m, SpindleAxis{});
  ASSERT_TRUE(g.found);
  EXPECT_GT(g.start, 56.0);
  EXPECT_LT(g.start, 60.0);
  EXPECT_GT(g.end, 430.0) << "on the dome";
  EXPECT_LT(g.end, 440.0) << "below its opening";
}

}  // namespace
}  // namespace windplan
