#include "planner/winding/clairaut.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// The profile on [x0, x1] as a polyline: the interpolated ends and the samples strictly between.
std::vector<Vec2> clip(const RadiusProfile& p, double x0, double x1, const char* what) {
  if (p.empty()) throw InputError(std::string(what) + ": empty radius profile");
  if (!(x1 > x0)) {
    throw InputError(std::string(what) + ": the ends must increase along the axis (" + num(x0) +
                     " -> " + num(x1) + " mm)");
  }
  // No clamped extension beyond the profile's ends: it would add a cylinder at the end radius.
  x0 = std::max(x0, p.axial.front());
  x1 = std::min(x1, p.axial.back());
  if (!(x1 > x0)) {
    throw InputError(std::string(what) + ": the radius profile does not cover the ends");
  }
  std::vector<Vec2> pts{Vec2(x0, p.at(x0))};
  for (std::size_t i = 0; i < p.axial.size(); ++i) {
    if (p.axial[i] > x0 && p.axial[i] < x1) pts.emplace_back(p.axial[i], p.radius[i]);
  }
  pts.emplace_back(x1, p.at(x1));
  return pts;
}

double min_radius(const std::vector<Vec2>& pts, std::size_t* at = nullptr) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    if (pts[i].y() < pts[best].y()) best = i;
  }
  if (at) *at = best;
  return pts[best].y();
}

double polyline_angle(const std::vector<Vec2>& pts, double c) {
  double phi = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    phi += clairaut_segment_angle(pts[i].x() - pts[i - 1].x(), pts[i - 1].y(), pts[i].y(), c);
  }
  return phi;
}

// 8-point Gauss-Legendre on [-1, 1].
constexpr double kGaussX[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                               0.9602898564975363};
constexpr double kGaussW[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                               0.1012285362903763};

}  // namespace

// The integral of c / (r sqrt(r^2 - c^2)) ds over one truncated cone, r from ra to rb over an
// axial step dx. With r linear in s it is l / |rb - ra| |arccos(c / rb) - arccos(c / ra)|; the
// difference of the arccos is atan(z) with z = q |rb - ra| (the tangent subtraction formula,
// sa = sqrt(ra^2 - c^2), sb likewise):
//   q = c (ra + rb) / ((sa + sb) (c^2 + sa sb)),
// so the segment gives l q atan(z) / z: no cancellation when rb -> ra (it tends to
// l c / (r sqrt(r^2 - c^2)), the integrand times the length) and exact at c = ra (sa = 0).
double clairaut_segment_angle(double dx, double ra, double rb, double c) {
  const double l = std::hypot(dx, rb - ra);
  if (c <= 0.0 || l == 0.0) return 0.0;
  const double sa = std::sqrt(std::max(0.0, (ra - c) * (ra + c)));
  const double sb = std::sqrt(std::max(0.0, (rb - c) * (rb + c)));
  if (sa + sb == 0.0) return kInf;  // a cylinder at r = c: the hoop
  const double q = c * (ra + rb) / ((sa + sb) * (c * c + sa * sb));
  const double z = q * std::abs(rb - ra);
  return l * q * (z < 1e-8 ? 1.0 - z * z / 3.0 : std::atan(z) / z);
}

double clairaut_angle(const RadiusProfile& profile, double x0, double x1, double c) {
  const std::vector<Vec2> pts = clip(profile, x0, x1, "clairaut_angle");
  const double rmin = min_radius(pts);
  // Rounding of r_min computed elsewhere is not an error; a real excess is.
  if (!(c >= 0.0) || c > rmin * (1.0 + 1e-12)) {
    throw InputError("clairaut_angle: the Clairaut constant " + num(c) + " mm must lie in [0, " +
                     num(rmin) + "] mm, the smallest radius");
  }
  return polyline_angle(pts, std::min(c, rmin));
}

ClairautQuadrature clairaut_angle(const Meridian& m, double c,
                                  const ClairautQuadratureOptions& options) {
  if (!(c >= 0.0)) throw InputError("clairaut_angle: the Clairaut constant must be >= 0 mm");
  if (!(m.t1 > m.t0)) throw InputError("clairaut_angle: the meridian needs t1 > t0");
  if (!(options.tolerance > 0.0) || options.max_panels < 1) {
    throw ConfigError("clairaut_angle: tolerance must be > 0 and max_panels >= 1");
  }
  ClairautQuadrature out;
  const double T = m.t1 - m.t0;
  // The integrand in u on [0, 1], t = t0 + T (3 u^2 - 2 u^3): near an end where r = c with
  // r' != 0, r^2 - c^2 ~ u^2 and dt ~ u du, so the quotient stays bounded and smooth.
  auto f = [&](double u) {
    ++out.evaluations;
    const double t = m.t0 + T * u * u * (3.0 - 2.0 * u);
    const double dt = T * 6.0 * u * (1.0 - u);
    const Vec2 p = m.point(t);
    const double r = p.y();
    if (r < c * (1.0 - 1e-12)) {
      throw InputError("clairaut_angle: the meridian's radius " + num(r) + " mm at t = " + num(t) +
                       " is below the Clairaut constant " + num(c) + " mm");
    }
    if (c == 0.0) return 0.0;
    const double g = (r - c) * (r + c);
    if (!(g > 0.0)) return kInf;  // a node exactly on a circle of radius c
    return c * m.derivative(t).norm() * dt / (r * std::sqrt(g));
  };
  auto estimate = [&](int panels) {
    double sum = 0.0;
    const double h = 1.0 / panels;
    for (int k = 0; k < panels; ++k) {
      const double mid = (k + 0.5) * h;
      for (int g = 0; g < 4; ++g) {
        sum += kGaussW[g] * (f(mid - 0.5 * h * kGaussX[g]) + f(mid + 0.5 * h * kGaussX[g]));
      }
    }
    return 0.5 * h * sum;
  };
  double prev = estimate(1);
  for (int panels = 2; panels <= options.max_panels; panels *= 2) {
    const double cur = estimate(panels);
    out.angle = cur;
    out.panels = panels;
    out.error = std::abs(cur - prev);
    if (!std::isfinite(cur)) break;
    if (out.error <= options.tolerance * std::abs(cur)) {
      out.converged = true;
      break;
    }
    prev = cur;
  }
  if (out.panels == 0) {  // max_panels == 1
    out.angle = prev;
    out.panels = 1;
    out.error = kInf;
  }
  return out;
}

