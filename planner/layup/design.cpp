#include "planner/layup/design.h"

#include <algorithm>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"

namespace windplan {

const char* to_string(DomeThicknessModel m) {
  return m == DomeThicknessModel::Spline ? "spline" : "continuity";
}

bool DesignOptions::is_valid(std::string* why) const {
  auto fail = [&](const std::string& key, const std::string& m) {
    if (why) *why = key + ": " + m;
    return false;
  };
  if (!std::isnan(pressure) && !(pressure > 0.0 && std::isfinite(pressure))) {
    return fail("pressure", "must be > 0 MPa (got " + format_number("%g", pressure) + ")");
  }
  if (!(burst_factor >= 1.0) || !std::isfinite(burst_factor)) {
    return fail("burst_factor", "must be >= 1 (got " + format_number("%g", burst_factor) + ")");
  }
  if (!std::isnan(fibre_strength) && !(fibre_strength > 0.0 && std::isfinite(fibre_strength))) {
    return fail("fibre_strength",
                "must be > 0 MPa (got " + format_number("%g", fibre_strength) + ")");
  }
  if (has_pressure() && std::isnan(fibre_strength)) {
    return fail("fibre_strength",
                "a pressure needs the fibre's tensile strength (MPa) to size or check the "
                "laminate");
  }
  std::string w;
  if (!ply.is_valid(&w)) {
    const std::string key = w.substr(0, w.find(' '));
    return fail(key, w.substr(w.find(' ') + 1));
  }
  if (!(transverse_strength > 0.0 && std::isfinite(transverse_strength))) {
    return fail("transverse_strength", "must be > 0 MPa");
  }
  if (!(shear_strength > 0.0 && std::isfinite(shear_strength))) {
    return fail("shear_strength", "must be > 0 MPa");
  }
  if (!(turnaround_stagger >= 0.0) || !std::isfinite(turnaround_stagger)) {
    return fail("turnaround_stagger",
                "must be >= 0 band widths (got " + format_number("%g", turnaround_stagger) + ")");
  }
  if (!std::isnan(pot_life) && !(pot_life > 0.0 && std::isfinite(pot_life))) {
    return fail("pot_life", "must be > 0 minutes (got " + format_number("%g", pot_life) + ")");
  }
  if (!(fea_edge > 0.0) || !std::isfinite(fea_edge)) {
    return fail("fea_edge", "must be > 0 mm (got " + format_number("%g", fea_edge) + ")");
  }
  return true;
}

DesignLayup design_layup(const DesignOptions& design, double radius, double angle_deg,
                         const WindingOptions& winding, double band_thickness) {
  std::string why;
  if (!design.is_valid(&why)) throw ConfigError("design." + why);
  if (!design.has_pressure()) throw ConfigError("design.pressure: needed to size a laminate");
  if (!(band_thickness > 0.0)) throw InputError("design: the band thickness must be > 0 mm");
  DesignLayup d;
  d.radius = radius;
  d.angle_deg = angle_deg;
  d.sigma = design.allowable_stress();
  d.design_pressure = design.design_pressure();
  d.required = netting_thickness(d.design_pressure, radius, angle_deg, d.sigma);
  d.layer_thickness = 2.0 * band_thickness;
  auto count = [&](double t) { return static_cast<int>(std::ceil(t / d.layer_thickness - 1e-9)); };
  d.helical_layers = std::max(1, count(d.required.helical_thickness));
  d.hoop_layers = count(d.required.hoop_thickness);
  for (int i = 0; i < std::max(d.helical_layers, d.hoop_layers); ++i) {
    if (i < d.hoop_layers) {
      LayerOptions L;
      L.kind = LayerKind::Hoop;
      L.name = "hoop" + std::to_string(i + 1);
      L.hoop.band_width = winding.band_width;
      L.hoop.mu = winding.mu;
      d.layers.push_back(L);
    }
    if (i < d.helical_layers) {
      LayerOptions L;
      L.kind = LayerKind::Helical;
      L.name = "helical" + std::to_string(i + 1);
      L.winding = winding;
      d.layers.push_back(L);
    }
  }
  return d;
}

}  // namespace windplan
