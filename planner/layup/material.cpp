#include "planner/layup/material.h"

#include <cstdio>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"

namespace windplan {

namespace {

bool positive(double v) { return v > 0.0 && std::isfinite(v); }

}  // namespace

double MaterialOptions::thickness(double band_width) const {
  if (has_band_thickness()) return band_thickness;
  return tows * tow_area() / (band_width * fibre_volume_fraction);
}

double MaterialOptions::tows_per_band(double band_width) const {
  if (!has_band_thickness()) return tows;
  return band_thickness * band_width * fibre_volume_fraction / tow_area();
}

bool MaterialOptions::is_valid(std::string* why) const {
  auto fail = [&](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (!positive(tex)) return fail("tex must be > 0 g/km (got " + format_number("%g", tex) + ")");
  if (!positive(fibre_density)) {
    return fail("fibre_density must be > 0 g/cm^3 (got " + format_number("%g", fibre_density) +
                ")");
  }
  if (!positive(resin_density)) {
    return fail("resin_density must be > 0 g/cm^3 (got " + format_number("%g", resin_density) +
                ")");
  }
  if (!(fibre_volume_fraction > 0.0 && fibre_volume_fraction < 1.0)) {
    return fail("fibre_volume_fraction must be in (0, 1) (got " +
                format_number("%g", fibre_volume_fraction) + ")");
  }
  if (!positive(tows)) return fail("tows must be > 0 (got " + format_number("%g", tows) + ")");
  if (!std::isnan(band_thickness) && !positive(band_thickness)) {
    return fail("band_thickness must be > 0 mm (got " + format_number("%g", band_thickness) + ")");
  }
  return true;
}

MaterialEstimate& MaterialEstimate::operator+=(const MaterialEstimate& o) {
  band_length += o.band_length;
  fibre_length += o.fibre_length;
  fibre_volume += o.fibre_volume;
  fibre_mass += o.fibre_mass;
  resin_mass += o.resin_mass;
  return *this;
}

MaterialEstimate estimate_material(const MaterialOptions& material, double band_width,
                                   double band_length) {
  std::string why;
  if (!material.is_valid(&why)) throw ConfigError("material: " + why);
  if (!positive(band_width))
    throw InputError("band width must be > 0 mm (got " + format_number("%g", band_width) + ")");
  if (!(band_length >= 0.0) || !std::isfinite(band_length)) {
    throw InputError("band length must be >= 0 mm (got " + format_number("%g", band_length) + ")");
  }
  MaterialEstimate e;
  e.band_length = band_length;
  e.band_thickness = material.thickness(band_width);
  e.tows = material.tows_per_band(band_width);
  e.fibre_length = e.tows * band_length;
  const double vf = material.fibre_volume_fraction;
  const double laminate = band_width * e.band_thickness * band_length;  // mm^3
  e.fibre_volume = vf * laminate;
  // g/cm^3 -> g/mm^3: 1e-3.
  e.fibre_mass = 1e-3 * material.fibre_density * e.fibre_volume;
  e.resin_mass = 1e-3 * material.resin_density * (1.0 - vf) * laminate;
  return e;
}

}  // namespace windplan
