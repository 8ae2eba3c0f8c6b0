// The fitted tube surface of a mesh (planner/winding/mesh_tube_surface.h) against closed forms:
// a straight tube of elliptical section is developable, so a constant angle to its rulings is a
// geodesic (no slippage needed) that unrolls to a straight line; on a torus-bend mesh the
// geodesic term and k_n match tube_centre_line.h's closed forms, so a 55 deg layer plans within
// mu on a 5r elbow mesh and is refused with about 0.33 on a 3r one.
#include "planner/winding/mesh_tube_surface.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geometry/base/errors.h"
#include "geometry/region/spine.h"
#include "planner/winding/tube_centre_line.h"
#include "planner/winding/tube_friction.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

// A tube mesh from rings P(s_i, theta_j), s_i = L i / m, n points around (the fixture's
// triangulation, outward).
Mesh tube_mesh(const std::function<Vec3(double, double)>& P, double L, int n, int m) {
  TriangleSoup soup = test::open_cylinder(1.0, 1.0, n, m);
  for (int i = 0; i <= m; ++i) {
    for (int j = 0; j < n; ++j) soup.points[i * n + j] = P(L * i / m, 2.0 * M_PI * j / n);
  }
  return Mesh(soup);
}

struct Fitted {
  Mesh mesh;
  MeshTubeSurfaceResult fit;
};

Fitted fit(const std::function<Vec3(double, double)>& P, double L, int n, int m) {
  Fitted f;
  f.mesh = tube_mesh(P, L, n, m);
  const auto loops = test::revolution_loops(n, m);
  const SpineResult sp = extract_spine(f.mesh, loops, SpindleAxis{});
  f.fit = mesh_tube_surface(f.mesh, sp.spine, SpindleAxis{});
  return f;
}

const double kA = 80.0, kB = 50.0;

Vec3 ellipse(double z, double t) { return Vec3(kA * std::cos(t), kB * std::sin(t), z); }

// Arc length of the ellipse from its parameter 0 to t (Simpson, 2000 panels per radian).
double ellipse_arc(double t) {
  auto f = [](double u) { return std::hypot(kA * std::sin(u), kB * std::cos(u)); };
  const int n = std::max(2, 2 * static_cast<int>(std::ceil(std::abs(t) * 1000.0)));
  const double h = t / n;
  double sum = f(0.0) + f(t);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(i * h);
  return sum * h / 3.0;
}

TEST(MeshTubeSurface, EllipticalCylinderNeedsNoSlippage) {
  const Fitted f = fit(ellipse, 600.0, 360, 60);
  const MeshTubeSurface& s = *f.fit.surface;
  EXPECT_NEAR(s.length(), 600.0, 0.01);
  EXPECT_LT(f.fit.summary.fit_residual, 0.01) << f.fit.summary.brief_report();
  for (double a : {30.0, 55.0, 75.0}) {
    const ConstantAngleDemand d = s.demand(50.0, 550.0, a * M_PI / 180.0);
    EXPECT_LT(d.slippage, 0.01) << a << " deg";
    EXPECT_GT(d.min_k_n, 0.0);
  }
  // k_n around the section (a = 90 deg) against the ellipse's curvature at the vertices.
  double s0 = 0.0, t0 = 0.0, dist = 0.0;
  s.locate(Vec3(kA, 0.0, 300.0), &s0, &t0, &dist);
  EXPECT_NEAR(s.rates(s0, t0, 0.5 * M_PI).k_n, kA / (kB * kB), 0.01 * kA / (kB * kB));
  s.locate(Vec3(0.0, kB, 300.0), &s0, &t0, &dist);
  EXPECT_NEAR(s.rates(s0, t0, 0.5 * M_PI).k_n, kB / (kA * kA), 0.01 * kB / (kA * kA));
}

