#pragma once
// The surfaces a plan's circuits were wound on, as the replays walk them: a layup's circuits lie
// on the surface of their layer (planner/plan_layup.h layup_circuit_surfaces), every other
// circuit on the mandrel. One entry per distinct surface, the mandrel first, and per circuit its
// entry, so that a replay builds one walking surface or closest-point query per surface.
#include <vector>

#include "geometry/mesh/mesh.h"
#include "planner/plan/plan.h"

namespace windplan {

struct CircuitSurfaces {
  std::vector<const Mesh*> meshes;  ///< the distinct surfaces, meshes[0] the mandrel
  std::vector<int> of;              ///< per circuit of the plan: its entry of `meshes`
};

/// \param circuit_surfaces per circuit of plan.circuits, its surface; null or missing: the mandrel
/// \throw InputError naming the circuit whose surface has no faces
CircuitSurfaces distinct_circuit_surfaces(const WindingPlan& plan, const Mesh& mandrel,
                                          const std::vector<const Mesh*>& circuit_surfaces);

}  // namespace windplan
