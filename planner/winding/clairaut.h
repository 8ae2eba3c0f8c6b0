#pragma once
// The geodesic turn limit of a shape of revolution (Clairaut's relation).
//
// On a surface of revolution a geodesic keeps r sin(a) = c (Clairaut), with r the distance from
// the axis and a the winding angle from the meridian; c is its Clairaut constant. A geodesic that
// runs from one end of the wound region to the other passes every radius in between, so
// c <= r_min, the smallest radius between the ends (the polar opening of a vessel, the small end
// of a cone). Along the meridian (arc length s) it turns about the axis by
//   dphi/ds = tan(a) / r = c / (r sqrt(r^2 - c^2)),
//   Phi(c) = integral from s0 to s1 of c / (r(s) sqrt(r(s)^2 - c^2)) ds        (radians),
// which increases with c. Phi_max = Phi(r_min) is finite when r_min is reached at an end with a
// non-zero meridian slope there: the integrand has an integrable 1 / sqrt singularity at that
// end. So a plain geodesic (beta = 0) makes at most N_max = Phi_max / (2 pi) turns between the
// ends; a pass with more turns cannot be a geodesic, and its shortest path in its homotopy class
// wraps along the smaller end (the fibre would slip). Closed forms (tests): on a cone of
// half-angle b between radii r1 < r2, Phi_max = arccos(r1 / r2) / sin(b) (unrolled, the line
// tangent to the small circle); on a sphere a geodesic is a great circle, so from the equator to
// any latitude Phi_max = pi / 2. When r_min is reached along a stretch (a cylinder: Phi -> inf
// as c -> R, the hoop) or at a waist (a parallel where dr/ds = 0 is itself a geodesic, and
// geodesics with c -> r_min wind towards it without end) there is no limit.
//
// Two evaluations of Phi:
// - a piecewise-linear radius profile (the tessellated mandrel: each segment a truncated cone) is
//   integrated exactly, segment by segment: with r linear in s on a segment of length l,
//   integral = l / |r_b - r_a| (arccos(c / r_b) - arccos(c / r_a)), written in a form that stays
//   accurate for |r_b - r_a| -> 0 and for c = r_a (see clairaut.cpp). So the limit c = r_min is
//   evaluated directly, not extrapolated.
// - a smooth meridian (x(t), r(t)) by composite Gauss-Legendre quadrature after the substitution
//   t = t0 + (t1 - t0) (3 u^2 - 2 u^3): dt ~ 6 u du near u = 0 and t - t0 ~ 3 u^2, so the
//   1 / sqrt(t - t0) singularity of an end where r = c becomes a bounded, smooth integrand (the
//   same at u = 1); c = r_min is again evaluated directly (the Gauss nodes are inside the
//   interval). The panels are doubled until two estimates agree; at an end where r = c with a
//   zero slope (r' = 0, e.g. the neck of an isotensoid dome) the integral diverges
//   logarithmically and the quadrature reports that it did not converge.
// Units: mm, radians, turns.
#include <functional>
#include <limits>
#include <string>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"