TEST(MeshTubeSurface, EllipticalCylinderPassUnrollsToAStraightLine) {
  const Fitted f = fit(ellipse, 600.0, 360, 60);
  WindingOptions o;
  o.angle = 55.0;
  o.slippage = 0.15;
  o.mu = 0.2;
  o.band_width = 12.0;
  o.circuits = 3;
  const TubeFrictionWinding w =
      plan_tube_friction(*f.fit.surface, 0.0, 600.0, f.mesh, {}, SpindleAxis{}, o);
  EXPECT_LT(w.required, 0.01);
  ASSERT_EQ(w.circuits.size(), 3u);
  EXPECT_TRUE(w.summary.closed) << w.summary.brief_report();
  // The outgoing pass of circuit 0 between z = 200 and 400 (clear of the turnarounds): the
  // ellipse's arc length from the first point grows as (z - z0) tan 55 (the unrolled line).
  const double ta = std::tan(55.0 * M_PI / 180.0);
  const Circuit& c = w.circuits[0];
  const int far = c.segments.front().last;
  double z0 = 0.0, arc0 = 0.0, prev_t = 0.0, unwrap = 0.0, worst = 0.0;
  bool started = false;
  int n = 0;
  for (int i = 0; i <= far; ++i) {
    const Vec3 p = c.points[i].position;
    if (p.z() < 200.0 || p.z() > 400.0) continue;
    double t = std::atan2(p.y() / kB, p.x() / kA);
    if (started) {
      while (t + unwrap - prev_t < -M_PI) unwrap += 2.0 * M_PI;
      while (t + unwrap - prev_t > M_PI) unwrap -= 2.0 * M_PI;
    }
    t += unwrap;
    const double arc = t >= 0.0 ? ellipse_arc(t) : -ellipse_arc(-t);
    if (!started) {
      z0 = p.z();
      arc0 = arc;
      started = true;
    }
    prev_t = t;
    worst = std::max(worst, std::abs(arc - arc0 - (p.z() - z0) * ta));
    ++n;
  }
  EXPECT_GT(n, 100);
  EXPECT_LT(worst, 0.1);
}

// A 90 deg elbow (tube radius 50, bend radius R, legs of 100) tessellated finely.
Fitted elbow(double R, TubeCentreLine* line) {
  *line = TubeCentreLine(50.0, {100.0, 100.0}, {{90.0, R, 0.0}});
  const TubeCentreLine& l = *line;
  const int m = static_cast<int>(std::ceil(l.length() / 2.0));
  return fit([&l](double s, double t) { return l.point(s, t); }, l.length(), 180, m);
}

TEST(MeshTubeSurface, TorusGeodesicTermMatchesTheClosedForm) {
  for (double R : {250.0, 150.0}) {
    TubeCentreLine line(50.0, {100.0}, {});
    const Fitted f = elbow(R, &line);
    const MeshTubeSurface& s = *f.fit.surface;
    const double a = 55.0 * M_PI / 180.0, mid = 100.0 + 0.25 * M_PI * R;
    double worst_exact = 0.0, worst_mesh = 0.0, err = 0.0;
    for (int k = 0; k < 360; ++k) {
      const double th = 2.0 * M_PI * k / 360.0;
      double sm = 0.0, tm = 0.0, d = 0.0;
      s.locate(line.point(mid, th), &sm, &tm, &d);
      const TubeSurface::Rates q = s.rates(sm, tm, a), e = line.rates(mid, th, a);
      const double lm = std::abs(q.w) / q.k_n, le = std::abs(e.w) / e.k_n;
      worst_exact = std::max(worst_exact, le);
      worst_mesh = std::max(worst_mesh, lm);
      err = std::max(err, std::abs(q.w - e.w) / std::abs(e.k_n));
      EXPECT_NEAR(q.k_n, e.k_n, 0.03 * e.k_n) << "R " << R << " theta " << k;
    }
    EXPECT_NEAR(worst_exact, R == 250.0 ? 0.179 : 0.328, 1e-3);
    EXPECT_NEAR(worst_mesh, worst_exact, 0.03 * worst_exact) << "R " << R;
    EXPECT_LT(err, 0.03 * worst_exact) << "R " << R;  // the sign too
  }
}

