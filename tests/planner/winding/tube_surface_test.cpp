// The default constant-angle demand of a tube surface (planner/winding/tube_surface.h: sampled
// over stations and angles from the rates) against the bent tube's closed form
// (tube_centre_line.h: (R + r cos t) sin^2 a + r cos^2 a cos t in the denominator): at 55 deg the
// worst is 0.179 on a bend of 5 tube radii and 0.328 on one of 3, and 0 on a straight tube.
#include "planner/winding/tube_surface.h"

#include <gtest/gtest.h>

#include <cmath>

#include "planner/winding/tube_centre_line.h"

namespace windplan {
namespace {

TEST(TubeSurface, SampledDemandMatchesTheClosedForm) {
  const double a = 55.0 * M_PI / 180.0;
  for (double R : {250.0, 150.0}) {
    const TubeCentreLine line(50, {100, 100}, {{90, R, 0}});
    const TubeSurface& surface = line;
    const ConstantAngleDemand exact = constant_angle_demand(line, 0.0, line.length(), a);
    const ConstantAngleDemand sampled = surface.TubeSurface::demand(0.0, line.length(), a);
    EXPECT_NEAR(exact.slippage, R == 250.0 ? 0.179 : 0.328, 1e-3);
    EXPECT_NEAR(sampled.slippage, exact.slippage, 1e-4 * exact.slippage) << R;
    EXPECT_NEAR(sampled.min_k_n, exact.min_k_n, 1e-6) << R;
    EXPECT_GT(sampled.s, 100.0);  // in the bend
    EXPECT_LT(sampled.s, 100.0 + 0.5 * M_PI * R);
    // The rates: a pass at constant angle is held by k_g = w, which the sampled demand divides.
    const TubeSurface::Rates q = surface.rates(sampled.s, sampled.theta_outside, a);
    EXPECT_NEAR(std::abs(q.w) / q.k_n, sampled.slippage, 1e-12);
  }
  const TubeCentreLine straight(50, {400}, {});
  const ConstantAngleDemand d =
      static_cast<const TubeSurface&>(straight).TubeSurface::demand(0.0, 400.0, a);
  EXPECT_EQ(d.slippage, 0.0);
  EXPECT_NEAR(d.min_k_n, std::pow(std::sin(a), 2) / 50.0, 1e-12);
}

}  // namespace
}  // namespace windplan
