// The positioner's E1: monotone within a circuit whatever A does, the least-squares monotone fit
// where no smoothing is asked, and the reversals counted inside passes only.
#include "export/robot/positioner_e1.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

// One circuit of n states whose A rises by 3 deg a step with a wobble of amplitude w, one pass over
// dense indices [0, n-1], and a second circuit falling.
struct Wobble {
  Motion motion;
  WindingPlan plan;
  Wobble(int n, double w) {
    plan.circuits.resize(2);
    for (int c = 0; c < 2; ++c) {
      plan.circuits[c].segments.push_back({CircuitSegment::Kind::Pass, 0, n - 1});
      for (int i = 0; i < n; ++i) {
        MachineState s;
        s.ordinal = c;
        s.index = i;
        s.t_s = 0.1 * (c * n + i);
        s.a_deg = (c == 0 ? 3.0 : -3.0) * i + w * std::sin(i * 1.3);
        motion.states.push_back(s);
      }
    }
  }
};

TEST(PositionerE1, MonotoneInEveryCircuitWhatEverAWobbles) {
  const Wobble f(200, 10.0);
  const PositionerE1 r = fit_positioner_e1(f.motion, f.plan);
  ASSERT_EQ(r.e1.size(), f.motion.states.size());
  for (int i = 1; i < 200; ++i) EXPECT_GE(r.e1[i], r.e1[i - 1]) << i;
  for (int i = 201; i < 400; ++i) EXPECT_LE(r.e1[i], r.e1[i - 1]) << i;
  EXPECT_EQ(r.reversals_in_passes, 0);
  EXPECT_GT(r.a_reversals_in_passes, 100);  // the wobble (10 deg) beats the rise (3 deg a step)
  // What the arm takes up: at most the wobble and the smoothing's share of the rise
  // (+-0.5 s twice = +-10 states of 3 deg).
  EXPECT_LE(r.max_offset, 10.0 + 30.0);
  EXPECT_EQ(reversals_in_passes(f.motion, f.plan, r.e1), 0);
}

TEST(PositionerE1, WithoutSmoothingItIsTheLeastSquaresMonotoneFit) {
  const Wobble f(50, 5.0);
  PositionerE1Options o;
  o.smoothing = 0.0;
  const PositionerE1 r = fit_positioner_e1(f.motion, f.plan, o);
  // A monotone sequence already (A without wobble) is left alone; the fit of the wobbly one is
  // no farther from A, in the sum of squares, than A's own monotone trend 3 i.
  double fit = 0.0, trend = 0.0;
  for (int i = 0; i < 50; ++i) {
    fit += std::pow(r.e1[i] - f.motion.states[i].a_deg, 2);
    trend += std::pow(3.0 * i - f.motion.states[i].a_deg, 2);
  }
  EXPECT_LE(fit, trend);
  const Wobble straight(50, 0.0);
  const PositionerE1 s = fit_positioner_e1(straight.motion, straight.plan, o);
  for (int i = 0; i < 100; ++i) EXPECT_DOUBLE_EQ(s.e1[i], straight.motion.states[i].a_deg);
  EXPECT_EQ(s.max_offset, 0.0);
}

TEST(PositionerE1, ReversalsCountOnlyStrictlyInsidePasses) {
  Wobble f(20, 0.0);
  std::vector<double> v(40);
  for (int i = 0; i < 40; ++i) v[i] = f.motion.states[i].a_deg;
  v[10] += 10.0;  // up then down inside the first circuit's pass: two reversals
  EXPECT_EQ(reversals_in_passes(f.motion, f.plan, v), 2);
  f.plan.circuits[0].segments[0].kind = CircuitSegment::Kind::Turnaround;
  EXPECT_EQ(reversals_in_passes(f.motion, f.plan, v), 0);
}

TEST(PositionerE1, NegativeSmoothingIsAConfigError) {
  const Wobble f(5, 0.0);
  PositionerE1Options o;
  o.smoothing = -1.0;
  std::string why;
  EXPECT_FALSE(o.is_valid(&why));
  EXPECT_THROW(fit_positioner_e1(f.motion, f.plan, o), ConfigError);
}

}  // namespace
}  // namespace windplan
