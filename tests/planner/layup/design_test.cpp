#include "planner/layup/design.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

DesignOptions design(double p, double strength) {
  DesignOptions d;
  d.present = true;
  d.pressure = p;
  d.fibre_strength = strength;
  d.ply.volume_fraction = 0.5;
  return d;
}

TEST(Design, SizesWholeLayersFromNetting) {
  DesignOptions d = design(35.0, 4000.0);  // sigma = 2000 MPa
  d.burst_factor = 2.0;                    // p_d = 70 MPa: the closed form of netting_test
  WindingOptions w;
  w.band_width = 10.0;
  const DesignLayup s = design_layup(d, 100.0, 15.0, w, 0.25);
  EXPECT_NEAR(s.sigma, 2000.0, 1e-12);
  EXPECT_NEAR(s.required.helical_thickness, 1.876, 5e-4);
  EXPECT_NEAR(s.required.hoop_thickness, 3.374, 5e-4);
  // Layers of 2 x 0.25 mm: ceil(1.876 / 0.5) = 4 helical, ceil(3.374 / 0.5) = 7 hoop.
  EXPECT_EQ(s.helical_layers, 4);
  EXPECT_EQ(s.hoop_layers, 7);
  ASSERT_EQ(s.layers.size(), 11u);
  EXPECT_EQ(s.layers[0].kind, LayerKind::Hoop);
  EXPECT_EQ(s.layers[1].kind, LayerKind::Helical);
  EXPECT_EQ(s.layers[10].name, "hoop7");
  EXPECT_DOUBLE_EQ(s.layers[0].hoop.band_width, 10.0);
  // The wound thickness covers the requirement.
  EXPECT_GE(s.helical_layers * s.layer_thickness, s.required.helical_thickness);
  EXPECT_GE(s.hoop_layers * s.layer_thickness, s.required.hoop_thickness);
}

TEST(Design, NoHoopLayersAbove54_74Degrees) {
  const DesignLayup s = design_layup(design(10.0, 3000.0), 100.0, 60.0, WindingOptions{}, 0.2);
  EXPECT_EQ(s.hoop_layers, 0);
  EXPECT_GE(s.helical_layers, 1);
  for (const LayerOptions& L : s.layers) EXPECT_EQ(L.kind, LayerKind::Helical);
}

TEST(Design, ValidationNamesTheKey) {
  std::string why;
  DesignOptions d = design(10.0, std::nan(""));
  EXPECT_FALSE(d.is_valid(&why));
  EXPECT_EQ(why.rfind("fibre_strength:", 0), 0u) << why;
  d = design(10.0, 3000.0);
  d.burst_factor = 0.9;
  EXPECT_FALSE(d.is_valid(&why));
  EXPECT_EQ(why.rfind("burst_factor:", 0), 0u) << why;
  d = design(10.0, 3000.0);
  d.ply.volume_fraction = 1.2;
  EXPECT_FALSE(d.is_valid(&why));
  EXPECT_EQ(why.rfind("fibre_volume_fraction:", 0), 0u) << why;
  EXPECT_THROW(design_layup(DesignOptions{}, 100.0, 20.0, WindingOptions{}, 0.2), ConfigError);
}

}  // namespace
}  // namespace windplan
