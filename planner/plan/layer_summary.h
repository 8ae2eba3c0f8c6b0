#pragma once
// The figures of one layer of a layup (planner/plan_layup.h), carried in WindingPlan::layers for
// the program (a layer comment and the transition between layers, export/program/gcode.h) and the
// per-layer report sections (export/files/layup_report.h). Units: mm, deg, g.
#include <cmath>
#include <string>

namespace windplan {

struct LayerSummary {
  std::string name;             ///< e.g. "hoop1"
  std::string kind;             ///< "helical" or "hoop"
  int first_circuit = 0;        ///< its first circuit in WindingPlan::circuits
  int circuit_count = 0;        ///< its circuits there (a hoop layer is one circuit)
  double band_width = 0.0;      ///< mm
  double band_thickness = 0.0;  ///< mm (material: band_thickness, or from tows)
  int circuits = 0;             ///< helical: K; hoop: passes
  double angle = 0.0;           ///< deg from the meridian, measured on the cylinder (or mid-range)
  double clairaut = std::nan("");  ///< helical: c = r sin a measured on the passes (mm)
  double pitch = std::nan("");     ///< hoop: axial advance per turn (mm)
  double coverage =
      0.0;  ///< hoop: measured covered fraction; helical: cover factor at the cylinder
  double surface_radius = 0.0;  ///< largest radius of the surface it is wound on (mm)
  /// Thickness (mm) on the cylinder (middle of the cylindrical part), at the turnarounds (the
  /// largest within a band width of the turnaround parallel r = c of a helical layer, at the
  /// range ends of a hoop layer) and its maximum; NaN off shapes of revolution.
  double thickness_cylinder = std::nan("");
  double thickness_turnaround = std::nan("");
  double thickness_max = std::nan("");
  double max_slippage = 0.0;         ///< passes: max |k_g/k_n|
  double turnaround_slippage = 0.0;  ///< turnarounds / reversal arcs: max |k_g/k_n|
  double band_length = 0.0;          ///< mm of band centre line
  double fibre_length = 0.0;         ///< mm of tow
  double fibre_mass = 0.0;           ///< g
  double resin_mass = 0.0;           ///< g
};

}  // namespace windplan
