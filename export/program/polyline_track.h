#pragma once
// The deviation track of the replay (export/program/replay.h): the nearest segment of the planned
// polyline to a point, searched in a short window of arc length round the last match.
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

/// Distance (mm) of p to the polyline q (cumulative arc length sq, sq[0] = 0, one per point),
/// searched on the segments from `back` mm behind the last match (*ptr, a segment index) to
/// `ahead` mm after it; moves *ptr to the nearest segment, the first of them on a tie. The
/// window is short in arc length so that a later pass crossing this one is never taken for it.
/// Only the segments between the points `first` and `limit` (the points of one layer, between
/// two tie-ons: the step from a layer's last point to the next one's first is no fibre, and a
/// layer's first point is reached by a rapid only, never by tracking). The same distance and
/// segment as the distance to every segment of the window, found sooner: runs of segments that
/// the triangle inequality puts farther than the best so far are skipped.
double track_polyline(const std::vector<Vec3>& q, const std::vector<double>& sq, const Vec3& p,
                      double back, double ahead, int first, int limit, int* ptr);

}  // namespace windplan
