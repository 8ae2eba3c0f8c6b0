// Semi-geodesic paths (planner/winding/semi_geodesic.h) against closed forms: on a cylinder a path
// at constant slippage lambda obeys cot(a0) - cot(a) = lambda l / R (l the fibre length), 1/sin(a0)
// - 1/sin(a) = lambda s / R (s axial) and phi = ln(tan(a/2) / tan(a0/2)) / lambda; lambda = 0 gives
// Clairaut's geodesic back (r sin a = c, Phi(c) of planner/winding/clairaut_pass.h).
#include "planner/winding/semi_geodesic.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"
#include "planner/winding/clairaut_pass.h"

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
  // c at the apex radius: nothing to turn.
  EXPECT_THROW(friction_turnaround(m, 1, 10.0, m.point(10.0).y(), 0.3), InputError);
}

// A hemispherical dome of radius R (polar angle theta from the axis, r = R sin theta): k_n = 1 / R
// in every direction, so d(r sin a)/dtheta = +-lambda R sin theta and a turnaround with its apex
// on r_a reaches r sin a = r_a +- lambda R (cos theta_a - cos theta) at theta. The meridian is a
// 400-segment polyline: its curvature comes from the vertices' turning angles, smoothed.
TEST(SemiGeodesic, FrictionOnASphericalDomeFollowsTheClosedForm) {
  const double R = 100, r0 = 20, lambda = 0.2, r_apex = 30;
  const double th0 = std::asin(r0 / R);
  std::vector<Vec2> pts;
  for (int i = 0; i <= 400; ++i) {
    const double th = th0 + (0.5 * M_PI - th0) * i / 400;
    pts.push_back({-R * std::cos(th), R * std::sin(th)});
  }
  pts.push_back({100.0, R});
  const MeridianLine m(pts, 2.0);
  EXPECT_NEAR(m.curvature(0.5 * R * (0.5 * M_PI - th0)), 1.0 / R, 2e-3 / R);  // chords
  EXPECT_NEAR(m.curvature(R * (0.5 * M_PI - th0) + 50.0), 0.0, 1e-12);        // the cylinder
  const double tha = std::asin(r_apex / R);
  const double apex_s = R * (tha - th0);
  for (double c : {40.0, 25.0}) {
    SCOPED_TRACE(c);
    const double sign = c > r_apex ? 1.0 : -1.0;
    const double cos_join = std::cos(tha) - sign * (c - r_apex) / (lambda * R);
    const FrictionTurnaround t = friction_turnaround(m, 0, apex_s, c, lambda, 1.0);
    ASSERT_TRUE(t.reached);
    EXPECT_NEAR(t.join_r, R * std::sqrt(1.0 - cos_join * cos_join), 0.05);
    EXPECT_NEAR(t.pass_angle, std::asin(c / t.join_r), 1e-9);
    // Every sample on the closed form: r sin a = r_a +- lambda R (cos theta_a - cos theta).
    double worst = 0.0;
    for (const PassSample& q : t.samples) {
      const double cos_th = -q.x / R;
      worst = std::max(worst, std::abs(q.r * std::sin(q.angle) -
                                       (r_apex + sign * lambda * R * (std::cos(tha) - cos_th))));
    }
    EXPECT_LT(worst, 0.05);
  }
  // Without the meridian's curvature (window 0) friction only has the parallel's term
  // sin^2(a) / R: it raises r sin a far less.
  const MeridianLine flat(pts);
  const FrictionTurnaround weak = friction_turnaround(flat, 0, apex_s, 40.0, lambda, 1.0);
  EXPECT_FALSE(weak.reached);
  EXPECT_LT(weak.lowest, 37.0);  // 36.2 mm
}

}  // namespace
}  // namespace windplan
