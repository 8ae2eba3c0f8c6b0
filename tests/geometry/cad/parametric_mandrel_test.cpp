// Parametric mandrels: areas against closed forms, validation messages naming the key, and the
// isotensoid meridian against its differential equation.
#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/cad/cad_shape.h"
#include "geometry/cad/parametric_mandrel.h"
#include "geometry/cad/tessellate.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/mesh_validation.h"

namespace windplan {
namespace {

// A tessellation inscribed in a surface of curvature radius >= R with chord deviation <= delta
// loses area: for a circle of n chords the perimeter ratio is sin(x)/x with x = pi/n and
// delta = R (1 - cos x) ~ R x^2 / 2, i.e. a relative loss ~ x^2 / 6 = delta / (3 R); a planar disk
// loses sin(2x)/(2x) ~ 4 delta / (3 R). Doubly curved patches stay below 2 delta / R. So the
// relative area error of every mandrel below is in [0, 2 delta / R_min].
struct AreaCheck {
  double mesh_area;
  double exact;
};

AreaCheck mesh_area(const CadShape& s, double exact, double deflection = 0.25) {
  TessellateOptions o;
  o.linear_deflection = deflection;
  o.angular_deflection = 30.0;  // let the linear deflection govern
  const Tessellation t = tessellate(s, o);
  const Mesh m(t.soup);
  return {m.total_area(), exact};
}

void expect_area(const AreaCheck& a, double delta, double r_min) {
  const double rel = (a.exact - a.mesh_area) / a.exact;
  EXPECT_GE(rel, -1e-9) << "an inscribed tessellation cannot exceed the exact area";
  EXPECT_LE(rel, 2.0 * delta / r_min) << "mesh " << a.mesh_area << " vs exact " << a.exact;
}

TEST(ParametricMandrel, PipeAreaIsCylinderPlusCaps) {
  const double R = 50, L = 500;
  const CadShape s = make_pipe({R, L});
  const CadShapeInfo info = cad_shape_info(s);
  EXPECT_EQ(info.solids, 1);
  EXPECT_EQ(info.free_edges, 0);
  EXPECT_NEAR(info.area, 2 * M_PI * R * L + 2 * M_PI * R * R, 1e-6 * info.area);
  EXPECT_NEAR(info.volume, M_PI * R * R * L, 1e-6 * info.volume);
  expect_area(mesh_area(s, 2 * M_PI * R * L + 2 * M_PI * R * R), 0.25, R);
}

TEST(ParametricMandrel, ConeAreaIsFrustumPlusCaps) {
  const double r1 = 60, r2 = 40, L = 400;
  const double slant = std::hypot(L, r1 - r2);
  const double exact = M_PI * (r1 + r2) * slant + M_PI * (r1 * r1 + r2 * r2);
  const CadShape s = make_cone({r1, r2, L});
  EXPECT_NEAR(cad_shape_info(s).area, exact, 1e-6 * exact);
  expect_area(mesh_area(s, exact), 0.25, r2);
}

TEST(ParametricMandrel, HemisphericalVesselAreaIsCylinderPlusSphericalZones) {
  VesselParams v;
  v.radius = 100;
  v.length = 300;
  v.dome_start.polar_opening = v.dome_end.polar_opening = 30;
  const double R = 100, h = std::sqrt(R * R - 30.0 * 30.0);  // zone height, equator to opening
  const double exact = 2 * M_PI * R * 300 + 2 * (2 * M_PI * R * h) + 2 * M_PI * 30 * 30;
  const CadShape s = make_vessel(v);
  const CadShapeInfo info = cad_shape_info(s);
  EXPECT_EQ(info.solids, 1);
  EXPECT_EQ(info.free_edges, 0);
  EXPECT_NEAR(info.area, exact, 1e-6 * exact);
  expect_area(mesh_area(s, exact), 0.25, 30.0);  // the caps have the smallest radius
}

// 2 pi int r ds along the ellipse r = R cos u, h = a R sin u, u in [0, acos(r0 / R)].
double ellipse_zone_area(double R, double a, double r0) {
  const double u0 = std::acos(r0 / R);
  const int n = 20000;
  double s = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) * u0 / n;
    s += R * std::cos(u) * std::hypot(R * std::sin(u), a * R * std::cos(u)) * (u0 / n);
  }
  return 2 * M_PI * s;
}

