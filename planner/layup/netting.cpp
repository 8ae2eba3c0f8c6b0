#include "planner/layup/netting.h"

#include <algorithm>
#include <cmath>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"

namespace windplan {

namespace {

void require(bool ok, const std::string& what, double v) {
  if (!ok) throw InputError("netting: " + what + " (got " + format_number("%g", v) + ")");
}

}  // namespace

NettingSizing netting_thickness(double pressure, double radius, double angle_deg, double sigma) {
  require(pressure > 0.0 && std::isfinite(pressure), "pressure must be > 0 MPa", pressure);
  require(radius > 0.0 && std::isfinite(radius), "radius must be > 0 mm", radius);
  require(angle_deg > 0.0 && angle_deg < 90.0, "angle must be in (0, 90) deg", angle_deg);
  require(sigma > 0.0 && std::isfinite(sigma), "allowable stress must be > 0 MPa", sigma);
  const double a = angle_deg * M_PI / 180.0, c = std::cos(a), t = std::tan(a);
  NettingSizing s;
  s.helical_thickness = pressure * radius / (2.0 * sigma * c * c);
  s.hoop_thickness = std::max(0.0, pressure * radius * (2.0 - t * t) / (2.0 * sigma));
  return s;
}

NettingBurst netting_burst(const std::vector<NettingLayer>& layers, double radius, double sigma) {
  require(radius > 0.0 && std::isfinite(radius), "radius must be > 0 mm", radius);
  require(sigma > 0.0 && std::isfinite(sigma), "allowable stress must be > 0 MPa", sigma);
  NettingBurst b;
  double ax = 0.0, hp = 0.0;
  for (const NettingLayer& L : layers) {
    require(L.thickness >= 0.0 && std::isfinite(L.thickness),
            L.name + ": thickness must be >= 0 mm", L.thickness);
    require(L.angle_deg >= 0.0 && L.angle_deg <= 90.0, L.name + ": angle must be in [0, 90] deg",
            L.angle_deg);
    const double a = L.angle_deg * M_PI / 180.0;
    const double c = std::cos(a), s = std::sin(a);
    b.axial_capacity.push_back(2.0 * sigma * L.thickness * c * c / radius);
    b.hoop_capacity.push_back(sigma * L.thickness * s * s / radius);
    ax += b.axial_capacity.back();
    hp += b.hoop_capacity.back();
    b.burst.push_back(std::min(ax, hp));
  }
  b.axial = ax;
  b.hoop = hp;
  b.pressure = std::min(ax, hp);
  b.governing = ax <= hp ? "axial" : "hoop";
  return b;
}

}  // namespace windplan
