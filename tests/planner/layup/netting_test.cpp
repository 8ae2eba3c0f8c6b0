#include "planner/layup/netting.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

// The closed form of the issue: 15 deg, R 100 mm, p 70 MPa, sigma 2000 MPa.
TEST(Netting, ThicknessesAt15Degrees) {
  const NettingSizing s = netting_thickness(70.0, 100.0, 15.0, 2000.0);
  EXPECT_NEAR(s.helical_thickness, 1.876, 5e-4);
  EXPECT_NEAR(s.hoop_thickness, 3.374, 5e-4);
  // Both burst formulas give the pressure back.
  const NettingBurst b = netting_burst(
      {{"helical", 15.0, s.helical_thickness}, {"hoop", 90.0, s.hoop_thickness}}, 100.0, 2000.0);
  EXPECT_NEAR(b.axial, 70.0, 1e-9);
  EXPECT_NEAR(b.hoop, 70.0, 1e-9);
  EXPECT_NEAR(b.pressure, 70.0, 1e-9);
}

TEST(Netting, HoopOverHelicalRatioIsThreeCosSquaredMinusOne) {
  for (double a : {5.0, 15.0, 30.0, 45.0, 54.0}) {
    const NettingSizing s = netting_thickness(10.0, 80.0, a, 1500.0);
    const double c = std::cos(a * M_PI / 180.0);
    EXPECT_NEAR(s.hoop_thickness / s.helical_thickness, 3.0 * c * c - 1.0, 1e-12) << a;
  }
}

TEST(Netting, NoHoopAbove54_74Degrees) {
  const double magic = std::atan(std::sqrt(2.0)) * 180.0 / M_PI;
  EXPECT_NEAR(magic, 54.7356, 1e-4);
  EXPECT_NEAR(netting_thickness(10.0, 80.0, magic, 1500.0).hoop_thickness, 0.0, 1e-12);
  for (double a : {55.0, 60.0, 75.0, 89.0}) {
    const NettingSizing s = netting_thickness(10.0, 80.0, a, 1500.0);
    EXPECT_EQ(s.hoop_thickness, 0.0) << a;  // zero, never negative
    EXPECT_GT(s.helical_thickness, 0.0);
  }
}

TEST(Netting, BurstByLayerAccumulates) {
  // Two helical layers and a hoop layer: the burst after each layer is the smaller capacity.
  const NettingBurst b =
      netting_burst({{"h1", 20.0, 0.5}, {"hoop", 90.0, 0.6}, {"h2", 20.0, 0.5}}, 100.0, 2000.0);
  ASSERT_EQ(b.burst.size(), 3u);
  const double c2 = std::pow(std::cos(20.0 * M_PI / 180.0), 2), s2 = 1.0 - c2;
  EXPECT_NEAR(b.axial_capacity[0], 2.0 * 2000.0 * 0.5 * c2 / 100.0, 1e-12);
  EXPECT_NEAR(b.hoop_capacity[1], 2000.0 * 0.6 / 100.0, 1e-9);
  EXPECT_NEAR(b.burst[0], 2000.0 * 0.5 * s2 / 100.0, 1e-12);  // hoop-limited
  EXPECT_NEAR(b.burst[2], std::min(2.0 * 2000.0 * c2, 2000.0 * (s2 + 0.6)) / 100.0, 1e-9);
  EXPECT_EQ(b.governing, "hoop");  // 14.3 MPa around against 35.3 MPa along
}

TEST(Netting, RejectsBadFigures) {
  EXPECT_THROW(netting_thickness(-1.0, 100.0, 15.0, 2000.0), InputError);
  EXPECT_THROW(netting_thickness(10.0, 100.0, 90.0, 2000.0), InputError);
  EXPECT_THROW(netting_thickness(10.0, 100.0, 15.0, 0.0), InputError);
  EXPECT_THROW(netting_burst({{"x", 15.0, -0.1}}, 100.0, 2000.0), InputError);
}

}  // namespace
}  // namespace windplan
