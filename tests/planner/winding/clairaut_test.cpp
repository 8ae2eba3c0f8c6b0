// planner/winding/clairaut.cpp: the geodesic turn limit of a shape of revolution, against closed
// forms (cone unrolled, sphere great circles, cylinder) with two independent evaluations: the exact
// truncated-cone sum over a profile and the Gauss-Legendre quadrature of a smooth meridian.
#include "planner/winding/clairaut.h"

#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

RadiusProfile sampled(const std::function<double(double)>& r, double x0, double x1, int n) {
  RadiusProfile p;
  for (int i = 0; i <= n; ++i) {
    const double x = x0 + (x1 - x0) * i / n;
    p.axial.push_back(x);
    p.radius.push_back(r(x));
  }
  return p;
}

// A cone of half-angle b between radii r1 < r2: unrolled, the geodesic tangent to the small
// circle covers the unrolled angle arccos(r1 / r2), i.e. arccos(r1 / r2) / sin(b) about the
// axis; for c < r1, Phi(c) = (arccos(c / r2) - arccos(c / r1)) / sin(b).
struct Cone {
  double r1 = 40.0, r2 = 60.0, length = 400.0;
  double sin_b() const { return (r2 - r1) / std::hypot(length, r2 - r1); }
  double phi(double c) const { return (std::acos(c / r2) - std::acos(c / r1)) / sin_b(); }
  double phi_max() const { return std::acos(r1 / r2) / sin_b(); }
  // Small end at x = length (as configs/cone.yaml: 60 mm at z = 0).
  double radius(double x) const { return r2 + (r1 - r2) * x / length; }
};

TEST(Clairaut, ConeProfileGivesTheUnrolledClosedForm) {
  const Cone k;
  // Two samples (one truncated cone) and 1000: the sum is exact per segment, so both agree with
  // the closed form to rounding, whichever end is the small one.
  for (int n : {1, 1000}) {
    const RadiusProfile p = sampled([&](double x) { return k.radius(x); }, 0.0, k.length, n);
    const ClairautLimit lim = clairaut_turn_limit(p, 0.0, k.length);
    ASSERT_TRUE(lim.bounded) << lim.reason;
    EXPECT_NEAR(lim.angle, k.phi_max(), 1e-12 * k.phi_max());
    EXPECT_NEAR(lim.turns, k.phi_max() / (2.0 * M_PI), 1e-12);
    EXPECT_DOUBLE_EQ(lim.min_radius, k.r1);
    EXPECT_DOUBLE_EQ(lim.min_at, k.length);
    for (double c : {0.0, 10.0, 30.0, 39.9}) {
      EXPECT_NEAR(clairaut_angle(p, 0.0, k.length, c), k.phi(c), 1e-12 * k.phi_max()) << c;
    }
    const RadiusProfile flipped =
        sampled([&](double x) { return k.radius(k.length - x); }, 0.0, k.length, n);
    EXPECT_NEAR(clairaut_turn_limit(flipped, 0.0, k.length).angle, k.phi_max(),
                1e-12 * k.phi_max());
  }
  // configs/cone.yaml (60 -> 40 mm over 400 mm): 16.84 rad, 2.68 turns.
  EXPECT_NEAR(k.phi_max() / (2.0 * M_PI), 2.6805, 1e-4);
}

// The same cone by the quadrature of the smooth meridian: the substitution makes the end where
// r = c regular, so c = r_min is evaluated directly and converges.
TEST(Clairaut, ConeQuadratureConvergesAtTheSmallEnd) {
  const Cone k;
  Meridian m;
  m.point = [&](double t) { return Vec2(k.length * t, k.radius(k.length * t)); };
  m.derivative = [&](double) { return Vec2(k.length, k.r1 - k.r2); };
  const ClairautQuadrature q = clairaut_angle(m, k.r1);
  ASSERT_TRUE(q.converged);
  EXPECT_NEAR(q.angle, k.phi_max(), 1e-6 * k.phi_max());
  EXPECT_LE(q.panels, 256);
  for (double c : {10.0, 30.0, 39.0}) {
    const ClairautQuadrature qc = clairaut_angle(m, c);
    ASSERT_TRUE(qc.converged) << c;
    EXPECT_NEAR(qc.angle, k.phi(c), 1e-9 * k.phi_max()) << c;
  }
}

