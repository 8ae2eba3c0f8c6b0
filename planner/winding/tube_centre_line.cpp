#include "planner/winding/tube_centre_line.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "geometry/base/errors.h"

namespace windplan {

TubeCentreLine::TubeCentreLine(double tube_radius, const std::vector<double>& segments,
                               const std::vector<TubeBend>& bends)
    : r_(tube_radius) {
  if (!(tube_radius > 0.0)) throw InputError("tube centre line: the tube radius must be > 0 mm");
  if (segments.empty() || bends.size() + 1 != segments.size()) {
    throw InputError("tube centre line: give one more straight segment than bends");
  }
  // The same construction as parametric_mandrel's spine_pieces: the reference normal u is
  // carried through each bend by the bend's rotation.
  TubeFrame f;
  double s = 0.0;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    if (!(segments[i] >= 0.0)) throw InputError("tube centre line: a segment length is < 0 mm");
    if (segments[i] > 0.0) {
      Piece p;
      p.s0 = s;
      p.len = segments[i];
      p.f0 = f;
      pieces_.push_back(p);
      f.c += segments[i] * f.t;
      s += segments[i];
    }
    if (i >= bends.size()) break;
    const TubeBend& b = bends[i];
    if (!(b.radius > r_)) {
      throw InputError("tube centre line: a bend radius must exceed the tube radius");
    }
    const double phi = b.plane_angle_deg * M_PI / 180.0, th = b.angle_deg * M_PI / 180.0;
    const Vec3 toward = std::cos(phi) * f.u + std::sin(phi) * f.t.cross(f.u);
    Piece p;
    p.bend = true;
    p.s0 = s;
    p.len = b.radius * th;
    p.f0 = f;
    p.f0.kappa = 1.0 / b.radius;
    p.f0.toward = phi;
    p.centre = f.c + b.radius * toward;
    p.axis = f.t.cross(toward).normalized();
    p.angle = th;
    pieces_.push_back(p);
    spans_.push_back({s, s + p.len, 1.0 / b.radius, phi});
    const Eigen::AngleAxisd rot(th, p.axis);
    f.c = p.centre + rot * (f.c - p.centre);
    f.t = (rot * f.t).normalized();
    f.u = (rot * f.u).normalized();
    f.v = f.t.cross(f.u);
    s += p.len;
  }
  if (pieces_.empty()) throw InputError("tube centre line: zero length");
  length_ = s;
}

std::vector<Vec3> TubeCentreLine::polyline(int per_bend) const {
  per_bend = std::max(1, per_bend);
  std::vector<Vec3> pts{pieces_.front().f0.c};
  for (const Piece& p : pieces_) {
    if (!p.bend) {
      pts.push_back(p.f0.c + p.len * p.f0.t);
      continue;
    }
    for (int k = 1; k <= per_bend; ++k) {
      const Eigen::AngleAxisd rot(p.angle * k / per_bend, p.axis);
      pts.push_back(p.centre + rot * (p.f0.c - p.centre));
    }
  }
  return pts;
}

int TubeCentreLine::piece(double s) const {
  int i = static_cast<int>(pieces_.size()) - 1;
  while (i > 0 && s < pieces_[i].s0) --i;
  return i;
}

TubeFrame TubeCentreLine::frame(double s) const {
  // Beyond the ends the end pieces continue straight.
  if (s < 0.0) {
    TubeFrame f = pieces_.front().f0;
    f.c += s * f.t;
    f.kappa = 0.0;
    return f;
  }
  if (s > length_) {
    TubeFrame f = frame(length_);
    f.c += (s - length_) * f.t;
    f.kappa = 0.0;
    return f;
  }
  const Piece& p = pieces_[piece(s)];
  const double ds = s - p.s0;
  TubeFrame f = p.f0;
  if (!p.bend) {
    f.c += ds * f.t;
    return f;
  }
  const Eigen::AngleAxisd rot(ds * p.f0.kappa, p.axis);
  f.c = p.centre + rot * (p.f0.c - p.centre);
  f.t = rot * p.f0.t;
  f.u = rot * p.f0.u;
  f.v = rot * p.f0.v;
  return f;
}

Vec3 TubeCentreLine::point(double s, double theta) const {
  const TubeFrame f = frame(s);
  return f.c + r_ * (std::cos(theta) * f.u + std::sin(theta) * f.v);
}

Vec3 TubeCentreLine::normal(double s, double theta) const {
  const TubeFrame f = frame(s);
  return std::cos(theta) * f.u + std::sin(theta) * f.v;
}

const TubeCentreLine::BendSpan* TubeCentreLine::bend_at(double s) const {
  for (const BendSpan& b : spans_) {
    if (s >= b.s0 && s < b.s1) return &b;
  }
  return nullptr;
}

double TubeCentreLine::stretch(const BendSpan* b, double theta) const {
  return b ? 1.0 - b->kappa * r_ * std::cos(theta - b->toward) : 1.0;
}

