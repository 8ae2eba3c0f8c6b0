// Section mandrels and mandrel features: exact B-rep areas and volumes against closed forms,
// the section outline, and parameter checks.
#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/cad/cad_shape.h"
#include "geometry/cad/section_mandrel.h"

namespace windplan {
namespace {

TEST(SectionMandrel, EllipticPrismAreaAndVolume) {
  SectionParams p;  // 80 x 50 ellipse, 400 long, flat ends
  const CadShapeInfo info = cad_shape_info(make_section_mandrel(p));
  EXPECT_EQ(info.solids, 1);
  EXPECT_EQ(info.free_edges, 0);
  const double ab = M_PI * 80.0 * 50.0;
  EXPECT_NEAR(info.volume, ab * 400.0, 1e-6 * ab * 400.0);
  // OCCT integrates the elliptic side to about 1e-5 (GProp's default accuracy).
  EXPECT_NEAR(info.area, 2.0 * ab + section_perimeter(p) * 400.0, 2e-5 * info.area);
}

TEST(SectionMandrel, RoundedRectanglePrismAreaAndVolume) {
  const SectionParams p = SectionParams::rounded_rectangle(120, 80, 15, 600);
  const CadShapeInfo info = cad_shape_info(make_section_mandrel(p));
  const double section = 120.0 * 80.0 - (4.0 - M_PI) * 15.0 * 15.0;
  EXPECT_NEAR(info.volume, section * 600.0, 1e-6 * section * 600.0);
  EXPECT_NEAR(section_perimeter(p), 2.0 * (120 - 30) + 2.0 * (80 - 30) + 2.0 * M_PI * 15.0, 1e-9);
  EXPECT_NEAR(info.area, 2.0 * section + section_perimeter(p) * 600.0, 1e-6 * info.area);
}

TEST(SectionMandrel, SectionRadius) {
  SectionParams e;
  EXPECT_NEAR(section_radius(e, 0.0), 80.0, 1e-12);
  EXPECT_NEAR(section_radius(e, M_PI / 2), 50.0, 1e-12);
  SectionParams r;
  r.shape = SectionShape::RoundedRectangle;  // 160 x 100, corner 20
  EXPECT_NEAR(section_radius(r, 0.0), 80.0, 1e-12);
  EXPECT_NEAR(section_radius(r, M_PI / 2), 50.0, 1e-12);
  // The diagonal hits the corner arc centred (60, 30): |t (c, s) - C| = 20.
  const double th = std::atan2(30.0, 60.0), t = section_radius(r, th);
  EXPECT_NEAR(std::hypot(t * std::cos(th) - 60.0, t * std::sin(th) - 30.0), 20.0, 1e-9);
}

TEST(SectionMandrel, DomedEndsCloseTheSolid) {
  SectionParams p;
  p.end_start.dome = p.end_end.dome = true;
  const CadShapeInfo info = cad_shape_info(make_section_mandrel(p));
  EXPECT_EQ(info.solids, 1);
  EXPECT_EQ(info.free_edges, 0);
  // More than the prism, less than the prism plus two full-height elliptic cylinders.
  const double ab = M_PI * 80.0 * 50.0;
  EXPECT_GT(info.volume, ab * 400.0);
  EXPECT_LT(info.volume, ab * (400.0 + 2.0 * p.end_end.height));
}

TEST(SectionMandrel, RejectsBadParameters) {
  const SectionParams p = SectionParams::rounded_rectangle(100, 200, 60, 400);  // r > width / 2
  std::string why;
  EXPECT_FALSE(p.is_valid(&why));
  EXPECT_NE(why.find("corner_radius"), std::string::npos) << why;
  EXPECT_THROW(make_section_mandrel(p), ConfigError);
  SectionParams d;
  d.end_end.dome = true;
  d.end_end.opening = 90;  // wider than the section
  EXPECT_FALSE(d.is_valid(&why));
  EXPECT_NE(why.find("end_end.opening"), std::string::npos) << why;
}

TEST(MandrelFeatures, FlangesShaftsBoltHolesAndBoreVolume) {
  // A pipe R 50, L 500 with bore r 20, shafts r 25, two flanges r 90 x 12 with 8 holes r 5.
  const SectionParams circle = SectionParams::ellipse(50, 50, 500);
  MandrelFeatures f;
  f.bore = 20;
  f.shaft_start = {25, 100};
  f.shaft_end = {25, 100};
  f.flanges = {FlangeParams{0, 90, 12, 8, 5, 75}, FlangeParams{488, 90, 12, 8, 5, 75}};
  const CadShape s =
      add_mandrel_features(make_section_mandrel(circle), f, [](double) { return 50.0; });
  const CadShapeInfo info = cad_shape_info(s);
  EXPECT_EQ(info.solids, 1);
  EXPECT_EQ(info.free_edges, 0);
  const double body = M_PI * 50 * 50 * 500, shafts = 2 * M_PI * 25 * 25 * 100;
  const double flanges = 2 * M_PI * (90 * 90 - 50 * 50) * 12, holes = 2 * 8 * M_PI * 5 * 5 * 12;
  const double bore = M_PI * 20 * 20 * 700;
  EXPECT_NEAR(info.volume, body + shafts + flanges - holes - bore, 1e-6 * info.volume);
}

TEST(MandrelFeatures, RejectsHolesOutsideTheFlange) {
  MandrelFeatures f;
  f.flanges = {FlangeParams{0, 90, 12, 8, 10, 85}};
  std::string why;
  EXPECT_FALSE(f.is_valid(&why));
  EXPECT_NE(why.find("features.flanges[0]"), std::string::npos) << why;
}

}  // namespace
}  // namespace windplan

