// The robot's payout eye at the true clearance from the mandrel (export/machine/clearance_eye.h)
// against closed forms: on a cylinder of radius r the tangent line at angle a to the axis is at
// distance sqrt(r^2 + L^2 sin^2 a) - r from it, so the eye is at L = sqrt((r + c)^2 - r^2) / sin a;
// on the inner equator of a torus the tangent along the big circle runs through the tube
// (`enters`) and the eye is where it has come out 20 mm beyond (radius R + r + c).
#include "export/machine/clearance_eye.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

TEST(ClearanceEye, CylinderClosedForm) {
  const double r = 50, c = 20;
  const Mesh mesh(test::open_cylinder(r, 400, 512, 100));  // chord sag 0.001 mm
  const ClosestPointQuery query(mesh);
  const Vec3 p(r, 0, 200);  // a vertex column of the mesh
  for (double a_deg : {30.0, 55.0, 80.0, 90.0}) {
    const double a = a_deg * M_PI / 180;
    const ClearanceEye e =
        solve_clearance_eye(mesh, query, p, Vec3(0, std::sin(a), std::cos(a)), c, "test");
    const double l = std::sqrt((r + c) * (r + c) - r * r) / std::sin(a);
    EXPECT_NEAR(e.free_length, l, 0.01) << a_deg;
    EXPECT_NEAR(e.distance, c, 1e-3) << a_deg;
    EXPECT_NEAR((e.eye - p).norm(), e.free_length, 1e-9);
    EXPECT_FALSE(e.enters) << a_deg;
  }
}

TEST(ClearanceEye, TangentThroughTheMandrelIsReported) {
  const double R = 100, r = 25, c = 20;
  const Mesh mesh(test::torus(R, r, 256, 128));
  const ClosestPointQuery query(mesh);
  // The inner equator, tangent along the big circle: the line runs into the tube.
  const ClearanceEye e = solve_clearance_eye(mesh, query, Vec3(R - r, 0, 0), Vec3(0, 1, 0), c);
  EXPECT_TRUE(e.enters);
  EXPECT_NEAR(e.distance, c, 1e-3);
  // It comes out at radius R + r and reaches the clearance beyond it.
  EXPECT_NEAR(std::hypot(e.eye.x(), e.eye.y()), R + r + c, 0.1);
  // The outer equator: the line leaves at once.
  const ClearanceEye o = solve_clearance_eye(mesh, query, Vec3(R + r, 0, 0), Vec3(0, 1, 0), c);
  EXPECT_FALSE(o.enters);
  EXPECT_NEAR(o.free_length, std::sqrt((R + r + c) * (R + r + c) - (R + r) * (R + r)), 0.05);
}

TEST(ClearanceEye, BadTangentIsRefused) {
  const Mesh mesh(test::open_cylinder(50, 100, 64, 10));
  const ClosestPointQuery query(mesh);
  EXPECT_THROW(solve_clearance_eye(mesh, query, Vec3(50, 0, 50), Vec3::Zero(), 20), InputError);
  // A line that never gets 20 mm from the mandrel within max_length.
  EXPECT_THROW(solve_clearance_eye(mesh, query, Vec3(50, 0, 50), Vec3(0, 0, 1), 20, "", 1e-4, 30),
               InputError);
}

}  // namespace
}  // namespace windplan
