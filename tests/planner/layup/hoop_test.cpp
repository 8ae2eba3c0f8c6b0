#include "planner/layup/hoop.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/base/errors.h"

namespace windplan {
namespace {

RadiusProfile cylinder(double R, double x0, double x1) {
  RadiusProfile p;
  p.axial = {x0, x1};
  p.radius = {R, R};
  return p;
}

// A vessel-like profile: cones standing in for the domes on either side of a cylinder [0, 300].
RadiusProfile vessel(double R) {
  RadiusProfile p;
  p.axial = {-60.0, 0.0, 150.0, 300.0, 360.0};
  p.radius = {30.0, R, R, R, 30.0};
  return p;
}

// Axial advance per turn of a pass, measured from its positions (unwrapped angle about z).
double measured_pitch(const Circuit& c, const CircuitSegment& sg) {
  double turned = 0.0;
  for (int i = sg.first + 1; i <= sg.last; ++i) {
    const Vec3 &a = c.points[i - 1].position, &b = c.points[i].position;
    turned += std::remainder(std::atan2(b.y(), b.x()) - std::atan2(a.y(), a.x()), 2.0 * M_PI);
  }
  const double dx = c.points[sg.last].position.z() - c.points[sg.first].position.z();
  return std::abs(dx) / (std::abs(turned) / (2.0 * M_PI));
}

TEST(Hoop, PitchAndAngleOnACylinder) {
  HoopOptions o;
  o.band_width = 10.0;
  o.overlap = 2.0;
  o.x0 = 20.0;
  o.x1 = 280.0;
  const double R = 100.0, p = 8.0;
  const HoopLayer L = plan_hoop_layer(cylinder(R, 0.0, 300.0), SpindleAxis{}, o);
  EXPECT_DOUBLE_EQ(L.pitch, p);
  EXPECT_NEAR(L.angle, std::atan(2.0 * M_PI * R / p) * 180.0 / M_PI, 1e-3);
  ASSERT_EQ(L.circuits.size(), 1u);
  const Circuit& c = L.circuits[0];
  // Tie-on turn, arc, pass, reversal, pass, arc, tie-off turn.
  ASSERT_EQ(c.segments.size(), 7u);
  for (int i : {1, 3, 5}) EXPECT_EQ(c.segments[i].kind, CircuitSegment::Kind::Turnaround);
  EXPECT_NEAR(measured_pitch(c, c.segments[2]), p, 1e-9);
  EXPECT_NEAR(measured_pitch(c, c.segments[4]), p, 1e-9);
  // Every point lies on the cylinder, its normal radial.
  for (const FibrePoint& fp : c.points) {
    EXPECT_NEAR(std::hypot(fp.position.x(), fp.position.y()), R, 1e-9);
    EXPECT_NEAR(fp.normal.z(), 0.0, 1e-9);
  }
  // Full coverage of the range on every meridian; the reversal within friction.
  EXPECT_GE(L.coverage, 1.0 - 1e-12);
  EXPECT_LE(L.reversal_slippage, o.mu);
  EXPECT_GT(L.reversal_slippage, 0.5 * o.reversal_friction * o.mu);  // the arc does bend
  EXPECT_TRUE(L.warnings.empty());
  // Its extreme axial positions: the reversal apex x1 - B/2 + p/2, and the tie turns at
  // x0 + B/2.
  double zmin = 1e9, zmax = -1e9;
  for (const FibrePoint& fp : c.points) {
    zmin = std::min(zmin, fp.position.z());
    zmax = std::max(zmax, fp.position.z());
  }
  EXPECT_NEAR(zmax, 280.0 - 5.0 + 4.0, 1e-6);
  EXPECT_NEAR(zmin, 20.0 + 5.0, 1e-9);
  // The band centre line: two tie turns of 2 pi R and 2 passes of (279 - 25) / p turns of a
  // helix of pitch p (the arcs stand in for pieces of about their own length).
  const double turn = std::hypot(2.0 * M_PI * R, p);
  EXPECT_NEAR(L.length, 2.0 * 2.0 * M_PI * R + 2.0 * (279.0 - 25.0) / p * turn, 1e-3 * L.length);
}

TEST(Hoop, ReversalArcKeepsTheSlippageBelowMu) {
  for (double mu : {0.1, 0.3}) {
    HoopOptions o;
    o.mu = mu;
    o.passes = 4;
    const HoopLayer L = plan_hoop_layer(cylinder(60.0, 0.0, 200.0), SpindleAxis{}, o);
    EXPECT_LE(L.reversal_slippage, mu) << mu;
    EXPECT_EQ(L.circuits[0].segments.size(), 11u);
    // The passes themselves are geodesic helices on the cylinder: no slippage.
    for (const CircuitSegment& sg : L.circuits[0].segments) {
      if (sg.kind != CircuitSegment::Kind::Pass) continue;
      for (int i = sg.first + 5; i < sg.last - 5; ++i) {
        EXPECT_LT(L.circuits[0].points[i].slippage, 1e-6);
      }
    }
  }
}

TEST(Hoop, DefaultRangeIsTheCylindricalPart) {
  const auto [x0, x1] = cylinder_range(vessel(100.0));
  EXPECT_DOUBLE_EQ(x0, 0.0);
  EXPECT_DOUBLE_EQ(x1, 300.0);
  const HoopLayer L = plan_hoop_layer(vessel(100.0), SpindleAxis{}, HoopOptions{});
  EXPECT_DOUBLE_EQ(L.x0, 0.0);
  EXPECT_DOUBLE_EQ(L.x1, 300.0);
  EXPECT_GE(L.coverage, 1.0 - 1e-12);
}

TEST(Hoop, ASecondLayerOnRadiusRPlusTHasTheAngleThatRadiusGives) {
  const double R = 80.0, t = 1.7, p = 10.0;
  const HoopLayer L = plan_hoop_layer(cylinder(R + t, 0.0, 200.0), SpindleAxis{}, HoopOptions{});
  EXPECT_NEAR(L.angle, std::atan(2.0 * M_PI * (R + t) / p) * 180.0 / M_PI, 1e-3);
}

TEST(Hoop, PipeWoundToItsEndsSaysWhatIsLeftBare) {
  // The range is the whole pipe: the apexes are pulled B/2 inside, the ends are not fully covered.
  const HoopLayer L = plan_hoop_layer(cylinder(50.0, 0.0, 100.0), SpindleAxis{}, HoopOptions{});
  EXPECT_LT(L.coverage, 1.0);
  EXPECT_GT(L.coverage, 0.89);
  ASSERT_FALSE(L.warnings.empty());
  EXPECT_NE(L.warnings[0].find("cover"), std::string::npos);
}

TEST(Hoop, RangeOutsideTheMandrelIsRejected) {
  HoopOptions o;
  o.x0 = -50.0;
  o.x1 = 100.0;
  try {
    plan_hoop_layer(cylinder(50.0, 0.0, 300.0), SpindleAxis{}, o, "layers[1]");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("layers[1].range"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("outside the mandrel"), std::string::npos) << e.what();
  }
}

TEST(Hoop, InvalidOptions) {
  HoopOptions o;
  std::string why;
  o.overlap = 10.0;
  EXPECT_FALSE(o.is_valid(&why));
  EXPECT_NE(why.find("overlap"), std::string::npos);
  o = {};
  o.mu = 0.0;
  EXPECT_FALSE(o.is_valid(&why));
  EXPECT_NE(why.find("mu"), std::string::npos);
  o = {};
  o.mu = 1e9;
  EXPECT_FALSE(o.is_valid(&why));
  EXPECT_NE(why.find("mu must be in (0, 2]"), std::string::npos) << why;
  o = {};
  o.x0 = 10.0;
  o.x1 = 5.0;
  EXPECT_FALSE(o.is_valid(&why));
  EXPECT_THROW(plan_hoop_layer(cylinder(50.0, 0.0, 300.0), SpindleAxis{}, o), ConfigError);
}

}  // namespace
}  // namespace windplan
