#pragma once
// The `design:` job section: from a pressure to a laminate (docs/config.md "design:").
//
// Sizing. With `pressure` p (MPa) and `fibre_strength` sigma_f (MPa) on a vessel or a pipe of
// cylinder radius R, the design pressure is p_d = burst_factor p and the allowable
// fibre-direction stress of the laminate sigma = sigma_f V_f (the fibres carry the load, at
// their volume fraction). Netting theory (planner/layup/netting.h) gives the helical thickness
// t_hel = p_d R / (2 sigma cos^2 a) at the cylinder's winding angle a and the hoop thickness
// t_hoop = p_d R (2 - tan^2 a) / (2 sigma) (0 above 54.74 deg). A helical layer at full coverage
// is two bands thick (its +a and -a passes), a hoop layer of 2 passes at pitch = band width too:
// the laminate is ceil(t_hel / 2 t) helical and ceil(t_hoop / 2 t) hoop layers (t the band's
// thickness), at least one helical, hoop and helical alternating from the inside, hoop first.
// A job that gives its own `layers:` is not sized: the report gives its netting burst pressure.
//
// The rest of the section: the ply's elastic constants (rule of mixtures from the fibre and the
// resin, planner/layup/laminate_theory.h), its transverse and shear strengths (the max-strain
// first-ply failure check of `windplan check-fea`), the dome thickness model, the turnaround
// stagger between helical layers, the resin pot life and the structural model's mesh size.
// Units: MPa, mm, minutes.
#include <cmath>
#include <string>
#include <vector>

#include "planner/layup/laminate_theory.h"
#include "planner/layup/layers.h"
#include "planner/layup/netting.h"

namespace windplan {

/// How a helical layer's thickness is modelled on the domes (planner/layup/dome_thickness.h).
enum class DomeThicknessModel {
  Continuity,  ///< fibre continuity averaged over a band width (laminate_thickness.h (2))
  Spline,      ///< fibre continuity, a cubic over the two band widths next to the turnaround
};

const char* to_string(DomeThicknessModel m);

struct DesignOptions {
  /// The section is in the job (its FEA model and design report are written).
  bool present = false;
  /// Operating pressure (MPa, > 0); NaN: no sizing and no burst check.
  double pressure = std::nan("");
  /// Burst factor: the laminate is sized for burst_factor x pressure (dimensionless, >= 1).
  double burst_factor = 1.0;
  /// Tensile strength of the fibre (MPa, > 0); required with pressure.
  double fibre_strength = std::nan("");
  /// Fibre, resin and volume fraction of the ply (volume_fraction defaults to material's).
  FibreResin ply;
  /// The ply's transverse tensile strength and in-plane shear strength (MPa, > 0).
  double transverse_strength = 50.0;
  double shear_strength = 70.0;
  /// The dome thickness model of helical layers.
  DomeThicknessModel dome_thickness = DomeThicknessModel::Continuity;
  /// Helical layer h (0 the innermost helical) turns around h x stagger band widths farther from
  /// the axis than its turnaround (dimensionless, >= 0; 0: no stagger).
  double turnaround_stagger = 0.0;
  /// Resin pot life (minutes, > 0); NaN: no check. A part whose wind time exceeds it is warned.
  double pot_life = std::nan("");
  /// Edge length of the structural model's shell mesh (mm, > 0).
  double fea_edge = 10.0;

  bool has_pressure() const { return std::isfinite(pressure); }
  /// sigma = fibre_strength x volume fraction (MPa).
  double allowable_stress() const { return fibre_strength * ply.volume_fraction; }
  double design_pressure() const { return burst_factor * pressure; }
  /// Sets *why to "<key>: <reason>" (the key named) when invalid.
  bool is_valid(std::string* why) const;
};

/// A laminate sized by netting theory (header comment).
struct DesignLayup {
  double radius = 0.0;           ///< cylinder radius R (mm)
  double angle_deg = 0.0;        ///< helical angle a on the cylinder (deg)
  double sigma = 0.0;            ///< allowable fibre-direction stress (MPa)
  double design_pressure = 0.0;  ///< burst_factor x pressure (MPa)
  NettingSizing required;        ///< the netting thicknesses (mm)
  double layer_thickness = 0.0;  ///< one layer: two bands (mm)
  int helical_layers = 0;
  int hoop_layers = 0;
  std::vector<LayerOptions> layers;  ///< innermost first
};

/// Sizes the laminate (header comment): helical layers take `winding` (the job's `winding:`),
/// hoop layers its band width and mu, 2 passes, the default range.
/// \param band_thickness the cured band thickness (mm, > 0)
/// \throw ConfigError for invalid options or a design without pressure, InputError for a radius
///        or angle outside the netting ranges.
DesignLayup design_layup(const DesignOptions& design, double radius, double angle_deg,
                         const WindingOptions& winding, double band_thickness);

}  // namespace windplan
