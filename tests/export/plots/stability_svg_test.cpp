// stability.svg (export/plots/stability_svg.h) read back: the circuit with the largest measured
// |k_g/k_n| is the one drawn, its extreme survives the envelope on the panel's own scale, mu and
// the planned friction are lines at their values, dwell arcs and bridging points are marked.
#include "export/plots/stability_svg.h"

#include <sstream>

#include <gtest/gtest.h>

#include "tests/export/plan_fixtures.h"
#include "tests/export/xml_reader.h"

namespace windplan {
namespace {

std::vector<Vec2> polyline_points(const test::XmlElement& e) {
  std::vector<Vec2> pts;
  std::istringstream in(e.attr("points"));
  for (std::string p; in >> p;)
    pts.emplace_back(std::stod(p.substr(0, p.find(','))), std::stod(p.substr(p.find(',') + 1)));
  return pts;
}

TEST(StabilitySvg, TheWorstCircuitAgainstMu) {
  WindingPlan plan = test::helix_plan(50, 40, 1.5, 3000, 3);
  plan.metrics.friction = 0.2;
  // Circuit 1 slips at one point, has a dwell arc and one point where the fibre would bridge.
  for (int k = 0; k < 3; ++k) {
    for (std::size_t i = 0; i < plan.circuits[k].points.size(); ++i) {
      plan.circuits[k].points[i].slippage = 0.05 + 0.01 * k + 0.02 * std::sin(0.01 * i);
    }
  }
  Circuit& c1 = plan.circuits[1];
  c1.points[1700].slippage = 0.3;
  c1.points[2100].k_n = -1e-4;
  c1.segments = {{CircuitSegment::Kind::Pass, 0, 1000},
                 {CircuitSegment::Kind::Turnaround, 1000, 1200},
                 {CircuitSegment::Kind::Pass, 1200, 2999}};
  plan.metrics.friction_turnarounds.planned = true;
  plan.metrics.friction_turnarounds.lambda = {0.12, 0.0};
  StabilitySvgOptions o;
  const auto root = test::XmlReader::parse(stability_svg(plan, o));
  EXPECT_EQ(root->attr("data-circuit"), "1");
  EXPECT_DOUBLE_EQ(std::stod(root->attr("data-max")), 0.3);
  std::vector<const test::XmlElement*> panels;
  root->find_all([](const test::XmlElement& e) { return e.attr("class") == "panel"; }, &panels);
  ASSERT_EQ(panels.size(), 2u);
  EXPECT_EQ(panels[0]->attr("data-quantity"), "angle");
  EXPECT_EQ(panels[1]->attr("data-quantity"), "slippage");
  for (int p = 0; p < 2; ++p) {
    const auto frame = panels[p]->by_name("rect");
    ASSERT_GE(frame.size(), 2u);  // the frame, then the dwell arc
    const double top = std::stod(frame[0]->attr("y")), ph = std::stod(frame[0]->attr("height"));
    const double lo = std::stod(panels[p]->attr("data-lo")),
                 hi = std::stod(panels[p]->attr("data-hi"));
    auto py = [&](double v) { return top + ph - (v - lo) / (hi - lo) * ph; };
    EXPECT_EQ(frame[1]->attr("class"), "dwell");
    const auto lines = panels[p]->by_name("polyline");
    ASSERT_EQ(lines.size(), 1u);
    const std::vector<Vec2> pts = polyline_points(*lines[0]);
    EXPECT_LE(pts.size(), 4u * static_cast<std::size_t>(o.width));
    double ymin = 1e9;
    for (const Vec2& q : pts) ymin = std::min(ymin, q.y());
    if (p == 0) {  // the helix's constant winding angle
      EXPECT_NEAR(ymin, py(c1.points[0].winding_angle), 0.006);
      continue;
    }
    EXPECT_NEAR(ymin, py(0.3), 0.006);  // the slipping point survives the envelope
    std::vector<const test::XmlElement*> mu, planned, bridging;
    panels[p]->find_all([](const test::XmlElement& e) { return e.attr("class") == "mu"; }, &mu);
    panels[p]->find_all([](const test::XmlElement& e) { return e.attr("class") == "planned"; },
                        &planned);
    panels[p]->find_all([](const test::XmlElement& e) { return e.attr("class") == "bridging"; },
                        &bridging);
    ASSERT_EQ(mu.size(), 1u);
    EXPECT_NEAR(std::stod(mu[0]->attr("y1")), py(0.2), 0.006);
    ASSERT_EQ(planned.size(), 1u);
    EXPECT_NEAR(std::stod(planned[0]->attr("y1")), py(0.12), 0.006);
    EXPECT_EQ(bridging.size(), 1u);
  }
}

}  // namespace
}  // namespace windplan
