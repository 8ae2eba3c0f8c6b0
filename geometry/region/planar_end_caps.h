#pragma once
// The flat end caps of a closed tube whose ends are not normal to the spindle axis (a bent pipe
// closed at the ends of its legs).
//
// planar_end_caps() groups the selected faces into planar patches (faces joined through an edge
// whose normals agree within `angle_deg` and whose vertices lie within `flatness` of the seed
// face's plane), and takes the two largest patches by area as the end caps when the selection
// without them is an annulus (one component, two boundary loops, genus 0). A tube's flat sides
// (the faces of a coarse polygonal section along a straight leg) are planar patches too, but the
// selection without them is not an annulus, so they are never taken for caps.
//
// Units: mm, degrees.
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

struct PlanarEndCapsOptions {
  double angle_deg = 1.0;  ///< largest angle between the normals of a patch's faces (deg, > 0)
  double flatness = 1e-6;  ///< largest distance from the patch plane / mesh diagonal (> 0)
  bool is_valid(std::string* why) const;
};

struct PlanarEndCaps {
  bool found = false;      ///< two caps whose removal leaves an annulus
  std::vector<char> keep;  ///< per face: the selection without the caps (empty when not found)
  double cap_area[2] = {0.0, 0.0};  ///< mm^2, the two caps
  int cap_faces[2] = {0, 0};        ///< triangles of each cap
  std::string brief() const;        ///< "two planar end caps (35 + 35 faces, ...)" or why not
};

/// \param keep per face of `mesh`: the selection to take the caps from (all faces when empty)
/// \throw ConfigError for invalid options; InputError when keep has the wrong size.
PlanarEndCaps planar_end_caps(const Mesh& mesh, const std::vector<char>& keep,
                              const PlanarEndCapsOptions& options = {});

}  // namespace windplan
