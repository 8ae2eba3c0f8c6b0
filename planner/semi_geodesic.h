#pragma once
// Semi-geodesic (friction-limited) paths on a shape of revolution, integrated on its meridian.
//
// A fibre on a surface of revolution: meridian arc length s (the meridian polyline of
// planner/clairaut_pass.h, (axial x, radius r) points, s from its first point), fibre length l,
// winding angle a measured from the meridian direction of increasing s, here in (0, pi): a < pi/2
// runs towards larger s, a > pi/2 back, a = pi/2 along a parallel (the apex of a turnaround).
// The mandrel turns one way, so phi increases. With psi the meridian's slope (dx/ds = cos psi,
// dr/ds = sin psi):
//   ds/dl   = cos a,
//   dphi/dl = sin a / r,
//   k_g     = da/dl + sin(a) sin(psi) / r          (Liouville's formula for a surface of
//   revolution) k_n     = k_m cos^2 a + sin^2 a |cos psi| / r  (Euler / Meusnier; k_m the
//   meridian's curvature)
// A geodesic has k_g = 0: da/dl = -sin a sin psi / r, i.e. d(r sin a)/dl = r cos a k_g = 0, which
// is Clairaut's r sin a = c. A path that leans on friction with slippage lambda = |k_g / k_n|
// on the side sigma = +-1 (sigma k_g > 0) obeys
//   da/dl = -sin(a) sin(psi) / r + sigma lambda k_n,     d(r sin a)/dl = sigma lambda k_n r cos a,
// so its "Clairaut constant" r sin a drifts at the rate friction allows. On the cylinder r = R
// (psi = 0, k_n = sin^2 a / R): d(cot a)/dl = -sigma lambda / R, the closed forms
//   cot(a0) - cot(a) = lambda l / R           (l: fibre length),
//   1/sin(a0) - 1/sin(a) = lambda s / R        (s: meridian, i.e. axial, length),
//   phi = (ln tan(a/2) - ln tan(a0/2)) / lambda,
// so a turnaround from a0 to 90 deg takes l = R cot(a0) / lambda of fibre, s = R (1 / sin(a0) - 1)
// / lambda along the axis and turns the mandrel by -ln(tan(a0 / 2)) / lambda (each half).
//
// The state (s, a, phi) is integrated in the fibre length l by classical RK4 with step doubling
// (the step halves until the two estimates agree to `tolerance`, and grows again after easy
// steps; never longer than `step`), so the path runs through a = pi/2 (where ds/dl = 0) with no
// singularity. Events (the turnaround's end, r sin a = c) are located by bisection on the last
// step. The meridian polyline is a chain of truncated cones: within a segment k_m = 0, so k_n is
// the parallel's term only; the meridian's curvature sits at the vertices and is left out of the
// friction term (on a pipe or cone, where the friction turnarounds are planned, there is none).
// Beyond its end points the meridian continues along its end segments' lines (so a turnaround
// that does not fit can say how long it would be).
//
// A friction turnaround at an end of the meridian (planner/friction_winding.h uses it): its apex
// (a = pi/2) on the parallel at meridian length s_apex; from there the fibre leaves back into
// the wound region under friction lambda until r sin a falls to the pass's Clairaut constant c,
// where the geodesic pass takes over tangentially (same angle). The arriving half is the mirror
// image (a -> pi - a, same s, phi reversed): one ODE with the same sigma runs through the apex.
// Units: mm, radians.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "geometry/errors.h"
#include "geometry/mesh.h"
#include "planner/clairaut_pass.h"

namespace windplan {

struct SemiGeodesicOptions {
  double slippage = 0.0;     ///< lambda = |k_g / k_n| held along the path (>= 0; 0: a geodesic)
  int side = 1;              ///< sigma: +1 friction turns a towards pi, -1 towards 0
  double step = 2.0;         ///< longest fibre length per step, also between samples (mm, > 0)
  double tolerance = 1e-10;  ///< per-step error of the step-doubling estimate (rad, > 0)
  /// Stop after this much fibre (mm, > 0): a path that never meets its event.
  double max_length = 1e5;
  bool is_valid(std::string* why) const;
};

/// The state of a path on the meridian.
struct MeridianState {
  double s = 0.0;    ///< meridian arc length from the meridian's first point (mm)
  double a = 0.0;    ///< winding angle from the +s meridian direction (radians, (0, pi))
  double phi = 0.0;  ///< angle about the axis (radians)
};

/// A meridian polyline by arc length, extended beyond its ends along its end segments.
class MeridianLine {
 public:
  /// \throw InputError for fewer than 2 points or a zero-length polyline
  explicit MeridianLine(const std::vector<Vec2>& points);
  double length() const { return cum_.back(); }
  /// Point (x, r) at meridian length s (extrapolated beyond [0, length()]).
  Vec2 point(double s) const;
  /// Unit tangent (dx/ds, dr/ds) of the segment holding s (the end segments beyond the ends).
  Vec2 tangent(double s) const;
  /// The meridian length at the first point whose axial position is x (NaN: none).
  double at_axial(double x) const;

