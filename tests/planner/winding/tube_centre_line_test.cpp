// Tube coordinates (planner/winding/tube_centre_line.h) against the parametric bent tube's own
// centre line (geometry/cad/parametric_mandrel.h), finite differences of the embedded surface,
// and the torus' closed forms: the constant-angle slippage
// lambda = r sin(t) cos(a) / ((R + r cos t) sin^2(a) + r cos^2(a) cos(t)) (t from the outside)
// at 55 deg is 0.179 at worst on a bend of 5 tube radii and 0.328 on one of 3; a geodesic keeps
// (R + r cos t) cos a constant (Clairaut).
#include "planner/winding/tube_centre_line.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"
#include "geometry/cad/parametric_mandrel.h"

namespace windplan {
namespace {

TEST(TubeCentreLine, MatchesTheParametricBentTube) {
  BentTubeParams p;
  p.radius = 20;
  p.segments = {50, 30, 40};
  p.bends = {{90, 80, 0}, {45, 60, 30}};
  std::vector<TubeBend> bends;
  for (const BendParams& b : p.bends) bends.push_back({b.angle, b.radius, b.plane_angle});
  const TubeCentreLine line(p.radius, p.segments, bends);
  EXPECT_NEAR(line.length(), bent_tube_length(p), 1e-9);
  // bent_tube_centreline: the start, the first segment's end, 8 points per bend, ...
  const std::vector<Vec3> pts = bent_tube_centreline(p, 8);
  ASSERT_EQ(pts.size(), 1u + 1 + 8 + 1 + 8 + 1);
  std::vector<double> s = {0, 50};
  for (int k = 1; k <= 8; ++k) s.push_back(50 + 80 * M_PI / 2 * k / 8);
  s.push_back(s.back() + 30);
  const double s2 = s.back();
  for (int k = 1; k <= 8; ++k) s.push_back(s2 + 60 * M_PI / 4 * k / 8);
  s.push_back(s.back() + 40);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    EXPECT_LT((line.frame(s[i]).c - pts[i]).norm(), 1e-9) << "point " << i;
  }
  // Its polyline is bent_tube_centreline's, to the bit (the wound region's Spine is sampled
  // from it: one centre line for the sections and the closed forms), at 8 and 90 per bend.
  for (int per_bend : {8, 90}) {
    const std::vector<Vec3> a = line.polyline(per_bend), b = bent_tube_centreline(p, per_bend);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << per_bend << " " << i;
  }
  // The frame is orthonormal, t the centre line's derivative, and u, v do not twist about t.
  for (double q = 1.0; q < line.length(); q += 7.3) {
    const TubeFrame f = line.frame(q), g = line.frame(q + 1e-4), e = line.frame(q - 1e-4);
    EXPECT_NEAR(f.t.norm(), 1.0, 1e-12);
    EXPECT_NEAR(f.u.dot(f.t), 0.0, 1e-12);
    EXPECT_NEAR(f.v.dot(f.u), 0.0, 1e-12);
    EXPECT_LT(((g.c - e.c) / 2e-4 - f.t).norm(), 1e-6);
    EXPECT_NEAR(((g.u - e.u) / 2e-4).dot(f.v), 0.0, 1e-6);  // Bishop: u' has no v part
    double s_back = 0, th_back = 0, d = 0;
    line.locate(line.point(q, 0.7), &s_back, &th_back, &d);
    EXPECT_NEAR(s_back, q, 1e-6);
    EXPECT_NEAR(th_back, 0.7, 1e-9);
    EXPECT_NEAR(d, p.radius, 1e-9);
  }
  EXPECT_THROW(TubeCentreLine(20, {10, 10}, {{90, 15, 0}}), InputError);  // bend radius <= r
}

// k_n and the geodesic term against the curvature vector of a constant-angle curve on the
// embedded surface, by finite differences of P(s, theta).
TEST(TubeCentreLine, CurvaturesMatchFiniteDifferences) {
  const double r = 50, R = 150;
  const TubeCentreLine line(r, {100, 100}, {{90, R, 20}});
  for (double a : {0.3, 0.96, 1.4}) {
    for (double th0 = 0.0; th0 < 2 * M_PI; th0 += 0.41) {
      const double s0 = 100 + 0.4 * R * M_PI / 2;  // in the bend
      // The curve s(l), theta(l) at angle a: ds/dl = cos a / h, dtheta/dl = sin a / r.
      auto at = [&](double l) {
        double s = s0, th = th0;
        const int n = 400;
        const double dl = l / n;
        for (int i = 0; i < n; ++i) {  // midpoint steps (a is constant)
          const double hm = line.stretch(s, th + 0.5 * dl * std::sin(a) / r);
          s += dl * std::cos(a) / hm;
          th += dl * std::sin(a) / r;
        }
        return line.point(s, th);
      };
      const double e = 0.05;
      const Vec3 p0 = line.point(s0, th0), pp = at(e), pm = at(-e);
      const Vec3 t = (pp - pm) / (2 * e), k = (pp - 2 * p0 + pm) / (e * e);
      const Vec3 n = line.normal(s0, th0);
      EXPECT_NEAR(t.norm(), 1.0, 1e-5);
      // k_n > 0 where the fibre presses on: the curvature vector points into the tube.
      EXPECT_NEAR(-k.dot(n), line.normal_curvature(s0, th0, a), 2e-5) << a << " " << th0;
      // With da/dl = 0, k_g = -geodesic_turn, k_g > 0 towards t x n (where a grows).
      EXPECT_NEAR(k.dot(t.normalized().cross(n)), -line.geodesic_turn(s0, th0, a), 2e-5)
          << a << " " << th0;
    }
  }
}

TEST(TubeCentreLine, ConstantAngleSlippageIsTheTorusClosedForm) {
  const double r = 50, a = 55.0 * M_PI / 180.0;
  for (double R : {250.0, 150.0}) {
    const TubeCentreLine line(r, {0, 0}, {{90, R, 0}});
    const TubeFrame f = line.frame(10);
    for (double t = -M_PI; t < M_PI; t += 0.1) {
      const double th = f.toward + M_PI + t;  // t from the outside
      const double closed = std::abs(r * std::sin(t) * std::cos(a) /
                                     ((R + r * std::cos(t)) * std::pow(std::sin(a), 2) +
                                      r * std::pow(std::cos(a), 2) * std::cos(t)));
      EXPECT_NEAR(constant_angle_slippage(line, 10, th, a), closed, 1e-12);
    }
  }
  const TubeCentreLine bend5(r, {100, 100}, {{90, 250, 0}});
  const TubeCentreLine bend3(r, {100, 100}, {{90, 150, 0}});
  EXPECT_NEAR(constant_angle_demand(bend5, 0, bend5.length(), a).slippage, 0.179, 5e-4);
  EXPECT_NEAR(constant_angle_demand(bend3, 0, bend3.length(), a).slippage, 0.328, 5e-4);
  // The straight legs alone need none.
  EXPECT_EQ(constant_angle_demand(bend5, 0, 99, a).slippage, 0.0);
  // Below tan^2 a = r / (R - r) the fibre bridges the inside of a 3r bend.
  EXPECT_LT(constant_angle_demand(bend3, 0, bend3.length(), 0.5).min_k_n, 0.0);
}

TEST(TubeCentreLine, GeodesicKeepsClairautsInvariantOnTheBend) {
  const double r = 50, R = 150;
  const TubeCentreLine line(r, {0, 0}, {{180, R, 0}});
  // da/dl = geodesic_turn (k_g = 0), RK4 in the fibre length.
  struct Y {
    double s, th, a;
  };
  auto rate = [&](const Y& y) {
    return Y{std::cos(y.a) / line.stretch(y.s, y.th), std::sin(y.a) / r,
             line.geodesic_turn(y.s, y.th, y.a)};
  };
  auto add = [](Y y, Y d, double h) { return Y{y.s + h * d.s, y.th + h * d.th, y.a + h * d.a}; };
  const double toward = line.frame(1).toward;
  auto invariant = [&](const Y& y) {
    return (R + r * std::cos(y.th - toward - M_PI)) * std::cos(y.a);
  };
  Y y{1.0, 0.3, 1.0};
  const double c0 = invariant(y);
  double worst = 0.0;
  for (int i = 0; i < 1500 && y.s < R * M_PI - 1; ++i) {
    const double h = 0.5;
    const Y k1 = rate(y), k2 = rate(add(y, k1, h / 2)), k3 = rate(add(y, k2, h / 2)),
            k4 = rate(add(y, k3, h));
    y = {y.s + h / 6 * (k1.s + 2 * k2.s + 2 * k3.s + k4.s),
         y.th + h / 6 * (k1.th + 2 * k2.th + 2 * k3.th + k4.th),
         y.a + h / 6 * (k1.a + 2 * k2.a + 2 * k3.a + k4.a)};
    worst = std::max(worst, std::abs(invariant(y) - c0));
  }
  EXPECT_GT(y.s, 200.0);  // it went round a good part of the bend
  EXPECT_LT(worst / c0, 1e-9);
}

}  // namespace
}  // namespace windplan
