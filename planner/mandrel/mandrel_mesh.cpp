#include "planner/mandrel/mandrel_mesh.h"

#include "geometry/base/errors.h"
#include "geometry/mesh/mesh_io.h"

namespace windplan {

TriangleSoup load_mandrel_soup(const MandrelOptions& mandrel) {
  if (mandrel.source != "mesh") {
    throw ConfigError("mandrel source '" + mandrel.source +
                      "' cannot be loaded as a triangle-mesh file");
  }
  TriangleSoup soup = read_mesh(mandrel.file);
  const double s = to_millimetres(mandrel.units);
  if (s != 1.0) {
    for (Vec3& p : soup.points) p *= s;
  }
  return soup;
}

Mesh load_mandrel_mesh(const MandrelOptions& mandrel, MeshHealth* health_out,
                       std::vector<std::string>* changes) {
  std::string why;
  if (!mandrel.is_valid(&why)) throw ConfigError("mandrel: " + why);
  if (mandrel.source == "mesh") {
    try {
      return build_mesh(load_mandrel_soup(mandrel), mandrel.repair, health_out, changes);
    } catch (const TopologyError& e) {
      throw TopologyError(mandrel.file.string() + ": " + e.what());
    }
  }
  throw ConfigError("mandrel source '" + mandrel.source + "' is not supported");
}

}  // namespace windplan