namespace windplan {

/// Phi(c) (radians) over a piecewise-linear radius profile between axial positions x0 < x1 (mm;
/// the profile is interpolated at x0 and x1; of a range beyond its ends only the part it covers
/// counts), exact per segment.
/// \param c Clairaut constant (mm), 0 <= c <= the smallest radius on [x0, x1]
/// \return +inf when c equals the radius along a segment (a cylinder at r = c)
/// \throw InputError for an empty profile, x1 <= x0 (also after clipping to the profile), or c
///        outside [0, smallest radius]
double clairaut_angle(const RadiusProfile& profile, double x0, double x1, double c);

/// The turning angle of a geodesic with Clairaut constant c over one truncated cone of the
/// meridian (radians): the integral of c / (r sqrt(r^2 - c^2)) ds with r linear in the arc length
/// s, from radius ra to rb over the axial step dx (mm; any sign). Exact, with no cancellation when
/// rb -> ra and finite at c = ra or c = rb (the turnaround); +inf on a cylinder at r = c.
/// \pre 0 <= c <= min(ra, rb)
double clairaut_segment_angle(double dx, double ra, double rb, double c);

/// A smooth meridian of a surface of revolution, t in [t0, t1].
struct Meridian {
  std::function<Vec2(double)> point;       ///< (axial position, radius) at t (mm)
  std::function<Vec2(double)> derivative;  ///< d(axial, radius) / dt (mm per unit of t)
  double t0 = 0.0, t1 = 1.0;
};

struct ClairautQuadratureOptions {
  /// Relative change between two panel doublings (dimensionless, > 0); below about 1e-12 the
  /// rounding of r - c near an end where r = c can keep it from being met.
  double tolerance = 1e-12;
  int max_panels = 1 << 14;  ///< 8-point Gauss-Legendre panels at most (count, >= 1)
};

struct ClairautQuadrature {
  double angle = 0.0;      ///< Phi(c) (radians): the finest estimate
  double error = 0.0;      ///< |last - previous estimate| (radians)
  int panels = 0;          ///< panels of the finest estimate
  int evaluations = 0;     ///< integrand evaluations over all doublings
  bool converged = false;  ///< error <= tolerance |angle|
};

/// Phi(c) along a smooth meridian by Gauss-Legendre after the end substitution (header comment).
/// \param c Clairaut constant (mm), 0 <= c <= r(t) on [t0, t1]
/// \throw InputError if c < 0, t1 <= t0, or r(t) < c at a quadrature node
ClairautQuadrature clairaut_angle(const Meridian& meridian, double c,
                                  const ClairautQuadratureOptions& options = {});

struct ClairautOptions {
  /// Radii within flat_tolerance r_min of r_min count as the smallest radius (dimensionless,
  /// >= 0): of the order of the tessellation's radial error over the radius.
  double flat_tolerance = 1e-3;
  /// There is no limit when the radius stays within that band over an axial length of at least
  /// flat_length r_min (a cylinder, or a cylindrical stretch at the smallest radius), or when the
  /// smallest radius lies inside, below both end radii by more than the band (a waist)
  /// (dimensionless, > 0).
  double flat_length = 1.0;
  bool is_valid(std::string* why) const;
};

/// The geodesic turn limit between two axial positions of a shape of revolution.
struct ClairautLimit {
  bool bounded = false;                                    ///< false: no limit (see `reason`)
  double angle = std::numeric_limits<double>::infinity();  ///< Phi_max (radians)
  double turns = std::numeric_limits<double>::infinity();  ///< N_max = Phi_max / (2 pi) (turns)
  double min_radius = 0.0;              ///< r_min, the largest Clairaut constant (mm)
  double min_at = 0.0;                  ///< axial position of r_min (mm)
  double x0 = 0.0, x1 = 0.0;            ///< the ends (mm along the axis)
  double radius0 = 0.0, radius1 = 0.0;  ///< the radii there (mm)
  std::string reason;  ///< why there is no limit ("cylinder at the smallest radius", "waist")
};

/// Phi_max and N_max of a radius profile between axial positions x0 < x1 (mm): c = r_min, the
/// profile's smallest radius on [x0, x1], evaluated exactly (clairaut_angle above).
/// \throw InputError as clairaut_angle; ConfigError for invalid options.
ClairautLimit clairaut_turn_limit(const RadiusProfile& profile, double x0, double x1,
                                  const ClairautOptions& options = {});

/// The meridian of a mesh of revolution between axial positions x0 < x1 (mm): at stations + 1
/// positions clustered towards both ends (x0 + (x1 - x0) (1 - cos(pi k / stations)) / 2, the end
/// ones moved 1e-9 (x1 - x0) inwards so that a boundary loop lying in the end plane is cut by
/// its edges; the profile lists them at x0 and x1), the largest distance from the axis of the
/// mesh's edge crossings of the plane normal to the axis. Positions without a crossing are left
/// out. Unlike compute_radius_profile
/// (geometry/region/winding_surface.h, the clearance envelope) no vertex is binned to a nearby
/// station, so a steep meridian (a dome near its opening) is not widened. \throw InputError for x1
/// <= x0 or stations < 1.
RadiusProfile meridian_profile(const Mesh& surface, const SpindleAxis& axis, double x0, double x1,
                               int stations = 400);

}  // namespace windplan
