// Semi-geodesic paths (planner/semi_geodesic.h) against closed forms: on a cylinder a path at
// constant slippage lambda obeys cot(a0) - cot(a) = lambda l / R (l the fibre length),
// 1/sin(a0) - 1/sin(a) = lambda s / R (s axial) and phi = ln(tan(a/2) / tan(a0/2)) / lambda;
// lambda = 0 gives Clairaut's geodesic back (r sin a = c, Phi(c) of planner/clairaut_pass.h).
#include "planner/semi_geodesic.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/errors.h"
#include "planner/clairaut_pass.h"

namespace windplan {
namespace {

double cot(double a) { return std::cos(a) / std::sin(a); }

TEST(SemiGeodesic, CylinderFollowsTheClosedForm) {
  const double R = 50, L = 600, lambda = 0.15, a0 = 50.0 * M_PI / 180.0;
  const MeridianLine m({{0, R}, {L, R}});
  SemiGeodesicOptions o;
  o.slippage = lambda;
  o.step = 1.0;
  const SemiGeodesicPath p =
      semi_geodesic(m, {10.0, a0, 0.0}, o,
                    [](const MeridianLine&, const MeridianState& y) { return y.a - 0.5 * M_PI; });
  ASSERT_TRUE(p.event);
  EXPECT_NEAR(p.end.a, 0.5 * M_PI, 1e-9);
  EXPECT_NEAR(p.length, R * cot(a0) / lambda, 1e-6);                           // fibre length
  EXPECT_NEAR(p.end.s - 10.0, R * (1.0 / std::sin(a0) - 1.0) / lambda, 1e-6);  // axial
  EXPECT_NEAR(p.end.phi, -std::log(std::tan(0.5 * a0)) / lambda, 1e-6);
  ASSERT_GT(p.samples.size(), 100u);
  for (const PassSample& q : p.samples) {
    EXPECT_NEAR(cot(a0) - cot(q.angle), lambda * q.length / R, 1e-8);
    EXPECT_NEAR(1.0 / std::sin(a0) - 1.0 / std::sin(q.angle), lambda * (q.x - 10.0) / R, 1e-8);
    EXPECT_NEAR(q.phi, std::log(std::tan(0.5 * q.angle) / std::tan(0.5 * a0)) / lambda, 1e-8);
  }
  for (std::size_t i = 1; i < p.samples.size(); ++i) {
    EXPECT_LE(p.samples[i].length - p.samples[i - 1].length, 1.0 + 1e-12);
  }
}

TEST(SemiGeodesic, ZeroSlippageIsClairautsGeodesic) {
  // A cone from r 30 to 80 over 250 mm, then a cylinder: the geodesic with c = 24.
  const std::vector<Vec2> pts{{0, 30}, {120, 55}, {250, 80}, {400, 80}};
  const MeridianLine m(pts);
  const double c = 24.0;
  SemiGeodesicOptions o;
  o.step = 1.5;
  const SemiGeodesicPath p = semi_geodesic(
      m, {0.0, std::asin(c / 30.0), 0.0}, o,
      [&](const MeridianLine& ml, const MeridianState& y) { return y.s - ml.length(); });
  ASSERT_TRUE(p.event);
  for (const PassSample& q : p.samples) EXPECT_NEAR(q.r * std::sin(q.angle), c, 1e-8);
  EXPECT_NEAR(p.end.phi, clairaut_pass_angle(pts, c), 1e-7);
  EXPECT_NEAR(p.length, clairaut_pass(pts, c).length, 1e-6);
}

TEST(SemiGeodesic, FrictionTurnaroundOnACylinder) {
  const double R = 50, L = 500, lambda = 0.12, a0 = 55.0 * M_PI / 180.0, c = R * std::sin(a0);
  const MeridianLine m({{0, R}, {L, R}});
  const double s_axial = R * (1.0 / std::sin(a0) - 1.0) / lambda;
  for (int end : {0, 1}) {
    const double apex = end == 1 ? L - 6.0 : 6.0;
    const FrictionTurnaround t = friction_turnaround(m, end, apex, c, lambda, 1.0);
    ASSERT_TRUE(t.reached);
    EXPECT_NEAR(t.length, 2.0 * R * cot(a0) / lambda, 1e-6);
    EXPECT_NEAR(t.angle, -2.0 * std::log(std::tan(0.5 * a0)) / lambda, 1e-6);
    EXPECT_NEAR(t.join_x, end == 1 ? apex - s_axial : apex + s_axial, 1e-6);
    EXPECT_NEAR(t.pass_angle, a0, 1e-9);
    // Arrives at the pass angle running towards the end, leaves at it running back.
    const double towards = end == 1 ? a0 : M_PI - a0;
    EXPECT_NEAR(t.samples.front().angle, towards, 1e-9);
    EXPECT_NEAR(t.samples.back().angle, M_PI - towards, 1e-9);
    EXPECT_NEAR(t.samples.front().phi, 0.0, 1e-12);
    EXPECT_NEAR(t.samples.back().phi, t.angle, 1e-12);
    double far = 0.0;
    for (const PassSample& q : t.samples) {
      far = std::max(far, std::abs(q.x - t.join_x));
      // The closed form from either side of the apex.
      const double from_join = std::min(q.length, t.length - q.length);
      EXPECT_NEAR(cot(a0) - std::abs(cot(q.angle)), lambda * from_join / R, 1e-8);
    }
    EXPECT_NEAR(far, s_axial, 1e-9);
  }
}

TEST(SemiGeodesic, TooLittleFrictionOnAWideningConeNeverTurns) {
  // At the large end of a cone of half-angle 20 deg, friction must beat tan(20 deg) = 0.36.
  const double b = 20.0 * M_PI / 180.0;
  const MeridianLine m({{0, 40}, {200 * std::cos(b), 40 + 200 * std::sin(b)}});
  const FrictionTurnaround weak = friction_turnaround(m, 1, m.length() - 5, 30.0, 0.2, 2.0);
  EXPECT_FALSE(weak.reached);
  const FrictionTurnaround strong = friction_turnaround(m, 1, m.length() - 5, 80.0, 0.6, 2.0);
  EXPECT_TRUE(strong.reached);
  EXPECT_THROW(friction_turnaround(m, 1, 10.0, 30.0, 0.0), InputError);
  EXPECT_THROW(friction_turnaround(m, 1, 10.0, 60.0, 0.3), InputError);  // c above the apex
}

}  // namespace
}  // namespace windplan