TEST(MeshTubeSurface, FivePipeRadiusElbowMeshPlansWithinMu) {
  TubeCentreLine line(50.0, {100.0}, {});
  const Fitted f = elbow(250.0, &line);
  WindingOptions o;
  o.angle = 55.0;
  o.slippage = 0.19;
  o.mu = 0.2;
  o.band_width = 12.0;
  const MeshTubeSurface& s = *f.fit.surface;
  const TubeFrictionWinding w =
      plan_tube_friction(s, 0.0, s.length(), f.mesh, {}, SpindleAxis{}, o);
  EXPECT_NEAR(w.required, 0.179, 0.03 * 0.179);
  EXPECT_TRUE(w.summary.closed) << w.summary.brief_report();
  EXPECT_EQ(w.K, 16);
  double worst = 0.0;
  for (const Circuit& c : w.circuits) {
    for (const FibrePoint& q : c.points) worst = std::max(worst, q.slippage);
  }
  EXPECT_LE(worst, 0.2);
}

TEST(MeshTubeSurface, ThreePipeRadiusElbowMeshIsRefusedWithTheSlippageItNeeds) {
  TubeCentreLine line(50.0, {100.0}, {});
  const Fitted f = elbow(150.0, &line);
  WindingOptions o;
  o.angle = 55.0;
  o.slippage = 0.19;
  o.mu = 0.2;
  o.band_width = 12.0;
  const MeshTubeSurface& s = *f.fit.surface;
  try {
    plan_tube_friction(s, 0.0, s.length(), f.mesh, {}, SpindleAxis{}, o);
    FAIL() << "a 3r elbow mesh at 55 deg was planned within slippage 0.19";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("winding.angle 55 deg needs |k_g/k_n| up to 0.3"), std::string::npos) << m;
    const double v = std::stod(m.substr(m.find("up to ") + 6));
    EXPECT_NEAR(v, 0.328, 0.03 * 0.328) << m;
  }
}

// A rounded rectangle 120 x 80 with 15 mm corners, by the fraction t / (2 pi) of its girth
// from the middle of the +x side, counter-clockwise.
Vec3 rounded_rectangle(double z, double t) {
  const double hw = 60.0, hh = 40.0, rc = 15.0, fx = hh - rc, fy = hw - rc;  // half flats
  const double girth = 4.0 * (fx + fy) + 2.0 * M_PI * rc;
  double l = std::fmod(t / (2.0 * M_PI), 1.0) * girth;
  if (l < 0.0) l += girth;
  // Four quarter pieces, each: half a side along, a corner, half the next side.
  const double q = 0.25 * girth;
  const int k = std::min(3, static_cast<int>(l / q));
  l -= k * q;
  const double a = k % 2 == 0 ? fx : fy, b = k % 2 == 0 ? fy : fx;  // half flats before, after
  const double ex = k % 2 == 0 ? hw : hh;                           // distance of the first side
  double x, y;  // in the quarter's frame: the first side is x = ex, going +y
  if (l <= a) {
    x = ex;
    y = l;
  } else if (l <= a + 0.5 * M_PI * rc) {
    const double phi = (l - a) / rc;
    x = ex - rc + rc * std::cos(phi);
    y = a + rc * std::sin(phi);
  } else {
    x = ex - rc - (l - a - 0.5 * M_PI * rc);
    y = a + rc;
  }
  (void)b;
  const double c = std::cos(0.5 * M_PI * k), sn = std::sin(0.5 * M_PI * k);
  return Vec3(c * x - sn * y, sn * x + c * y, z);
}

