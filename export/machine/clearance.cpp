#include "export/machine/clearance.h"

#include <limits>

namespace windplan {

ClearanceCheck check_clearance(const ClosestPointQuery& mandrel, const std::vector<Vec3>& eyes) {
  ClearanceCheck c;
  c.min_distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < eyes.size(); ++i) {
    const ClosestPointQuery::Hit h = mandrel.closest(eyes[i]);
    ++c.checked;
    if (h.distance < c.min_distance) {
      c.min_distance = h.distance;
      c.worst = static_cast<int>(i);
      c.worst_eye = eyes[i];
      c.worst_surface = h.position;
    }
  }
  return c;
}

}  // namespace windplan
