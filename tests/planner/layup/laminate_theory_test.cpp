#include "planner/layup/laminate_theory.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

ElasticConstants carbon() {
  FibreResin m;
  return rule_of_mixtures(m);
}

TEST(LaminateTheory, RuleOfMixtures) {
  FibreResin m;
  m.fibre_modulus = 230000.0;
  m.resin_modulus = 3500.0;
  m.volume_fraction = 0.6;
  const ElasticConstants c = rule_of_mixtures(m);
  EXPECT_NEAR(c.e1, 0.6 * 230000.0 + 0.4 * 3500.0, 1e-9);
  EXPECT_NEAR(c.e2, 1.0 / (0.6 / 15000.0 + 0.4 / 3500.0), 1e-9);
  EXPECT_NEAR(c.nu12, 0.6 * 0.2 + 0.4 * 0.35, 1e-12);
  std::string why;
  EXPECT_TRUE(c.is_valid(&why)) << why;
  m.volume_fraction = 1.0;
  EXPECT_THROW(rule_of_mixtures(m), ConfigError);
}

// A single ply along x: eps_x = N_x / (E1 t) - nu12 N_y / (E1 t), eps_y = N_y / (E2 t) -
// nu12 N_x / (E1 t).
TEST(LaminateTheory, SinglePlyClosedForm) {
  const ElasticConstants c = carbon();
  const double t = 0.7, nx = 300.0, ny = 50.0;
  const Vec3d e = membrane_strains(c, {{0.0, t}}, {nx, ny, 0.0});
  EXPECT_NEAR(e[0], nx / (c.e1 * t) - c.nu12 * ny / (c.e1 * t), 1e-12);
  EXPECT_NEAR(e[1], ny / (c.e2 * t) - c.nu12 * nx / (c.e1 * t), 1e-12);
  EXPECT_NEAR(e[2], 0.0, 1e-15);
  // The same ply turned by 90 deg swaps the roles.
  const Vec3d f = membrane_strains(c, {{90.0, t}}, {ny, nx, 0.0});
  EXPECT_NEAR(f[0], e[1], 1e-12);
  EXPECT_NEAR(f[1], e[0], 1e-12);
  // The ply's own strains and stresses give its load back.
  const Vec3d s = ply_stresses(c, ply_strains(e, 0.0));
  EXPECT_NEAR(s[0] * t, nx, 1e-9);
  EXPECT_NEAR(s[1] * t, ny, 1e-9);
}

// An isotropic "ply" (E1 = E2, G = E / 2 (1 + nu)) is the same at every angle.
TEST(LaminateTheory, IsotropicIsInvariant) {
  ElasticConstants c;
  c.e1 = c.e2 = c.e3 = 70000.0;
  c.nu12 = c.nu13 = c.nu23 = 0.3;
  c.g12 = c.g13 = c.g23 = 70000.0 / 2.6;
  const Mat3d q0 = rotated_stiffness(c, 0.0);
  for (double a : {17.0, 45.0, -63.0}) {
    const Mat3d q = rotated_stiffness(c, a);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(q[i][j], q0[i][j], 1e-8 * q0[0][0]);
  }
}

// A balanced +a/-a pair does not shear under N_x, N_y; ply strains transform as tensors.
TEST(LaminateTheory, BalancedAnglePly) {
  const ElasticConstants c = carbon();
  const Vec3d e = membrane_strains(c, {{25.0, 0.3}, {-25.0, 0.3}, {89.0, 0.4}, {-89.0, 0.4}},
                                   {500.0, 1000.0, 0.0});
  EXPECT_NEAR(e[2], 0.0, 1e-14);
  EXPECT_GT(e[1], 0.0);
  // Invariant: eps_1 + eps_2 = eps_x + eps_y.
  const Vec3d p = ply_strains(e, 25.0);
  EXPECT_NEAR(p[0] + p[1], e[0] + e[1], 1e-15);
}

}  // namespace
}  // namespace windplan