TEST(ParametricMandrel, EllipticalVesselAreaMatchesQuadrature) {
  for (double aspect : {0.5, 1.6}) {
    VesselParams v;
    v.dome_start.type = v.dome_end.type = DomeType::Elliptical;
    v.dome_start.aspect = v.dome_end.aspect = aspect;
    const double R = v.radius, r0 = 30.0;
    const double exact =
        2 * M_PI * R * v.length + 2 * ellipse_zone_area(R, aspect, r0) + 2 * M_PI * r0 * r0;
    const CadShape s = make_vessel(v);
    EXPECT_NEAR(cad_shape_info(s).area, exact, 1e-5 * exact) << "aspect " << aspect;
    // The ellipse's smallest curvature radius is min(a^2 R, R / a) (at the ends of its axes).
    const double rmin = std::min({aspect * aspect * R, R / aspect, r0});
    expect_area(mesh_area(s, exact), 0.25, rmin);
  }
}

TEST(ParametricMandrel, IsotensoidMeridianSolvesItsEquation) {
  const double R = 100, r0 = 30;
  DomeParams d;
  d.type = DomeType::Isotensoid;
  d.polar_opening = r0;
  const double r1 = isotensoid_neck_radius(R, r0);
  const double rho0 = r0 / R, rho1 = r1 / R;
  // The neck is the inner root of the radicand, just above r0.
  EXPECT_NEAR(rho1 * rho1 - rho0 * rho0 - (1 - rho0 * rho0) * std::pow(rho1, 6), 0.0, 1e-12);
  EXPECT_GT(r1, r0);
  EXPECT_LT(r1, 1.01 * r0);
  const std::vector<Vec2> m = dome_meridian(d, R, 2001);
  EXPECT_DOUBLE_EQ(m.front().x(), R);
  EXPECT_DOUBLE_EQ(m.front().y(), 0.0);
  EXPECT_DOUBLE_EQ(m.back().x(), r1);
  // Central differences against dz/dr away from the two vertical-tangent ends.
  int checked = 0;
  for (std::size_t i = 1; i + 1 < m.size(); ++i) {
    const double r = m[i].x() / R;
    if (r < rho1 + 0.05 || r > 0.95) continue;
    const double slope = (m[i + 1].y() - m[i - 1].y()) / (m[i + 1].x() - m[i - 1].x());
    const double f = r * r - rho0 * rho0 - (1 - rho0 * rho0) * std::pow(r, 6);
    const double expected = -std::pow(r, 3) * std::sqrt(1 - rho0 * rho0) / std::sqrt(f);
    EXPECT_NEAR(slope, expected, 1e-3 * std::abs(expected)) << "at r = " << m[i].x();
    ++checked;
  }
  EXPECT_GT(checked, 100);
  // The height converges: 2001 and 501 samples agree (the integrand is smooth in t).
  const double h_coarse = dome_meridian(d, R, 501).back().y();
  EXPECT_NEAR(m.back().y(), h_coarse, 1e-9 * h_coarse);
}

TEST(ParametricMandrel, IsotensoidHeightHoldsAtAMillionSamples) {
  // The radicand vanishes at the neck: evaluated directly it loses every digit within 1e-8 of
  // it, and from about 3e5 samples on the dome height came out near 1e136 mm.
  DomeParams d;
  d.type = DomeType::Isotensoid;
  d.polar_opening = 30;
  const double h = dome_meridian(d, 100, 501).back().y();
  EXPECT_GT(h, 50.0);
  EXPECT_LT(h, 100.0);
  for (int n : {300001, 1000001}) {
    const std::vector<Vec2> m = dome_meridian(d, 100, n);
    EXPECT_NEAR(m.back().y(), h, 1e-12 * h) << n << " samples";
    for (std::size_t i = 1; i < m.size(); ++i)
      ASSERT_GE(m[i].y(), m[i - 1].y()) << "height not monotone at sample " << i << " of " << n;
  }
}

