#pragma once
// Resampling a dense polyline by a chord tolerance: keep few points such that every dropped point
// lies within `tolerance` (mm) of the chord between the kept points around it.
//
// Greedy forward simplification: from each kept point the next kept point is the farthest one
// whose chord covers every point in between, searched by doubling then bisection over the end
// index (exact where validity is monotone in the end index, as on convex arcs; elsewhere a valid
// but possibly shorter chord is taken). This is not guaranteed to be the global minimum number of
// points (that needs a quadratic shortest-path search), but it is close to it on smooth winding
// paths and runs in O(n log span). A chord never spans more than `max_span` dense points.
// Forced indices (segment ends, turnaround boundaries) are always kept.
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

struct ResampleResult {
  std::vector<int> kept;       ///< increasing indices into the dense polyline; first and last kept
  double max_deviation = 0.0;  ///< mm, largest distance of a dropped point to its chord
};

/// \param polylines one or more dense polylines of the same length, sampled at the same
///        parameters (e.g. the fibre path and the payout-eye path); a point is dropped only when
///        it is within tolerance in every one of them
/// \param tolerance mm, > 0
/// \param forced indices that must be kept (any order, out-of-range ignored)
/// \param max_span the largest index gap between two kept points (>= 1)
/// \throw InvariantError if the polylines have different lengths
ResampleResult resample_by_chord(const std::vector<const std::vector<Vec3>*>& polylines,
                                 double tolerance, const std::vector<int>& forced = {},
                                 int max_span = 2048);

/// Distance from p to the segment [a, b] (mm).
double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b);

}  // namespace windplan
