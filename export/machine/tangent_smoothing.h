#pragma once
// Fibre tangents for the payout eye, free of mesh faceting noise.
//
// A fibre path on a triangle mesh is straight inside each face and bends at the edges, so its
// tangent jumps by up to the dihedral angle at every edge crossing; the eye E = P + L t turns that
// into steps of L times the jump (on the shipped vessel, L ~ 100 mm and 6 mm triangles gave eye
// steps of up to 3.9 mm and carriage reversals in the middle of passes). Here the tangent at point
// i is the derivative at s_i of the least-squares quadratic P(s) ~ a + b u + c u^2 (u = s - s_i)
// over the points with |s - s_i| <= w_i (arc length), w_i = clamp(0.5 / kappa_i, w_min, w_max)
// with kappa_i = sqrt(k_n^2 + k_g^2) of the plan, and the window symmetric (shrunk near the ends
// of the polyline and of the point's piece; fewer than 3 points: the plan's tangent). On a
// symmetric window the slope is that of the straight-line fit, biased by O((w kappa)^2) on a
// smooth curve (a helix of radius 50 mm and pitch 20 mm/rad, w = 15 mm: 3e-3 rad); a cubic would
// remove the bias but measured 7 times the carriage reversals on the vessel (its slope is
// noisier), and the reversals are what reach the machine. The noise, which changes sign face by
// face, averages out over the several faces in the window.
// The result points the same way as the plan's tangent. Its effect on the laid fibre is measured
// by the replay (export/program/replay.h).
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

/// \param points, s, curvature, tangents the dense polyline: positions (mm), arc length (mm,
///        non-decreasing), curvature (1/mm, <= 0: unknown) and unit tangents, all the same size
/// \param w_max mm, largest half window (0: the tangents are returned unchanged)
/// \param w_min mm, smallest half window
/// \param piece optional piece id per point: windows stay within the piece of their point (the
///        planned path may turn a corner where a pass meets a dwell arc on pins)
/// \return unit tangents, one per point
std::vector<Vec3> smooth_tangents(const std::vector<Vec3>& points, const std::vector<double>& s,
                                  const std::vector<double>& curvature,
                                  const std::vector<Vec3>& tangents, double w_max,
                                  double w_min = 2.0, const std::vector<int>& piece = {});

}  // namespace windplan
