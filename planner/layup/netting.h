#pragma once
// Netting theory of a wound cylinder under internal pressure: the fibres carry every load, along
// their own direction only (resin, transverse and shear stiffness neglected). A cylinder of
// radius R under the pressure p carries the axial stress resultant N_x = p R / 2 (closed ends)
// and the hoop resultant N_y = p R. A family of layers at the angle a (from the meridian) with
// thickness t and allowable fibre-direction stress sigma (of the laminate: fibre strength times
// volume fraction) carries sigma t cos^2 a axially and sigma t sin^2 a around, so
//   axial:  sum_i sigma t_i cos^2 a_i = p R / 2,
//   hoop:   sum_i sigma t_i sin^2 a_i = p R.
// A helical layer at a alone with a hoop layer (a = 90 deg) gives the sizing
//   t_hel  = p R / (2 sigma cos^2 a),
//   t_hoop = p R (2 - tan^2 a) / (2 sigma)   (zero above a = atan(sqrt 2) = 54.74 deg),
// and t_hoop / t_hel = 3 cos^2 a - 1. A laminate's netting burst pressure is the smaller of the
// two pressures the sums carry: p_b = min(2 sum sigma t_i cos^2 a_i, sum sigma t_i sin^2 a_i) / R.
// Units: mm, MPa, degrees.
#include <string>
#include <vector>

namespace windplan {

/// Thicknesses of a helical + hoop laminate sized by netting theory.
struct NettingSizing {
  double helical_thickness = 0.0;  ///< mm (the +a/-a pair)
  double hoop_thickness = 0.0;     ///< mm (0 above 54.74 deg, never negative)
};

/// The helical and hoop thicknesses for `pressure` p (MPa, > 0) on radius R (mm, > 0) with the
/// helical angle a (deg, in (0, 90)) and allowable fibre-direction stress sigma (MPa, > 0).
/// \throw InputError for a figure outside its range.
NettingSizing netting_thickness(double pressure, double radius, double angle_deg, double sigma);

/// One family of a laminate on the cylinder.
struct NettingLayer {
  std::string name;
  double angle_deg = 0.0;  ///< from the meridian
  double thickness = 0.0;  ///< mm on the cylinder
};

/// The netting figures of a laminate, layer by layer (innermost first).
struct NettingBurst {
  std::vector<double> axial_capacity;  ///< per layer: 2 sigma t cos^2 a / R (MPa of pressure)
  std::vector<double> hoop_capacity;   ///< per layer: sigma t sin^2 a / R (MPa of pressure)
  std::vector<double> burst;           ///< after layers 0..k: min of the summed capacities (MPa)
  double axial = 0.0;                  ///< the whole laminate's axial burst pressure (MPa)
  double hoop = 0.0;                   ///< the whole laminate's hoop burst pressure (MPa)
  double pressure = 0.0;               ///< min(axial, hoop) (MPa)
  std::string governing;               ///< "axial" or "hoop"
};

/// The netting burst pressure of `layers` on radius R (mm) with allowable stress sigma (MPa).
/// \throw InputError for R or sigma <= 0, a thickness < 0 or an angle outside [0, 90].
NettingBurst netting_burst(const std::vector<NettingLayer>& layers, double radius, double sigma);

}  // namespace windplan
