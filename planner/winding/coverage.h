#pragma once
// Coverage measured on the laid bands.
//
// What a shop checks on a wound part, computed from the fibre paths alone (the circuits' points:
// nothing of the planner's pattern or turnaround arithmetic), so that a planner bug shows up
// here. At `stations` axial positions spread over the wound length (between the axial extremes
// of the passes, `end_margin` in from each), the mandrel is cut by the plane normal to the
// spindle axis (the section loop around the mandrel, planner/cutlines/cutlines.h). Every pass that
// crosses that plane lays a band of width B centred on its crossing; on the section loop the
// band covers B / sin(theta) of the loop's length, theta the angle between the fibre and the
// loop there (B / cos(a) on a parallel, a the winding angle). The bands of each pass family
// (those running towards larger axial positions, and those running back) are laid out on the
// loop and the loop is swept:
// - bare fraction: the part of the loop no band of the family covers (the worse family);
// - widest gap: the longest uncovered run (mm along the loop);
// - widest overlap: the most two neighbouring bands of a family share, across the band (mm:
//   the shared length along the loop times sin(theta));
//   also over the stations on the largest sections only (within 0.5% of the longest loop: a
//   vessel's cylinder), where the bands of a family lie side by side;
// - most bands stacked over one point of the loop (of one family), and the mean plies (all
//   bands of both families per point: 2 for a full-coverage helical layer);
// - cover factor: the family's band length over the loop length (the smaller family): >= 1 is
//   enough band for full cover; full cover also needs the bands spread evenly (bare 0).
// - spacing: the distances between neighbouring band centres of a family, across the band; its
//   coefficient of variation is 0 for evenly spread bands.
// Stations whose plane does not cut the mandrel in a loop around the axis are skipped (counted).
// Off a shape of revolution a plane normal to the axis cuts a bent tube obliquely, so there the
// stations are the level sets of a height field of the wound region (CoverageOptions::height),
// its natural cross-sections; StationCoverage::station is then the level (dimensionless).
// Better, for a wound region that is a tube (CoverageOptions::spine, geometry/region/spine.h):
// the stations are sections by planes NORMAL TO THE CENTRE LINE at arc lengths spread over the
// passes' range along it (`end_margin` in from each end), the section loop the one around the
// tube nearest the centre point; a pass crosses a station where it changes side of that plane
// within reach of the loop (1.5 times the loop's largest distance from the centre point: a plane
// through a bend also cuts the far leg), and its family is the sign of its direction along the
// centre line's tangent. StationCoverage::station is then mm along the centre line.
// Units: mm.
#include <array>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"
#include "geometry/region/spine.h"
#include "planner/plan/plan.h"

namespace windplan {

struct CoverageOptions {
  double band_width = 10.0;  ///< B (mm, > 0)
  int stations = 12;         ///< stations measured (count, >= 1)
  /// Distance of the first and last station from the axial extremes of the passes (mm, >= 0;
  /// NaN: one band width).
  double end_margin = std::nan("");
  /// Off shapes of revolution: a per-vertex field of `surface` rising from one end of the wound
  /// region to the other (the harmonic height h in [0, 1], planner/winding/harmonic.h, a property
  /// of the mandrel, not of the paths); the stations are then its level sets, spread over the range
  /// of h on the passes (5% in from each end), instead of planes normal to the axis. null: planes.
  const std::vector<double>* height = nullptr;
  /// A tube's centre line (geometry/region/spine.h): stations are sections normal to it (wins
  /// over `height`). null: none.
  const Spine* spine = nullptr;
  bool is_valid(std::string* why) const;
};

/// Measures the coverage of the circuits' passes (CircuitSegment::Kind::Pass) on `surface`.
/// \throw ConfigError for invalid options.
CoverageReport measure_coverage(const Mesh& surface, const SpindleAxis& axis,
                                const std::vector<Circuit>& circuits,
                                const CoverageOptions& options = {});

}  // namespace windplan
