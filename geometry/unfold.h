#pragma once
// Planar unfolding helpers shared by the initial-path graph and the geodesic refinement.
#include <algorithm>
#include <cmath>

#include "geometry/mesh.h"

namespace windplan {

/// z component of the 2D cross product a x b.
inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Places the third corner c of a triangle in the plane, given the placed corners a and b and the
/// lengths |c - a| = la, |c - b| = lb: on the left of a -> b when `left`, else on the right.
inline Vec2 place_third(const Vec2& a, const Vec2& b, double la, double lb, bool left) {
  const Vec2 ab = b - a;
  const double L = ab.norm();
  const double x = (la * la - lb * lb + L * L) / (2.0 * L);
  const double y = std::sqrt(std::max(0.0, la * la - x * x));
  const Vec2 u = ab / L;
  const Vec2 n(-u.y(), u.x());
  return a + x * u + (left ? y : -y) * n;
}

}  // namespace windplan
