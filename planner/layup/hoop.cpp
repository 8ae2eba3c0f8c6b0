#include "planner/layup/hoop.h"

#include <algorithm>
#include <cstdio>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "planner/winding/fibre_metrics.h"
#include "planner/winding/winding_options.h"

namespace windplan {

namespace {

// A point of the band centre line in the developed surface, before it is placed on the mandrel.
struct Developed {
  double phi = 0.0;    // radians about the axis (increasing: the mandrel turns one way)
  double x = 0.0;      // mm along the axis
  double theta = 0.0;  // direction against the axis in the developed surface (radians)
};

}  // namespace

bool HoopOptions::is_valid(std::string* why) const {
  auto fail = [&](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (std::isfinite(x0) != std::isfinite(x1)) return fail("range needs both ends");
  if (has_range() && !(x0 < x1)) {
    return fail("range must run from a lower to a higher axial position (got [" +
                format_number("%.6g", x0) + ", " + format_number("%.6g", x1) + "])");
  }
  if (!(band_width > 0.0) || !std::isfinite(band_width)) {
    return fail("band_width must be > 0 mm (got " + format_number("%.6g", band_width) + ")");
  }
  if (!(overlap >= 0.0) || !(overlap < band_width)) {
    return fail("overlap must be >= 0 mm and below band_width (got " +
                format_number("%.6g", overlap) + ")");
  }
  if (passes < 1) return fail("passes must be >= 1 (got " + std::to_string(passes) + ")");
  if (!(mu > 0.0 && mu <= kMaxMu)) {
    return fail("mu must be in (0, 2] for a hoop layer: its reversals need friction (got " +
                format_number("%.6g", mu) + ")");
  }
  if (!(reversal_friction > 0.0 && reversal_friction <= 1.0)) {
    return fail("reversal_friction must be in (0, 1] (got " +
                format_number("%.6g", reversal_friction) + ")");
  }
  if (!(point_spacing > 0.0)) return fail("point_spacing must be > 0 mm");
  if (meridians < 4) return fail("meridians must be >= 4");
  return true;
}

std::pair<double, double> cylinder_range(const RadiusProfile& profile, double tolerance) {
  if (profile.empty()) throw InputError("cylinder range: empty radius profile");
  const double rmax = *std::max_element(profile.radius.begin(), profile.radius.end());
  double best_lo = 0.0, best_hi = -1.0;
  std::size_t i = 0;
  const std::size_t n = profile.axial.size();
  while (i < n) {
    if (profile.radius[i] < rmax * (1.0 - tolerance)) {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < n && profile.radius[j + 1] >= rmax * (1.0 - tolerance)) ++j;
    if (profile.axial[j] - profile.axial[i] > best_hi - best_lo) {
      best_lo = profile.axial[i];
      best_hi = profile.axial[j];
    }
    i = j + 1;
  }
  if (!(best_hi > best_lo)) {
    throw InputError("the mandrel has no cylindrical part (no stretch at its largest radius " +
                     format_number("%.6g", rmax) + " mm): give the hoop layer a range");
  }
  return {best_lo, best_hi};
}

HoopLayer plan_hoop_layer(const RadiusProfile& profile, const SpindleAxis& axis,
                          const HoopOptions& o, const std::string& what) {
  std::string why;
  if (!o.is_valid(&why)) throw ConfigError(what + ": " + why);
  if (profile.empty()) throw InputError(what + ": empty radius profile");
  HoopLayer L;
  if (o.has_range()) {
    L.x0 = o.x0;
    L.x1 = o.x1;
  } else {
    std::tie(L.x0, L.x1) = cylinder_range(profile);
  }
  const double lo = profile.axial.front(), hi = profile.axial.back();
  const double eps = 1e-9 * std::max(1.0, hi - lo);
  if (L.x0 < lo - eps || L.x1 > hi + eps) {
    throw InputError(what + ".range [" + format_number("%.6g", L.x0) + ", " +
                     format_number("%.6g", L.x1) +
                     "] mm lies outside the mandrel (its axial extent is [" +
                     format_number("%.6g", lo) + ", " + format_number("%.6g", hi) + "] mm)");
  }
  const double B = o.band_width, p = o.pitch();
  L.pitch = p;
  // The reversal apexes (header comment), pulled inside the profile when needed.
  double xa0 = std::max(L.x0 + 0.5 * B - 0.5 * p, lo + 0.5 * B);
  double xa1 = std::min(L.x1 - 0.5 * B + 0.5 * p, hi - 0.5 * B);
  if (!(xa1 > xa0)) {
    throw InputError(what + ".range [" + format_number("%.6g", L.x0) + ", " +
                     format_number("%.6g", L.x1) + "] mm is too short for a band " +
                     format_number("%.6g", B) + " mm wide at pitch " + format_number("%.6g", p) +
                     " mm");
  }
  L.turns_per_pass = (xa1 - xa0) / p;

  auto hoop_angle = [&](double x) { return std::atan(2.0 * M_PI * profile.at(x) / p); };
  auto arc_radius = [&](double x) {
    const double a = hoop_angle(x), sa = std::sin(a);
    return profile.at(x) / (o.reversal_friction * o.mu * sa * sa);
  };
  auto rise = [&](double x) { return arc_radius(x) * (1.0 - std::sin(hoop_angle(x))); };
  if (rise(xa0) + rise(xa1) >= xa1 - xa0) {
    throw InputError(what + ": the reversals (" + format_number("%.6g", rise(xa0) + rise(xa1)) +
                     " mm along the axis at mu = " + format_number("%.6g", o.mu) +
                     ") do not fit in the range");
  }

  // Developed centre line: tie-on turn, passes with x linear in phi (constant pitch) joined by
  // reversal arcs of constant geodesic curvature, tie-off turn.
  std::vector<Developed> dev;
  std::vector<CircuitSegment> segments;
  double phi = 0.0, x = L.x0 + 0.5 * B;
  dev.push_back({phi, x, 0.5 * M_PI});
  auto close_segment = [&](CircuitSegment::Kind kind, int first) {
    segments.push_back({kind, first, static_cast<int>(dev.size()) - 1});
  };
  // One turn along the parallel at x (a geodesic on a cylinder).
  auto circle = [&]() {
    const int first = static_cast<int>(dev.size()) - 1;
    const double r = profile.at(x);
    const int n = std::max(16, static_cast<int>(std::ceil(2.0 * M_PI * r / o.point_spacing)));
    const double phis = phi;
    for (int i = 1; i <= n; ++i) {
      phi = phis + 2.0 * M_PI * i / n;
      dev.push_back({phi, x, 0.5 * M_PI});
    }
    close_segment(CircuitSegment::Kind::Pass, first);
  };
  // An arc of |k_g| = 1 / rho(x) turning theta from theta0 to theta1 (radians).
  auto arc = [&](double theta0, double theta1) {
    const int first = static_cast<int>(dev.size()) - 1;
    const double rho = arc_radius(x), r = profile.at(x);
    const double kappa = theta1 > theta0 ? 1.0 / rho : -1.0 / rho;
    const double length = std::abs(theta1 - theta0) * rho;
    const int m = std::max(16, static_cast<int>(std::ceil(length / o.point_spacing)));
    const double xs = x, phis = phi;
    for (int i = 1; i <= m; ++i) {
      const double th = theta0 + kappa * length * i / m;
      x = xs + (std::sin(th) - std::sin(theta0)) / kappa;
      phi = phis - (std::cos(th) - std::cos(theta0)) / kappa / r;
      dev.push_back({phi, x, th});
    }
    close_segment(CircuitSegment::Kind::Turnaround, first);
  };
  // The helix from x to `stop` (axial direction dir).
  auto pass = [&](double stop, int dir) {
    const int first = static_cast<int>(dev.size()) - 1;
    const double turns = std::abs(stop - x) / p;
    const double rmax = std::max(profile.at(x), profile.at(stop));
    const int n =
        std::max(2, static_cast<int>(std::ceil(2.0 * M_PI * turns * rmax / o.point_spacing)));
    const double x_start = x, phi_start = phi;
    for (int i = 1; i <= n; ++i) {
      const double u = static_cast<double>(i) / n;
      x = x_start + u * (stop - x_start);
      phi = phi_start + 2.0 * M_PI * turns * u;
      const double a = hoop_angle(x);
      dev.push_back({phi, x, dir > 0 ? a : M_PI - a});
    }
    close_segment(CircuitSegment::Kind::Pass, first);
  };
  // Tie-on: a full turn with the band's edge on x0, then half a reversal arc onto the helix.
  circle();
  arc(0.5 * M_PI, hoop_angle(x));
  for (int k = 0; k < o.passes; ++k) {
    const int dir = k % 2 == 0 ? +1 : -1;
    const double a_end = hoop_angle(dir > 0 ? xa1 : xa0);
    if (k + 1 == o.passes) {
      // Tie-off: half an arc off the helix and a full turn with the band's edge on the range end.
      const double end = dir > 0 ? L.x1 - 0.5 * B : L.x0 + 0.5 * B;
      pass(end - dir * rise(end), dir);
      arc(dir > 0 ? a_end : M_PI - a_end, 0.5 * M_PI);
      circle();
      break;
    }
    const double apex = dir > 0 ? xa1 : xa0;
    pass(apex - dir * rise(apex), dir);
    arc(dir > 0 ? a_end : M_PI - a_end, dir > 0 ? M_PI - a_end : a_end);
  }

  // On the mandrel: position, outward normal from the profile's slope.
  const Vec3 d = axis.direction.normalized();
  const Vec3 e1 = (std::abs(d.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(d).normalized();
  const Vec3 e2 = d.cross(e1);
  const double h = std::max(1e-3, 1e-3 * (hi - lo));
  Circuit c;
  c.index = 0;
  c.points.resize(dev.size());
  for (std::size_t i = 0; i < dev.size(); ++i) {
    const Developed& q = dev[i];
    const Vec3 radial = std::cos(q.phi) * e1 + std::sin(q.phi) * e2;
    const double slope = (profile.at(q.x + h) - profile.at(q.x - h)) / (2.0 * h);
    c.points[i].position = axis.origin + q.x * d + profile.at(q.x) * radial;
    c.points[i].normal = (radial - slope * d).normalized();
  }
  // Differential geometry per segment (passes over a band width, arcs over a quarter of their
  // length, so that the arc's bend is resolved), then arc length along the whole circuit.
  for (const CircuitSegment& sg : segments) {
    std::vector<FibrePoint> part(c.points.begin() + sg.first, c.points.begin() + sg.last + 1);
    double len = 0.0;
    for (std::size_t i = 1; i < part.size(); ++i) {
      len += (part[i].position - part[i - 1].position).norm();
    }
    const double window = sg.kind == CircuitSegment::Kind::Pass ? B : std::max(1e-6, 0.25 * len);
    annotate_fibre_points(&part, axis, window);
    const bool joint = sg.first > 0;  // the junction keeps the previous segment's figures
    std::copy(part.begin() + (joint ? 1 : 0), part.end(),
              c.points.begin() + sg.first + (joint ? 1 : 0));
    if (sg.kind == CircuitSegment::Kind::Turnaround) {
      L.reversal_length += len;
      for (const FibrePoint& fp : part)
        L.reversal_slippage = std::max(L.reversal_slippage, fp.slippage);
    }
  }
  double s = 0.0;
  for (std::size_t i = 0; i < c.points.size(); ++i) {
    if (i > 0) s += (c.points[i].position - c.points[i - 1].position).norm();
    c.points[i].s = s;
  }
  L.length = s;
  c.segments = segments;
  // The hoop angle measured at the point of the first pass nearest the middle of the range.
  {
    const double mid = 0.5 * (L.x0 + L.x1);
    int best = segments[2].first;
    for (int i = segments[2].first; i <= segments[2].last; ++i) {
      if (std::abs(dev[i].x - mid) < std::abs(dev[best].x - mid)) best = i;
    }
    L.angle = c.points[best].winding_angle;
  }
  if (L.reversal_slippage > o.mu) {
    L.warnings.push_back(what + ": reversal slippage " +
                         format_number("%.6g", L.reversal_slippage) +
                         " exceeds mu = " + format_number("%.6g", o.mu));
  }

  // Coverage on `meridians` lines of constant phi.
  const int M = o.meridians;
  std::vector<std::vector<std::pair<double, double>>> cover(M);
  for (std::size_t i = 0; i + 1 < dev.size(); ++i) {
    const Developed &a = dev[i], &b = dev[i + 1];
    if (!(b.phi > a.phi)) continue;
    long k = static_cast<long>(std::ceil(a.phi / (2.0 * M_PI) * M));
    for (; 2.0 * M_PI * k / M < b.phi; ++k) {
      const double u = (2.0 * M_PI * k / M - a.phi) / (b.phi - a.phi);
      const double xc = a.x + u * (b.x - a.x);
      const double th = a.theta + u * (b.theta - a.theta);
      const double half = 0.5 * B / std::max(std::sin(th), 1e-9);
      cover[((k % M) + M) % M].emplace_back(xc - half, xc + half);
    }
  }
  L.coverage = 1.0;
  for (auto& iv : cover) {
    std::sort(iv.begin(), iv.end());
    double covered = 0.0, reach = L.x0;
    for (const auto& [a, b] : iv) {
      const double a2 = std::max(a, reach), b2 = std::min(b, L.x1);
      if (b2 > a2) covered += b2 - a2;
      reach = std::max(reach, std::min(b, L.x1));
    }
    L.coverage = std::min(L.coverage, covered / (L.x1 - L.x0));
  }
  if (L.coverage < 1.0 - 1e-9) {
    L.warnings.push_back(what + ": the bands cover " + format_number("%.6g", 100.0 * L.coverage) +
                         "% of the range on the worst meridian (the reversals are pulled inside "
                         "the mandrel's ends)");
  }
  L.circuits.push_back(std::move(c));
  return L;
}

}  // namespace windplan
