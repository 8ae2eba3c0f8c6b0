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

/// Places d, the far corner of the triangle across edge a -> b (placed at a2 -> b2), on the
/// right of a2 -> b2: d2 = a2 + u e2 + w perp(e2) with e2 = b2 - a2, u and w read off the 3D
/// triangle (one square root, no lengths of the placed edge: cheaper than place_third).
inline Vec2 place_across(const Vec3& a, const Vec3& b, const Vec3& d, const Vec2& a2,
                         const Vec2& b2) {
  const Vec3 e = b - a, f = d - a;
  const double inv = 1.0 / e.squaredNorm();
  const double u = e.dot(f) * inv, w = e.cross(f).norm() * inv;
  const Vec2 e2 = b2 - a2;
  return a2 + u * e2 + w * Vec2(e2.y(), -e2.x());
}

}  // namespace windplan
