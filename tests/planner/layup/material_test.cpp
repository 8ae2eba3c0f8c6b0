#include "planner/layup/material.h"

#include <gtest/gtest.h>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

TEST(Material, MassOfAKnownLengthOfTow) {
  // 1 km of an 800 tex tow weighs 800 g, whatever the band it is spread into.
  MaterialOptions m;
  m.tex = 800.0;
  m.fibre_density = 1.8;
  m.fibre_volume_fraction = 0.6;
  m.resin_density = 1.2;
  m.tows = 1.0;
  const MaterialEstimate e = estimate_material(m, 5.0, 1e6);
  EXPECT_NEAR(e.fibre_mass, 800.0, 1e-9);
  EXPECT_NEAR(e.fibre_length, 1e6, 1e-6);
  // Band thickness = tow area / (B V_f) = (800 / 1800) mm^2 / (5 mm * 0.6).
  EXPECT_NEAR(e.band_thickness, (800.0 / 1800.0) / 3.0, 1e-12);
  // Resin at the volume fraction: m_f rho_r (1 - V_f) / (rho_f V_f).
  EXPECT_NEAR(e.resin_mass, 800.0 * 1.2 * 0.4 / (1.8 * 0.6), 1e-9);
  EXPECT_NEAR(e.composite_mass(), e.fibre_mass + e.resin_mass, 1e-12);
}

TEST(Material, TwoTowsPerBandDoubleTheFibreLengthAndMass) {
  MaterialOptions m;
  m.tows = 2.0;
  const MaterialEstimate one = estimate_material(MaterialOptions{}, 8.0, 1000.0);
  const MaterialEstimate two = estimate_material(m, 8.0, 1000.0);
  EXPECT_NEAR(two.fibre_length, 2.0 * one.fibre_length, 1e-9);
  EXPECT_NEAR(two.fibre_mass, 2.0 * one.fibre_mass, 1e-12);
  EXPECT_NEAR(two.band_thickness, 2.0 * one.band_thickness, 1e-15);
}

TEST(Material, BandThicknessGivesTheTowsPerBand) {
  // A band_thickness given: the fibre mass is rho_f V_f B t L, and the tows per band follow.
  MaterialOptions m;
  m.band_thickness = 0.5;
  const MaterialEstimate e = estimate_material(m, 12.0, 2000.0);
  EXPECT_DOUBLE_EQ(e.band_thickness, 0.5);
  EXPECT_NEAR(e.fibre_mass, 1e-3 * m.fibre_density * m.fibre_volume_fraction * 12.0 * 0.5 * 2000.0,
              1e-12);
  EXPECT_NEAR(e.tows * m.tex * 1e-6 * 2000.0, e.fibre_mass, 1e-12);  // tex: g per km
}

TEST(Material, EstimatesAdd) {
  MaterialEstimate a = estimate_material(MaterialOptions{}, 10.0, 100.0);
  const MaterialEstimate b = estimate_material(MaterialOptions{}, 10.0, 300.0);
  a += b;
  EXPECT_NEAR(a.fibre_mass, estimate_material(MaterialOptions{}, 10.0, 400.0).fibre_mass, 1e-12);
}

TEST(Material, NonPositiveFiguresAreRejectedByName) {
  auto why = [](MaterialOptions m) {
    std::string w;
    EXPECT_FALSE(m.is_valid(&w));
    return w;
  };
  MaterialOptions m;
  m.tex = 0.0;
  EXPECT_NE(why(m).find("tex"), std::string::npos);
  m = {};
  m.fibre_density = -1.0;
  EXPECT_NE(why(m).find("fibre_density"), std::string::npos);
  m = {};
  m.resin_density = 0.0;
  EXPECT_NE(why(m).find("resin_density"), std::string::npos);
  m = {};
  m.fibre_volume_fraction = 1.0;
  EXPECT_NE(why(m).find("fibre_volume_fraction"), std::string::npos);
  m = {};
  m.band_thickness = 0.0;
  EXPECT_NE(why(m).find("band_thickness"), std::string::npos);
  m = {};
  m.tows = -2.0;
  EXPECT_NE(why(m).find("tows"), std::string::npos);
  EXPECT_THROW(estimate_material(m, 10.0, 1.0), ConfigError);
  EXPECT_THROW(estimate_material(MaterialOptions{}, 0.0, 1.0), InputError);
}

}  // namespace
}  // namespace windplan
