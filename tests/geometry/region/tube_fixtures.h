#pragma once
// A synthetic bent tube for the tube-coordinate and coverage tests: a straight leg of length
// `leg` along +z from the origin, a bend of centre-line radius `bend` through `angle` radians in
// the xz plane (towards +x), and a second straight leg of length `leg`; the section an ellipse
// with semi-axis `a` in the bend plane and `b` along y (a == b: a circular tube, whose bend is a
// piece of a torus). Rings of `around` vertices, `per_mm` rings per mm of centre line (at least
// one per piece), quads split along a diagonal: an annulus. The centre line and its tangent are
// exact (the same formulas), so tests compare against them.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan::test {

struct BentTube {
  double leg = 100, bend = 100, angle = M_PI / 2, a = 25, b = 25;
  int around = 96;
  double per_mm = 0.5;

  double length() const { return 2 * leg + bend * angle; }
  /// Centre point at arc length s in [0, length()].
  Vec3 centre(double s) const {
    if (s <= leg) return Vec3(0, 0, s);
    const double phi = std::min(angle, (s - leg) / bend);
    const Vec3 c(bend - bend * std::cos(phi), 0, leg + bend * std::sin(phi));
    if (s <= leg + bend * angle) return c;
    return c + (s - leg - bend * angle) * tangent(s);
  }
  /// Unit tangent at arc length s.
  Vec3 tangent(double s) const {
    const double phi = std::clamp((s - leg) / bend, 0.0, angle);
    return Vec3(std::sin(phi), 0, std::cos(phi));
  }
  /// In-plane unit normal (towards the outside of the bend: -x on the first leg).
  Vec3 normal(double s) const { return Vec3(0, 1, 0).cross(tangent(s)); }
  /// The surface point at arc length s and section angle t (t = 0: outside of the bend).
  Vec3 at(double s, double t) const {
    return centre(s) + a * std::cos(t) * normal(s) + b * std::sin(t) * Vec3(0, 1, 0);
  }
  /// The ring stations (mm of centre line).
  std::vector<double> stations() const {
    std::vector<double> st;
    auto piece = [&](double s0, double len) {
      const int n = std::max(1, static_cast<int>(std::ceil(len * per_mm)));
      for (int k = (st.empty() ? 0 : 1); k <= n; ++k) st.push_back(s0 + len * k / n);
    };
    piece(0, leg);
    piece(leg, bend * angle);
    piece(leg + bend * angle, leg);
    return st;
  }
  Mesh mesh() const {
    TriangleSoup s;
    const std::vector<double> st = stations();
    for (double z : st) {
      for (int i = 0; i < around; ++i) s.points.push_back(at(z, 2 * M_PI * i / around));
    }
    auto id = [&](int i, int j) { return j * around + (i % around); };
    for (int j = 0; j + 1 < static_cast<int>(st.size()); ++j) {
      for (int i = 0; i < around; ++i) {
        s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
    return Mesh(std::move(s));
  }
  /// Boundary loops as vertex lists: the first ring and the last.
  std::array<std::vector<int>, 2> loops() const {
    const int rings = static_cast<int>(stations().size());
    std::array<std::vector<int>, 2> l;
    for (int i = 0; i < around; ++i) {
      l[0].push_back(i);
      l[1].push_back((rings - 1) * around + i);
    }
    return l;
  }
};

}  // namespace windplan::test
