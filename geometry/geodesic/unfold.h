#pragma once
// Planar unfolding helpers shared by the initial-path graph and the geodesic refinement.
#include <algorithm>
#include <cmath>

#include "geometry/mesh/mesh.h"

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

/// The far corner d of the triangle across edge a -> b (d on its right, as in the face of the
/// edge's twin) in the edge's frame: d = a + u (b - a) + w perp(b - a), perp(x, y) = (y, -x);
/// returns (u, w). Dimensionless, so they place d from any placement of the edge.
inline Vec2 across_coefficients(const Vec3& a, const Vec3& b, const Vec3& d) {
  const Vec3 e = b - a, f = d - a;
  const double inv = 1.0 / e.squaredNorm();
  return Vec2(e.dot(f) * inv, e.cross(f).norm() * inv);
}

/// Places d from the placed edge a2 -> b2 and its across_coefficients (u, w): no square root.
inline Vec2 place_across(const Vec2& a2, const Vec2& b2, const Vec2& uw) {
  const Vec2 e2 = b2 - a2;
  return a2 + uw.x() * e2 + uw.y() * Vec2(e2.y(), -e2.x());
}

}  // namespace windplan
