#include "export/machine/circuit_surfaces.h"

#include <algorithm>
#include <string>

#include "geometry/base/errors.h"

namespace windplan {

CircuitSurfaces distinct_circuit_surfaces(const WindingPlan& plan, const Mesh& mandrel,
                                          const std::vector<const Mesh*>& circuit_surfaces) {
  CircuitSurfaces out;
  out.meshes.push_back(&mandrel);
  out.of.assign(plan.circuits.size(), 0);
  for (std::size_t ci = 0; ci < plan.circuits.size() && ci < circuit_surfaces.size(); ++ci) {
    const Mesh* m = circuit_surfaces[ci] ? circuit_surfaces[ci] : &mandrel;
    auto it = std::find(out.meshes.begin(), out.meshes.end(), m);
    if (it == out.meshes.end()) {
      if (m->num_faces() == 0)
        throw InputError("the mesh under circuit " + std::to_string(ci) + " is empty");
      out.meshes.push_back(m);
      it = out.meshes.end() - 1;
    }
    out.of[ci] = static_cast<int>(it - out.meshes.begin());
  }
  return out;
}

}  // namespace windplan