TEST(ParametricMandrel, IsotensoidVesselAreaMatchesItsMeridian) {
  VesselParams v;
  v.dome_start.type = v.dome_end.type = DomeType::Isotensoid;
  const double R = v.radius;
  const std::vector<Vec2> m = dome_meridian(v.dome_end, R, 4001);
  double zone = 0.0;  // 2 pi int r ds (trapezoid on a fine, end-clustered sampling)
  for (std::size_t i = 0; i + 1 < m.size(); ++i) {
    zone += M_PI * (m[i].x() + m[i + 1].x()) * (m[i + 1] - m[i]).norm();
  }
  const double r1 = m.back().x();
  const double exact = 2 * M_PI * R * v.length + 2 * zone + 2 * M_PI * r1 * r1;
  const CadShape s = make_vessel(v);
  EXPECT_NEAR(cad_shape_info(s).area, exact, 1e-4 * exact);
  expect_area(mesh_area(s, exact), 0.25, r1);
}

TEST(ParametricMandrel, BentTubeAreaIsPappus) {
  BentTubeParams b;
  b.radius = 25;
  b.segments = {200, 150, 100};
  b.bends = {{90, 100, 0}, {45, 80, 90}};
  const double centre = 450 + 100 * M_PI / 2 + 80 * M_PI / 4;
  EXPECT_NEAR(bent_tube_length(b), centre, 1e-9);
  const double exact = 2 * M_PI * 25 * centre + 2 * M_PI * 25 * 25;
  const CadShape s = make_bent_tube(b);
  const CadShapeInfo info = cad_shape_info(s);
  EXPECT_EQ(info.solids, 1);
  EXPECT_EQ(info.free_edges, 0);
  EXPECT_NEAR(info.area, exact, 1e-5 * exact);
  EXPECT_NEAR(info.volume, M_PI * 25 * 25 * centre, 1e-5 * info.volume);
  expect_area(mesh_area(s, exact), 0.25, 25);
  // The centreline ends where the polyline says: the second leg is perpendicular to the first.
  const std::vector<Vec3> c = bent_tube_centreline(b);
  EXPECT_NEAR((c[1] - c[0]).norm(), 200, 1e-9);
}

TEST(ParametricMandrel, FinerDeflectionGivesSmallerAreaError) {
  const double R = 100, exact = 4 * M_PI * R * R;
  const CadShape s = make_sphere(R);
  const AreaCheck coarse = mesh_area(s, exact, 1.0), fine = mesh_area(s, exact, 0.1);
  expect_area(coarse, 1.0, R);
  expect_area(fine, 0.1, R);
  EXPECT_LT(exact - fine.mesh_area, 0.5 * (exact - coarse.mesh_area));
}

void expect_config_error(const std::function<void()>& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no error, expected one naming " << needle;
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(ParametricMandrel, InvalidParametersNameTheKey) {
  expect_config_error([] { make_pipe({-5, 100}); }, "radius");
  expect_config_error([] { make_pipe({50, 0}); }, "length");
  expect_config_error([] { make_cone({60, 0, 100}); }, "radius_end");
  VesselParams v;
  v.dome_end.polar_opening = 120;
  expect_config_error([&] { make_vessel(v); }, "dome_end.polar_opening");
  v.dome_end.polar_opening = 100;  // equal is not smaller
  expect_config_error([&] { make_vessel(v); }, "polar_opening");
  VesselParams e;
  e.dome_start.type = DomeType::Elliptical;
  e.dome_start.aspect = 0;
  expect_config_error([&] { make_vessel(e); }, "dome_start.aspect");
  VesselParams iso;
  iso.dome_start.type = DomeType::Isotensoid;
  iso.dome_start.polar_opening = 90;
  expect_config_error([&] { make_vessel(iso); }, "isotensoid");
  BentTubeParams b;
  b.bends[0].radius = 20;  // below the tube radius 25
  expect_config_error([&] { make_bent_tube(b); }, "bends[0].radius");
  b.bends[0].radius = 25;  // equal: the inner wall would pinch
  expect_config_error([&] { make_bent_tube(b); }, "bends[0].radius");
  BentTubeParams c;
  c.bends.clear();
  expect_config_error([&] { make_bent_tube(c); }, "bends");
  expect_config_error([] { make_sphere(0); }, "radius");
}

}  // namespace
}  // namespace windplan
