#include "planner/winding/mesh_tube_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "geometry/base/errors.h"
#include "geometry/base/format_number.h"
#include "geometry/region/plane_section.h"

namespace windplan {

namespace {

constexpr int kCentre = 0, kU = 3, kV = 6, kRho = 9;  // channel offsets
constexpr int kMaxHarmonics = 256;                    // of the convex fit

// Local linear least squares of values y(x) at x0 (tricube weights, half-width w): the value
// and the first derivative there. Linear, not quadratic: inside the data its value is a
// positive-kernel average, so a step in the curvature (a bend meeting a straight) is smoothed
// into a ramp without overshoot (a local quadratic overshoots it by about 5%).
void local_fit(const std::vector<double>& x, const std::vector<std::vector<double>>& y, double x0,
               double w, std::vector<double>* value, std::vector<double>* slope) {
  const std::size_t nc = y.front().size();
  Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(2, static_cast<Eigen::Index>(nc));
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = (x[i] - x0) / w;
    if (std::abs(t) >= 1.0) continue;
    const double k = std::pow(1.0 - std::pow(std::abs(t), 3), 3);
    const Eigen::Vector2d f(1.0, t);
    A += k * f * f.transpose();
    for (std::size_t c = 0; c < nc; ++c) b.col(static_cast<Eigen::Index>(c)) += k * y[i][c] * f;
  }
  const Eigen::MatrixXd sol = A.ldlt().solve(b);
  value->assign(nc, 0.0);
  slope->assign(nc, 0.0);
  for (std::size_t c = 0; c < nc; ++c) {
    (*value)[c] = sol(0, static_cast<Eigen::Index>(c));
    (*slope)[c] = sol(1, static_cast<Eigen::Index>(c)) / w;
  }
}

// Second derivatives of the clamped cubic spline through y (uniform spacing h) with end slopes
// d0, d1 (the tridiagonal system, Thomas' algorithm).
std::vector<double> clamped_spline(const std::vector<double>& y, double h, double d0, double d1) {
  const std::size_t n = y.size();
  std::vector<double> a(n, 1.0), b(n, 4.0), c(n, 1.0), r(n, 0.0);
  b[0] = 2.0;
  r[0] = 6.0 / h * ((y[1] - y[0]) / h - d0);
  b[n - 1] = 2.0;
  r[n - 1] = 6.0 / h * (d1 - (y[n - 1] - y[n - 2]) / h);
  for (std::size_t i = 1; i + 1 < n; ++i) r[i] = 6.0 * (y[i + 1] - 2.0 * y[i] + y[i - 1]) / (h * h);
  for (std::size_t i = 1; i < n; ++i) {
    const double m = a[i] / b[i - 1];
    b[i] -= m * c[i - 1];
    r[i] -= m * r[i - 1];
  }
  std::vector<double> M(n);
  M[n - 1] = r[n - 1] / b[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) M[i] = (r[i] - c[i] * M[i + 1]) / b[i];
  return M;
}

Vec3 any_normal(const Vec3& t) {
  const Vec3 ref = std::abs(t.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return (ref - ref.dot(t) * t).normalized();
}

}  // namespace

struct MeshTubeSurface::Eval {
  Vec3 P, Ps, Pt, Pss, Pst, Ptt, C, U, V;
};

MeshTubeSurface::Eval MeshTubeSurface::eval(double s, double theta) const {
  const int n = static_cast<int>(y_.size());
  const int nc = kRho + 2 * harmonics_ + 1;
  // Channel values and derivatives at s from the interval's cubic; beyond the ends the end
  // node's values (C goes on straight along its end slope).
  std::array<double, kRho + 2 * kMaxHarmonics + 1> v, d1, d2;
  const double sc = std::clamp(s, 0.0, length_);
  const int i = std::min(n - 2, std::max(0, static_cast<int>(std::floor(sc / h_))));
  const double t = sc - i * h_, t2 = t * t;
  const double* p = &poly_[static_cast<std::size_t>(i) * poly_stride_];
  for (int c = 0; c < nc; ++c, p += 4) {
    v[c] = p[0] + t * p[1] + t2 * p[2] + t2 * t * p[3];
    d1[c] = p[1] + 2.0 * t * p[2] + 3.0 * t2 * p[3];
    d2[c] = 2.0 * p[2] + 6.0 * t * p[3];
  }
  if (s != sc) {
    for (int c = 0; c < nc; ++c) {
      if (c < kU) v[c] += (s - sc) * d1[c];
      if (c >= kU) d1[c] = 0.0;
      d2[c] = 0.0;
    }
  }
  auto vec = [](const std::array<double, kRho + 2 * kMaxHarmonics + 1>& x, int c) {
    return Vec3(x[c], x[c + 1], x[c + 2]);
  };
  Eval e;
  e.C = vec(v, kCentre);
  e.U = vec(v, kU);
  e.V = vec(v, kV);
  const Vec3 C1 = vec(d1, kCentre), C2 = vec(d2, kCentre);
  const Vec3 U1 = vec(d1, kU), U2 = vec(d2, kU), V1 = vec(d1, kV), V2 = vec(d2, kV);
  // rho and its derivatives from the Fourier series (cos k theta, sin k theta by recurrence);
  // in the convex fit the series is u = 1 / rho's, turned into rho's below.
  double r = v[kRho], rs = d1[kRho], rss = d2[kRho], rt = 0.0, rtt = 0.0, rst = 0.0;
  const double c1 = std::cos(theta), s1 = std::sin(theta);
  double ck = 1.0, sk = 0.0;
  for (int k = 1; k <= harmonics_; ++k) {
    const double cn = ck * c1 - sk * s1, sn = sk * c1 + ck * s1;
    ck = cn;
    sk = sn;
    const int ca = kRho + 2 * k - 1, cb = kRho + 2 * k;
    r += v[ca] * ck + v[cb] * sk;
    rs += d1[ca] * ck + d1[cb] * sk;
    rss += d2[ca] * ck + d2[cb] * sk;
    rt += k * (-v[ca] * sk + v[cb] * ck);
    rtt -= k * k * (v[ca] * ck + v[cb] * sk);
    rst += k * (-d1[ca] * sk + d1[cb] * ck);
  }
  if (inverse_) {
    // rho = 1 / u: rho' = -u' / u^2, rho'' = -u'' / u^2 + 2 u'^2 / u^3 (mixed alike).
    const double u = r, i2 = 1.0 / (u * u), i3 = i2 / u;
    const double us = rs, ut = rt;
    r = 1.0 / u;
    rs = -us * i2;
    rt = -ut * i2;
    rss = -rss * i2 + 2.0 * us * us * i3;
    rtt = -rtt * i2 + 2.0 * ut * ut * i3;
    rst = -rst * i2 + 2.0 * us * ut * i3;
  }
  const Vec3 d = c1 * e.U + s1 * e.V, dp = -s1 * e.U + c1 * e.V;
  const Vec3 ds = c1 * U1 + s1 * V1, dss = c1 * U2 + s1 * V2, dps = -s1 * U1 + c1 * V1;
  e.P = e.C + r * d;
  e.Ps = C1 + rs * d + r * ds;
  e.Pt = rt * d + r * dp;
  e.Pss = C2 + rss * d + 2.0 * rs * ds + r * dss;
  e.Pst = rst * d + rs * dp + rt * ds + r * dps;
  e.Ptt = rtt * d + 2.0 * rt * dp - r * d;
  return e;
}

void MeshTubeSurface::build_polynomials() {
  // Per interval and channel: v = p0 + p1 t + p2 t^2 + p3 t^3 (t from the interval's start).
  const int n = static_cast<int>(y_.size());
  const int nc = kRho + 2 * harmonics_ + 1;
  poly_stride_ = 4 * static_cast<std::size_t>(nc);
  poly_.assign(static_cast<std::size_t>(n - 1) * poly_stride_, 0.0);
  for (int i = 0; i + 1 < n; ++i) {
    for (int c = 0; c < nc; ++c) {
      const double y0 = y_[i][c], y1 = y_[i + 1][c], m0 = m_[i][c], m1 = m_[i + 1][c];
      double* p = &poly_[i * poly_stride_ + 4 * c];
      p[0] = y0;
      p[1] = (y1 - y0) / h_ - h_ * (2.0 * m0 + m1) / 6.0;
      p[2] = 0.5 * m0;
      p[3] = (m1 - m0) / (6.0 * h_);
    }
  }
}

Vec3 MeshTubeSurface::point(double s, double theta) const { return eval(s, theta).P; }

Vec3 MeshTubeSurface::normal(double s, double theta) const {
  const Eval e = eval(s, theta);
  return e.Pt.cross(e.Ps).normalized();  // outward: P_theta x P_s (theta turns about +C')
}

TubeSurface::Rates MeshTubeSurface::rates(int, double s, double theta, double a) const {
  const Eval e = eval(s, theta);
  const Vec3 n = e.Pt.cross(e.Ps).normalized();
  const double h = e.Ps.norm();
  const Vec3 e1 = e.Ps / h, e2 = e1.cross(n);
  const double m = e.Pt.dot(e1), g = e.Pt.dot(e2);
  const double ca = std::cos(a), sa = std::sin(a);
  Rates q;
  q.dth = sa / g;
  q.ds = (ca - m * q.dth) / h;
  q.k_n = -(e.Pss * (q.ds * q.ds) + 2.0 * e.Pst * (q.ds * q.dth) + e.Ptt * (q.dth * q.dth)).dot(n);
  q.w = (e.Pss * q.ds + e.Pst * q.dth).dot(e2) / h;
  return q;
}

void MeshTubeSurface::centre(double s, Vec3* c, Vec3* c1, Vec3* c2) const {
  // The centre's channels only: the series at theta = 0 costs little more.
  const Eval e = eval(s, 0.0);
  *c = e.C;
  const double eps = 1e-3 * h_;
  const Eval a = eval(s - eps, 0.0), b = eval(s + eps, 0.0);
  if (c1) *c1 = (b.C - a.C) / (2.0 * eps);
  if (c2) *c2 = (b.C - 2.0 * e.C + a.C) / (eps * eps);
}

namespace {

// Cumulative chord length of the section at s over theta_j = 2 pi j / n, j = 0..n.
std::vector<double> section_table(const MeshTubeSurface& m, double s, int n) {
  std::vector<double> t(n + 1, 0.0);
  Vec3 prev = m.point(s, 0.0);
  for (int j = 1; j <= n; ++j) {
    const Vec3 p = m.point(s, 2.0 * M_PI * j / n);
    t[j] = t[j - 1] + (p - prev).norm();
    prev = p;
  }
  return t;
}

constexpr int kEvenSamples = 720;

}  // namespace

double MeshTubeSurface::even_angle(double s, double theta) const {
  const std::vector<double> t = section_table(*this, s, kEvenSamples);
  const double turns = std::floor(theta / (2.0 * M_PI));
  const double x = (theta - 2.0 * M_PI * turns) / (2.0 * M_PI) * kEvenSamples;
  const int j = std::min(kEvenSamples - 1, static_cast<int>(x));
  const double sigma = t[j] + (x - j) * (t[j + 1] - t[j]);
  return 2.0 * M_PI * (turns + sigma / t[kEvenSamples]);
}

double MeshTubeSurface::from_even_angle(double s, double psi) const {
  const std::vector<double> t = section_table(*this, s, kEvenSamples);
  const double turns = std::floor(psi / (2.0 * M_PI));
  const double sigma = (psi / (2.0 * M_PI) - turns) * t[kEvenSamples];
  const int j =
      std::clamp(static_cast<int>(std::upper_bound(t.begin(), t.end(), sigma) - t.begin()) - 1, 0,
                 kEvenSamples - 1);
  const double x = j + (t[j + 1] > t[j] ? (sigma - t[j]) / (t[j + 1] - t[j]) : 0.0);
  return 2.0 * M_PI * (turns + x / kEvenSamples);
}

double MeshTubeSurface::girth(double s) const {
  return section_table(*this, s, kEvenSamples).back();
}

void MeshTubeSurface::locate(const Vec3& p, double* s, double* theta, double* distance) const {
  double t = nodes_.project(p);
  // Newton on (p - C(s)) . C'(s) = 0 from the polyline's guess.
  for (int it = 0; it < 4; ++it) {
    const Eval e = eval(t, 0.0);
    const double eps = 1e-3 * h_;
    const Vec3 c1 = (eval(t + eps, 0.0).C - eval(t - eps, 0.0).C) / (2.0 * eps);
    const double f = (p - e.C).dot(c1), fp = -c1.squaredNorm();
    t = std::clamp(t - f / fp, 0.0, length_);
  }
  const Eval e = eval(t, 0.0);
  const Vec3 d = p - e.C;
  *s = t;
  *theta = std::atan2(d.dot(e.V), d.dot(e.U));
  *distance = d.norm();
}

ConstantAngleDemand MeshTubeSurface::demand(double s0, double s1, double a) const {
  ConstantAngleDemand d = TubeSurface::demand(s0, s1, a);
  const Eval e = eval(d.s, 0.0);
  Vec3 c, c1, c2;
  centre(d.s, &c, &c1, &c2);
  // Outside of the bend: opposite the centre line's curvature vector (theta unchanged where the
  // centre line is straight).
  const Vec3 k = c2 - c2.dot(c1.normalized()) * c1.normalized();
  if (k.norm() > 1e-9) {
    const double toward = std::atan2(k.dot(e.V), k.dot(e.U));
    d.theta_outside = std::remainder(d.theta_outside - toward - M_PI, 2.0 * M_PI);
  }
  return d;
}

bool MeshTubeSurfaceOptions::is_valid(std::string* why) const {
  auto fail = [&](const std::string& m) {
    if (why) *why = m;
    return false;
  };
  if (!std::isnan(step) && !(step > 0.0)) return fail("step must be > 0 mm");
  if (!std::isnan(window) && !(window > 0.0)) return fail("window must be > 0 mm");
  if (harmonics < 1 || harmonics > 64) return fail("harmonics must be in 1..64");
  if (rays < 4 * harmonics) return fail("rays must be at least 4 x harmonics");
  if (!(convex_width >= 0.03 && convex_width <= 1.0)) {
    return fail("convex_width must be in 0.03..1 rad");
  }
  return true;
}

std::string MeshTubeSurfaceSummary::brief_report() const {
  return std::to_string(sections) + " sections every " + format_fixed(step, 2) +
         " mm, smoothed over +-" + format_fixed(window, 1) + " mm, mean radius " +
         format_fixed(mean_radius, 2) + " mm, " + std::to_string(harmonics) + " harmonics" +
         (convex_fit ? " of 1 / rho (convex fit)" : "") + ", fit within " +
         format_fixed(fit_residual, 3) + " mm of the rays" +
         (non_star_rays > 0 ? ", " + std::to_string(non_star_rays) + " rays met a section twice"
                            : std::string());
}

MeshTubeSurfaceResult mesh_tube_surface(const Mesh& mesh, const Spine& spine,
                                        const SpindleAxis& axis, const MeshTubeSurfaceOptions& o) {
  std::string why;
  if (!o.is_valid(&why)) throw ConfigError("tube surface: " + why);
  if (spine.empty()) throw InputError("tube surface: the centre line is empty");
  MeshTubeSurfaceResult res;
  auto surf = std::make_shared<MeshTubeSurface>();
  MeshTubeSurfaceSummary& sum = res.summary;
  // The mean radius from the spine's end points' distances to the mesh boundary is not at
  // hand: the mean distance of the vertices from the spine serves.
  double rsum = 0.0;
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    double dist = 0.0;
    spine.project(mesh.position(v), &dist);
    rsum += dist;
  }
  const double r_mean = rsum / std::max(1, mesh.num_vertices());
  const double L = spine.length();
  double step = std::isnan(o.step) ? 0.25 * r_mean : o.step;
  const int n = std::max(2, static_cast<int>(std::ceil(L / step)) + 1);
  step = L / (n - 1);
  const double window = std::isnan(o.window) ? std::max(0.75 * r_mean, 2.5 * step) : o.window;
  sum.step = step;
  sum.window = window;
  sum.sections = n;
  // The centre line: local fits of the spine's points, then a clamped spline.
  std::vector<std::vector<double>> pts;
  for (const Vec3& p : spine.points) pts.push_back({p.x(), p.y(), p.z()});
  std::vector<std::vector<double>> cy(n);
  std::vector<std::vector<double>> cd(n);
  for (int i = 0; i < n; ++i) local_fit(spine.s, pts, step * i, window, &cy[i], &cd[i]);
  const int M = o.harmonics, nc = kRho + 2 * M + 1;
  surf->h_ = step;
  surf->length_ = L;
  surf->y_.assign(n, std::vector<double>(nc, 0.0));
  surf->m_.assign(n, std::vector<double>(nc, 0.0));
  auto fit_channels = [&](int c0, int count, const std::vector<std::vector<double>>& val,
                          const std::vector<std::vector<double>>& slope) {
    for (int c = c0; c < c0 + count; ++c) {
      std::vector<double> y(n);
      for (int i = 0; i < n; ++i) y[i] = val[i][c - c0];
      const std::vector<double> m = clamped_spline(y, step, slope[0][c - c0], slope[n - 1][c - c0]);
      for (int i = 0; i < n; ++i) {
        surf->y_[i][c] = y[i];
        surf->m_[i][c] = m[i];
      }
    }
  };
  fit_channels(kCentre, 3, cy, cd);
  surf->harmonics_ = 0;
  surf->build_polynomials();
  // The rotation-minimising frame at the nodes (double reflection), along the spline's tangent.
  std::vector<Vec3> C(n), T(n), U(n), V(n);
  for (int i = 0; i < n; ++i) {
    Vec3 c, c1;
    surf->centre(step * i, &c, &c1, nullptr);
    C[i] = c;
    T[i] = c1.normalized();
  }
  U[0] = any_normal(T[0]);
  for (int i = 0; i + 1 < n; ++i) {
    const Vec3 v1 = C[i + 1] - C[i];
    const double c1 = v1.squaredNorm();
    const Vec3 rL = U[i] - (2.0 / c1) * v1.dot(U[i]) * v1;
    const Vec3 tL = T[i] - (2.0 / c1) * v1.dot(T[i]) * v1;
    const Vec3 v2 = T[i + 1] - tL;
    const double c2 = v2.squaredNorm();
    U[i + 1] = c2 > 0.0 ? (rL - (2.0 / c2) * v2.dot(rL) * v2) : rL;
    U[i + 1] = (U[i + 1] - U[i + 1].dot(T[i + 1]) * T[i + 1]).normalized();
  }
  for (int i = 0; i < n; ++i) V[i] = T[i].cross(U[i]);
  std::vector<std::vector<double>> fy(n), fd(n, std::vector<double>(6, 0.0));
  for (int i = 0; i < n; ++i) {
    fy[i] = {U[i].x(), U[i].y(), U[i].z(), V[i].x(), V[i].y(), V[i].z()};
  }
  for (int e : {0, n - 1}) {  // end slopes of the frame: one-sided differences
    const int a = e == 0 ? 0 : n - 2;
    for (int c = 0; c < 6; ++c) fd[e][c] = (fy[a + 1][c] - fy[a][c]) / step;
  }
  fit_channels(kU, 6, fy, fd);
  surf->build_polynomials();
  // rho: rays in each node's section, a Fourier series, smoothed along s.
  // The farthest crossing of the ray from the origin at angle th with the closed polygon q
  // (-1 if none), the count of crossings and the second farthest.
  auto cast = [](const std::vector<Eigen::Vector2d>& q, double th, int* hits_out,
                 double* second_out) {
    const Eigen::Vector2d dir(std::cos(th), std::sin(th));
    double best = -1.0, second = -1.0;
    int hits = 0;
    for (std::size_t k = 0; k < q.size(); ++k) {
      const Eigen::Vector2d a = q[k], b = q[(k + 1) % q.size()], e = b - a;
      const double den = dir.x() * (-e.y()) - dir.y() * (-e.x());
      if (std::abs(den) < 1e-300) continue;
      // dir rho = a + tau e  ->  rho dir - tau e = a
      const double rho = (a.x() * (-e.y()) - a.y() * (-e.x())) / den;
      const double tau = (dir.x() * a.y() - dir.y() * a.x()) / den;
      // (a ray through a vertex meets both its segments, within rounding)
      if (tau >= -1e-9 && tau <= 1.0 + 1e-9 && rho > 0.0) {
        ++hits;
        second = std::min(best, rho) > second ? std::min(best, rho) : second;
        best = std::max(best, rho);
      }
    }
    *hits_out = hits;
    *second_out = second;
    return best;
  };
  std::vector<std::vector<Eigen::Vector2d>> polys(n);
  const PlaneSectioner sectioner(mesh, axis);
  const int R = o.rays;
  std::vector<std::vector<double>> coef(n, std::vector<double>(2 * M + 1, 0.0));
  std::vector<std::vector<double>> rays(n, std::vector<double>(R, 0.0));
  for (int i = 0; i < n; ++i) {
    // The end nodes' sections are cut a little inside (off the boundary loops themselves, which
    // the smoothed centre line need not meet quite normally): 1% of the radius, more if needed.
    double si = step * i;
    Vec3 c, c1, t;
    PlaneSection sec;
    bool found = false;
    for (double inset : {0.0, 0.01, 0.03, 0.06, 0.1, 0.2}) {
      si = std::clamp(step * i, inset * r_mean, L - inset * r_mean);
      if (inset == 0.0 && i > 0 && i + 1 < n) si = step * i;
      if (inset == 0.0 && (i == 0 || i + 1 == n)) continue;
      surf->centre(si, &c, &c1, nullptr);
      t = c1.normalized();
      if (sectioner.around_loop(t, t.dot(c), &c, &sec) && sec.points.size() >= 3) {
        found = true;
        break;
      }
      if (i > 0 && i + 1 < n) break;
    }
    if (!found) {
      throw InputError("tube surface: the section normal to the centre line at " +
                       format_fixed(si, 1) + " mm does not go around the tube");
    }
    // The node's own frame, moved to si (only at the ends, by a few millimetres at most).
    const Vec3 u = (U[i] - U[i].dot(t) * t).normalized(), v = t.cross(u);
    std::vector<Eigen::Vector2d> q;
    for (const Vec3& p : sec.points) q.emplace_back((p - c).dot(u), (p - c).dot(v));
    polys[i] = q;
    for (int j = 0; j < R; ++j) {
      const double th = 2.0 * M_PI * j / R;
      double second = -1.0;
      int hits = 0;
      const double best = cast(q, th, &hits, &second);
      if (best <= 0.0) {
        throw InputError("tube surface: a ray from the centre line at " + format_fixed(si, 1) +
                         " mm misses its section (the section does not enclose the centre)");
      }
      if (hits > 2 || (hits == 2 && best - second > 1e-6 * best)) ++sum.non_star_rays;
      rays[i][j] = best;
      coef[i][0] += best / R;
      for (int k = 1; k <= M; ++k) {
        coef[i][2 * k - 1] += 2.0 * best * std::cos(k * th) / R;
        coef[i][2 * k] += 2.0 * best * std::sin(k * th) / R;
      }
    }
  }
  // The series' section curvature, sign of rho^2 + 2 rho'^2 - rho rho'' (720 angles per node):
  // where it is negative beyond 1e-3 / r_mean, the convex fit of u = 1 / rho.
  double least = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < 720; ++j) {
      const double th = 2.0 * M_PI * j / 720;
      double r = coef[i][0], rt = 0.0, rtt = 0.0;
      for (int k = 1; k <= M; ++k) {
        const double c = std::cos(k * th), sn = std::sin(k * th);
        r += coef[i][2 * k - 1] * c + coef[i][2 * k] * sn;
        rt += k * (-coef[i][2 * k - 1] * sn + coef[i][2 * k] * c);
        rtt -= k * k * (coef[i][2 * k - 1] * c + coef[i][2 * k] * sn);
      }
      const double kappa = (r * r + 2.0 * rt * rt - r * rtt) / std::pow(r * r + rt * rt, 1.5);
      least = std::min(least, kappa * r_mean);
    }
  }
  sum.least_curvature = least;
  int terms = M;
  if (least < -1e-3) {
    // The kernel's series down to 1e-9 of its first term: 6.5 / width terms.
    terms = std::min(kMaxHarmonics, static_cast<int>(std::ceil(6.5 / o.convex_width)));
    const int R2 = std::max(R, 4 * terms);
    sum.convex_fit = true;
    surf->inverse_ = true;
    const int nct = kRho + 2 * terms + 1;
    for (auto& row : surf->y_) row.resize(nct, 0.0);
    for (auto& row : surf->m_) row.resize(nct, 0.0);
    for (int i = 0; i < n; ++i) {
      coef[i].assign(2 * terms + 1, 0.0);
      for (int j = 0; j < R2; ++j) {
        const double th = 2.0 * M_PI * j / R2;
        int hits = 0;
        double second = 0.0;
        const double u = 1.0 / cast(polys[i], th, &hits, &second);
        coef[i][0] += u / R2;
        for (int k = 1; k <= terms; ++k) {
          const double g = std::exp(-0.5 * std::pow(k * o.convex_width, 2));
          coef[i][2 * k - 1] += 2.0 * g * u * std::cos(k * th) / R2;
          coef[i][2 * k] += 2.0 * g * u * std::sin(k * th) / R2;
        }
      }
    }
  }
  std::vector<double> nodes_s(n);
  for (int i = 0; i < n; ++i) nodes_s[i] = step * i;
  std::vector<std::vector<double>> ry(n), rd(n);
  for (int i = 0; i < n; ++i) local_fit(nodes_s, coef, step * i, window, &ry[i], &rd[i]);
  fit_channels(kRho, 2 * terms + 1, ry, rd);
  // Harmonics that change no curvature: dropped (k^2 |c_k| below 1e-5 of the mean radius at
  // every node, i.e. under 1e-5 of k_n around the section; of 1 / r_mean in the convex fit).
  int keep = 0;
  const double scale = surf->inverse_ ? 1.0 / r_mean : r_mean;
  for (int k = 1; k <= terms; ++k) {
    for (int i = 0; i < n; ++i) {
      const double amp = std::hypot(surf->y_[i][kRho + 2 * k - 1], surf->y_[i][kRho + 2 * k]);
      if (k * k * amp > 1e-5 * scale) keep = k;
    }
  }
  // (The convex fit keeps every term: its smoothing kernel is positive only whole.)
  surf->harmonics_ = surf->inverse_ ? terms : keep;
  surf->build_polynomials();
  // Figures: the fit against the rays, the mean radius, the largest girth.
  double mean = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < R; ++j) {
      const double th = 2.0 * M_PI * j / R;
      const double rho = (surf->point(step * i, th) - C[i]).norm();
      sum.fit_residual = std::max(sum.fit_residual, std::abs(rho - rays[i][j]));
      mean += rho / (static_cast<double>(n) * R);
    }
    surf->section_radius_ = std::max(surf->section_radius_, surf->girth(step * i) / (2.0 * M_PI));
  }
  sum.mean_radius = mean;
  sum.harmonics = surf->harmonics_;
  surf->nodes_ = spine_from_polyline(C);
  res.surface = std::move(surf);
  return res;
}

}  // namespace windplan
