#pragma once
// Where two windows of the exact window search (geometry/geodesic/geodesic_windows.h) give an
// edge's points the same distance, and the cut that follows: the window intersection of Mitchell,
// Mount and Papadimitriou ("The discrete geodesic problem", SIAM J. Comput. 1987), by which
// windows on one edge cut each other down to where each is the shorter.
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

/// Two windows of one edge against each other over their overlap [lo, hi] (lo < hi), from the
/// ends only. The overlap is split where a - b crosses +eps or -eps; each window loses the pieces
/// at its ends that the overlap reaches and where the other is strictly shorter, by more than
/// eps. Within eps both keep a piece (one of them may hold the ray to a vertex that the other's
/// rays miss), unless they are the same rays (sigma within eps, pseudo-sources within tol): then
/// a loses the tie, so that a window made twice is dropped and the first one kept.
/// The intervals [*a0, *a1] and [*b0, *b1], in the frame of a's halfedge, are cut in place (a
/// window cut to nothing ends with a1 - a0 <= tol); both cuts come from the same split.
void cut_overlap(const EdgeDistance& a, const EdgeDistance& b, double lo, double hi, double eps,
                 double tol, double* a0, double* a1, double* b0, double* b1);

}  // namespace windplan
