#include "export/files/layup_report.h"

#include <gtest/gtest.h>

namespace windplan {
namespace {

WindingPlan two_layer_plan() {
  WindingPlan plan;
  plan.circuits.resize(3);
  LayerSummary a;
  a.name = "hoop1";
  a.kind = "hoop";
  a.first_circuit = 0;
  a.circuit_count = 1;
  a.thickness_cylinder = 0.4;
  a.fibre_mass = 10.0;
  a.resin_mass = 4.0;
  LayerSummary b = a;
  b.name = "helical1";
  b.kind = "helical";
  b.first_circuit = 1;
  b.circuit_count = 2;
  b.thickness_cylinder = 0.3;
  b.fibre_mass = 20.0;
  plan.layers = {a, b};
  return plan;
}

Motion motion_of(const std::vector<std::pair<int, double>>& ordinal_duration) {
  Motion m;
  for (const auto& [ordinal, duration] : ordinal_duration) {
    MachineState s;
    s.ordinal = ordinal;
    s.duration = duration;
    m.states.push_back(s);
  }
  return m;
}

TEST(LayupReport, WindTimePerLayerFromItsCircuitsStates) {
  const WindingPlan plan = two_layer_plan();
  const Motion m = motion_of({{0, 1.0}, {0, 2.0}, {1, 4.0}, {2, 8.0}});
  const std::vector<double> t = layer_wind_times(plan, m);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_DOUBLE_EQ(t[0], 3.0);
  EXPECT_DOUBLE_EQ(t[1], 12.0);
}

TEST(LayupReport, SectionsPerLayerAndTotals) {
  const WindingPlan plan = two_layer_plan();
  const Motion m = motion_of({{0, 1.0}, {1, 2.0}});
  const std::string md = layers_markdown(plan, m);
  EXPECT_NE(md.find("## Layers"), std::string::npos);
  EXPECT_NE(md.find("### Layer 1: hoop1 (hoop)"), std::string::npos);
  EXPECT_NE(md.find("### Layer 2: helical1 (helical)"), std::string::npos);
  EXPECT_NE(md.find("| total | | | 0.7000 (cylinder) |"), std::string::npos) << md;
  JsonWriter j;
  j.begin_object();
  layers_json(j, plan, m);
  j.end_object();
  EXPECT_NE(j.str().find("\"wind_time_s\": 2"), std::string::npos) << j.str();
  EXPECT_NE(j.str().find("\"composite_mass_g\": 38"), std::string::npos) << j.str();
  EXPECT_NE(layers_summary(plan, m).find("laminate         0.700 mm"), std::string::npos);
}

TEST(LayupReport, NothingWithoutLayers) {
  const WindingPlan plan;
  const Motion m;
  EXPECT_EQ(layers_markdown(plan, m), "");
  EXPECT_EQ(layers_summary(plan, m), "");
  JsonWriter j;
  j.begin_object();
  layers_json(j, plan, m);
  j.end_object();
  EXPECT_EQ(j.str().find("layers"), std::string::npos);
}

}  // namespace
}  // namespace windplan
