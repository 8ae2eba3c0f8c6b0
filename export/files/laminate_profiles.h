#pragma once
// The laminate's meridian profiles (shapes of revolution): the mandrel's meridian and the outer
// surface after each layer, with each layer's thickness along the meridian
// (planner/layup/laminate_thickness.h), as CSV and as an SVG plot.
//
// layer_profiles.csv: surface (0 = the mandrel, k = the outer surface after layer k), index,
//   s [mm] (arc length of the mandrel's meridian at the point the surface point was offset from),
//   axial [mm], radius [mm], thickness [mm] (of layer k there; 0 for the mandrel),
//   total [mm] (of layers 1..k); with LaminateProfiles::alternative (design.dome_thickness:
//   spline) also "thickness <alternative_name> [mm]", the other model's thickness of layer k.
// layer_profiles.svg: top, the profiles (axial position against radius, true scale, the mandrel
//   grey, each outer surface in its layer's colour); bottom, the cumulative thickness (total of
//   layers 1..k) against the axial position of the mandrel's meridian, thickness exaggerated to
//   fill the panel, with the scale labelled; with an alternative model, its cumulative thickness
//   dashed in the same colours. Deterministic text (fixed decimals).
#include <string>
#include <vector>

#include "export/files/csv.h"
#include "planner/layup/laminate_thickness.h"

namespace windplan {

/// layer_profiles.csv. Each layer's surface has the points of the surface under it (offset one
/// for one), so the rows of every surface line up with the mandrel's meridian.
/// \throw InputError when the sizes do not match.
CsvTable laminate_profiles_table(const LaminateProfiles& p);

/// layer_profiles.svg (width x height px).
std::string laminate_profiles_svg(const LaminateProfiles& p, int width = 1100, int height = 700);

}  // namespace windplan
