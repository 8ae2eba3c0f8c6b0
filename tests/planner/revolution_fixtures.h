#pragma once
// Surfaces of revolution about z made in code (annuli), with their two boundary loops, for the
// helix, harmonic and fibre-metric tests.
#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"
#include "tests/mesh_fixtures.h"

namespace windplan::test {

/// The two boundary loops of an annulus about z, the one at lower z first.
inline std::array<std::vector<int>, 2> loops_by_z(const Mesh& m) {
  std::vector<std::vector<int>> loops;
  for (const auto& l : m.boundary_loops()) loops.push_back(m.loop_vertices(l));
  std::array<std::vector<int>, 2> out{loops.at(0), loops.at(1)};
  if (m.position(out[0][0]).z() > m.position(out[1][0]).z()) std::swap(out[0], out[1]);
  return out;
}

inline double polyline_length(const std::vector<Vec3>& p) {
  double L = 0.0;
  for (std::size_t i = 1; i < p.size(); ++i) L += (p[i] - p[i - 1]).norm();
  return L;
}

/// Winding angle (deg from the z meridian) of the polyline segment a -> b on a surface of
/// revolution about z, with the surface normal estimated from the radial direction and the
/// profile slope `drdz` at the segment's middle.
inline double segment_angle(const Vec3& a, const Vec3& b, double drdz) {
  const Vec3 mid = 0.5 * (a + b);
  const Vec3 radial = Vec3(mid.x(), mid.y(), 0.0).normalized();
  const Vec3 meridian = (Vec3(0, 0, 1) + drdz * radial).normalized();
  const Vec3 t = (b - a).normalized();
  return std::acos(std::min(1.0, std::fabs(t.dot(meridian)))) * 180.0 / M_PI;
}

}  // namespace windplan::test