double TubeCentreLine::stretch_theta(const BendSpan* b, double theta) const {
  return b ? b->kappa * r_ * std::sin(theta - b->toward) : 0.0;
}

double TubeCentreLine::normal_curvature(const BendSpan* b, double theta, double a) const {
  const double ca = std::cos(a), sa = std::sin(a);
  double along = 0.0;
  if (b) {
    const double c = std::cos(theta - b->toward);
    along = -b->kappa * c / (1.0 - b->kappa * r_ * c);
  }
  return along * ca * ca + sa * sa / r_;
}

double TubeCentreLine::geodesic_turn(const BendSpan* b, double theta, double a) const {
  return stretch_theta(b, theta) * std::cos(a) / (stretch(b, theta) * r_);
}

double TubeCentreLine::stretch(double s, double theta) const { return stretch(bend_at(s), theta); }

double TubeCentreLine::stretch_theta(double s, double theta) const {
  return stretch_theta(bend_at(s), theta);
}

double TubeCentreLine::normal_curvature(double s, double theta, double a) const {
  return normal_curvature(bend_at(s), theta, a);
}

double TubeCentreLine::geodesic_turn(double s, double theta, double a) const {
  return geodesic_turn(bend_at(s), theta, a);
}

void TubeCentreLine::locate(const Vec3& p, double* s_out, double* theta_out,
                            double* distance) const {
  double best = std::numeric_limits<double>::infinity(), best_s = 0.0;
  for (const Piece& pc : pieces_) {
    double ds = 0.0;
    if (!pc.bend) {
      ds = std::clamp((p - pc.f0.c).dot(pc.f0.t), 0.0, pc.len);
    } else {
      // The angle of p about the bend axis from the bend's start, in the bend plane.
      const Vec3 a = pc.f0.c - pc.centre, q = p - pc.centre;
      const Vec3 qp = q - q.dot(pc.axis) * pc.axis;
      const double ang = std::atan2(a.cross(qp).dot(pc.axis), a.dot(qp));
      ds = std::clamp(ang / pc.f0.kappa, 0.0, pc.len);
    }
    const double d = (p - frame(pc.s0 + ds).c).norm();
    if (d < best) {
      best = d;
      best_s = pc.s0 + ds;
    }
  }
  const TubeFrame f = frame(best_s);
  const Vec3 d = p - f.c;
  *s_out = best_s;
  *theta_out = std::atan2(d.dot(f.v), d.dot(f.u));
  *distance = best;
}

int TubeCentreLine::piece_at(double s) const {
  for (std::size_t i = 0; i < spans_.size(); ++i) {
    if (s >= spans_[i].s0 && s < spans_[i].s1) return static_cast<int>(i);
  }
  return -1;
}

std::vector<double> TubeCentreLine::piece_ends() const {
  std::vector<double> e;
  for (const BendSpan& b : spans_) {
    e.push_back(b.s0);
    e.push_back(b.s1);
  }
  return e;
}

TubeSurface::Rates TubeCentreLine::rates(int piece, double, double theta, double a) const {
  const BendSpan* b = piece < 0 ? nullptr : &spans_[piece];
  Rates q;
  q.ds = std::cos(a) / stretch(b, theta);
  q.dth = std::sin(a) / r_;
  q.k_n = normal_curvature(b, theta, a);
  q.w = -geodesic_turn(b, theta, a);
  return q;
}

ConstantAngleDemand TubeCentreLine::demand(double s0, double s1, double a) const {
  return constant_angle_demand(*this, s0, s1, a);
}

double constant_angle_slippage(const TubeCentreLine& line, double s, double theta, double a) {
  const double kn = line.normal_curvature(s, theta, a);
  if (!(kn > 0.0)) return std::numeric_limits<double>::infinity();
  return std::abs(line.geodesic_turn(s, theta, a)) / kn;
}

ConstantAngleDemand constant_angle_demand(const TubeCentreLine& line, double s0, double s1,
                                          double a) {
  ConstantAngleDemand d;
  // On straight pieces k_g = 0 and k_n = sin^2 a / r; in a bend nothing depends on s.
  d.min_k_n = std::pow(std::sin(a), 2) / line.tube_radius();
  d.s = s0;
  for (const TubeCentreLine::BendSpan& b : line.bends()) {
    if (b.s1 <= s0 || b.s0 >= s1) continue;
    const double s = std::max(s0, b.s0);
    for (int k = 0; k < 7200; ++k) {
      const double th = b.toward + M_PI + (k - 3600) * M_PI / 3600.0;  // from the outside
      const double lam = constant_angle_slippage(line, s, th, a);
      d.min_k_n = std::min(d.min_k_n, line.normal_curvature(s, th, a));
      if (lam > d.slippage) {
        d.slippage = lam;
        d.s = s;
        d.theta_outside = (k - 3600) * M_PI / 3600.0;
      }
    }
  }
  return d;
}

}  // namespace windplan
