#pragma once
// Semi-geodesic (friction-limited) paths on a shape of revolution, integrated on its meridian.
//
// A fibre on a surface of revolution: meridian arc length s (the meridian polyline of
// planner/winding/clairaut_pass.h, (axial x, radius r) points, s from its first point), fibre
// length l, winding angle a measured from the meridian direction of increasing s, here in (0, pi):
// a < pi/2 runs towards larger s, a > pi/2 back, a = pi/2 along a parallel (the apex of a
// turnaround). The mandrel turns one way, so phi increases. With psi the meridian's slope (dx/ds =
// cos psi, dr/ds = sin psi):
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
// step. The meridian polyline is a chain of truncated cones whose curvature sits at the
// vertices; k_m is that curvature spread over a window (MeridianLine's `curvature_window`: the
// turning angles smoothed with a hat of that half-width, so k_m is continuous and a sphere's
// polyline gives 1 / R). It matters on domes: on a sphere k_n = 1 / R in every direction, while
// the parallel's term alone gives sin^2(a) / R; left out (window 0; on a pipe or a cone k_m = 0
// anyway) friction at lambda 0.2 raises r sin a on a hemispherical dome of radius 100 from an
// apex on r = 30 to 40 mm by 63 deg from the pole, but to only 36.2 mm over the whole dome
// without it (tests/planner/winding/semi_geodesic_test.cpp). Beyond its end points the meridian
// continues along its end segments' lines (so a turnaround that does not fit can say how long it
// would be).
//
// A friction turnaround at an end of the meridian (planner/winding/friction_winding.h uses it): its
// apex (a = pi/2) on the parallel at meridian length s_apex; from there the fibre leaves back into
// the wound region under friction lambda until r sin a reaches the pass's Clairaut constant c,
// where the geodesic pass takes over tangentially (same angle). c below the apex radius: friction
// lowers r sin a (a pipe end, or a dome wound at a lower angle than its geodesic); above it: it
// raises r sin a (a dome wound at a higher angle, more turns, than the geodesic turning around
// on the same parallel). The arriving half is the mirror image (a -> pi - a, same s, phi
// reversed): one ODE with the same sigma runs through the apex.
//
// A friction transition on a pass (friction_transition): from a point where the fibre runs at
// the geodesic with constant c_from, friction lambda carries r sin a to c_to, where the geodesic
// with c_to takes over: how a pass joins two domes whose turnarounds differ.
// Units: mm, radians.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "geometry/base/errors.h"
#include "geometry/mesh/mesh.h"
#include "planner/winding/clairaut_pass.h"

namespace windplan {

struct SemiGeodesicOptions {
  double slippage = 0.0;     ///< lambda = |k_g / k_n| held along the path (>= 0; 0: a geodesic)
  int side = 1;              ///< sigma: +1 friction turns a towards pi, -1 towards 0
  double step = 2.0;         ///< longest fibre length per step, also between samples (mm, > 0)
  double tolerance = 1e-10;  ///< per-step error of the step-doubling estimate (rad, > 0)
  /// Stop after this much fibre (mm, > 0): a path that never meets its event.
  double max_length = 1e5;
  /// Stop (no event) where the path leaves [s_min, s_max] of the meridian (mm).
  double s_min = -std::numeric_limits<double>::infinity();
  double s_max = std::numeric_limits<double>::infinity();
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
  /// \param curvature_window half-width of the hat the vertices' turning angles are spread
  ///        over for curvature() (mm; 0: curvature() is 0, the parallel's term only)
  /// \throw InputError for fewer than 2 points, a zero-length polyline or a negative window
  explicit MeridianLine(const std::vector<Vec2>& points, double curvature_window = 0.0);
  double length() const { return cum_.back(); }
  /// k_m at meridian length s (1/mm): > 0 where the meridian bends towards the axis (a dome,
  /// for a meridian running from the smaller axial position to the larger); 0 beyond the ends.
  double curvature(double s) const;
  /// Point (x, r) at meridian length s (extrapolated beyond [0, length()]); with `tangent`, also
  /// tangent(s) there (one segment search for both).
  Vec2 point(double s, Vec2* tangent = nullptr) const;
  /// Unit tangent (dx/ds, dr/ds) of the segment holding s (the end segments beyond the ends).
  Vec2 tangent(double s) const;
  /// The meridian length at the first point whose axial position is x (NaN: none).
  double at_axial(double x) const;
  /// The meridian length where the radius first crosses r walking in from `end` (0: the first
  /// point, 1: the last; NaN: nowhere).
  double at_radius(double r, int end) const;
  /// The meridian length of point i of the polyline.
  double vertex_s(std::size_t i) const { return cum_[i]; }

 private:
  int segment(double s) const;
  std::vector<Vec2> pts_;
  std::vector<double> cum_;
  double grid_h_ = 0.0;        // spacing of the curvature samples (mm; 0: no curvature)
  std::vector<double> kappa_;  // k_m at s = i * grid_h_
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
  bool reached = true;  ///< false: friction never brought r sin a to c on the meridian
  /// The r sin a nearest c the leaving half reached on the meridian (mm; c when reached).
  double lowest = 0.0;
};

/// The turnaround at `end` of `m` with its apex at meridian length apex_s, slippage lambda > 0
/// and the pass's Clairaut constant c (> 0, not the apex radius: below it friction lowers
/// r sin a from the apex, above it raises it).
/// \throw InputError for lambda <= 0, c <= 0, c within 1e-9 of the apex radius or a bad step.
/// \param on_meridian true: the turnaround must join the pass on the meridian (a dome: beyond
///        its ends there is no mandrel), else it is not reached; false: the meridian's end lines
///        carry it on (a pipe end: the caller says how much longer the region would have to be)
FrictionTurnaround friction_turnaround(const MeridianLine& m, int end, double apex_s, double c,
                                       double lambda, double step = 2.0, bool on_meridian = false);

/// A friction transition along a pass (see the header comment).
struct FrictionTransition {
  double slippage = 0.0;                ///< lambda used (the same at every point)
  double c_from = 0.0, c_to = 0.0;      ///< Clairaut constants of the geodesics it joins (mm)
  double start_s = 0.0, start_x = 0.0;  ///< where it leaves the c_from geodesic (mm)
  double end_s = 0.0, end_x = 0.0;      ///< where the c_to geodesic takes over (mm)
  double length = 0.0;                  ///< fibre length carried by friction (mm)
  double angle = 0.0;                   ///< the mandrel's turn over it (rad)
  /// From start to end, phi and length from 0, `angle` the winding angle in (0, pi/2).
  std::vector<PassSample> samples;
  bool reached = true;  ///< false: r sin a did not reach c_to before s_max
};

/// The transition from the geodesic with Clairaut constant c_from at meridian length start_s,
/// running towards larger s, to c_to, at slippage lambda > 0, within s <= s_max.
/// \throw InputError for lambda <= 0, c_from or c_to not in (0, r) at start_s, or a bad step.
FrictionTransition friction_transition(const MeridianLine& m, double start_s, double c_from,
                                       double c_to, double lambda, double s_max, double step = 2.0);

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
    if (y.s < o.s_min || y.s > o.s_max) break;  // off the region: no event
    if (err < 0.03 * o.tolerance) h *= 2.0;
  }
  p.end = y;
  p.length = l;
  return p;
}

}  // namespace windplan
