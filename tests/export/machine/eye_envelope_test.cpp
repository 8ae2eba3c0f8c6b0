#include "export/machine/eye_envelope.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "export/machine/clearance.h"
#include "export/machine/kinematics.h"
#include "geometry/base/errors.h"
#include "tests/export/plan_fixtures.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

RadiusProfile sampled(double x0, double x1, int n, double (*r)(double, double), double p) {
  RadiusProfile out;
  for (int i = 0; i <= n; ++i) {
    const double x = x0 + (x1 - x0) * i / n;
    out.axial.push_back(x);
    out.radius.push_back(r(x, p));
  }
  return out;
}

double sphere_r(double x, double R) { return std::sqrt(std::max(0.0, R * R - x * x)); }
double torus_r(double x, double rt) { return 80.0 + std::sqrt(std::max(0.0, rt * rt - x * x)); }

TEST(EyeEnvelope, DilatedSphereIsTheConcentricSphere) {
  // The region under a half circle of radius R dilated by c is the half disc of radius R + c.
  const double R = 60, c = 20;
  const RadiusProfile d = dilate_profile(sampled(-R, R, 4000, sphere_r, R), c);
  int checked = 0;
  for (std::size_t i = 0; i < d.axial.size(); ++i) {
    const double x = d.axial[i];
    if (std::fabs(x) > R) continue;
    EXPECT_NEAR(d.radius[i], std::sqrt((R + c) * (R + c) - x * x), 0.01) << x;
    EXPECT_LE(d.radius[i], std::sqrt((R + c) * (R + c) - x * x) + 1e-9) << x;
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST(EyeEnvelope, DilatedTorusProfileIsTheOffsetTube) {
  // A torus about z (tube centre radius 80, tube radius rt): the swept profile's upper half,
  // dilated by c, is 80 + sqrt((rt + c)^2 - x^2) over the tube.
  const double rt = 25, c = 15;
  const RadiusProfile d = dilate_profile(sampled(-rt, rt, 4000, torus_r, rt), c);
  for (std::size_t i = 0; i < d.axial.size(); ++i) {
    const double x = d.axial[i];
    if (std::fabs(x) > rt) continue;
    EXPECT_NEAR(d.radius[i], 80 + std::sqrt((rt + c) * (rt + c) - x * x), 0.01) << x;
  }
}

TEST(EyeEnvelope, ClearanceIsTheTrueDistanceOnSphereAndTorusMeshes) {
  // Points on the offset surfaces are at distance c from the exact surfaces; the inscribed meshes
  // are at most their sagitta farther.
  const double c = 20;
  {
    const double R = 60;
    const Mesh mesh(test::uv_sphere(R, 256, 128));
    const ClosestPointQuery q(mesh);
    std::vector<Vec3> eyes;
    for (int i = 0; i < 50; ++i) {
      const double th = M_PI * (i + 0.5) / 50 - M_PI / 2, ph = 0.37 * i;
      eyes.push_back((R + c) *
                     Vec3(std::cos(th) * std::cos(ph), std::cos(th) * std::sin(ph), std::sin(th)));
    }
    const ClearanceCheck cc = check_clearance(q, eyes);
    EXPECT_EQ(cc.checked, 50);
    EXPECT_NEAR(cc.min_distance, c, 0.02);
    EXPECT_GE(cc.min_distance, c - 1e-9);
  }
  {
    const double Rt = 80, rt = 25;
    const Mesh mesh(test::torus(Rt, rt, 256, 128));
    const ClosestPointQuery q(mesh);
    std::vector<Vec3> eyes;
    for (int i = 0; i < 50; ++i) {
      const double v = 2 * M_PI * i / 50, u = 0.61 * i;
      const double rho = Rt + (rt + c) * std::cos(v);
      eyes.push_back(Vec3(rho * std::cos(u), rho * std::sin(u), (rt + c) * std::sin(v)));
    }
    const ClearanceCheck cc = check_clearance(q, eyes);
    EXPECT_NEAR(cc.min_distance, c, 0.02);
  }
}

TEST(EyeEnvelope, ClearanceIsTheMinimumOfEveryEyesFullQuery) {
  // check_clearance bounds each query by the nearest eye so far (closest_within); the minimum,
  // its index and both points must be those of querying every eye in full, bit for bit.
  const Mesh mesh(test::torus(80, 25, 96, 48));
  const ClosestPointQuery q(mesh);
  std::vector<Vec3> eyes;
  for (int i = 0; i < 400; ++i) {
    const double v = 2 * M_PI * std::fmod(0.377 * i, 1.0), u = 0.61 * i;
    const double d = 25 + 5 + 30 * std::fmod(0.7131 * i * i + 0.5, 1.0);  // 5..35 mm off
    const double rho = 80 + d * std::cos(v);
    eyes.push_back(Vec3(rho * std::cos(u), rho * std::sin(u), d * std::sin(v)));
  }
  double best = std::numeric_limits<double>::infinity();
  int worst = -1;
  Vec3 surface = Vec3::Zero();
  for (int i = 0; i < static_cast<int>(eyes.size()); ++i) {
    const ClosestPointQuery::Hit h = q.closest(eyes[i]);
    if (h.distance < best) {
      best = h.distance;
      worst = i;
      surface = h.position;
    }
    // Bounded above the distance: the same hit; at or below it: none.
    const double d2 = (h.position - eyes[i]).squaredNorm();
    const ClosestPointQuery::Hit above = q.closest_within(eyes[i], d2 * (1 + 1e-12));
    EXPECT_EQ(above.point.element, h.point.element);
    EXPECT_EQ(above.distance, h.distance);
    EXPECT_EQ(q.closest_within(eyes[i], d2).point.element, -1);
    EXPECT_EQ(q.closest_within(eyes[i], 0.9 * d2).distance,
              std::numeric_limits<double>::infinity());
  }
  const ClearanceCheck cc = check_clearance(q, eyes);
  EXPECT_EQ(cc.checked, 400);
  EXPECT_EQ(cc.min_distance, best);
  EXPECT_EQ(cc.worst, worst);
  EXPECT_EQ(cc.worst_eye, eyes[worst]);
  EXPECT_EQ(cc.worst_surface, surface);
  EXPECT_GT(worst, 0);  // the nearest eye is not the first one (the bound was used)
}

TEST(EyeEnvelope, Lathe2EyeRunsOnTheCylinderOfTheGivenRadius) {
  const WindingPlan plan = test::helix_plan(50, 40, 2, 801);
  MachineOptions m;  // lathe2
  for (double radius : {0.0, 95.0}) {
    m.envelope.radius = radius;
    const double expect = radius > 0 ? radius : 50 + m.envelope.clearance;
    const Motion mo = compute_motion(plan, m);
    for (const MachineState& s : mo.states) EXPECT_NEAR(s.y_mm, expect, 1e-6);
    EXPECT_NE(mo.envelope.find("cylinder"), std::string::npos) << mo.envelope;
  }
  // A lathe2 cannot follow a varying profile or a free length.
  m.envelope.radius = 0;
  m.envelope.profile = {{0, 70}, {100, 90}};
  EXPECT_THROW(compute_motion(plan, m), ConfigError);
}

TEST(EyeEnvelope, Lathe4EyeKeepsTheClearanceFromTheMeshAndAViolationNamesThePoint) {
  // A helix on a cylinder mesh: the lathe4 eye on the clearance envelope is c from the mesh.
  const double R = 50, c = 20;
  const WindingPlan plan = test::helix_plan(R, 50, 1, 801);
  const Mesh mesh(test::open_cylinder(R, 400, 256, 20));
  MachineOptions m;
  m.kind = "lathe4";
  m.envelope.clearance = c;
  const Motion mo = compute_motion(plan, m, &mesh);
  EXPECT_NEAR(mo.min_clearance, c, 0.02);
  EXPECT_GE(mo.min_clearance, c - 0.05);
  // An explicit profile closer than the clearance is an error naming the point.
  m.envelope.profile = {{-100, 60}, {1000, 60}};
  try {
    compute_motion(plan, m, &mesh);
    FAIL();
  } catch (const InputError& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("circuit 0, point"), std::string::npos) << w;
    EXPECT_NE(w.find("less than the clearance 20"), std::string::npos) << w;
  }
}

}  // namespace
}  // namespace windplan
