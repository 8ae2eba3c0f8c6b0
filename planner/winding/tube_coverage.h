#pragma once
// Coverage of a bent tube's laid bands on sections normal to its centre line
// (planner/winding/tube_centre_line.h), from the circuits' points alone: every point is located
// on the centre line (station s, angle theta); at each station every segment that crosses it lays
// a band whose trace on the section circle is B / cos(a) long, a the fibre's angle to the centre
// line there (B across the fibre, the section at 90 - a to it). Families: + where the fibre runs
// towards larger s, - back. Per family the union of its traces on the circle (sampled at 0.1 deg)
// gives the bare fraction and the widest gap; bare_fraction is the worse family's. The plane
// sections of planner/winding/coverage.h cut a bend obliquely and are no measure there.
// Units: mm; StationCoverage::station is along the centre line here.
#include <vector>

#include "planner/plan/plan.h"
#include "planner/winding/tube_centre_line.h"
#include "planner/winding/tube_surface.h"

namespace windplan {

/// Coverage at `stations` (>= 2) stations evenly from s0 to s1 (mm along the centre line).
/// Overlaps and spacing are not measured (0).
CoverageReport measure_tube_coverage(const TubeCentreLine& line,
                                     const std::vector<Circuit>& circuits, double band_width,
                                     double s0, double s1, int stations);

/// The same on any tube surface (planner/winding/tube_surface.h), for the fitted mesh tubes: the
/// section at s is the loop P(s, theta) in 3600 bins of theta, each as long as its chord; a
/// band's trace is B / |T . nu| long (nu the loop's in-surface normal), laid bin by bin both ways
/// from the crossing; bare fractions and gaps are lengths along the loop.
CoverageReport measure_tube_coverage(const TubeSurface& surface,
                                     const std::vector<Circuit>& circuits, double band_width,
                                     double s0, double s1, int stations);

}  // namespace windplan