// The limit c -> r_min: Phi_max - Phi(r_min (1 - e)) ~ sqrt(2 e) / sin(b) (the arccos at the
// small end), so it converges like sqrt(e): c = r_min (1 - 1e-9) would still be 5e-5 short,
// which is why c = r_min itself is evaluated. Both evaluations show the same approach.
TEST(Clairaut, TheLimitIsApproachedLikeTheSquareRoot) {
  const Cone k;
  const RadiusProfile p = sampled([&](double x) { return k.radius(x); }, 0.0, k.length, 50);
  Meridian m;
  m.point = [&](double t) { return Vec2(k.length * t, k.radius(k.length * t)); };
  m.derivative = [&](double) { return Vec2(k.length, k.r1 - k.r2); };
  const double phi_max = clairaut_turn_limit(p, 0.0, k.length).angle;
  for (double e : {1e-4, 1e-6, 1e-8, 1e-10}) {
    const double c = k.r1 * (1.0 - e);
    const double gap = phi_max - clairaut_angle(p, 0.0, k.length, c);
    EXPECT_NEAR(gap / (std::sqrt(2.0 * e) / k.sin_b()), 1.0, 0.01) << e;
    EXPECT_NEAR(phi_max - clairaut_angle(m, c).angle, gap, 1e-8 * phi_max) << e;
  }
}

// A sphere of radius a: a geodesic is a great circle; tangent to the latitude p_m it satisfies
// tan p = tan p_m sin(l), so from latitude p1 (|p1| < p_m) up to p_m it turns by
// pi / 2 + arcsin(tan(-p1) / tan(p_m)); from the equator exactly pi / 2, whatever the opening.
TEST(Clairaut, SphereZoneGivesTheGreatCircle) {
  const double a = 80.0;
  for (const auto& [p1, pm] : {std::pair{0.0, 1.2}, std::pair{-0.5, 1.0}, std::pair{-0.9, 1.3}}) {
    const double expected = M_PI / 2.0 + std::asin(std::tan(-p1) / std::tan(pm));
    Meridian m;
    m.point = [&](double t) { return Vec2(a * std::sin(t), a * std::cos(t)); };
    m.derivative = [&](double t) { return Vec2(a * std::cos(t), -a * std::sin(t)); };
    m.t0 = p1;
    m.t1 = pm;
    const ClairautQuadrature q = clairaut_angle(m, a * std::cos(pm));
    ASSERT_TRUE(q.converged) << p1 << " " << pm;
    EXPECT_NEAR(q.angle, expected, 1e-10) << p1 << " " << pm;
    // The profile r(x) = sqrt(a^2 - x^2) sampled by chords: order 1.5 in the sample step (the
    // chords' O(h^2) radius error meets the 1 / sqrt singularity at the end where r = c).
    const double x0 = a * std::sin(p1), x1 = a * std::sin(pm);
    auto r = [&](double x) { return std::sqrt(a * a - x * x); };
    const ClairautLimit coarse = clairaut_turn_limit(sampled(r, x0, x1, 400), x0, x1);
    const ClairautLimit fine = clairaut_turn_limit(sampled(r, x0, x1, 4000), x0, x1);
    ASSERT_TRUE(fine.bounded) << fine.reason;
    EXPECT_NEAR(fine.angle, expected, 1e-5 * expected) << p1 << " " << pm;
    EXPECT_LT(std::abs(fine.angle - expected), 0.05 * std::abs(coarse.angle - expected));
  }
}

// A cylinder has no limit: Phi(c) = L c / (R sqrt(R^2 - c^2)) -> infinity as c -> R (the hoop).
TEST(Clairaut, CylinderHasNoLimit) {
  const double R = 50.0, L = 200.0;
  const RadiusProfile p = sampled([&](double) { return R; }, 0.0, L, 20);
  for (double c : {10.0, 49.0, 49.999}) {
    EXPECT_NEAR(clairaut_angle(p, 0.0, L, c), L * c / (R * std::sqrt(R * R - c * c)),
                1e-12 * L * c / (R * std::sqrt(R * R - c * c)))
        << c;
  }
  EXPECT_EQ(clairaut_angle(p, 0.0, L, R), std::numeric_limits<double>::infinity());
  const ClairautLimit lim = clairaut_turn_limit(p, 0.0, L);
  EXPECT_FALSE(lim.bounded);
  EXPECT_TRUE(std::isinf(lim.turns));
  EXPECT_NE(lim.reason.find("cylinder"), std::string::npos) << lim.reason;
  // Tessellation noise on the radius does not make a cylinder bounded.
  RadiusProfile noisy = p;
  for (std::size_t i = 0; i < noisy.radius.size(); ++i) noisy.radius[i] += 0.02 * std::sin(7.0 * i);
  EXPECT_FALSE(clairaut_turn_limit(noisy, 0.0, L).bounded);
  // A cone with a cylindrical stretch at its small end neither.
  const RadiusProfile stepped =
      sampled([](double x) { return x < 100.0 ? 40.0 : 40.0 + 0.1 * (x - 100.0); }, 0.0, 300.0, 30);
  EXPECT_FALSE(clairaut_turn_limit(stepped, 0.0, 300.0).bounded);
}

