#include "planner/winding/semi_geodesic.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "geometry/base/errors.h"

namespace windplan {

bool SemiGeodesicOptions::is_valid(std::string* why) const {
  auto fail = [&](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (!(slippage >= 0.0) || !std::isfinite(slippage)) return fail("slippage must be >= 0");
  if (side != 1 && side != -1) return fail("side must be +1 or -1");
  if (!(step > 0.0) || !std::isfinite(step)) return fail("step must be > 0 mm");
  if (!(tolerance > 0.0)) return fail("tolerance must be > 0");
  if (!(max_length > 0.0)) return fail("max_length must be > 0 mm");
  return true;
}

MeridianLine::MeridianLine(const std::vector<Vec2>& points, double window) : pts_(points) {
  if (pts_.size() < 2) throw InputError("semi_geodesic: a meridian needs at least 2 points");
  if (!(window >= 0.0) || !std::isfinite(window)) {
    throw InputError("semi_geodesic: the curvature window must be >= 0 mm");
  }
  cum_.push_back(0.0);
  for (std::size_t i = 1; i < pts_.size(); ++i) {
    cum_.push_back(cum_.back() + (pts_[i] - pts_[i - 1]).norm());
  }
  if (!(cum_.back() > 0.0)) throw InputError("semi_geodesic: the meridian has no length");
  if (window == 0.0) return;
  // Turning angles at the vertices between segments with a length (tangent angle atan2(dr, dx);
  // a turn towards the axis is negative for a meridian running towards larger x), spread with
  // a hat of half-width `window` and unit integral, sampled on a grid.
  std::vector<double> at, turn;
  double prev = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 1; i < pts_.size(); ++i) {
    const Vec2 d = pts_[i] - pts_[i - 1];
    if (!(d.norm() > 0.0)) continue;
    const double th = std::atan2(d.y(), d.x());
    if (std::isfinite(prev)) {
      at.push_back(cum_[i - 1]);
      turn.push_back(std::remainder(th - prev, 2.0 * M_PI));
    }
    prev = th;
  }
  grid_h_ = std::min(0.125 * window, 0.5 * length());
  const int n = static_cast<int>(std::ceil(length() / grid_h_)) + 1;
  kappa_.assign(n, 0.0);
  for (std::size_t j = 0; j < at.size(); ++j) {
    const int lo = std::max(0, static_cast<int>(std::floor((at[j] - window) / grid_h_)));
    const int hi = std::min(n - 1, static_cast<int>(std::ceil((at[j] + window) / grid_h_)));
    for (int i = lo; i <= hi; ++i) {
      const double w = 1.0 - std::abs(i * grid_h_ - at[j]) / window;
      if (w > 0.0) kappa_[i] -= turn[j] * w / window;
    }
  }
}

double MeridianLine::curvature(double s) const {
  if (kappa_.empty() || !(s >= 0.0) || !(s <= length())) return 0.0;
  const double u = s / grid_h_;
  const int i = std::min(static_cast<int>(kappa_.size()) - 2, static_cast<int>(u));
  const double f = u - i;
  return (1.0 - f) * kappa_[i] + f * kappa_[i + 1];
}

int MeridianLine::segment(double s) const {
  // The last segment starting at or before s with a length (zero-length ones are skipped).
  const int n = static_cast<int>(pts_.size()) - 1;
  int i = static_cast<int>(std::upper_bound(cum_.begin(), cum_.end(), s) - cum_.begin()) - 1;
  i = std::clamp(i, 0, n - 1);
  while (i > 0 && cum_[i + 1] - cum_[i] <= 0.0) --i;
  while (i < n - 1 && cum_[i + 1] - cum_[i] <= 0.0) ++i;
  return i;
}

Vec2 MeridianLine::point(double s, Vec2* tangent) const {
  const int i = segment(s);
  const Vec2 t = (pts_[i + 1] - pts_[i]) / (cum_[i + 1] - cum_[i]);  // tangent(s), found once
  if (tangent) *tangent = t;
  return pts_[i] + (s - cum_[i]) * t;
}

Vec2 MeridianLine::tangent(double s) const {
  const int i = segment(s);
  return (pts_[i + 1] - pts_[i]) / (cum_[i + 1] - cum_[i]);
}

double MeridianLine::at_axial(double x) const {
  for (std::size_t i = 1; i < pts_.size(); ++i) {
    const double a = pts_[i - 1].x(), b = pts_[i].x();
    if ((a - x) * (b - x) <= 0.0 && a != b) {
      return cum_[i - 1] + (cum_[i] - cum_[i - 1]) * (x - a) / (b - a);
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double MeridianLine::at_radius(double r, int end) const {
  const int n = static_cast<int>(pts_.size());
  for (int k = 1; k < n; ++k) {
    const int i = end == 0 ? k - 1 : n - 1 - k, j = i + 1;
    const double a = pts_[i].y() - r, b = pts_[j].y() - r;
    if (a * b <= 0.0 && a != b) return cum_[i] + (cum_[j] - cum_[i]) * a / (a - b);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

std::array<double, 3> semi_geodesic_rate(const MeridianLine& m, const MeridianState& y,
                                         double lambda, int side) {
  // point(s) and tangent(s) with one segment search (the rate is the friction planner's
  // innermost call; the same arithmetic as the two calls, so the same bits).
  Vec2 t;
  const double r = m.point(y.s, &t).y();
  if (!(r > 0.0)) {
    std::ostringstream s;
    s << "semi_geodesic: the path reached the axis (radius " << r << " mm) at meridian length "
      << y.s << " mm";
    throw InputError(s.str());
  }
  const double sa = std::sin(y.a), ca = std::cos(y.a);
  const double kn = std::abs(m.curvature(y.s) * ca * ca + sa * sa * std::abs(t.x()) / r);
  return {ca, -sa * t.y() / r + side * lambda * kn, sa / r};
}

namespace semi_geodesic_detail {

MeridianState rk4(const MeridianLine& m, const MeridianState& y, double h, double lambda,
                  int side) {
  auto at = [&](const MeridianState& b, const std::array<double, 3>& k, double f) {
    return MeridianState{b.s + f * k[0], b.a + f * k[1], b.phi + f * k[2]};
  };
  const auto k1 = semi_geodesic_rate(m, y, lambda, side);
  const auto k2 = semi_geodesic_rate(m, at(y, k1, 0.5 * h), lambda, side);
  const auto k3 = semi_geodesic_rate(m, at(y, k2, 0.5 * h), lambda, side);
  const auto k4 = semi_geodesic_rate(m, at(y, k3, h), lambda, side);
  MeridianState out;
  out.s = y.s + h / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]);
  out.a = y.a + h / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]);
  out.phi = y.phi + h / 6.0 * (k1[2] + 2.0 * k2[2] + 2.0 * k3[2] + k4[2]);
  return out;
}

PassSample sample_of(const MeridianLine& m, const MeridianState& y, double length) {
  const Vec2 p = m.point(y.s);
  return {p.x(), p.y(), y.phi, length, y.a};
}

}  // namespace semi_geodesic_detail

FrictionTurnaround friction_turnaround(const MeridianLine& m, int end, double apex_s, double c,
                                       double lambda, double step, bool on_meridian) {
  if (!(lambda > 0.0) || !std::isfinite(lambda)) {
    throw InputError("friction_turnaround: the slippage must be > 0");
  }
  FrictionTurnaround t;
  t.end = end;
  t.slippage = lambda;
  t.c = c;
  t.apex_s = apex_s;
  const Vec2 apex = m.point(apex_s);
  t.apex_x = apex.x();
  t.apex_r = apex.y();
  if (!(c > 0.0) || !(std::abs(c - apex.y()) > 1e-9 * apex.y())) {
    std::ostringstream s;
    s << "friction_turnaround: the Clairaut constant " << c << " mm must be > 0 and differ from "
      << "the apex radius " << apex.y() << " mm";
    throw InputError(s.str());
  }
  // Leaving the apex at the far end the fibre runs back (a > pi/2): sigma = +1 turns a towards
  // pi, lowering r sin a; at the start end a < pi/2 and sigma = -1 lowers it. Raising: the other.
  const bool lower = c < apex.y();
  SemiGeodesicOptions o;
  o.slippage = lambda;
  o.side = (end == 1 ? 1 : -1) * (lower ? 1 : -1);
  o.step = step;
  o.max_length = 200.0 * std::max(m.length(), apex.y());
  if (on_meridian || !lower) {  // raising r sin a is bounded by r: stop off the meridian
    const double margin = on_meridian ? 0.0 : 0.5 * m.length();
    o.s_min = -margin;
    o.s_max = m.length() + margin;
    o.max_length = 20.0 * (m.length() + 2.0 * M_PI * apex.y());
  }
  // Leaving half: from the apex until r sin a reaches c.
  const SemiGeodesicPath half = semi_geodesic(m, MeridianState{apex_s, 0.5 * M_PI, 0.0}, o,
                                              [c](const MeridianLine& ml, const MeridianState& y) {
                                                return ml.point(y.s).y() * std::sin(y.a) - c;
                                              });
  // Beyond the meridian's ends (on_meridian false): the caller's fit check says how far.
  t.reached = half.event && (!on_meridian || (half.end.s >= 0.0 && half.end.s <= m.length()));
  t.lowest = apex.y();
  for (std::size_t i = 0; i < half.samples.size(); ++i) {
    if (half.s[i] < 0.0 || half.s[i] > m.length()) break;  // off the meridian's ends
    const double q = half.samples[i].r * std::sin(half.samples[i].angle);
    if (std::abs(q - c) < std::abs(t.lowest - c)) t.lowest = q;
  }
  const Vec2 join = m.point(half.end.s);
  t.join_s = half.end.s;
  t.join_x = join.x();
  t.join_r = join.y();
  t.pass_angle = std::asin(std::min(1.0, c / join.y()));
  t.length = 2.0 * half.length;
  const double ph = half.end.phi;
  t.angle = 2.0 * ph;
  const std::vector<PassSample>& h = half.samples;
  const double lh = half.length;
  for (std::size_t i = h.size(); i-- > 0;) {  // arriving: the mirror image, reversed
    t.samples.push_back({h[i].x, h[i].r, ph - h[i].phi, lh - h[i].length, M_PI - h[i].angle});
  }
  for (std::size_t i = 1; i < h.size(); ++i) {
    t.samples.push_back({h[i].x, h[i].r, ph + h[i].phi, lh + h[i].length, h[i].angle});
  }
  return t;
}

FrictionTransition friction_transition(const MeridianLine& m, double start_s, double c_from,
                                       double c_to, double lambda, double s_max, double step) {
  if (!(lambda > 0.0) || !std::isfinite(lambda)) {
    throw InputError("friction_transition: the slippage must be > 0");
  }
  const Vec2 p0 = m.point(start_s);
  for (double c : {c_from, c_to}) {
    if (!(c > 0.0 && c < p0.y())) {
      std::ostringstream s;
      s << "friction_transition: the Clairaut constant " << c << " mm must be in (0, " << p0.y()
        << " mm), the radius where the transition starts";
      throw InputError(s.str());
    }
  }
  FrictionTransition t;
  t.slippage = lambda;
  t.c_from = c_from;
  t.c_to = c_to;
  t.start_s = start_s;
  t.start_x = p0.x();
  SemiGeodesicOptions o;
  o.slippage = lambda;
  o.side = c_to > c_from ? 1 : -1;  // a < pi/2: a larger a raises r sin a
  o.step = step;
  o.s_max = s_max;
  o.max_length = 200.0 * std::max(m.length(), p0.y());
  const SemiGeodesicPath path =
      semi_geodesic(m, MeridianState{start_s, std::asin(c_from / p0.y()), 0.0}, o,
                    [c_to](const MeridianLine& ml, const MeridianState& y) {
                      return ml.point(y.s).y() * std::sin(y.a) - c_to;
                    });
  t.reached = path.event && path.end.s <= s_max;
  t.end_s = path.end.s;
  t.end_x = m.point(path.end.s).x();
  t.length = path.length;
  t.angle = path.end.phi;
  t.samples = path.samples;
  return t;
}

}  // namespace windplan
