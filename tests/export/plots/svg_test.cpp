// development.svg (export/plots/svg.h) and the unrolling (export/plots/unroll.h), read back with an
// independent XML reader: well-formed, the legend and band elements, bands as wide as the closed
// form of a helix on a cylinder, marker labels that do not overlap, the conformal unrolling of a
// tube against its exact coordinates.
#include "export/plots/svg.h"

#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

#include "export/plots/svg_util.h"
#include "export/plots/unroll.h"
#include "tests/export/plan_fixtures.h"
#include "tests/export/xml_reader.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

std::vector<Vec2> points_of(const std::string& attr) {
  std::vector<Vec2> out;
  std::istringstream in(attr);
  std::string pair;
  while (in >> pair) {
    const auto c = pair.find(',');
    out.emplace_back(std::stod(pair.substr(0, c)), std::stod(pair.substr(c + 1)));
  }
  return out;
}

// Plot scale from the tick labels: px per mm along, px per degree around, and the origin.
struct Scale {
  double x0 = 0, sx = 0;  // px = x0 + sx * mm
  double y0 = 0, sy = 0;  // px = y0 + sy * deg
};
Scale scale_of(const test::XmlElement& svg) {
  const test::XmlElement* grid = svg.by_id("grid");
  EXPECT_NE(grid, nullptr);
  std::vector<std::pair<double, double>> along, around;  // (value, px)
  for (const test::XmlElement* t : grid->by_name("text")) {
    if (t->attr("text-anchor") == "middle" && !t->attr("transform").size() &&
        t->text.find('[') == std::string::npos)
      along.push_back({std::stod(t->text), std::stod(t->attr("x"))});
    if (t->attr("text-anchor") == "end")
      around.push_back({std::stod(t->text), std::stod(t->attr("y")) - 4});
  }
  Scale s;
  EXPECT_GE(along.size(), 2u);
  EXPECT_EQ(around.size(), 9u);  // 0, 45, ..., 360
  if (along.size() < 2 || around.size() < 2) return s;
  s.sx = (along.back().second - along.front().second) / (along.back().first - along.front().first);
  s.x0 = along.front().second - s.sx * along.front().first;
  s.sy =
      (around.back().second - around.front().second) / (around.back().first - around.front().first);
  s.y0 = around.front().second - s.sy * around.front().first;
  return s;
}

// Every text under e, concatenated.
std::string svg_text_of(const test::XmlElement& e) {
  std::string t = e.text;
  for (const auto& c : e.children) t += " " + svg_text_of(*c);
  return t;
}

WindingPlan cylinder_plan(double w) {
  WindingPlan plan = test::helix_plan(50, 40, 1.5, 400, 3);
  plan.metrics.band_width = w;
  plan.metrics.geodesic_turn_limit = std::numeric_limits<double>::infinity();  // revolution
  return plan;
}

TEST(DevelopmentSvg, WellFormedWithLegendAndOneBandPerCircuit) {
  const WindingPlan plan = cylinder_plan(10);
  const Unrolling un = Unrolling::make(plan, Mesh());
  EXPECT_EQ(un.kind(), Unrolling::Kind::Axis);
  const std::string svg = development_svg(plan, un);
  std::unique_ptr<test::XmlElement> root;
  ASSERT_NO_THROW(root = test::XmlReader::parse(svg)) << svg.substr(0, 400);
  EXPECT_EQ(root->name, "svg");
  const test::XmlElement* legend = root->by_id("legend");
  ASSERT_NE(legend, nullptr);
  int circuit_swatches = 0, coverage_swatches = 0;
  for (const test::XmlElement* r : legend->by_name("rect")) {
    circuit_swatches += r->attr("class") == "legend-circuit";
    coverage_swatches += r->attr("class") == "legend-coverage";
  }
  EXPECT_EQ(circuit_swatches, 3);
  EXPECT_EQ(coverage_swatches, 3);  // bare, one band, overlap
  std::vector<const test::XmlElement*> bands;
  root->find_all([](const test::XmlElement& e) { return e.attr("class") == "band"; }, &bands);
  ASSERT_EQ(bands.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(bands[k]->name, "polygon");
    EXPECT_EQ(bands[k]->attr("data-circuit"), std::to_string(k));
    // Placed (by <use>) with a translucent fill of the circuit's colour.
    std::vector<const test::XmlElement*> uses;
    root->find_all(
        [&](const test::XmlElement& e) {
          return e.name == "use" && e.attr("xlink:href") == "#band-" + std::to_string(k);
        },
        &uses);
    ASSERT_FALSE(uses.empty());
    EXPECT_EQ(uses[0]->attr("fill"), circuit_colour(k));
    EXPECT_EQ(uses[0]->attr("fill-opacity"), "0.45");
  }
  EXPECT_NE(root->by_id("cutlines"), nullptr);
}

