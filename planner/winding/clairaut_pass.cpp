#include "planner/winding/clairaut_pass.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geometry/base/errors.h"
#include "geometry/region/plane_section.h"
#include "planner/winding/clairaut.h"

namespace windplan {

namespace {

// sqrt(r^2 - c^2) without the cancellation of r^2 - c^2 near the turnaround.
double q_of(double r, double c) { return std::sqrt(std::max(0.0, (r - c) * (r + c))); }

// The part of the meridian where r >= c, with the crossings of r = c as its end points.
std::vector<Vec2> pass_polyline(const std::vector<Vec2>& m, double c, std::array<bool, 2>* turns) {
  if (m.size() < 2) throw InputError("clairaut_pass: a meridian needs at least 2 points");
  if (!(c > 0.0) || !std::isfinite(c)) {
    throw InputError("clairaut_pass: the Clairaut constant must be > 0 mm");
  }
  const int n = static_cast<int>(m.size());
  int a = 0;
  while (a < n && m[a].y() < c) ++a;
  int b = n - 1;
  while (b >= 0 && m[b].y() < c) --b;
  if (a > b) {
    std::ostringstream s;
    s << "no part of the mandrel has a radius >= " << c << " mm: no geodesic with that "
      << "turnaround radius crosses it";
    throw InputError(s.str());
  }
  for (int i = a; i <= b; ++i) {
    if (m[i].y() < c) {
      std::ostringstream s;
      s << "the radius " << m[i].y() << " mm at " << m[i].x() << " mm along the axis is below "
        << "the turnaround radius " << c << " mm: a geodesic with that turnaround cannot cross "
        << "this waist";
      throw InputError(s.str());
    }
  }
  std::vector<Vec2> pts;
  auto crossing = [&](int i, int j) {  // r = c on segment i -> j (r_i < c <= r_j)
    const double t = (c - m[i].y()) / (m[j].y() - m[i].y());
    return Vec2(m[i].x() + t * (m[j].x() - m[i].x()), c);
  };
  (*turns)[0] = a > 0;
  if (a > 0) pts.push_back(crossing(a - 1, a));
  for (int i = a; i <= b; ++i) {
    if (!pts.empty() && (pts.back() - m[i]).norm() == 0.0) continue;
    pts.push_back(m[i]);
  }
  (*turns)[1] = b < n - 1;
  if (b < n - 1) {
    const Vec2 e = crossing(b + 1, b);
    if ((pts.back() - e).norm() > 0.0) pts.push_back(e);
  }
  if (pts.size() < 2) throw InputError("clairaut_pass: the pass has no length");
  return pts;
}

}  // namespace

std::array<Vec3, 2> axis_frame(const SpindleAxis& axis) {
  const Vec3 d = axis.direction.normalized();
  Vec3 seed = Vec3::UnitX();
  if (std::abs(d.x()) > std::abs(d.y()) || std::abs(d.x()) > std::abs(d.z())) {
    seed = std::abs(d.y()) < std::abs(d.z()) ? Vec3::UnitY() : Vec3::UnitZ();
  }
  const Vec3 e1 = (seed - seed.dot(d) * d).normalized();
  return {e1, d.cross(e1)};
}

Vec3 point_on_axis_frame(const SpindleAxis& axis, const std::array<Vec3, 2>& frame, double x,
                         double r, double phi) {
  return axis.origin + x * axis.direction +
         r * (std::cos(phi) * frame[0] + std::sin(phi) * frame[1]);
}

std::vector<Vec2> annulus_meridian(const Mesh& annulus, const SpindleAxis& axis) {
  const std::array<Vec3, 2> f = axis_frame(axis);
  const std::vector<PlaneSection> chains =
      plane_sections(annulus, f[1], f[1].dot(axis.origin), axis);
  const PlaneSection* best = nullptr;
  int best_count = 0;
  for (const PlaneSection& c : chains) {
    if (c.closed) continue;
    int count = 0;
    for (const Vec3& p : c.points) count += (p - axis.origin).dot(f[0]) > 0.0;
    if (count > best_count) best = &c, best_count = count;
  }
  if (!best || best_count < 2 || best_count != static_cast<int>(best->points.size())) {
    throw TopologyError(
        "the wound region's meridian: the half-plane through the spindle axis does not cut it "
        "in one chain from one end to the other (not an annulus about that axis)");
  }
  std::vector<Vec2> m;
  m.reserve(best->points.size());
  for (const Vec3& p : best->points) {
    m.emplace_back(axis.axial(p), (p - axis.origin).dot(f[0]));
  }
  if (m.front().x() > m.back().x()) std::reverse(m.begin(), m.end());
  return m;
}

double clairaut_pass_angle(const std::vector<Vec2>& meridian, double c) {
  std::array<bool, 2> turns{};
  const std::vector<Vec2> pts = pass_polyline(meridian, c, &turns);
  double phi = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    phi += clairaut_segment_angle(pts[i].x() - pts[i - 1].x(), pts[i - 1].y(), pts[i].y(), c);
  }
  return phi;
}

ClairautPass clairaut_pass(const std::vector<Vec2>& meridian, double c,
                           const ClairautPassOptions& options) {
  if (!(options.step > 0.0) || !std::isfinite(options.step)) {
    throw InputError("clairaut_pass: step must be > 0 mm");
  }
  ClairautPass pass;
  pass.c = c;
  const std::vector<Vec2> pts = pass_polyline(meridian, c, &pass.turns_around);
  auto sample = [&](double x, double r, double phi, double len) {
    pass.samples.push_back({x, r, phi, len, std::asin(std::min(1.0, c / r))});
  };
  sample(pts[0].x(), pts[0].y(), 0.0, 0.0);
  double phi = 0.0, len = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const Vec2 &A = pts[i - 1], &B = pts[i];
    const double ra = A.y(), rb = B.y();
    const double sa = q_of(ra, c), sb = q_of(rb, c);
    if (sa + sb == 0.0) {
      throw InputError("clairaut_pass: the mandrel is a cylinder of radius c there (a hoop)");
    }
    const double l = (B - A).norm();
    const double seg_len = l * (ra + rb) / (sa + sb);  // integral of r / sqrt(r^2 - c^2) ds
    const int n = std::max(1, static_cast<int>(std::ceil(seg_len / options.step)));
    const bool radial = std::abs(rb - ra) > 1e-12 * (ra + rb);
    for (int j = 1; j <= n; ++j) {
      const double f = static_cast<double>(j) / n;  // q is linear in the fibre length
      double r = rb, u = 1.0;
      if (j < n) {
        if (radial) {
          const double q = sa + (sb - sa) * f;
          r = std::sqrt(c * c + q * q);
          u = std::clamp((r - ra) / (rb - ra), 0.0, 1.0);
        } else {
          r = ra + (rb - ra) * f;
          u = f;
        }
      }
      const double dphi = clairaut_segment_angle((B.x() - A.x()) * u, ra, r, c);
      sample(A.x() + (B.x() - A.x()) * u, r, phi + dphi, len + seg_len * f);
    }
    phi += clairaut_segment_angle(B.x() - A.x(), ra, rb, c);
    len += seg_len;
    pass.samples.back().phi = phi;
  }
  pass.angle = phi;
  pass.length = len;
  return pass;
}

}  // namespace windplan
