#pragma once
// The sharp edges of a wound surface: interior edges across which the surface turns by more than
// a given angle (the angle between the two faces' normals), i.e. corners without a radius, as on
// a mandrel whose section is a polygon (a flat slab's edges). Off a shape of revolution the
// planner refuses a wound surface with such edges before any long work
// (planner/pipeline.cpp): friction holds a turning fibre only where the surface curves
// (|k_g/k_n| <= mu needs k_n > 0), which a flat face with sharp edges does not, and a band laid
// over a corner without radius is not laid as planned.
//
// Units: mm, degrees.
#include <string>

#include "geometry/mesh/mesh.h"

namespace windplan {

struct SharpEdges {
  int count = 0;               ///< interior edges turning by more than the threshold
  double length = 0.0;         ///< mm, their total length
  double max_angle_deg = 0.0;  ///< the largest turn across any interior edge (deg)
  double flat_area = 0.0;      ///< mm^2: faces whose three edges all turn by less than 0.5 deg
  double area = 0.0;           ///< mm^2: the whole surface
  /// "117 edges (78.2 mm) turning by up to 90.0 deg; 55.8% of the area flat"
  std::string brief() const;
};

/// The interior edges of `mesh` across which the normals of the two faces differ by more than
/// `angle_deg` (degrees, in (0, 180)). Zero-area faces are skipped.
/// \throw InputError for an angle outside (0, 180).
SharpEdges sharp_edges(const Mesh& mesh, double angle_deg);

}  // namespace windplan
