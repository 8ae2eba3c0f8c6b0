// joints.svg: one panel per joint with one polyline each, its points inside the panel, a joint
// limit inside the range drawn dashed and one outside it not.
#include "export/plots/joints_svg.h"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <sstream>

namespace windplan {
namespace {

int count(const std::string& s, const std::string& what) {
  int n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TEST(JointsSvg, PanelsPolylinesAndLimits) {
  std::vector<double> t;
  JointSeries a{"A1", {}, -9.0, 9.0};      // its range (+-10) crosses both limits
  JointSeries b{"A2", {}, -170.0, 170.0};  // far inside them: no limit line
  for (int i = 0; i <= 200; ++i) {
    t.push_back(0.1 * i);
    a.values.push_back(10.0 * std::sin(0.05 * i));
    b.values.push_back(5.0 * i / 200.0);
  }
  const std::string svg = joints_svg(t, {a, b}, "job");
  EXPECT_EQ(count(svg, "<g class=\"panel\""), 2);
  EXPECT_EQ(count(svg, "data-joint=\"A1\""), 1);
  EXPECT_EQ(count(svg, "<polyline"), 2);
  EXPECT_EQ(count(svg, "stroke-dasharray"), 2);  // A1 -9 and +9 only
  EXPECT_EQ(svg, joints_svg(t, {a, b}, "job"));  // deterministic
  // Every polyline point lies inside the plot area (x 90..1080, y 40 .. 40 + 2 * 80 + 18).
  const std::regex pts("points=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), pts); it != std::sregex_iterator();
       ++it) {
    std::istringstream in((*it)[1].str());
    std::string xy;
    int n = 0;
    while (in >> xy) {
      const double x = std::stod(xy.substr(0, xy.find(','))),
                   y = std::stod(xy.substr(xy.find(',') + 1));
      EXPECT_GE(x, 90.0 - 1e-9);
      EXPECT_LE(x, 1080.0 + 1e-9);
      EXPECT_GE(y, 40.0 - 1e-9);
      EXPECT_LE(y, 40.0 + 2 * 80 + 18 + 1e-9);
      ++n;
    }
    EXPECT_GT(n, 50);
  }
}

}  // namespace
}  // namespace windplan
