// axes.svg (export/plots/axes_svg.h) read back: five panels, each polyline an envelope no longer
// than four points a pixel column, its ends at the first and last machine values on the panel's
// scale.
#include "export/plots/axes_svg.h"

#include <sstream>

#include <gtest/gtest.h>

#include "tests/export/plan_fixtures.h"
#include "tests/export/xml_reader.h"

namespace windplan {
namespace {

TEST(AxesSvg, FivePanelsWithTheirEnvelopes) {
  const WindingPlan plan = test::helix_plan(50, 40, 1.5, 3000, 4);
  const MachineOptions machine;  // (named: GCC 12 warns maybe-uninitialized on the temporary)
  const Motion motion = compute_motion(plan, machine);
  ASSERT_GT(motion.states.size(), 100u);
  AxesSvgOptions o;
  const auto root = test::XmlReader::parse(axes_svg(motion, "helix", o));
  std::vector<const test::XmlElement*> panels;
  root->find_all([](const test::XmlElement& e) { return e.attr("class") == "panel"; }, &panels);
  ASSERT_EQ(panels.size(), 5u);
  const char* names[] = {"A", "X", "Y", "B", "F"};
  double MachineState::*fields[] = {&MachineState::a_deg, &MachineState::x_mm, &MachineState::y_mm,
                                    &MachineState::b_deg, &MachineState::feed};
  for (int k = 0; k < 5; ++k) {
    EXPECT_EQ(panels[k]->attr("data-axis"), names[k]);
    const auto lines = panels[k]->by_name("polyline");
    ASSERT_EQ(lines.size(), 1u);
    std::vector<Vec2> pts;
    std::istringstream in(lines[0]->attr("points"));
    for (std::string p; in >> p;)
      pts.emplace_back(std::stod(p.substr(0, p.find(','))), std::stod(p.substr(p.find(',') + 1)));
    EXPECT_LE(pts.size(), 4u * static_cast<std::size_t>(o.width));
    // The panel's frame gives its scale; the values' range fills it.
    const auto rects = panels[k]->by_name("rect");
    ASSERT_EQ(rects.size(), 1u);
    const double top = std::stod(rects[0]->attr("y")), ph = std::stod(rects[0]->attr("height"));
    double lo = motion.states.front().*fields[k], hi = lo;
    for (const MachineState& s : motion.states) {
      lo = std::min(lo, s.*fields[k]);
      hi = std::max(hi, s.*fields[k]);
    }
    const bool constant = !(hi - lo > 1e-9 * std::max(1.0, std::fabs(hi)));
    const double v0 = lo, v1 = hi;  // the values' range
    if (constant) {                 // a constant axis: a +-1 band about it, the line in the middle
      lo -= 1;
      hi += 1;
    }
    auto py = [&](double v) { return top + ph - (v - lo) / (hi - lo) * ph; };
    EXPECT_NEAR(pts.front().y(), py(motion.states.front().*fields[k]), 0.006) << names[k];
    EXPECT_NEAR(pts.back().y(), py(motion.states.back().*fields[k]), 0.006) << names[k];
    double ymin = 1e9, ymax = -1e9;
    for (const Vec2& p : pts) {
      ymin = std::min(ymin, p.y());
      ymax = std::max(ymax, p.y());
    }
    EXPECT_NEAR(ymin, py(v1), 0.006) << names[k];  // the extremes survive the envelope
    EXPECT_NEAR(ymax, py(v0), 0.006) << names[k];
    if (constant) {
      EXPECT_NEAR(ymin, top + ph / 2, 0.006) << names[k];
    }
  }
}

}  // namespace
}  // namespace windplan
