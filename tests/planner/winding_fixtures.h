#pragma once
// Meridians and meshes of revolution made in code for the winding-pattern tests: a cylinder
// with hemispherical or elliptical domes open at the poles, revolved from (axial, radius)
// points about z.
#include <cmath>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "tests/mesh_fixtures.h"

namespace windplan::test {

/// A capsule's meridian: a dome from the polar opening r0 to the equator (radius R), a cylinder
/// of length L (z from 0 to L), the mirror dome; `per_dome` points on each dome, `cyl` segments
/// on the cylinder. Domes are ellipses with semi-axes R (radial) and k R (axial): k = 1 a
/// hemisphere. Points from the lower opening up.
inline std::vector<Vec2> capsule_meridian(double R, double L, double r0, int per_dome, int cyl,
                                          double k = 1.0) {
  std::vector<Vec2> m;
  const double t0 = std::asin(r0 / R);  // polar angle of the opening
  for (int i = 0; i < per_dome; ++i) {
    const double t = t0 + (M_PI / 2 - t0) * i / per_dome;
    m.emplace_back(-k * R * std::cos(t), R * std::sin(t));
  }
  for (int i = 0; i <= cyl; ++i) m.emplace_back(L * i / cyl, R);
  for (int i = per_dome - 1; i >= 0; --i) {
    const double t = t0 + (M_PI / 2 - t0) * i / per_dome;
    m.emplace_back(L + k * R * std::cos(t), R * std::sin(t));
  }
  return m;
}

/// The surface of revolution of a meridian about z, n vertices per ring (vertex 0 of every ring
/// on +x), quads split along a diagonal: an annulus with outward normals.
inline Mesh revolve(const std::vector<Vec2>& meridian, int n) {
  TriangleSoup s;
  for (const Vec2& p : meridian) {
    for (int i = 0; i < n; ++i) {
      const double t = 2.0 * M_PI * i / n;
      s.points.emplace_back(p.y() * std::cos(t), p.y() * std::sin(t), p.x());
    }
  }
  const int m = static_cast<int>(meridian.size()) - 1;
  auto id = [n](int i, int j) { return j * n + (i % n); };
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < n; ++i) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return Mesh(std::move(s));
}

}  // namespace windplan::test
