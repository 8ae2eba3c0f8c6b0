// planner/plan/plan.h: where the layers of a layup start (layer_start_circuits), the rule the
// G-code replay, the robot cell's tie-ons and the link eyes of compute_motion share.
#include "planner/plan/plan.h"

#include <gtest/gtest.h>

namespace windplan {
namespace {

WindingPlan plan_of(const std::vector<int>& points_per_circuit) {
  WindingPlan plan;
  for (int n : points_per_circuit) {
    Circuit c;
    c.points.resize(n);
    plan.circuits.push_back(c);
  }
  return plan;
}

LayerSummary layer(int first, int count) {
  LayerSummary l;
  l.first_circuit = first;
  l.circuit_count = count;
  return l;
}

TEST(Plan, LayersStartAtTheirFirstCircuitWithPoints) {
  WindingPlan plan = plan_of({5, 5, 0, 0, 5, 5, 0, 5});
  EXPECT_EQ(layer_start_circuits(plan), std::vector<char>(8, 0));  // no layers
  // Layer 0: circuits 0-1; layer 1: 2-5, its first two empty (starts at 4); layer 2: circuit 6
  // only, empty (starts nowhere); layer 3: circuit 7; a layer of no circuits.
  plan.layers = {layer(0, 2), layer(2, 4), layer(6, 1), layer(7, 1), layer(8, 0)};
  EXPECT_EQ(layer_start_circuits(plan), (std::vector<char>{1, 0, 0, 0, 1, 0, 0, 1}));
  // A layer running past the plan's end is clipped to it.
  plan.layers = {layer(6, 9)};
  EXPECT_EQ(layer_start_circuits(plan), (std::vector<char>{0, 0, 0, 0, 0, 0, 0, 1}));
}

}  // namespace
}  // namespace windplan
