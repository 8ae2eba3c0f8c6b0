#pragma once
// The wound region of a tube given by two stations along its centre line: each end is the
// section of the tube by the plane normal to the centre line there, so the legs of a bent pipe
// are trimmed at their own ends (not on planes normal to one global axis).
//
// select_centre_line_region() checks both stations, checks that each end plane cuts a closed
// section loop around the centre line (the loop of the plane's section that winds once about the
// line through c(s) along t(s), nearest c(s)), cuts the full mesh exactly on both planes
// (geometry/region/plane_cut.h, the same no-sliver rule) and keeps the faces between them: near
// an end (within twice that end's section radius of it along the centre line) a face is inside
// when its centroid lies on the inner side of the end plane, elsewhere when its centroid projects
// onto the centre line between the stations (so a plane that also crosses another leg of the
// tube farther away does not cut that leg out). Of the connected parts kept, the wound one is an
// annulus (one component, two loops, genus 0): the largest, or `component`.
//
// Units: mm. Frame: the mesh frame. Spine convention: geometry/region/spine.h.
#include <string>

#include "geometry/mesh/mesh.h"
#include "geometry/region/mandrel_region.h"
#include "geometry/region/spine.h"

namespace windplan {

/// The two stations (mm of arc length along `spine`, 0 < from < to < length) and the YAML keys
/// that gave them (for the messages).
struct CentreLineEnds {
  double from = 0.0;  ///< mm along the centre line
  double to = 0.0;    ///< mm along the centre line
  std::string from_key = "mandrel.region.centre_line.from";
  std::string to_key = "mandrel.region.centre_line.to";
};

/// Cuts `full` on the sections normal to `spine` at ends.from and ends.to and picks the annulus
/// between them. `axis` is only used to describe the candidates (their axial extents).
/// \param component 1-based candidate to take; 0: the largest annulus
/// \throw ConfigError naming the key for: a station outside the centre line (ends excluded) or
///        not after the other, an end plane that does not cut a closed section loop around the
///        centre line, nothing between the planes that is an annulus (with the candidates).
RegionSelection select_centre_line_region(const Mesh& full, const Spine& spine,
                                          const CentreLineEnds& ends, const SpindleAxis& axis,
                                          int component = 0, const PlaneCutOptions& cut = {});

}  // namespace windplan
