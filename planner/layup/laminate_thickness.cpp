#include "planner/layup/laminate_thickness.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"

namespace windplan {

namespace {

// integral ds / sqrt(r^2 - c^2) over a piece of meridian of length `length` along which r runs
// linearly from ra to rb, the part with r < c counting 0. With d = rb - ra, S = sqrt(r^2 - c^2):
// [ln(r + S)] / (d / length) written as length log1p(d q) / d, q = (1 + (ra + rb) / (Sa + Sb)) /
// (ra + Sa), which stays accurate for d -> 0 (where it tends to length / S).
double piece_integral(double ra, double rb, double length, double c) {
  if (length <= 0.0) return 0.0;
  if (ra <= c && rb <= c) {
    if (ra == c && rb == c) {
      throw InputError("the meridian runs along the turnaround radius " + format_number("%.4g", c) +
                       " mm (a hoop: the helical thickness is not integrable there)");
    }
    return 0.0;
  }
  if (ra < c || rb < c) {  // keep the part above c
    const double lo = std::min(ra, rb), hi = std::max(ra, rb);
    length *= (hi - c) / (hi - lo);
    (ra < c ? ra : rb) = c;
  }
  const double sa = std::sqrt(std::max(0.0, ra * ra - c * c));
  const double sb = std::sqrt(std::max(0.0, rb * rb - c * c));
  if (sa + sb == 0.0) {
    throw InputError("the meridian runs along the turnaround radius " + format_number("%.4g", c) +
                     " mm");
  }
  if (ra + sa <= 0.0) {
    throw InputError("the meridian reaches the axis where the layer has fibre (c = 0)");
  }
  const double d = rb - ra;
  const double q = (1.0 + (ra + rb) / (sa + sb)) / (ra + sa);
  if (d == 0.0) return length * q;
  const double x = d * q;
  return length * std::log1p(x) / d;
}

}  // namespace

// ---- MeridianPolyline ----

MeridianPolyline MeridianPolyline::from_points(std::vector<Vec2> points) {
  if (points.size() < 2) throw InputError("a meridian needs at least two points");
  MeridianPolyline m;
  m.s.assign(points.size(), 0.0);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!(points[i].y() >= 0.0) || !points[i].allFinite()) {
      throw InputError("meridian point " + std::to_string(i) + " has radius " +
                       format_number("%.4g", points[i].y()) + " mm (must be finite and >= 0)");
    }
    if (i > 0) {
      const double l = (points[i] - points[i - 1]).norm();
      if (!(l > 0.0)) {
        throw InputError("meridian points " + std::to_string(i - 1) + " and " + std::to_string(i) +
                         " coincide");
      }
      m.s[i] = m.s[i - 1] + l;
    }
  }
  m.points = std::move(points);
  return m;
}

MeridianPolyline MeridianPolyline::from_profile(const RadiusProfile& profile) {
  std::vector<Vec2> p;
  for (std::size_t i = 0; i < profile.axial.size(); ++i) {
    p.emplace_back(profile.axial[i], profile.radius[i]);
  }
  return from_points(std::move(p));
}

MeridianPolyline MeridianPolyline::resampled(double step) const {
  if (!(step > 0.0)) throw InputError("meridian resampling step must be > 0 mm");
  std::vector<Vec2> out{points.front()};
  for (std::size_t i = 1; i < points.size(); ++i) {
    const int n = std::max(1, static_cast<int>(std::ceil((s[i] - s[i - 1]) / step - 1e-9)));
    for (int k = 1; k <= n; ++k) {
      const double u = static_cast<double>(k) / n;
      out.push_back(k == n ? points[i] : (1.0 - u) * points[i - 1] + u * points[i]);
    }
  }
  return from_points(std::move(out));
}

Vec2 MeridianPolyline::at(double x) const {
  if (x <= 0.0) return points.front();
  if (x >= length()) return points.back();
  const std::size_t i = std::upper_bound(s.begin(), s.end(), x) - s.begin();
  const double u = (x - s[i - 1]) / (s[i] - s[i - 1]);
  return (1.0 - u) * points[i - 1] + u * points[i];
}

Vec2 MeridianPolyline::normal(int i) const {
  const int n = static_cast<int>(points.size());
  Vec2 sum = Vec2::Zero();
  for (int j : {i - 1, i}) {
    if (j < 0 || j + 1 >= n) continue;
    const Vec2 d = (points[j + 1] - points[j]).normalized();
    sum += Vec2(-d.y(), d.x());
  }
  return sum.normalized();
}

double MeridianPolyline::project(const Vec2& q) const {
  double best = std::numeric_limits<double>::infinity(), at_s = 0.0;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const Vec2 d = points[i + 1] - points[i];
    const double u = std::clamp((q - points[i]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const double dist = (points[i] + u * d - q).squaredNorm();
    if (dist < best) {
      best = dist;
      at_s = s[i] + u * (s[i + 1] - s[i]);
    }
  }
  return at_s;
}

RadiusProfile MeridianPolyline::to_profile() const {
  RadiusProfile p;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i > 0 && !(points[i].x() > points[i - 1].x())) {
      throw InputError(
          "the meridian is not a radius profile: its axial position decreases at "
          "point " +
          std::to_string(i) + " (" + format_number("%.4g", points[i].x()) + " mm)");
    }
    p.axial.push_back(points[i].x());
    p.radius.push_back(points[i].y());
  }
  return p;
}

// ---- LayerThickness ----

