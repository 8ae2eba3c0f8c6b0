// Tests for export/machine/circuit_surfaces.h: one entry per distinct surface, the mandrel first,
// each circuit pointing at its own; an empty surface named by its circuit.
#include "export/machine/circuit_surfaces.h"

#include <gtest/gtest.h>

#include <string>

#include "geometry/base/errors.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

TEST(CircuitSurfaces, DistinctSurfacesMandrelFirstAndEachCircuitsEntry) {
  const Mesh mandrel(test::open_cylinder(50, 100, 32, 4));
  const Mesh inner(test::open_cylinder(52, 100, 32, 4));
  const Mesh outer(test::open_cylinder(54, 100, 32, 4));
  WindingPlan plan;
  plan.circuits.resize(6);
  // Circuit 0 on the mandrel (null), 1-2 on the inner layer, 3 on the outer, 4 on the inner
  // again; circuit 5 has no entry (the mandrel).
  const CircuitSurfaces s =
      distinct_circuit_surfaces(plan, mandrel, {nullptr, &inner, &inner, &outer, &inner});
  ASSERT_EQ(s.meshes.size(), 3u);
  EXPECT_EQ(s.meshes[0], &mandrel);
  EXPECT_EQ(s.meshes[1], &inner);
  EXPECT_EQ(s.meshes[2], &outer);
  EXPECT_EQ(s.of, (std::vector<int>{0, 1, 1, 2, 1, 0}));
  // The mandrel given by name is the same entry as null.
  EXPECT_EQ(distinct_circuit_surfaces(plan, mandrel, {&mandrel, &outer}).of,
            (std::vector<int>{0, 1, 0, 0, 0, 0}));
}

TEST(CircuitSurfaces, AnEmptySurfaceIsNamedByItsCircuit) {
  const Mesh mandrel(test::open_cylinder(50, 100, 32, 4));
  const Mesh empty;
  WindingPlan plan;
  plan.circuits.resize(3);
  try {
    distinct_circuit_surfaces(plan, mandrel, {nullptr, nullptr, &empty});
    FAIL() << "an empty surface was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("circuit 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace windplan
