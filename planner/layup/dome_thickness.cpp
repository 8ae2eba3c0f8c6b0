#include "planner/layup/dome_thickness.h"

#include <algorithm>
#include <cmath>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"

namespace windplan {

namespace {

// A piece of meridian inside the region: r linear from ra to rb over `length` of arc.
struct Piece {
  double ra, rb, length;
};

// integral of r ds / sqrt(r^2 - c^2) over a piece (r >= c on it): length (Sb - Sa) / (rb - ra)
// = length (ra + rb) / (Sa + Sb).
double continuity_volume_integral(const Piece& p, double c) {
  const double sa = std::sqrt(std::max(0.0, p.ra * p.ra - c * c));
  const double sb = std::sqrt(std::max(0.0, p.rb * p.rb - c * c));
  return p.length * (p.ra + p.rb) / (sa + sb);
}

// integral of (r - c)^k 2 pi r ds over a piece, k = 0, 2, 3: a polynomial of degree <= 4 in s,
// exact with 3-point Gauss.
void moments(const Piece& p, double c, double m[4]) {
  static const double x[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  static const double w[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  for (int g = 0; g < 3; ++g) {
    const double u = 0.5 * (1.0 + x[g]);
    const double r = p.ra + u * (p.rb - p.ra), d = r - c;
    const double f = 0.5 * p.length * w[g] * 2.0 * M_PI * r;
    m[0] += f;
    m[1] += f * d;
    m[2] += f * d * d;
    m[3] += f * d * d * d;
  }
}

double det3(const double a[3][3]) {
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
         a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

}  // namespace

LayerThickness helical_layer_thickness_spline(const MeridianPolyline& m, double c, double circuits,
                                              double band_width, double band_thickness) {
  if (!(c > 0.0) || !std::isfinite(c)) throw InputError("turnaround radius must be > 0 mm");
  if (!(circuits > 0.0)) throw InputError("circuits must be > 0");
  if (!(band_width > 0.0) || !(band_thickness > 0.0)) {
    throw InputError("band width and band thickness must be > 0 mm");
  }
  const int n = static_cast<int>(m.points.size());
  const double rb = c + 2.0 * band_width;
  double rmax = 0.0;
  for (const Vec2& p : m.points) rmax = std::max(rmax, p.y());
  if (!(rb < rmax)) {
    throw InputError("the spline dome thickness needs the turnaround radius + 2 band widths (" +
                     format_number("%.4g", rb) + " mm) below the largest radius (" +
                     format_number("%.4g", rmax) + " mm)");
  }
  const double k = circuits * band_width * band_thickness / M_PI;
  LayerThickness t;
  t.s = m.s;
  t.thickness.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    const double r = m.points[i].y();
    if (r > rb)
      t.thickness[i] = helical_thickness_unbounded(r, c, circuits, band_width, band_thickness);
  }
  // The region of each end: segments from that end until the first point beyond r_b.
  for (int end = 0; end < 2; ++end) {
    std::vector<int> pts;  // point indices from the end inward while r <= r_b
    for (int j = 0; j < n; ++j) {
      const int i = end == 0 ? j : n - 1 - j;
      pts.push_back(i);
      if (m.points[i].y() > rb) break;
    }
    std::vector<Piece> pieces;
    for (std::size_t q = 0; q + 1 < pts.size(); ++q) {
      double ra = m.points[pts[q]].y(), rbb = m.points[pts[q + 1]].y();
      double len = std::abs(m.s[pts[q + 1]] - m.s[pts[q]]);
      const double lo = std::min(ra, rbb), hi = std::max(ra, rbb);
      if (hi <= c) continue;
      double keep_lo = std::max(lo, c), keep_hi = std::min(hi, rb);
      if (keep_hi <= keep_lo) continue;
      if (hi > lo) len *= (keep_hi - keep_lo) / (hi - lo);
      pieces.push_back({keep_lo, keep_hi, len});
    }
    if (pieces.empty()) continue;
    double mom[4] = {0, 0, 0, 0}, volume = 0.0;
    for (const Piece& p : pieces) {
      moments(p, c, mom);
      volume += 2.0 * M_PI * k * continuity_volume_integral(p, c);
    }
    const double X = rb - c, S = std::sqrt(rb * rb - c * c);
    const double t1 = k / S, d1 = -k * rb / (S * S * S);
    // Unknowns (a0, a2, a3): a0 + a2 X^2 + a3 X^3 = t1; 2 a2 X + 3 a3 X^2 = d1;
    // a0 M0 + a2 M2 + a3 M3 = volume.
    const double A[3][3] = {
        {1.0, X * X, X * X * X}, {0.0, 2.0 * X, 3.0 * X * X}, {mom[0], mom[2], mom[3]}};
    const double rhs[3] = {t1, d1, volume};
    const double D = det3(A);
    if (!(std::abs(D) > 0.0)) throw InputError("the spline dome thickness is singular");
    double a[3];
    for (int col = 0; col < 3; ++col) {
      double B[3][3];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) B[i][j] = j == col ? rhs[i] : A[i][j];
      a[col] = det3(B) / D;
    }
    for (int i : pts) {
      const double r = m.points[i].y();
      if (r < c || r > rb) continue;
      const double x = r - c;
      t.thickness[i] = std::max(0.0, a[0] + a[1] * x * x + a[2] * x * x * x);
    }
  }
  return t;
}

double layer_volume(const MeridianPolyline& m, const LayerThickness& t, double s0, double s1) {
  double v = 0.0;
  for (std::size_t i = 0; i + 1 < m.points.size(); ++i) {
    const double a = std::max(s0, m.s[i]), b = std::min(s1, m.s[i + 1]);
    if (!(b > a)) continue;
    // Simpson on [a, b] of t(s) 2 pi r(s), both linear: exact.
    auto f = [&](double s) { return t.at(s) * 2.0 * M_PI * m.at(s).y(); };
    v += (b - a) / 6.0 * (f(a) + 4.0 * f(0.5 * (a + b)) + f(b));
  }
  return v;
}

}  // namespace windplan
