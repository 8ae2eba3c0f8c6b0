#include "export/machine/eye_envelope.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "geometry/base/errors.h"
#include "geometry/region/winding_surface.h"

namespace windplan {

namespace {

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// The highest y with dist((x, y), segment ab) <= c, or -inf when x is out of the capsule's reach.
double capsule_top(double x, double xa, double ya, double xb, double yb, double c) {
  double top = -std::numeric_limits<double>::infinity();
  for (const double* p : {&xa, &xb}) {
    const double dx = x - *p;
    if (std::fabs(dx) <= c) top = std::max(top, (p == &xa ? ya : yb) + std::sqrt(c * c - dx * dx));
  }
  const double ex = xb - xa, ey = yb - ya;
  const double len = std::hypot(ex, ey);
  if (len > 0.0) {
    // Upward unit normal (ex > 0 on a profile, so -ey, ex points up).
    const double nx = -ey / len, ny = ex / len;
    const double x0 = xa + c * nx, x1 = xb + c * nx;
    if (x >= std::min(x0, x1) && x <= std::max(x0, x1) && x1 != x0) {
      const double t = (x - x0) / (x1 - x0);
      top = std::max(top, ya + c * ny + t * ey);
    }
  }
  return top;
}

}  // namespace

double Envelope::radius_at(double ax) const {
  if (x.empty()) return 0.0;
  if (ax <= x.front()) return r.front();
  if (ax >= x.back()) return r.back();
  const auto it = std::upper_bound(x.begin(), x.end(), ax);
  const std::size_t i = static_cast<std::size_t>(it - x.begin());
  const double t = (ax - x[i - 1]) / (x[i] - x[i - 1]);
  return (1.0 - t) * r[i - 1] + t * r[i];
}

RadiusProfile swept_profile(const WindingPlan& plan, const Mesh* mandrel) {
  if (!mandrel || mandrel->num_faces() == 0 || plan.profile.empty()) return plan.profile;
  const double span = plan.profile.axial.back() - plan.profile.axial.front();
  const int stations = std::clamp(static_cast<int>(std::ceil(span / 0.5)), 200, 4000);
  return compute_radius_profile(*mandrel, plan.axis, stations, true);
}

RadiusProfile dilate_profile(const RadiusProfile& profile, double c) {
  RadiusProfile out;
  if (profile.empty()) return out;
  // The profile extended by constants beyond its ends.
  std::vector<double> px = profile.axial, pr = profile.radius;
  px.insert(px.begin(), px.front() - 2.0 * c);
  pr.insert(pr.begin(), pr.front());
  px.push_back(px.back() + 2.0 * c);
  pr.push_back(pr.back());
  const double lo = profile.axial.front() - c, hi = profile.axial.back() + c;
  std::vector<double> xs;
  for (double x : profile.axial) {
    for (double d : {-c, 0.0, c}) {
      if (x + d >= lo && x + d <= hi) xs.push_back(x + d);
    }
  }
  const double step = std::min(1.0, c / 10.0);
  const int n = static_cast<int>(std::ceil((hi - lo) / step));
  for (int i = 0; i <= n; ++i) xs.push_back(lo + (hi - lo) * i / n);
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end(), [](double a, double b) { return b - a < 1e-9; }),
           xs.end());
  auto top_at = [&](double x) {
    double top = -std::numeric_limits<double>::infinity();
    // Only segments within c of x can reach it; the profile is sorted by x.
    const std::size_t first = static_cast<std::size_t>(
        std::max<long>(0, std::lower_bound(px.begin(), px.end(), x - c) - px.begin() - 1));
    for (std::size_t k = first; k + 1 < px.size() && px[k] <= x + c; ++k) {
      top = std::max(top, capsule_top(x, px[k], pr[k], px[k + 1], pr[k + 1], c));
    }
    return top;
  };
  for (double x : xs) {
    const double top = top_at(x);
    // Where the envelope is steep (the side of a capsule's disc: a bent tube's profile about its
    // principal axis, a flange), equal steps in x leave chords up to 0.25 mm inside the disc
    // (clearance 20, 1 mm steps): an eye there fell 0.07 mm inside the clearance on 3r and 5r
    // elbows. Such intervals are split until no chord is longer than about 1.5 steps (chord sag
    // <= (1.5 step)^2 / (8 c)).
    if (!out.axial.empty() && std::fabs(top - out.radius.back()) > step) {
      const double x0 = out.axial.back(), r0 = out.radius.back();
      const int parts = static_cast<int>(std::ceil(std::fabs(top - r0) / step));
      for (int k = 1; k < parts; ++k) {
        const double xi = x0 + (x - x0) * k / parts;
        out.axial.push_back(xi);
        out.radius.push_back(top_at(xi));
      }
    }
    out.axial.push_back(x);
    out.radius.push_back(top);
  }
  return out;
}

Envelope make_envelope(const RadiusProfile& mandrel, const EnvelopeOptions& eo,
                       const std::string& kind) {
  Envelope e;
  const std::string mode = eo.mode();
  const bool lathe2 = kind == "lathe2";
  if (mode == "free_length") {
    if (lathe2) {
      throw ConfigError(
          "machine.envelope.free_length: a lathe2 has no cross-feed, its eye stays on a "
          "cylinder (use envelope.radius, or kind lathe4)");
    }
    e.fixed_length = true;
    e.free_length = eo.free_length;
    e.description = "fixed free length " + num(eo.free_length) + " mm";
    return e;
  }
  if (mode == "profile") {
    for (const auto& xr : eo.profile) {
      e.x.push_back(xr[0]);
      e.r.push_back(xr[1]);
    }
    if (lathe2 &&
        *std::max_element(e.r.begin(), e.r.end()) != *std::min_element(e.r.begin(), e.r.end())) {
      throw ConfigError(
          "machine.envelope.profile: a lathe2 has no cross-feed, its eye stays on a cylinder "
          "(give a constant profile or envelope.radius, or use kind lathe4)");
    }
    e.description = lathe2 ? "cylinder r = " + num(e.r.front()) + " mm (profile)"
                           : "explicit profile (" + std::to_string(e.x.size()) + " points)";
  } else if (lathe2) {
    double radius = eo.radius;
    if (!(radius > 0.0)) {
      if (mandrel.empty()) {
        throw InputError(
            "machine.envelope: the plan has no mandrel radius profile; give "
            "machine.envelope.radius for the lathe2 eye cylinder");
      }
      radius = *std::max_element(mandrel.radius.begin(), mandrel.radius.end()) + eo.clearance;
    }
    e.x = {0.0, 1.0};
    e.r = {radius, radius};
    e.description = "cylinder r = " + num(radius) + " mm" +
                    (eo.radius > 0.0 ? std::string(" (envelope.radius)")
                                     : " (largest mandrel radius + " + num(eo.clearance) + " mm)");
  } else {
    if (mandrel.empty()) {
      throw InputError(
          "machine.envelope: the plan has no mandrel radius profile for 'clearance'; give "
          "machine.envelope.profile or machine.envelope.free_length");
    }
    const RadiusProfile d = dilate_profile(mandrel, eo.clearance);
    e.x = d.axial;
    e.r = d.radius;
    e.description = "clearance envelope, " + num(eo.clearance) + " mm from the swept mandrel";
  }
  for (std::size_t i = 1; i < e.x.size(); ++i) {
    const double dx = e.x[i] - e.x[i - 1];
    if (dx > 0.0) e.max_slope = std::max(e.max_slope, std::fabs(e.r[i] - e.r[i - 1]) / dx);
  }
  return e;
}

}  // namespace windplan