TEST(DevelopmentSvg, BandIsAsWideAsOnTheMandrel) {
  // Helix on a cylinder R = 50 at alpha = 40 deg from the axis: the band's edges lie at
  // +-w/2 (n x t) = +-w/2 (sin a along the axis, cos a around) in the tangent plane, i.e.
  // delta x = w sin a, delta theta = 2 atan(w cos a / (2 R)).
  const double w = 10, R = 50, a = 40 * M_PI / 180;
  const WindingPlan plan = cylinder_plan(w);
  const std::string svg = development_svg(plan, Unrolling::make(plan, Mesh()));
  const auto root = test::XmlReader::parse(svg);
  const Scale s = scale_of(*root);
  ASSERT_GT(s.sx, 0);
  ASSERT_GT(s.sy, 0);
  const test::XmlElement* band = root->by_id("band-1");
  ASSERT_NE(band, nullptr);
  const std::vector<Vec2> pts = points_of(band->attr("points"));
  ASSERT_GE(pts.size(), 4u);
  ASSERT_EQ(pts.size() % 2, 0u);
  // First point: left edge at the first fibre point; last point: right edge at the same point.
  const Vec2 d = pts.front() - pts.back();
  EXPECT_NEAR(std::fabs(d.x()) / s.sx, w * std::sin(a), 0.01 * w);
  EXPECT_NEAR(std::fabs(d.y()) / s.sy, 2 * std::atan(w * std::cos(a) / (2 * R)) * 180 / M_PI, 0.02);
  // And the centre line lies half way: its first point at the fibre's axial position 0.
  const test::XmlElement* path = root->by_id("path-1");
  ASSERT_NE(path, nullptr);
  const Vec2 c = points_of(path->attr("points")).front();
  EXPECT_NEAR((c.x() - s.x0) / s.sx, 0.0, 0.05);
  EXPECT_NEAR((c.y() - s.y0) / s.sy, 120.0, 0.05);  // circuit 1 of 3 starts at 120 deg
}

TEST(DevelopmentSvg, LayersColourTheBandsAndSetTheirWidth) {
  WindingPlan plan = cylinder_plan(10);
  LayerSummary a, b;
  a.name = "inner";
  a.kind = "helical";
  a.first_circuit = 0;
  a.circuit_count = 2;
  a.band_width = 10;
  b.name = "outer";
  b.kind = "helical";
  b.first_circuit = 2;
  b.circuit_count = 1;
  b.band_width = 20;
  plan.layers = {a, b};
  const auto root = test::XmlReader::parse(development_svg(plan, Unrolling::make(plan, Mesh())));
  std::vector<const test::XmlElement*> sw;
  root->find_all([](const test::XmlElement& e) { return e.attr("class") == "legend-layer"; }, &sw);
  ASSERT_EQ(sw.size(), 2u);
  EXPECT_NE(svg_text_of(*root->by_id("legend")).find("outer (helical, 0.0 deg)"),
            std::string::npos);
  EXPECT_EQ(root->by_id("band-1")->attr("data-layer"), "0");
  EXPECT_EQ(root->by_id("band-2")->attr("data-layer"), "1");
  // The outer layer's band is 20 mm wide: delta x = w sin a.
  const Scale sc = scale_of(*root);
  const std::vector<Vec2> pts = points_of(root->by_id("band-2")->attr("points"));
  EXPECT_NEAR(std::fabs(pts.front().x() - pts.back().x()) / sc.sx, 20 * std::sin(40 * M_PI / 180),
              0.2);
}

TEST(DevelopmentSvg, MarkerLabelsDoNotOverlap) {
  // Mandrel ends 10 mm beyond the fibre's ends: four labels, pairwise close.
  WindingPlan plan = cylinder_plan(10);
  const auto root = test::XmlReader::parse(development_svg(plan, Unrolling::make(plan, Mesh())));
  const test::XmlElement* labels = root->by_id("labels");
  ASSERT_NE(labels, nullptr);
  const auto texts = labels->by_name("text");
  ASSERT_EQ(texts.size(), 4u);
  double frame_top = 1e9;
  for (const test::XmlElement* r :
       root->children.size() ? root->by_name("rect") : decltype(root->by_name("rect")){})
    if (r->attr("fill") == "none" && r->attr("stroke") == "#333")
      frame_top = std::stod(r->attr("y"));
  struct Box {
    double x0, x1, y;
  };
  std::vector<Box> boxes;
  for (const test::XmlElement* t : texts) {
    const double x = std::stod(t->attr("x")), y = std::stod(t->attr("y"));
    const double wpx = 6.0 * static_cast<double>(t->text.size());  // 10 px sans: < 6 px a glyph
    boxes.push_back(t->attr("text-anchor") == "end" ? Box{x - wpx, x, y} : Box{x, x + wpx, y});
    EXPECT_LT(y, frame_top) << t->text << ": inside the plot";
  }
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      const bool apart_y = std::fabs(boxes[i].y - boxes[j].y) >= 11;
      const bool apart_x = boxes[i].x1 <= boxes[j].x0 || boxes[j].x1 <= boxes[i].x0;
      EXPECT_TRUE(apart_x || apart_y) << texts[i]->text << " / " << texts[j]->text;
    }
}

