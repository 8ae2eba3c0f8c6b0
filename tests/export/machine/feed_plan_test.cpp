#include "export/machine/feed_plan.h"

#include <cmath>

#include <gtest/gtest.h>

namespace windplan {
namespace {

TEST(FeedPlan, TrapezoidTimeClosedForms) {
  // Rest to rest, long enough to cruise: l / v + v / a.
  EXPECT_NEAR(trapezoid_time(100, 0, 0, 50, 200), 100.0 / 50 + 50.0 / 200, 1e-12);
  // Too short to cruise: a triangle, 2 sqrt(l / a).
  EXPECT_NEAR(trapezoid_time(4, 0, 0, 50, 200), 2 * std::sqrt(4.0 / 200), 1e-12);
  // From v0 up to the cap and down to v1.
  const double l = 100, v0 = 10, v1 = 20, v = 50, a = 200;
  const double t = (v - v0) / a + (v - v1) / a +
                   (l - (v * v - v0 * v0) / (2 * a) - (v * v - v1 * v1) / (2 * a)) / v;
  EXPECT_NEAR(trapezoid_time(l, v0, v1, v, a), t, 1e-12);
}

TEST(FeedPlan, StraightLineInManyBlocksIsOneTrapezoid) {
  // A straight move of X 100 mm in 200 collinear blocks: no corners, so the plan is the single
  // trapezoid at half the axis acceleration (the other half is kept for direction changes).
  std::vector<AxisValues> v;
  for (int i = 0; i <= 200; ++i) v.push_back({0, 0.5 * i, 0, 0});
  std::array<FeedAxis, 4> ax{FeedAxis{100, 100}, FeedAxis{50, 400}, FeedAxis{}, FeedAxis{}};
  const FeedPlan p = plan_feed(v, 2, ax);
  EXPECT_NEAR(p.total_time, 100.0 / 50 + 50.0 / 200, 1e-9);
  EXPECT_EQ(p.duration[0], 0.0);
  const AxisLimitCheck c = check_axis_limits(v, p.duration, 2, ax);
  EXPECT_LE(c.velocity_ratio, 1 + 1e-12);
  EXPECT_LE(c.acceleration_ratio, 1 + 1e-12);
}

TEST(FeedPlan, CircleStaysWithinEveryAxisLimitAndTooFastIsCaught) {
  // A circle in (A, X) sampled in 720 blocks: corners everywhere.
  std::vector<AxisValues> v;
  for (int i = 0; i <= 720; ++i) {
    const double t = 2 * M_PI * i / 720;
    v.push_back({100 * std::cos(t), 100 * std::sin(t), 0, 0});
  }
  std::array<FeedAxis, 4> ax{FeedAxis{300, 500}, FeedAxis{200, 800}, FeedAxis{}, FeedAxis{}};
  const FeedPlan p = plan_feed(v, 2, ax);
  const AxisLimitCheck c = check_axis_limits(v, p.duration, 2, ax);
  EXPECT_LE(c.velocity_ratio, 1 + 1e-9);
  EXPECT_LE(c.acceleration_ratio, 1 + 1e-9);
  EXPECT_GT(c.acceleration_ratio, 0.3);  // not absurdly slow either
  // The corner caps (v^2 <= amax rho / 2 / |turning share| per axis) keep the speed below
  // sqrt(800 * 100) everywhere, which bounds the lap time below.
  EXPECT_GT(p.total_time, 2 * M_PI * 100 / std::sqrt(800.0 * 100));
  // Every block at its velocity limit alone breaks the acceleration limit.
  std::vector<double> fast(v.size(), 0.0);
  for (std::size_t k = 1; k < v.size(); ++k) {
    fast[k] =
        std::max(std::fabs(v[k][0] - v[k - 1][0]) / 300, std::fabs(v[k][1] - v[k - 1][1]) / 200);
  }
  EXPECT_GT(check_axis_limits(v, fast, 2, ax).acceleration_ratio, 1.0);
}

}  // namespace
}  // namespace windplan
