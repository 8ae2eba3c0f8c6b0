#include "export/machine/clearance.h"

#include <limits>

namespace windplan {

ClearanceCheck check_clearance(const ClosestPointQuery& mandrel, const std::vector<Vec3>& eyes) {
  ClearanceCheck c;
  c.min_distance = std::numeric_limits<double>::infinity();
  // Only the nearest eye matters: each query looks only for mandrel points nearer than the
  // nearest so far (squared distance `bound2`). A nearer one is the very hit closest() gives, so
  // the minimum, its index and its points are those of querying every eye in full.
  double bound2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < eyes.size(); ++i) {
    const ClosestPointQuery::Hit h = mandrel.closest_within(eyes[i], bound2);
    ++c.checked;
    if (h.point.element < 0) continue;  // no mandrel point nearer than the nearest so far
    bound2 = (h.position - eyes[i]).squaredNorm();
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