TEST(DevelopmentSvg, MeasuredBareStationsAreMarked) {
  WindingPlan plan = cylinder_plan(10);
  StationCoverage covered, bare;
  covered.station = 50;
  bare.station = 200;
  bare.bare_fraction = 0.0321;
  bare.widest_gap = 4.5;
  plan.metrics.coverage.stations = {covered, bare};
  plan.metrics.coverage.bare_fraction = 0.0321;
  const auto root = test::XmlReader::parse(development_svg(plan, Unrolling::make(plan, Mesh())));
  const Scale sc = scale_of(*root);
  std::vector<const test::XmlElement*> st;
  root->find_all([](const test::XmlElement& e) { return e.attr("class") == "station"; }, &st);
  ASSERT_EQ(st.size(), 2u);
  EXPECT_EQ(st[0]->attr("data-bare"), "0.00");
  EXPECT_EQ(st[1]->attr("data-bare"), "3.21");
  EXPECT_EQ(st[1]->attr("fill"), "#c00000");
  // The bare station's line and label, at its axial position.
  bool labelled = false;
  for (const test::XmlElement* t : root->by_id("labels")->by_name("text"))
    labelled |= t->text == "3.2% bare";
  EXPECT_TRUE(labelled);
  bool line = false;
  for (const test::XmlElement* l : root->by_id("labels")->by_name("line"))
    line |= l->attr("stroke") == "#c00000" &&
            std::fabs(std::stod(l->attr("x1")) - (sc.x0 + sc.sx * 200)) < 0.02;
  EXPECT_TRUE(line);
  const test::XmlElement* sub = root->by_id("coverage");
  ASSERT_NE(sub, nullptr);
  EXPECT_NE(sub->text.find("measured coverage: bare 3.21%"), std::string::npos) << sub->text;
}

TEST(Unrolling, ConformalCoordinatesOfATube) {
  // Open cylinder r = 50, length 700 along z: h is linear in z (exactly harmonic on the regular
  // grid), L = area / mean perimeter = 700, and the conjugate angle is the angle about the axis
  // up to its direction and origin.
  WindingPlan plan = test::helix_plan(50, 40, 1.5, 20, 1);
  plan.metrics.geodesic_turn_limit = std::nan("");  // not a shape of revolution
  const Mesh tube(test::open_cylinder(50, 700, 24, 10));
  const Unrolling un = Unrolling::make(plan, tube);
  ASSERT_EQ(un.kind(), Unrolling::Kind::Conformal) << un.fallback_reason;
  EXPECT_NEAR(un.length(), 700.0, 1e-6);
  const double ang0 = 0.0, ang1 = 90.0 * M_PI / 180;
  for (double z : {0.0, 210.0, 455.0, 700.0}) {
    const Vec2 a = un.map(Vec3(50 * std::cos(ang0), 50 * std::sin(ang0), z));
    const Vec2 b = un.map(Vec3(50 * std::cos(ang1), 50 * std::sin(ang1), z));
    const double along = a.x();
    EXPECT_TRUE(std::fabs(along - z) < 1e-6 || std::fabs(along - (700 - z)) < 1e-6) << along;
    EXPECT_NEAR(a.x(), b.x(), 1e-6);
    double d = std::fabs(b.y() - a.y());
    d = std::min(d, 360.0 - d);
    EXPECT_NEAR(d, 90.0, 1e-6);
  }
  const std::string svg = development_svg(plan, un);
  EXPECT_NO_THROW(test::XmlReader::parse(svg));
  EXPECT_NE(svg.find("own coordinates"), std::string::npos);
}

TEST(Unrolling, ClosedMeshFallsBackToTheAxisAndSaysWhy) {
  WindingPlan plan = test::helix_plan(50, 40, 1.5, 20, 1);
  const Mesh sphere(test::uv_sphere(50, 16, 8));
  const Unrolling un = Unrolling::make(plan, sphere);
  EXPECT_EQ(un.kind(), Unrolling::Kind::Axis);
  EXPECT_NE(un.fallback_reason.find("0 boundary loops"), std::string::npos);
  EXPECT_NE(development_svg(plan, un).find("0 boundary loops"), std::string::npos);
}

}  // namespace
}  // namespace windplan
