// planner/winding/harmonic.cpp: conformal coordinates of an annulus.
#include "planner/winding/harmonic.h"

#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "tests/mesh_fixtures.h"
#include "tests/planner/revolution_fixtures.h"

namespace windplan {
namespace {

using test::loops_by_z;

TEST(Harmonic, CylinderHeightIsLinearInZ) {
  const double R = 30.0, L = 120.0;
  const Mesh m(test::open_cylinder(R, L, 48, 20));
  const HarmonicCoordinates hc = compute_harmonic_coordinates(m, loops_by_z(m));
  for (int v = 0; v < m.num_vertices(); ++v) {
    EXPECT_NEAR(hc.height[v], m.position(v).z() / L, 1e-9) << "vertex " << v;
  }
}

TEST(Harmonic, CylinderAngleIsThePolarAngleWithA2PiPeriod) {
  const int n = 48;
  const Mesh m(test::open_cylinder(30.0, 120.0, n, 20));
  const HarmonicCoordinates hc = compute_harmonic_coordinates(m, loops_by_z(m));
  // Inside every face the lifted angle differs from the polar angle by one constant (modulo the
  // 2 pi lift), and its total change around a ring is exactly 2 pi.
  double offset = 0.0;
  bool first = true;
  for (int f = 0; f < m.num_faces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = m.position(m.triangle(f)[k]);
      // theta runs along n x grad h = n x z: clockwise seen from +z.
      const double polar = -std::atan2(p.y(), p.x());
      double d = hc.corner_theta(m, f, k) - polar;
      if (first) {
        offset = d;
        first = false;
      }
      d -= offset;
      d -= 2.0 * M_PI * std::round(d / (2.0 * M_PI));
      // Within a face, corners lie on one branch: compare with corner 0 of the same face too.
      ASSERT_NEAR(d, 0.0, 1e-7) << "face " << f << " corner " << k;
    }
  }
  EXPECT_LT(hc.conformal_error, 1e-6);
  EXPECT_FALSE(hc.cut_faces.empty());
}

TEST(Harmonic, ConeIsConformalAndHeightMonotone) {
  const Mesh m(test::revolution([](double z) { return 60.0 - 0.2 * z; }, 0.0, 150.0, 64, 40));
  const HarmonicCoordinates hc = compute_harmonic_coordinates(m, loops_by_z(m));
  // Conformal coordinates of a cone: h ~ log(r) scaled (h' = c / (r sin)); monotone in z.
  for (int v = 0; v < m.num_vertices(); ++v) {
    const double z = m.position(v).z();
    const double r0 = 60.0, r1 = 30.0, r = 60.0 - 0.2 * z;
    const double expected = std::log(r / r0) / std::log(r1 / r0);
    EXPECT_NEAR(hc.height[v], expected, 2e-3) << "vertex " << v;
  }
  EXPECT_LT(hc.conformal_error, 1.0);  // degrees, tessellation-level
}

TEST(Harmonic, RejectsMeshesThatAreNotAnnuli) {
  const Mesh disk(test::grid(4, 4));
  std::array<std::vector<int>, 2> loops{std::vector<int>{0}, std::vector<int>{1}};
  try {
    compute_harmonic_coordinates(disk, loops);
    FAIL() << "a disk was accepted";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("1 boundary loop(s)"), std::string::npos) << e.what();
  }
  const Mesh torus(test::torus(3.0, 1.0, 12, 8));
  try {
    compute_harmonic_coordinates(torus, loops);
    FAIL() << "a torus was accepted";
  } catch (const TopologyError& e) {
    EXPECT_NE(std::string(e.what()).find("0 boundary loop(s)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("genus 1"), std::string::npos) << e.what();
  }
  const Mesh cyl(test::open_cylinder(1.0, 2.0, 8, 2));
  std::array<std::vector<int>, 2> bad{std::vector<int>{9}, std::vector<int>{0}};  // 9: interior
  EXPECT_THROW(compute_harmonic_coordinates(cyl, bad), InputError);
}

}  // namespace
}  // namespace windplan
