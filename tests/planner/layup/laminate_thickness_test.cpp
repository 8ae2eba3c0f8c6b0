#include "planner/layup/laminate_thickness.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

MeridianPolyline cylinder(double R, double L, double step) {
  return MeridianPolyline::from_points({Vec2(0.0, R), Vec2(L, R)}).resampled(step);
}

// A hemispherical dome of radius R from the polar opening r0 to the equator, then a cylinder of
// length L: the start half of a vessel, axial increasing.
MeridianPolyline dome_and_cylinder(double R, double r0, double L, int n) {
  std::vector<Vec2> p;
  const double phi0 = std::acos(r0 / R);  // latitude of the opening
  for (int i = 0; i <= n; ++i) {
    const double phi = phi0 * (1.0 - static_cast<double>(i) / n);
    p.emplace_back(-R * std::sin(phi), R * std::cos(phi));
  }
  p.emplace_back(L, R);
  return MeridianPolyline::from_points(p);
}

TEST(LaminateThickness, HelicalOnACylinderFromItsOwnCircuits) {
  const double R = 100.0, B = 8.0, t = 0.3, alpha = 30.0 * M_PI / 180.0;
  const MeridianPolyline m = cylinder(R, 400.0, 2.0);
  const double c = R * std::sin(alpha);
  for (double K : {5.0, 17.0}) {
    const LayerThickness th = helical_layer_thickness(m, c, K, B, t);
    const double expect = 2.0 * K * B * t / (2.0 * M_PI * R * std::cos(alpha));
    EXPECT_NEAR(th.at(200.0), expect, 1e-12 * expect);
    // The band average over a uniform cylinder changes nothing away from the ends.
    EXPECT_NEAR(th.at(100.0), expect, 1e-12 * expect);
  }
  // Full coverage: K = 2 pi R cos(alpha) / B circuits lay 2 t.
  const double K_full = 2.0 * M_PI * R * std::cos(alpha) / B;
  EXPECT_NEAR(helical_layer_thickness(m, c, K_full, B, t).at(200.0), 2.0 * t, 1e-12);
}

TEST(LaminateThickness, GeodesicDomeRatioAwayFromTheTurnaround) {
  const double R = 100.0, c = 30.0, B = 2.0, t = 0.25, K = 40.0;
  const MeridianPolyline m = dome_and_cylinder(R, c, 200.0, 2000).resampled(1.0);
  const LayerThickness th = helical_layer_thickness(m, c, K, B, t);
  const double tR = th.at(m.length() - 50.0);  // on the cylinder
  const double cos_aR = std::sqrt(1.0 - c * c / (R * R));
  // Unbounded form: the closed ratio to rounding.
  for (double r : {40.0, 60.0, 80.0}) {
    const double ratio =
        helical_thickness_unbounded(r, c, K, B, t) / helical_thickness_unbounded(R, c, K, B, t);
    const double cos_ar = std::sqrt(1.0 - c * c / (r * r));
    EXPECT_NEAR(ratio, R * cos_aR / (r * cos_ar), 1e-12);
  }
  // Band-averaged, at points of the dome: within the O(B^2) of the average.
  for (int i = 100; i < 2000; i += 100) {
    const double r = m.points[i].y();
    if (r < c + 10.0 * B) continue;
    const double cos_ar = std::sqrt(1.0 - c * c / (r * r));
    const double expect = R * cos_aR / (r * cos_ar);
    EXPECT_NEAR(th.thickness[i] / tR, expect, 1e-3 * expect) << "r = " << r;
  }
}

TEST(LaminateThickness, BoundedAtTheTurnaroundAndMassConserving) {
  // A cone from r = 5 to r = 25 and back below the turnaround c = 10: (1) diverges at r = c, the
  // band average is finite and integral t ds = K B t / pi * integral ds / sqrt(r^2 - c^2)
  // = K B t / pi * 2 acosh(25 / 10) / m, with m = dr/ds on the cones.
  const double c = 10.0, B = 4.0, t = 0.2, K = 12.0;
  const MeridianPolyline m = MeridianPolyline::from_points({Vec2(0, 5), Vec2(20, 5), Vec2(120, 25),
                                                            Vec2(220, 5), Vec2(240, 5)})
                                 .resampled(0.02);
  const LayerThickness th = helical_layer_thickness(m, c, K, B, t);
  double integral = 0.0, peak = 0.0;
  for (std::size_t i = 1; i < th.s.size(); ++i) {
    integral += 0.5 * (th.thickness[i] + th.thickness[i - 1]) * (th.s[i] - th.s[i - 1]);
    peak = std::max(peak, th.thickness[i]);
  }
  const double slope = 20.0 / std::hypot(100.0, 20.0);
  const double expect = K * B * t / M_PI * 2.0 * std::acosh(25.0 / 10.0) / slope;
  EXPECT_NEAR(integral, expect, 1e-4 * expect);
  EXPECT_TRUE(std::isfinite(peak));
  EXPECT_GT(peak, helical_thickness_unbounded(12.0, c, K, B, t));  // the pile-up near r = c
  // No fibre inside the turnaround, beyond half a band.
  const double s_c = std::hypot(100.0, 20.0) * (c - 5.0) / 20.0 + 20.0;  // r = c on the cone
  EXPECT_EQ(th.at(s_c - 0.5 * B - 0.1), 0.0);
  EXPECT_GT(th.at(s_c - 0.5 * B + 0.1), 0.0);
}

