#pragma once
// The centre line of a mandrel whose wound region is a tube (geometry/region/spine.h for the
// convention: s from the wound region's start loop, loop 0, to its end loop).
//
// A parametric bent tube (mandrel.source: bent_tube) has it in closed form: its centre line
// (planner/winding/tube_centre_line.h, the closed forms the friction layers use) sampled at 90
// points per bend,
// oriented from loop 0. Every other source that is not a shape of revolution gets it from the
// centroids of its sections (extract_spine). The analytic line is used only when both loops'
// centroids lie on it (within 2% of the tube radius; a region cut or a remesh can move them);
// otherwise it is extracted too.
#include <memory>
#include <string>

#include "geometry/region/spine.h"
#include "planner/mandrel/mandrel_builder.h"
#include "planner/winding/tube_centre_line.h"

namespace windplan {

struct TubeSpine {
  /// A parametric bent tube's exact centre line with the closed forms of its surface
  /// (planner/winding/tube_centre_line.h): the whole tube's, s from the tube's own start (not
  /// the region's); null for every other source. `spine` is sampled from it (90 points per
  /// bend), so both are one centre line.
  std::shared_ptr<const TubeCentreLine> exact;
  Spine spine;         ///< empty when the wound region is not a tube
  std::string source;  ///< "bent_tube centre line", "section centroids" or "" (none)
  std::string why;     ///< when empty: why (the extraction's message)
  SpineSummary summary;
};

/// The centre line of the winding surface `ws` (an annulus; s from its loop 0). A bent tube's
/// analytic line is trimmed to the stations of the loops' centroids (a region with
/// centre-line ends). Never throws for a region that is not a tube: `spine` is then empty and
/// `why` says what failed.
TubeSpine tube_spine(const WindingSurface& ws, const SpindleAxis& axis,
                     const MandrelOptions& options);

/// The wound region's centre line: tube_spine(mandrel.winding, mandrel.axis, options).
TubeSpine mandrel_tube_spine(const Mandrel& mandrel, const MandrelOptions& options);

}  // namespace windplan
