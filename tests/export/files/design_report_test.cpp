#include "export/files/design_report.h"

#include <gtest/gtest.h>

namespace windplan {
namespace {

// design.md from a plan without a run: pot life and the burst table.
TEST(DesignReport, PotLifeAndBurst) {
  DesignOptions d;
  d.present = true;
  d.pressure = 10.0;
  d.fibre_strength = 4900.0;
  d.pot_life = 5.0;  // minutes
  EXPECT_EQ(pot_life_warning(d, 299.0), "");
  EXPECT_NE(pot_life_warning(d, 301.0).find("pot life of 5 min"), std::string::npos);
  LayupResult layup;
  layup.plan.job_name = "t";
  LayerSummary L;
  L.name = "helical1";
  L.angle = 20.0;
  L.thickness_cylinder = 0.5;
  layup.plan.layers = {L};
  layup.has_netting = true;
  layup.netting_radius = 100.0;
  layup.netting = netting_burst({{"helical1", 20.0, 0.5}}, 100.0, d.allowable_stress());
  const std::string md = design_markdown(d, false, DesignLayup{}, layup, {400.0}, false);
  EXPECT_NE(md.find("| 1 helical1 | 20.000 | 0.5000 |"), std::string::npos) << md;
  EXPECT_NE(md.find("WARNING"), std::string::npos) << md;
  EXPECT_NE(md.find("NOT met"), std::string::npos) << md;  // hoop capacity 1.7 MPa < 10
}

}  // namespace
}  // namespace windplan