TEST(LaminateThickness, HoopOnACylinder) {
  const double R = 100.0, B = 10.0, t = 0.25, p = 8.0;
  const MeridianPolyline m = cylinder(R, 300.0, 1.0);
  const LayerThickness th = hoop_layer_thickness(m, 50.0, 250.0, p, B, t, 2);
  const double sin_a = std::sin(std::atan(2.0 * M_PI * R / p));
  EXPECT_NEAR(th.at(150.0), 2.0 * B * t / (p * sin_a), 1e-12);
  EXPECT_EQ(th.at(20.0), 0.0);
  EXPECT_EQ(th.at(280.0), 0.0);
}

TEST(LaminateThickness, OffsetOfACylinderIsRPlusT) {
  const MeridianPolyline m = cylinder(50.0, 100.0, 5.0);
  LayerThickness th;
  th.s = m.s;
  th.thickness.assign(m.s.size(), 1.25);
  const MeridianPolyline out = offset_meridian(m, th, "layers[0]");
  for (const Vec2& p : out.points) EXPECT_NEAR(p.y(), 51.25, 1e-12);
  // A sphere's meridian moves to the sphere of radius R + t.
  const MeridianPolyline d = dome_and_cylinder(80.0, 20.0, 10.0, 400);
  th.s = d.s;
  th.thickness.assign(d.s.size(), 2.0);
  const MeridianPolyline od = offset_meridian(d, th, "layers[0]");
  for (int i = 1; i < 400; ++i) EXPECT_NEAR(od.points[i].norm(), 82.0, 1e-3) << i;
}

TEST(LaminateThickness, AThicknessThatWouldCloseThePolarOpeningIsRejected) {
  // A boss neck (r = 10 from x = 0 to 5) and a flange rising to r = 40: a laminate 3 mm thick
  // fills the corner and folds the next surface onto itself at the opening.
  const MeridianPolyline m =
      MeridianPolyline::from_points({Vec2(0, 10), Vec2(5, 10), Vec2(6, 40), Vec2(100, 40)})
          .resampled(1.0);
  LayerThickness th;
  th.s = m.s;
  th.thickness.assign(m.s.size(), 3.0);
  try {
    offset_meridian(m, th, "layers[2]");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("layers[2]"), std::string::npos) << w;
    EXPECT_NE(w.find("close the start polar opening"), std::string::npos) << w;
  }
  // A thin layer there is fine.
  th.thickness.assign(m.s.size(), 0.2);
  EXPECT_NO_THROW(offset_meridian(m, th, "layers[2]"));
}

TEST(LaminateThickness, MeridianHelpers) {
  const MeridianPolyline m = MeridianPolyline::from_points({Vec2(0, 10), Vec2(3, 14)});
  EXPECT_DOUBLE_EQ(m.length(), 5.0);
  EXPECT_NEAR(m.project(Vec2(1.5, 12.0) + 2.0 * m.normal(0)), 2.5, 1e-12);
  EXPECT_NEAR(m.normal(0).x(), -0.8, 1e-15);
  EXPECT_NEAR(m.normal(0).y(), 0.6, 1e-15);
  EXPECT_EQ(m.resampled(1.0).points.size(), 6u);
  EXPECT_THROW(MeridianPolyline::from_points({Vec2(0, 1)}), InputError);
  EXPECT_THROW(MeridianPolyline::from_points({Vec2(0, 1), Vec2(0, 1)}), InputError);
  EXPECT_THROW(helical_layer_thickness(cylinder(20.0, 50.0, 1.0), 20.0, 3.0, 5.0, 0.2),
               InputError);  // along r = c: a hoop
}

}  // namespace
}  // namespace windplan
