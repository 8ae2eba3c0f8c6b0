#pragma once
// The `material:` job section (the tow and the composite) and the estimates that follow from it:
// fibre length, fibre mass and resin mass of a layer, from the length of its band centre lines.
//
// The band laid by one pass is `tows` tows side by side, band_width B wide. One tow has the
// linear density `tex` (g/km; or linear_density in g/m, 1 g/m = 1000 tex), so its fibre
// cross-section is A = tex / rho_f (tex in g/km = 1e-6 g/mm, rho_f in g/cm^3 = 1e-3 g/mm^3:
// A = tex / (1000 rho_f) mm^2). In the cured laminate the fibres fill the fraction V_f of the
// band, so a band is t = tows A / (B V_f) thick (band_thickness). Either `band_thickness` or
// `tows` is given: with band_thickness the tows per band follow as t B V_f / A (need not be
// whole: a spread tow). For a band centre line of length L (mm):
//   fibre length (tow length) = tows L,
//   fibre mass  m_f = rho_f V_f B t L       (= tows tex L, the same figure),
//   resin mass  m_r = rho_r (1 - V_f) B t L  (the matrix at the volume fraction, voids ignored).
// Units: mm, g, g/cm^3, g/km (tex).
#include <cmath>
#include <string>

namespace windplan {

struct MaterialOptions {
  /// Linear density of one tow (tex = g/km, > 0). Default: a 12K carbon tow (T700S: 800 tex).
  double tex = 800.0;
  /// Fibre density (g/cm^3, > 0). Default: carbon (T700S: 1.80).
  double fibre_density = 1.80;
  /// Resin density (g/cm^3, > 0). Default: epoxy, 1.20.
  double resin_density = 1.20;
  /// Fibre volume fraction of the cured laminate (dimensionless, (0, 1)).
  double fibre_volume_fraction = 0.60;
  /// Tows side by side in one band (count, > 0; need not be whole). Used when band_thickness is
  /// not given (NaN).
  double tows = 1.0;
  /// Cured thickness of one band (mm, > 0); NaN: from tows (header comment).
  double band_thickness = std::nan("");

  bool has_band_thickness() const { return std::isfinite(band_thickness); }
  /// Fibre cross-section of one tow (mm^2).
  double tow_area() const { return tex / (1000.0 * fibre_density); }
  /// Cured band thickness for a band `band_width` wide (mm).
  double thickness(double band_width) const;
  /// Tows per band of `band_width` (count).
  double tows_per_band(double band_width) const;

  bool is_valid(std::string* why) const;
};

/// The material estimates of a length of band.
struct MaterialEstimate {
  double band_length = 0.0;     ///< mm of band centre line
  double fibre_length = 0.0;    ///< mm of tow: tows per band times band_length
  double fibre_volume = 0.0;    ///< mm^3
  double fibre_mass = 0.0;      ///< g
  double resin_mass = 0.0;      ///< g
  double band_thickness = 0.0;  ///< mm
  double tows = 0.0;            ///< tows per band

  double composite_mass() const { return fibre_mass + resin_mass; }
  MaterialEstimate& operator+=(const MaterialEstimate& o);
};

/// Fibre length, fibre mass and resin mass of `band_length` mm of band `band_width` mm wide.
/// \throw ConfigError for invalid options, InputError for band_width <= 0 or band_length < 0.
MaterialEstimate estimate_material(const MaterialOptions& material, double band_width,
                                   double band_length);

}  // namespace windplan
