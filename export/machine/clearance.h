#pragma once
// Clearance of the payout eye: its true distance to the mandrel surface (the closest point on the
// mandrel mesh, geometry/mesh/closest_point.h), checked on every eye point.
#include <string>
#include <vector>

#include "geometry/mesh/closest_point.h"
#include "geometry/mesh/mesh.h"

namespace windplan {

struct ClearanceCheck {
  double min_distance = 0.0;  ///< mm, smallest eye-mandrel distance (+inf: nothing checked)
  int worst = -1;             ///< index of that eye point in the input, -1 if none
  Vec3 worst_eye = Vec3::Zero();
  Vec3 worst_surface = Vec3::Zero();  ///< its closest mandrel point
  int checked = 0;                    ///< eye points checked
};

/// Distance of every eye point to the mesh; the minimum and where it is.
ClearanceCheck check_clearance(const ClosestPointQuery& mandrel, const std::vector<Vec3>& eyes);

}  // namespace windplan
