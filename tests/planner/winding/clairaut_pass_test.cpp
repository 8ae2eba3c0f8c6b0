// Geodesic passes from Clairaut's integral (planner/winding/clairaut_pass.h) against closed forms:
// the cylinder helix, the cone's development and the great circles of a hemisphere.
#include "planner/winding/clairaut_pass.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"
#include "tests/planner/winding_fixtures.h"

namespace windplan {
namespace {

TEST(ClairautPass, CylinderIsTheHelix) {
  const double R = 50, L = 400, c = 30;
  const std::vector<Vec2> m{{0, R}, {L, R}};
  const ClairautPass p = clairaut_pass(m, c, {1.5});
  const double ca = std::sqrt(R * R - c * c) / R;     // cos a
  EXPECT_NEAR(p.angle, L * c / (R * R * ca), 1e-12);  // L tan(a) / R
  EXPECT_NEAR(p.length, L / ca, 1e-9);
  EXPECT_FALSE(p.turns_around[0]);
  EXPECT_FALSE(p.turns_around[1]);
  for (std::size_t i = 1; i < p.samples.size(); ++i) {
    const PassSample &a = p.samples[i - 1], &b = p.samples[i];
    EXPECT_LE(b.length - a.length, 1.5 + 1e-9);
    EXPECT_NEAR(b.phi, b.x * c / (R * R * ca), 1e-12);  // phi linear in x
    EXPECT_NEAR(b.r * std::sin(b.angle), c, 1e-12);     // Clairaut
  }
}

TEST(ClairautPass, ConeTurnsAroundWhereItsDevelopmentSays) {
  // Unrolled, the cone is a plane sector and the geodesic a straight line tangent to the circle
  // of radius c / sin(b) about the apex: from the tangent point to the large end it turns the
  // mandrel by arccos(c / r2) / sin(b) and is sqrt(r2^2 - c^2) / sin(b) long.
  const double r1 = 20, r2 = 60, L = 300, c = 35;
  const double sb = (r2 - r1) / std::hypot(L, r2 - r1);
  const ClairautPass p = clairaut_pass({{0, r1}, {L, r2}}, c);
  EXPECT_TRUE(p.turns_around[0]);
  EXPECT_FALSE(p.turns_around[1]);
  EXPECT_NEAR(p.angle, std::acos(c / r2) / sb, 1e-12);
  EXPECT_NEAR(p.length, std::sqrt(r2 * r2 - c * c) / sb, 1e-9);
  EXPECT_NEAR(p.samples.front().r, c, 1e-12);
  EXPECT_NEAR(p.samples.front().x, L * (c - r1) / (r2 - r1), 1e-9);
  EXPECT_NEAR(p.samples.front().angle, M_PI / 2, 1e-12);  // tangent to the parallel
  // Every sample on the line: in the development (rho = r / sin b, psi = phi sin b) the
  // distance from the apex to the line is rho cos(psi0 - psi)... i.e. rho cos(psi) = c / sin b.
  for (const PassSample& s : p.samples) {
    EXPECT_NEAR(s.r / sb * std::cos(s.phi * sb), c / sb, 1e-9);
  }
}

TEST(ClairautPass, HemisphericalDomesTurnAQuarterTurnEach) {
  // A great circle turns 90 deg about the axis from its highest latitude (the turnaround
  // parallel r = c) to the equator, whatever c: Phi = pi + L tan(a) / R on the capsule.
  const double R = 100, L = 300, r0 = 30;
  const std::vector<Vec2> m = test::capsule_meridian(R, L, r0, 4000, 10);
  for (double c : {35.0, 45.0, 70.0}) {
    const ClairautPass p = clairaut_pass(m, c);
    EXPECT_TRUE(p.turns_around[0] && p.turns_around[1]);
    const double expected = M_PI + L * c / (R * std::sqrt(R * R - c * c));
    EXPECT_NEAR(p.angle, expected, 2e-5) << "c = " << c;
    EXPECT_NEAR(clairaut_pass_angle(m, c), p.angle, 1e-12);
  }
}

TEST(ClairautPass, MeshMeridianGivesTheSameAngle) {
  const double R = 100, L = 300, r0 = 30, c = 45;
  const std::vector<Vec2> m = test::capsule_meridian(R, L, r0, 200, 20);
  const Mesh mesh = test::revolve(m, 96);
  const std::vector<Vec2> section = annulus_meridian(mesh, SpindleAxis{});
  ASSERT_GE(section.size(), m.size());
  EXPECT_NEAR(section.front().x(), m.front().x(), 1e-9);
  EXPECT_NEAR(section.back().x(), m.back().x(), 1e-9);
  const double expected = M_PI + L * c / (R * std::sqrt(R * R - c * c));
  EXPECT_NEAR(clairaut_pass_angle(section, c), expected, 2e-3);
}

TEST(ClairautPass, WaistAndBadInputAreRefused) {
  const std::vector<Vec2> waist{{0, 50}, {100, 30}, {200, 50}};
  EXPECT_THROW(clairaut_pass(waist, 40), InputError);  // cannot cross r = 30 < c
  EXPECT_NO_THROW(clairaut_pass(waist, 25));
  EXPECT_THROW(clairaut_pass(waist, 60), InputError);  // nowhere r >= c
  EXPECT_THROW(clairaut_pass(waist, -1), InputError);
  EXPECT_THROW(clairaut_pass(waist, 25, {0.0}), InputError);
}

TEST(ClairautPass, AxisFrameIsRightHanded) {
  for (const Vec3& d : {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0.3, -0.4, 0.866)}) {
    SpindleAxis a;
    a.direction = d.normalized();
    const auto f = axis_frame(a);
    EXPECT_NEAR(f[0].dot(a.direction), 0.0, 1e-15);
    EXPECT_NEAR(f[0].cross(f[1]).dot(a.direction), 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace windplan