// Geodesics on the elliptic cylinder: it develops onto the plane (arc length s along the
// section, z along the axis), where a geodesic is a straight line, so its angle to the
// generators is constant: tan(alpha) = (s_B - s_A) / (z_B - z_A), s the ellipse's arc length.
#include "geometry/cad/tessellate.h"
#include "geometry/geodesic/geodesic.h"
#include "geometry/mesh/surface_path.h"

namespace windplan {
namespace {

TEST(SectionMandrel, EllipseGeodesicCrossingAngleMatchesTheDevelopment) {
  SectionParams p;  // a = 80, b = 50, L = 400, flat ends
  TessellateOptions to;
  to.linear_deflection = 0.02;
  to.angular_deflection = 5.0;
  const Mesh full(tessellate(make_section_mandrel(p), to).soup);
  // The side wall only (the caps would be a shortcut for neither end point).
  TriangleSoup side{full.points(), {}};
  for (int f = 0; f < full.num_faces(); ++f) {
    if (std::abs(full.face_normal(f).z()) < 0.5) side.triangles.push_back(full.triangle(f));
  }
  const Mesh m(side);
  auto nearest = [&](const Vec3& q) {
    int best = 0;
    for (int v = 0; v < m.num_vertices(); ++v) {
      if ((m.position(v) - q).norm() < (m.position(best) - q).norm()) best = v;
    }
    return best;
  };
  const int a = nearest(Vec3(80, 0, 0)), b = nearest(Vec3(0, 50, 400));
  ASSERT_LT((m.position(a) - Vec3(80, 0, 0)).norm(), 1e-9);
  ASSERT_NEAR(m.position(b).z(), 400.0, 1e-9);
  // Arc length of the ellipse (a cos t, b sin t) from t = 0 to b's parameter: the incomplete
  // elliptic integral of the second kind, by Simpson's rule on 20000 intervals.
  const double tb = std::atan2(m.position(b).y() / 50.0, m.position(b).x() / 80.0);
  auto speed = [](double t) { return std::hypot(80.0 * std::sin(t), 50.0 * std::cos(t)); };
  double arc = 0.0;
  const int n = 20000;
  for (int i = 0; i <= n; ++i) {
    arc += (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0)) * speed(tb * i / n);
  }
  arc *= tb / n / 3.0;
  const GeodesicContext ctx(m);
  const OpenGeodesicResult g =
      geodesic_between(ctx, SurfacePoint::at_vertex(a), SurfacePoint::at_vertex(b));
  const std::vector<Vec3> pts = polyline(m, g.path);
  ASSERT_GE(pts.size(), 3u);
  const double expected = std::atan2(arc, 400.0);
  EXPECT_NEAR(arc, section_perimeter(p) / 4.0, 2.0) << "b is near (0, 50, 400)";
  double lo = 10.0, hi = -10.0;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    const Vec3 d = pts[i + 1] - pts[i];
    if (d.norm() < 1e-6) continue;
    const double alpha = std::acos(std::abs(d.z()) / d.norm());
    lo = std::min(lo, alpha);
    hi = std::max(hi, alpha);
  }
  // The tessellated section is a polygon inscribed in the ellipse: its quarter is shorter by
  // about sagitta / (3 r) relatively, which bounds the angle error.
  const double bound = std::atan2(arc * (0.02 / 50.0), 400.0) + 1e-4;
  EXPECT_NEAR(lo, expected, bound) << "expected " << expected * 180 / M_PI << " deg";
  EXPECT_NEAR(hi, expected, bound) << "expected " << expected * 180 / M_PI << " deg";
  EXPECT_LT(hi - lo, 1e-6) << "a geodesic on a developable cylinder keeps its angle";
}

}  // namespace
}  // namespace windplan