 private:
  int segment(double s) const;
  std::vector<Vec2> pts_;
  std::vector<double> cum_;
};

/// (ds/dl, da/dl, dphi/dl) of the semi-geodesic ODE at `y` (see the header comment).
/// \throw InputError where the radius is <= 0 (the path ran off the mandrel).
std::array<double, 3> semi_geodesic_rate(const MeridianLine& m, const MeridianState& y,
                                         double slippage, int side);

/// The path from `start` until `event` changes sign from its value at the start (located to
/// ~1e-12 of a step), or options.max_length. Samples at every accepted step, as PassSample
/// with `angle` the winding angle a in (0, pi) and `phi` from start.phi.
struct SemiGeodesicPath {
  std::vector<PassSample> samples;
  std::vector<double> s;  ///< meridian length of each sample (mm)
  bool event = false;     ///< false: stopped at max_length
  MeridianState end;
  double length = 0.0;  ///< fibre length (mm)
  int steps = 0, rejected = 0;
};

template <typename F>
SemiGeodesicPath semi_geodesic(const MeridianLine& m, const MeridianState& start,
                               const SemiGeodesicOptions& options, F event);

/// A friction turnaround (see the header comment): from where the pass meets it, through the
/// apex, back to the same parallel.
struct FrictionTurnaround {
  int end = 1;            ///< 0: at the meridian's start, 1: at its far end
  double slippage = 0.0;  ///< lambda used (the same at every point)
  double c = 0.0;         ///< the pass's Clairaut constant (mm)
  double apex_s = 0.0, apex_x = 0.0, apex_r = 0.0;  ///< apex on the meridian (mm)
  double join_s = 0.0, join_x = 0.0, join_r = 0.0;  ///< where the geodesic pass joins (mm)
  double pass_angle = 0.0;  ///< winding angle where the pass joins, asin(c / join_r) (rad)
  double length = 0.0;      ///< fibre length carried by friction, both halves (mm)
  double angle = 0.0;       ///< Theta: the mandrel's turn over the turnaround (rad)
  /// Samples from the join through the apex back to the join, phi from 0 to angle; `angle` in
  /// (0, pi) as the fibre runs (towards the end, then back).
  std::vector<PassSample> samples;
  bool reached = true;  ///< false: friction never brought r sin a down to c
  /// The smallest r sin a the leaving half reached on the meridian (mm; c when reached).
  double lowest = 0.0;
};

/// The turnaround at `end` of `m` with its apex at meridian length apex_s, slippage lambda > 0
/// and the pass's Clairaut constant c (< the apex radius).
/// \throw InputError for lambda <= 0, c >= the apex radius or a bad step.
FrictionTurnaround friction_turnaround(const MeridianLine& m, int end, double apex_s, double c,
                                       double lambda, double step = 2.0);

// ---- template implementation ----

namespace semi_geodesic_detail {
MeridianState rk4(const MeridianLine& m, const MeridianState& y, double h, double lambda, int side);
PassSample sample_of(const MeridianLine& m, const MeridianState& y, double length);
}  // namespace semi_geodesic_detail

template <typename F>
SemiGeodesicPath semi_geodesic(const MeridianLine& m, const MeridianState& start,
                               const SemiGeodesicOptions& o, F event) {
  using semi_geodesic_detail::rk4;
  using semi_geodesic_detail::sample_of;
  SemiGeodesicPath p;
  std::string why;
  if (!o.is_valid(&why)) throw InputError("semi_geodesic: " + why);
  MeridianState y = start;
  double l = 0.0;
  p.samples.push_back(sample_of(m, y, l));
  p.s.push_back(y.s);
  const double g0 = event(m, y);
  const bool neg0 = g0 < 0.0;
  double h = o.step;
  while (l < o.max_length) {
    h = std::min({h, o.step, o.max_length - l});
    const MeridianState full = rk4(m, y, h, o.slippage, o.side);
    const MeridianState half =
        rk4(m, rk4(m, y, 0.5 * h, o.slippage, o.side), 0.5 * h, o.slippage, o.side);
    const double err = std::max({std::abs(full.a - half.a), std::abs(full.phi - half.phi),
                                 std::abs(full.s - half.s) / std::max(1.0, m.point(y.s).y())});
    if (err > o.tolerance && h > 1e-6) {
      h *= 0.5;
      ++p.rejected;
      continue;
    }
    MeridianState next = half;
    double hn = h;
    if ((event(m, next) < 0.0) != neg0) {  // the event lies in this step: bisect on h
      double lo = 0.0, hi = h;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        const MeridianState t =
            rk4(m, rk4(m, y, 0.5 * mid, o.slippage, o.side), 0.5 * mid, o.slippage, o.side);
        ((event(m, t) < 0.0) != neg0 ? hi : lo) = mid;
      }
      hn = hi;
      next = rk4(m, rk4(m, y, 0.5 * hn, o.slippage, o.side), 0.5 * hn, o.slippage, o.side);
      p.event = true;
    }
    y = next;
    l += hn;
    ++p.steps;
    p.samples.push_back(sample_of(m, y, l));
    p.s.push_back(y.s);
    if (p.event) break;
    if (err < 0.03 * o.tolerance) h *= 2.0;
  }
  p.end = y;
  p.length = l;
  return p;
}

}  // namespace windplan