// A rounded rectangle's flat sides have no curvature across them: the series of rho ripples
// below 0 there, so the section is fitted by the smoothed series of 1 / rho, which keeps it
// convex. Checked around the mid section at a = 90 deg (across the tube): k_n >= 0 everywhere,
// ~0 in the middle of the flats, and its integral over a quarter (mid-flat to mid-flat) is the
// quarter turn pi / 2 (whatever the smoothing); the geodesic term is 0 (a straight tube), so a
// 55 deg layer needs no slippage.
TEST(MeshTubeSurface, RoundedRectangleFitStaysConvexAndTurnsAQuarterPerCorner) {
  const Fitted f = fit(rounded_rectangle, 400.0, 400, 40);
  const MeshTubeSurface& s = *f.fit.surface;
  EXPECT_TRUE(f.fit.summary.convex_fit) << f.fit.summary.brief_report();
  EXPECT_LT(f.fit.summary.least_curvature, -1e-3);  // the plain series is not convex
  EXPECT_LT(f.fit.summary.fit_residual, 0.5) << f.fit.summary.brief_report();  // 0.34
  const double z = 0.5 * s.length();
  double theta0 = 0.0, dist = 0.0, sz = 0.0;
  s.locate(Vec3(60.0, 0.0, 200.0), &sz, &theta0, &dist);  // the middle of the +x side
  EXPECT_NEAR(dist, 60.0, 0.5);
  const int n = 4000;
  double turn = 0.0, least = 1.0;
  Vec3 prev = s.point(z, theta0);
  for (int j = 1; j <= n; ++j) {
    const double th = theta0 + 0.5 * M_PI * j / n;  // a quarter of theta: to the +y side's middle
    const Vec3 p = s.point(z, th);
    const TubeSurface::Rates q = s.rates(z, th - 0.25 * M_PI / n, 0.5 * M_PI);
    turn += q.k_n * (p - prev).norm();
    least = std::min(least, q.k_n);
    prev = p;
  }
  EXPECT_GE(least, -1e-9);
  EXPECT_NEAR(turn, 0.5 * M_PI, 2e-3 * M_PI);
  EXPECT_LT(std::abs(s.rates(z, theta0, 0.5 * M_PI).k_n), 1e-5);  // mid-flat: ~straight
  const ConstantAngleDemand d = s.demand(20.0, 380.0, 55.0 * M_PI / 180.0);
  EXPECT_LT(d.slippage, 1e-3);
  EXPECT_GE(d.min_k_n, -kFlatCurvature);
}

// A section with truly concave sides (r = 50 (1 - 0.35 cos 2 theta): dented at 0 and 180 deg)
// stays concave in the convex fit, and a friction layer on it is refused with one line naming
// the bridge before anything is traced.
TEST(MeshTubeSurface, ConcaveSectionIsRefusedNamingTheBridge) {
  auto peanut = [](double z, double t) {
    const double r = 50.0 * (1.0 - 0.35 * std::cos(2.0 * t));
    return Vec3(r * std::cos(t), r * std::sin(t), z);
  };
  const Fitted f = fit(peanut, 400.0, 360, 40);
  const MeshTubeSurface& s = *f.fit.surface;
  EXPECT_TRUE(f.fit.summary.convex_fit);
  EXPECT_LT(s.rates(200.0, 0.0, 0.5 * M_PI).k_n, -1e-3);  // the dent's curvature stays < 0
  WindingOptions o;
  o.angle = 55.0;
  o.slippage = 0.15;
  o.mu = 0.2;
  o.band_width = 12.0;
  try {
    plan_tube_friction(s, 0.0, s.length(), f.mesh, {}, SpindleAxis{}, o);
    FAIL() << "a concave section was planned";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("winding.angle 55 deg: the fibre would bridge"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

TEST(MeshTubeSurface, RefusesBadOptions) {
  MeshTubeSurfaceOptions o;
  std::string why;
  EXPECT_TRUE(o.is_valid(&why));
  o.harmonics = 0;
  EXPECT_FALSE(o.is_valid(&why));
  o.harmonics = 16;
  o.rays = 10;
  EXPECT_FALSE(o.is_valid(&why));
  o.rays = 256;
  o.step = -1.0;
  EXPECT_FALSE(o.is_valid(&why));
  o.step = std::nan("");
  o.convex_width = 0.0;
  EXPECT_FALSE(o.is_valid(&why));
}

}  // namespace
}  // namespace windplan
