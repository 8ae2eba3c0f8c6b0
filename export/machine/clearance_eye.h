#pragma once
// The payout eye of a robot cell at the true clearance from the mandrel (issue #26).
//
// A lathe's eye moves on a surface of revolution about the spindle, so it must clear the solid the
// mandrel sweeps as it turns (export/machine/eye_envelope.h); on a bent tube that solid is far
// larger than the tube and the eye sits up to hundreds of mm out along the tangent. A robot arm
// can follow the tube itself: for a fibre point P with unit tangent t the eye is E = P + L t with
// L the first length at which the distance from E(L) to the (unswept) mandrel mesh reaches the
// clearance c. The mesh distance d(L) is 1-Lipschitz in L, so marching by c - d(L) never steps
// past the first L with d = c (sphere tracing, monotone-safe); the last bracket is refined by
// bisection to `tolerance`. The distance is unsigned, so every point of the march is also tested
// for being inside the mandrel (below the closest face's plane by more than 1e-3 mm): where the
// free fibre P -> E would cut into the mandrel (a concave stretch, e.g. along the inside of a
// bend), the march goes on through it by steps of d (the ball of radius d is inside) and the eye
// is the first point beyond with d = c; this is reported (`enters`), never hidden.
#include <string>

#include "geometry/mesh/closest_point.h"
#include "geometry/mesh/mesh.h"

namespace windplan {

struct ClearanceEye {
  Vec3 eye = Vec3::Zero();
  double free_length = 0.0;  ///< mm, L
  double distance = 0.0;     ///< mm, the eye's distance to the mandrel (c within tolerance)
  int iterations = 0;        ///< distance queries
  bool enters = false;       ///< a point of the march was inside the mandrel (see above)
};

/// Solves the eye of point p (on the mandrel) with tangent t at distance `clearance` (mm, > 0)
/// from the mandrel mesh of `query`, to within `tolerance` mm of L.
/// \throw InputError when t is zero or not finite, p is not finite, or the tangent line stays
///        within the clearance for `max_length` mm; `where` names the point in the message.
ClearanceEye solve_clearance_eye(const Mesh& mesh, const ClosestPointQuery& query, const Vec3& p,
                                 const Vec3& t, double clearance, const std::string& where = "",
                                 double tolerance = 1e-4, double max_length = 1e4);

}  // namespace windplan
