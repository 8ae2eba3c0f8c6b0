#pragma once
// Where two windows of the exact window search (geometry/geodesic/geodesic_windows.h) give an
// edge's points the same distance: the window intersection of Mitchell, Mount and Papadimitriou
// ("The discrete geodesic problem", SIAM J. Comput. 1987), by which windows on one edge cut each
// other down to where each is the shorter.
#include <cmath>

namespace windplan {

/// The distance function of a window on an edge, in the frame of one of the edge's halfedges
/// (the edge on the x axis): sigma + |(x, 0) - (sx, sy)|, with (sx, sy) the unfolded
/// pseudo-source.
struct EdgeDistance {
  double sigma, sx, sy;
  double at(double x) const { return sigma + std::sqrt((x - sx) * (x - sx) + sy * sy); }
};

/// Candidates for the points of (lo, hi) where a and b are equal, ascending, in out[0..n) with
/// n <= 2 returned: every point where a - b changes sign is among them (squaring
/// r_a - r_b = sigma_b - sigma_a twice leaves a quadratic; a double root that round-off
/// pushes below zero is kept). Some candidates may be points where a - b keeps its sign.
int equal_distance_points(const EdgeDistance& a, const EdgeDistance& b, double lo, double hi,
                          double out[2]);

}  // namespace windplan