double LayerThickness::at(double x) const {
  if (s.empty() || x < s.front() || x > s.back()) return 0.0;
  const std::size_t i = std::upper_bound(s.begin(), s.end(), x) - s.begin();
  if (i >= s.size()) return thickness.back();
  const double u = (x - s[i - 1]) / (s[i] - s[i - 1]);
  return (1.0 - u) * thickness[i - 1] + u * thickness[i];
}

double LayerThickness::max() const {
  return thickness.empty() ? 0.0 : *std::max_element(thickness.begin(), thickness.end());
}

// ---- the thickness models ----

double helical_thickness_unbounded(double r, double c, double circuits, double band_width,
                                   double band_thickness) {
  if (r <= c) return 0.0;
  return circuits * band_width * band_thickness / (M_PI * std::sqrt(r * r - c * c));
}

LayerThickness helical_layer_thickness(const MeridianPolyline& m, double c, double circuits,
                                       double band_width, double band_thickness) {
  if (!(c >= 0.0) || !std::isfinite(c)) throw InputError("turnaround radius must be >= 0 mm");
  if (!(circuits > 0.0)) throw InputError("circuits must be > 0");
  if (!(band_width > 0.0) || !(band_thickness > 0.0)) {
    throw InputError("band width and band thickness must be > 0 mm");
  }
  const int n = static_cast<int>(m.points.size());
  // F[i]: integral of ds / sqrt(r^2 - c^2) from the start to point i.
  std::vector<double> F(n, 0.0);
  for (int i = 1; i < n; ++i) {
    F[i] = F[i - 1] + piece_integral(m.points[i - 1].y(), m.points[i].y(), m.s[i] - m.s[i - 1], c);
  }
  auto cumulative = [&](double x) {
    x = std::clamp(x, 0.0, m.length());
    const std::size_t i =
        std::min<std::size_t>(std::upper_bound(m.s.begin(), m.s.end(), x) - m.s.begin(), n - 1);
    const double u = (x - m.s[i - 1]) / (m.s[i] - m.s[i - 1]);
    const double r = (1.0 - u) * m.points[i - 1].y() + u * m.points[i].y();
    return F[i - 1] + piece_integral(m.points[i - 1].y(), r, x - m.s[i - 1], c);
  };
  LayerThickness t;
  t.s = m.s;
  t.thickness.resize(n);
  const double k = circuits * band_width * band_thickness / M_PI;
  for (int i = 0; i < n; ++i) {
    const double a = cumulative(m.s[i] - 0.5 * band_width);
    const double b = cumulative(m.s[i] + 0.5 * band_width);
    t.thickness[i] = k * (b - a) / band_width;
  }
  return t;
}

LayerThickness hoop_layer_thickness(const MeridianPolyline& m, double x0, double x1, double pitch,
                                    double band_width, double band_thickness, int passes) {
  if (!(x1 > x0)) throw InputError("hoop range: x0 must be < x1");
  if (!(pitch > 0.0) || !(band_width > 0.0) || !(band_thickness > 0.0) || passes < 1) {
    throw InputError("hoop pitch, band width, band thickness and passes must be > 0");
  }
  const int n = static_cast<int>(m.points.size());
  LayerThickness t;
  t.s = m.s;
  t.thickness.assign(n, 0.0);
  const double eps = 1e-9 * std::max(1.0, std::abs(x1 - x0));
  for (int i = 0; i < n; ++i) {
    const Vec2& p = m.points[i];
    if (p.x() < x0 - eps || p.x() > x1 + eps) continue;
    const Vec2 nrm = m.normal(i);
    const double cos_psi = std::max(std::abs(nrm.y()), 1e-6);  // dx/ds of the meridian
    const double ps = pitch / cos_psi;
    const double hoop = 2.0 * M_PI * p.y();
    const double sin_a = hoop / std::hypot(ps, hoop);
    t.thickness[i] = passes * band_width * band_thickness / (ps * sin_a);
  }
  return t;
}

MeridianPolyline offset_meridian(const MeridianPolyline& m, const LayerThickness& thickness,
                                 const std::string& what) {
  const int n = static_cast<int>(m.points.size());
  std::vector<Vec2> out(n);
  auto end_name = [&](int i) {
    return std::string(2 * i < n ? "the start" : "the end") + " polar opening";
  };
  for (int i = 0; i < n; ++i) {
    const double t = thickness.at(m.s[i]);
    out[i] = m.points[i] + t * m.normal(i);
    if (!(out[i].y() > 0.0)) {
      throw InputError(what + ": a thickness of " + format_number("%.4g", t) + " mm at radius " +
                       format_number("%.4g", m.points[i].y()) + " mm (" +
                       format_number("%.4g", m.points[i].x()) + " mm along the axis) would close " +
                       end_name(i) + " (the next surface would reach the axis)");
    }
  }
  for (int i = 0; i + 1 < n; ++i) {
    if ((out[i + 1] - out[i]).dot(m.points[i + 1] - m.points[i]) <= 0.0) {
      throw InputError(what + ": a thickness of " + format_number("%.4g", thickness.at(m.s[i])) +
                       " mm at radius " + format_number("%.4g", m.points[i].y()) + " mm (" +
                       format_number("%.4g", m.points[i].x()) +
                       " mm along the axis) folds the next surface onto itself: it would close " +
                       end_name(i));
    }
  }
  return MeridianPolyline::from_points(std::move(out));
}

}  // namespace windplan