// A waist (the smallest radius inside) is a geodesic parallel: geodesics wind towards it.
TEST(Clairaut, WaistHasNoLimit) {
  const RadiusProfile p =
      sampled([](double x) { return std::sqrt(30.0 * 30.0 + 0.5 * x * x); }, -100.0, 100.0, 200);
  const ClairautLimit lim = clairaut_turn_limit(p, -100.0, 100.0);
  EXPECT_FALSE(lim.bounded);
  EXPECT_NE(lim.reason.find("waist"), std::string::npos) << lim.reason;
  EXPECT_NEAR(lim.min_at, 0.0, 1e-12);
  // Between two axial positions on one side of the waist the limit is that of the zone.
  EXPECT_TRUE(clairaut_turn_limit(p, 10.0, 100.0).bounded);
}

// An end where r = c with a zero meridian slope (the neck of an isotensoid dome) makes the
// integral diverge logarithmically: the quadrature says it did not converge.
TEST(Clairaut, TangentEndDoesNotConverge) {
  Meridian m;
  m.point = [](double t) { return Vec2(t, 30.0 + t * t); };
  m.derivative = [](double t) { return Vec2(1.0, 2.0 * t); };
  m.t1 = 10.0;
  ClairautQuadratureOptions o;
  o.max_panels = 1 << 10;
  const ClairautQuadrature q = clairaut_angle(m, 30.0, o);
  EXPECT_FALSE(q.converged);
  EXPECT_GT(q.error, 1e-3);
  // With c below the neck radius it is an ordinary (converging) integral.
  EXPECT_TRUE(clairaut_angle(m, 29.9).converged);
}

TEST(Clairaut, BadInputThrows) {
  const Cone k;
  const RadiusProfile p = sampled([&](double x) { return k.radius(x); }, 0.0, k.length, 4);
  EXPECT_THROW(clairaut_angle(p, 0.0, k.length, 41.0), InputError);
  EXPECT_THROW(clairaut_angle(p, 0.0, k.length, -1.0), InputError);
  EXPECT_THROW(clairaut_turn_limit(p, 100.0, 100.0), InputError);
  EXPECT_THROW(clairaut_turn_limit(RadiusProfile{}, 0.0, 1.0), InputError);
  ClairautOptions bad;
  bad.flat_length = 0.0;
  EXPECT_THROW(clairaut_turn_limit(p, 0.0, k.length, bad), ConfigError);
  EXPECT_THROW(meridian_profile(Mesh(test::open_cylinder(10, 10, 8, 2)), SpindleAxis{}, 1.0, 0.0),
               InputError);
}

// meridian_profile on meshes of revolution: a cone's generators lie on it, so its section radii
// are exact and so is the limit; a sphere zone's meridian edges are chords, so the limit is off
// by the tessellation (order 1.5 in the ring spacing, as for the sampled profile above: 4.8e-3
// with 20 rings over 1.2 rad, 6.6e-4 with 80).
TEST(Clairaut, MeshedConeAndSphereZone) {
  const Cone k;
  const Mesh cone(test::revolution([&](double z) { return k.radius(z); }, 0.0, k.length, 48, 20));
  const RadiusProfile pc = meridian_profile(cone, SpindleAxis{}, 0.0, k.length);
  ASSERT_GT(pc.axial.size(), 300u);
  EXPECT_DOUBLE_EQ(pc.axial.front(), 0.0);
  EXPECT_DOUBLE_EQ(pc.axial.back(), k.length);
  const ClairautLimit lc = clairaut_turn_limit(pc, 0.0, k.length);
  ASSERT_TRUE(lc.bounded) << lc.reason;
  EXPECT_NEAR(lc.angle, k.phi_max(), 1e-6 * k.phi_max());
  EXPECT_NEAR(lc.min_radius, k.r1, 1e-6);

  const double a = 80.0, z1 = a * std::sin(1.2);
  auto r = [&](double z) { return std::sqrt(a * a - z * z); };
  std::vector<double> err;
  for (int rings : {20, 80}) {
    const Mesh zone(test::revolution(r, 0.0, z1, 64, rings));
    const ClairautLimit lz =
        clairaut_turn_limit(meridian_profile(zone, SpindleAxis{}, 0.0, z1), 0.0, z1);
    ASSERT_TRUE(lz.bounded) << lz.reason;
    err.push_back(std::abs(lz.angle - M_PI / 2.0) / (M_PI / 2.0));
  }
  EXPECT_LT(err[0], 6e-3);
  EXPECT_LT(err[1], 1e-3);
  EXPECT_GT(err[0] / err[1], std::pow(4.0, 1.3));
}

}  // namespace
}  // namespace windplan
