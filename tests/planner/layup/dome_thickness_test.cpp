#include "planner/layup/dome_thickness.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

// A hemispherical dome of radius R from the pole region (radius r0) to the equator, then a
// cylinder of length L.
MeridianPolyline dome_and_cylinder(double R, double r0, double L, int n) {
  std::vector<Vec2> p;
  const double phi0 = std::acos(r0 / R);
  for (int i = 0; i <= n; ++i) {
    const double phi = phi0 * (1.0 - static_cast<double>(i) / n);
    p.emplace_back(-R * std::sin(phi), R * std::cos(phi));
  }
  p.emplace_back(L, R);
  return MeridianPolyline::from_points(p).resampled(0.5);
}

// On a sphere a geodesic is a great circle: each pass runs a quarter circle (pi R / 2) from its
// turnaround to the equator, whatever c. K circuits turn around once each on this dome, in and
// out: the fibre volume laid on the dome is K pi R B t.
TEST(DomeThickness, SplineConservesTheBandVolumeOnTheDome) {
  const double R = 100.0, c = 38.0, B = 16.0, t = 0.2, K = 20.0;
  const MeridianPolyline m = dome_and_cylinder(R, 30.0, 200.0, 4000);
  double s_equator = 0.0;
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    if (m.points[i].x() <= 0.0) s_equator = m.s[i];
  }
  const double laid = K * M_PI * R * B * t;
  const LayerThickness spline = helical_layer_thickness_spline(m, c, K, B, t);
  const double v = layer_volume(m, spline, 0.0, s_equator);
  EXPECT_NEAR(v, laid, 0.01 * laid);
  // The band-averaged continuity model conserves it too.
  const LayerThickness avg = helical_layer_thickness(m, c, K, B, t);
  EXPECT_NEAR(layer_volume(m, avg, 0.0, s_equator), laid, 0.01 * laid);
  // Finite at the turnaround, flat there, nothing inside it, continuity beyond c + 2B.
  EXPECT_TRUE(std::isfinite(spline.max()));
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const double r = m.points[i].y();
    if (r < c) {
      EXPECT_EQ(spline.thickness[i], 0.0);
    } else if (r > c + 2.0 * B) {
      EXPECT_NEAR(spline.thickness[i], helical_thickness_unbounded(r, c, K, B, t), 1e-12);
    }
  }
  // On the cylinder: full-coverage figure 2 K B t / (2 pi sqrt(R^2 - c^2)).
  EXPECT_NEAR(spline.at(m.length() - 50.0), K * B * t / (M_PI * std::sqrt(R * R - c * c)), 1e-9);
}

TEST(DomeThickness, RejectsARegionBeyondTheLargestRadius) {
  const MeridianPolyline m = dome_and_cylinder(100.0, 30.0, 100.0, 400);
  EXPECT_THROW(helical_layer_thickness_spline(m, 80.0, 10.0, 16.0, 0.2), InputError);
  EXPECT_THROW(helical_layer_thickness_spline(m, 0.0, 10.0, 16.0, 0.2), InputError);
}

}  // namespace
}  // namespace windplan
