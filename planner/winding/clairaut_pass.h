#pragma once
// Geodesic passes on a shape of revolution from Clairaut's integral on its meridian.
//
// On a surface of revolution a geodesic keeps r sin(a) = c (Clairaut; planner/winding/clairaut.h),
// with a the winding angle from the meridian. Along the meridian (arc length s) it turns about the
// axis by dphi/ds = c / (r sqrt(r^2 - c^2)) and its own length grows by dl/ds = r / sqrt(r^2 -
// c^2). Where the wound region narrows below c (a dome towards its polar opening, the small end
// of a cone) the geodesic reaches the parallel r = c tangentially (a = 90 deg) and turns around
// by itself: that is the geodesic turnaround a shop winds on a dome. Where the region's end is
// wider than c (a pipe end, a station) the pass reaches the end at the angle asin(c / r) and
// something must hold the fibre there (pins or a ring: a dwell).
//
// The meridian is a polyline in the (axial, radius) half-plane: the mesh's own section by a
// half-plane through the axis (annulus_meridian), so the passes follow the tessellated surface
// and need no smooth profile. Each polyline segment is a truncated cone with r linear in s; on
// it both integrals are closed forms (clairaut_segment_angle, and for the length
// l (ra + rb) / (sa + sb) with sa = sqrt(ra^2 - c^2)), and q = sqrt(r^2 - c^2) is linear in the
// fibre length, so samples equally spaced along the fibre are placed exactly, also through the
// turnaround where the fibre runs along the parallel.
//
// Frame: e1, e2 (axis_frame) complete the spindle direction d to a right-handed frame; the
// meridian lies at angle phi = 0 (towards e1) and phi increases about d (right hand).
// Units: mm, radians.
#include <array>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"

namespace windplan {

/// Unit vectors e1, e2 with (e1, e2, d) right-handed, d the spindle direction.
std::array<Vec3, 2> axis_frame(const SpindleAxis& axis);

/// The point at axial position x, radius r and angle phi about the axis (mm, radians).
Vec3 point_on_axis_frame(const SpindleAxis& axis, const std::array<Vec3, 2>& frame, double x,
                         double r, double phi);

/// The meridian of a wound region (an annulus between two boundary loops) that is a shape of
/// revolution: its section by the half-plane through the axis towards e1, as (axial, radius)
/// points from the end with the smaller axial position to the other.
/// \throw TopologyError when the half-plane does not cut the annulus in one chain from loop to
///        loop (not an annulus about this axis).
std::vector<Vec2> annulus_meridian(const Mesh& annulus, const SpindleAxis& axis);

/// One sample of a pass, in meridian coordinates.
struct PassSample {
  double x = 0.0;       ///< axial position (mm)
  double r = 0.0;       ///< radius (mm)
  double phi = 0.0;     ///< angle about the axis from the pass start (radians, increasing)
  double length = 0.0;  ///< fibre length from the pass start (mm)
  double angle = 0.0;   ///< winding angle asin(c / r) (radians from the meridian)
};

/// A geodesic pass from the start end of a meridian to its far end.
struct ClairautPass {
  double c = 0.0;  ///< Clairaut constant (mm): the turnaround radius
  /// Per end (0: start, 1: far end): true when the pass turns around on the parallel r = c
  /// inside the meridian (tangentially), false when it runs to the meridian's end point.
  std::array<bool, 2> turns_around = {false, false};
  std::vector<PassSample> samples;  ///< from the start end to the far end
  double angle = 0.0;               ///< Phi: phi at the far end (radians)
  double length = 0.0;              ///< fibre length (mm)
};

struct ClairautPassOptions {
  double step = 2.0;  ///< largest fibre length between samples (mm, > 0)
};

/// The geodesic with Clairaut constant c along `meridian` ((axial, radius) points, at least 2).
/// The pass covers the part of the meridian where r >= c: from the first crossing of r = c (or
/// the start point when r >= c there) to the last (or the end point).
/// \throw InputError if c <= 0, if r < c at both ends of every segment (no pass) or if the radius
///        dips below c between the two turnarounds (a waist the geodesic cannot cross), naming
///        the axial position; InputError for options.step <= 0.
ClairautPass clairaut_pass(const std::vector<Vec2>& meridian, double c,
                           const ClairautPassOptions& options = {});

/// Phi(c) of clairaut_pass without the samples (radians): the angle the geodesic with Clairaut
/// constant c turns about the axis from one end of the meridian (or its turnaround) to the other.
/// \throw as clairaut_pass
double clairaut_pass_angle(const std::vector<Vec2>& meridian, double c);

}  // namespace windplan