bool ClairautOptions::is_valid(std::string* why) const {
  if (!(flat_tolerance >= 0.0) || !std::isfinite(flat_tolerance) || !(flat_length > 0.0) ||
      !std::isfinite(flat_length)) {
    if (why) *why = "clairaut: flat_tolerance must be >= 0 and flat_length > 0";
    return false;
  }
  return true;
}

ClairautLimit clairaut_turn_limit(const RadiusProfile& profile, double x0, double x1,
                                  const ClairautOptions& options) {
  if (std::string why; !options.is_valid(&why)) throw ConfigError(why);
  const std::vector<Vec2> pts = clip(profile, x0, x1, "clairaut_turn_limit");
  ClairautLimit out;
  out.x0 = x0;
  out.x1 = x1;
  out.radius0 = pts.front().y();
  out.radius1 = pts.back().y();
  std::size_t at = 0;
  out.min_radius = min_radius(pts, &at);
  out.min_at = pts[at].x();
  if (!(out.min_radius > 0.0)) {
    out.reason = "the wound region reaches the axis";
    return out;
  }
  const double band = options.flat_tolerance * out.min_radius;
  if (out.min_radius < std::min(out.radius0, out.radius1) - band) {
    out.reason = "waist: the smallest radius " + num(out.min_radius) + " mm is at " +
                 num(out.min_at) + " mm, inside the wound region";
    return out;
  }
  // Axial length where the radius is within the band of r_min (linear on each segment).
  const double top = out.min_radius + band;
  double flat = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const double dx = pts[i].x() - pts[i - 1].x();
    const double lo = std::min(pts[i].y(), pts[i - 1].y());
    const double hi = std::max(pts[i].y(), pts[i - 1].y());
    if (hi <= top) {
      flat += dx;
    } else if (lo < top) {
      flat += dx * (top - lo) / (hi - lo);
    }
  }
  if (flat >= options.flat_length * out.min_radius) {
    out.reason = "cylinder: the radius stays within " + num(band) + " mm of its smallest, " +
                 num(out.min_radius) + " mm, over " + num(flat) + " mm of the axis";
    return out;
  }
  out.angle = polyline_angle(pts, out.min_radius);
  if (!std::isfinite(out.angle)) {
    out.reason = "cylinder: a stretch of the wound region has the smallest radius";
    return out;
  }
  out.bounded = true;
  out.turns = out.angle / (2.0 * M_PI);
  return out;
}

RadiusProfile meridian_profile(const Mesh& surface, const SpindleAxis& axis, double x0, double x1,
                               int stations) {
  if (!(x1 > x0) || stations < 1) {
    throw InputError("meridian_profile: needs x0 < x1 (" + num(x0) + ", " + num(x1) +
                     " mm) and stations >= 1");
  }
  const double L = x1 - x0;
  std::vector<double> xs(static_cast<std::size_t>(stations) + 1);
  for (int k = 0; k <= stations; ++k) {
    xs[k] = x0 + 0.5 * L * (1.0 - std::cos(M_PI * k / stations));
  }
  xs.front() = x0 + 1e-9 * L;
  xs.back() = x1 - 1e-9 * L;
  std::vector<double> best(xs.size(), -1.0);
  for (int e = 0; e < surface.num_edges(); ++e) {
    const int he = surface.edge_halfedge(e);
    const Vec3& p = surface.position(surface.from(he));
    const Vec3& q = surface.position(surface.to(he));
    const double ap = axis.axial(p), aq = axis.axial(q);
    if (std::abs(aq - ap) < 1e-12) continue;
    const auto first = std::lower_bound(xs.begin(), xs.end(), std::min(ap, aq));
    const auto last = std::upper_bound(xs.begin(), xs.end(), std::max(ap, aq));
    for (auto it = first; it != last; ++it) {
      const double t = (*it - ap) / (aq - ap);
      const std::size_t k = static_cast<std::size_t>(it - xs.begin());
      best[k] = std::max(best[k], axis.radius(p + t * (q - p)));
    }
  }
  // The end samples stand for the end planes themselves.
  xs.front() = x0;
  xs.back() = x1;
  RadiusProfile prof;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    if (best[k] < 0.0) continue;
    prof.axial.push_back(xs[k]);
    prof.radius.push_back(best[k]);
  }
  return prof;
}

}  // namespace windplan
