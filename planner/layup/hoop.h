#pragma once
// A hoop layer on a shape of revolution: circumferential winding over an axial range with a
// constant axial pitch, reversing at the range ends within friction, covering the range.
//
// The band centre line runs on the surface r(x) of the radius profile as a curve (phi(s), x(s))
// whose direction makes the angle theta with the axis in the developed surface: d phi = sin(theta)
// ds / r, dx = cos(theta) ds. Along a pass theta is the hoop angle a(x), tan a = 2 pi r(x) / p,
// so the pass advances the pitch p = band_width - overlap along the axis per turn (on a cylinder
// of radius R: a = atan(2 pi R / p), the closed form of the tests). At a range end the path
// reverses on an arc of constant geodesic curvature k_g = f mu k_n(a) with k_n(a) = sin^2(a) / r
// (the normal curvature of the pass, the smallest along the arc, where theta runs from a through
// 90 deg to 180 deg - a): |k_g / k_n| <= f mu all along the arc (f = reversal_friction < 1 keeps
// a margin below the friction coefficient). The arc of radius rho = r / (f mu sin^2 a) turns by
// 180 deg - 2a, rises rho (1 - sin a) along the axis and runs 2 rho cos a around.
//
// The layer starts with a tie-on turn: one full turn along the parallel x0 + B/2 (the band's
// edge on the range end; a geodesic on a cylinder) and half a reversal arc (theta from 90 deg to
// a) onto the first pass; it ends the same way (half an arc and a full turn at x1 - B/2 or
// x0 + B/2). So the circuit's segments are: turn (Pass), arc (Turnaround), then passes and
// reversal arcs alternating, then arc (Turnaround), turn (Pass).
//
// Coverage: the apex of a reversal (the band centre at its extreme axial position) is placed at
// x1 - B/2 + p/2 (x0 + B/2 - p/2 at the start): at every angle one of the two passes meeting
// there is within p/2 of the apex, so its band reaches the range end; the band overhangs the
// range by up to p/2 at the apex itself. When that would leave the profile (a pipe wound to its
// ends) the apex is pulled in to B/2 inside the profile's end, and the measured coverage says
// what is left bare. The tie turns cover their range end at every angle. Coverage is measured on
// `meridians` lines of constant phi: the union of the axial intervals x +- B / (2 sin theta) of
// the bands crossing them, over the range. Units: mm, degrees in the result.
#include <cmath>
#include <string>
#include <vector>

#include "geometry/region/axis.h"
#include "planner/plan/plan.h"

namespace windplan {

struct HoopOptions {
  /// Axial range (mm along the spindle axis) to cover, x0 < x1; NaN: the cylindrical part
  /// (cylinder_range).
  double x0 = std::nan("");
  double x1 = std::nan("");
  /// Width of the band (mm, > 0).
  double band_width = 10.0;
  /// Axial overlap of neighbouring turns (mm, >= 0, < band_width): pitch = band_width - overlap.
  double overlap = 0.0;
  /// Passes over the range (count, >= 1): 2 = out and back (an even count ends where it began).
  int passes = 2;
  /// Friction coefficient fibre/mandrel (dimensionless, > 0: the reversal needs friction).
  double mu = 0.2;
  /// Fraction of mu the reversal arcs use (dimensionless, (0, 1]).
  double reversal_friction = 0.8;
  /// Spacing of the path points along the passes (mm, > 0); arcs get at least 16 points.
  double point_spacing = 5.0;
  /// Lines of constant angle on which coverage is measured (count, >= 4).
  int meridians = 72;

  bool has_range() const { return std::isfinite(x0) && std::isfinite(x1); }
  double pitch() const { return band_width - overlap; }
  bool is_valid(std::string* why) const;
};

struct HoopLayer {
  std::vector<Circuit> circuits;  ///< one continuous circuit: passes and reversal (Turnaround) arcs
  double x0 = 0.0, x1 = 0.0;      ///< the range covered (mm)
  double pitch = 0.0;             ///< mm
  double angle = 0.0;             ///< hoop angle at the middle of the range (deg from the meridian)
  double turns_per_pass = 0.0;    ///< turns
  double length = 0.0;            ///< mm of band centre line
  double reversal_length = 0.0;   ///< mm of reversal arcs
  double reversal_slippage = 0.0;  ///< max |k_g / k_n| measured on the reversal arcs
  double coverage = 0.0;           ///< smallest covered fraction of the range over the meridians
  std::vector<std::string> warnings;
};

/// The longest axial stretch where the profile's radius is within `tolerance` (relative) of its
/// largest radius: the cylindrical part of a vessel, the whole of a pipe.
/// \throw InputError for an empty profile or a stretch of zero length.
std::pair<double, double> cylinder_range(const RadiusProfile& profile, double tolerance = 1e-3);

/// Plans a hoop layer on the shape of revolution with radius profile `profile` about `axis`.
/// \param what the job key naming the layer in messages (e.g. "layers[0]")
/// \throw ConfigError for invalid options; InputError "<what>.range ..." when the range lies
///        outside the profile's axial extent.
HoopLayer plan_hoop_layer(const RadiusProfile& profile, const SpindleAxis& axis,
                          const HoopOptions& options, const std::string& what = "hoop");

}  // namespace windplan
