#include "export/machine/kinematics.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "tests/export/plan_fixtures.h"
#include "tests/mesh_fixtures.h"

namespace windplan {
namespace {

// A unit vector tangent to the surface at p (normal n), at angle `a` in the tangent plane.
Vec3 tangent_in_plane(const Vec3& n, double a) {
  Vec3 e1 = n.cross(Vec3::UnitZ());
  if (e1.norm() < 1e-9) e1 = n.cross(Vec3::UnitX());
  e1.normalize();
  const Vec3 e2 = n.cross(e1);
  return std::cos(a) * e1 + std::sin(a) * e2;
}

// Checks the eye of every (p, t): on the tangent line, ahead of p, on the envelope, and the first
// crossing (the tangent line stays inside the envelope before it).
void check_eyes(const Envelope& env, const std::vector<std::pair<Vec3, Vec3>>& pts) {
  const AxisFrame f = make_axis_frame(SpindleAxis{});
  for (const auto& [p, t] : pts) {
    const EyeSolution s = solve_payout_eye(f, env, p, t);
    ASSERT_GE(s.free_length, 0.0);
    EXPECT_LT((s.eye - p).cross(t).norm(), 1e-9);
    EXPECT_NEAR((s.eye - p).dot(t), s.free_length, 1e-9);
    EXPECT_NEAR(f.radius(s.eye), env.radius_at(f.axial(s.eye)), 1e-6);
    for (int k = 1; k < 50; ++k) {
      const Vec3 q = p + s.free_length * (k / 50.0) * t;
      EXPECT_LT(f.radius(q), env.radius_at(f.axial(q)) + 1e-9);
    }
  }
}

TEST(Kinematics, AxisFrameForZAxisIsXY) {
  const AxisFrame f = make_axis_frame(SpindleAxis{});
  EXPECT_NEAR((f.u - Vec3::UnitX()).norm(), 0.0, 1e-15);
  EXPECT_NEAR((f.v - Vec3::UnitY()).norm(), 0.0, 1e-15);
  EXPECT_NEAR(f.angle(Vec3(0, 2, 5)), M_PI / 2, 1e-15);
}

TEST(Kinematics, EyeOnCylinderEnvelopeClosedForm) {
  // Cylinder R = 50, clearance 20: a fibre at winding angle alpha leaves the envelope after
  // L = sqrt((R + c)^2 - R^2) / sin(alpha).
  const double R = 50, cl = 20;
  RadiusProfile prof;
  prof.axial = {-100, 100};
  prof.radius = {R, R};
  EnvelopeOptions eo;
  eo.clearance = cl;
  const Envelope env = make_envelope(prof, eo);
  const AxisFrame f = make_axis_frame(SpindleAxis{});
  for (double alpha : {10.0, 30.0, 45.0, 60.0, 89.0, 90.0}) {
    const double a = alpha * M_PI / 180;
    const Vec3 p(R, 0, 0);
    const Vec3 t(0, std::sin(a), std::cos(a));
    const EyeSolution s = solve_payout_eye(f, env, p, t);
    EXPECT_NEAR(s.free_length, std::sqrt((R + cl) * (R + cl) - R * R) / std::sin(a), 1e-9) << alpha;
  }
  std::vector<std::pair<Vec3, Vec3>> pts;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 2 * M_PI), z(-50, 50);
  for (int i = 0; i < 300; ++i) {
    const double ph = u(rng);
    const Vec3 n(std::cos(ph), std::sin(ph), 0);
    Vec3 t = tangent_in_plane(n, u(rng));
    if (std::fabs(t.z()) > 0.999) continue;  // nearly axial: leaves far away, fine but slow
    pts.push_back({Vec3(R * n.x(), R * n.y(), z(rng)), t});
  }
  check_eyes(env, pts);
}

TEST(Kinematics, EyeOnConeAndDomeEnvelopes) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 2 * M_PI), w(0.05, 0.95);
  // Cone r(x) = 20 + 0.3 (x + 100) on [-100, 100], clearance 15 (clearance mode).
  {
    RadiusProfile prof;
    prof.axial = {-100, 100};
    prof.radius = {20, 80};
    EnvelopeOptions eo;
    eo.clearance = 15;
    const Envelope env = make_envelope(prof, eo);
    EXPECT_NEAR(env.max_slope, 0.3, 1e-12);
    std::vector<std::pair<Vec3, Vec3>> pts;
    for (int i = 0; i < 300; ++i) {
      const double x = -100 + 200 * w(rng), ph = u(rng);
      const double r = prof.at(x);
      const Vec3 radial(std::cos(ph), std::sin(ph), 0);
      const Vec3 n = (radial - 0.3 * Vec3::UnitZ()).normalized();
      pts.push_back({r * radial + x * Vec3::UnitZ(), tangent_in_plane(n, u(rng))});
    }
    check_eyes(env, pts);
  }
  // Sphere R = 60 with a dome-like explicit envelope sqrt(R^2 - x^2) + 25 (profile mode).
  {
    const double R = 60;
    EnvelopeOptions eo;
    for (int i = 0; i <= 120; ++i) {
      const double x = -R + i;
      eo.profile.push_back({x, std::sqrt(std::max(0.0, R * R - x * x)) + 25});
    }
    const Envelope env = make_envelope(RadiusProfile{}, eo);
    std::vector<std::pair<Vec3, Vec3>> pts;
    for (int i = 0; i < 300; ++i) {
      const double th = M_PI * w(rng), ph = u(rng);
      const Vec3 n(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
      Vec3 t = tangent_in_plane(n, u(rng));
      pts.push_back({R * n, t});
    }
    check_eyes(env, pts);
  }
}

TEST(Kinematics, EnvelopeInsideMandrelAndAxialTangentAreRejected) {
  const AxisFrame f = make_axis_frame(SpindleAxis{});
  EnvelopeOptions eo;
  eo.profile = {{-100, 40}, {100, 40}};
  const Envelope env = make_envelope(RadiusProfile{}, eo);
  try {
    solve_payout_eye(f, env, Vec3(50, 0, 0), Vec3(0, 1, 0), "circuit 3, point 7");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("inside the mandrel"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("circuit 3, point 7"), std::string::npos);
  }
  try {
    solve_payout_eye(f, env, Vec3(30, 0, 0), Vec3(0, 0, 1));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("parallel"), std::string::npos) << e.what();
  }
  // A whole plan with an envelope inside the mandrel.
  WindingPlan plan = test::helix_plan(50, 45, 1, 100);
  MachineOptions m;
  m.envelope.profile = {{-100, 45}, {1000, 45}};
  EXPECT_THROW(compute_motion(plan, m), InputError);
}

TEST(Kinematics, HelixAxesAreLinearWithWindingAngleSlope) {
  const double R = 50, alpha = 35, cl = 20;
  const WindingPlan plan = test::helix_plan(R, alpha, 3, 3001);
  MachineOptions m;
  m.kind = "lathe4";
  m.envelope.clearance = cl;
  m.chord_tolerance = 0.01;
  m.tangent_window = 0;  // the exact tangents (the smoothing has its own test)
  const Motion mo = compute_motion(plan, m);
  ASSERT_GT(mo.states.size(), 20u);
  const double a = alpha * M_PI / 180;
  const double slope = -R / std::tan(a);  // dX/dA per radian (A = -theta)
  // B = atan2(sin(alpha) cos(delta), cos(alpha)), cos(delta) = R / (R + cl).
  const double b = std::atan2(std::sin(a) * R / (R + cl), std::cos(a)) * 180 / M_PI;
  const MachineState& s0 = mo.states.front();
  for (const MachineState& s : mo.states) {
    if (&s != &s0) {
      EXPECT_NEAR((s.x_mm - s0.x_mm) / ((s.a_deg - s0.a_deg) * M_PI / 180), slope, 1e-7);
    }
    EXPECT_NEAR(s.y_mm, R + cl, 1e-6);
    EXPECT_NEAR(s.b_deg, b, 1e-6);
  }
  // Unwrapped A covers three turns.
  EXPECT_NEAR(std::fabs(mo.states.back().a_deg - s0.a_deg), 3 * 360.0, 1e-6);
  // Resampling kept fewer points and stayed within tolerance.
  EXPECT_LT(mo.states.size(), 3001u);
  EXPECT_LE(mo.max_chord_deviation, 0.01);
}

TEST(Kinematics, FeedPlanKeepsEveryAxisWithinItsLimitsAndTimeAccumulates) {
  const WindingPlan plan = test::helix_plan(40, 55, 2, 801, 3);
  MachineOptions m;
  m.kind = "lathe4";
  m.a.max_velocity = 360;
  m.x.max_velocity = 50;
  m.y.max_velocity = 20;
  m.b.max_velocity = 90;
  m.x.max_acceleration = 200;
  const Motion mo = compute_motion(plan, m);
  ASSERT_FALSE(mo.states.empty());
  EXPECT_EQ(mo.states.front().t_s, 0.0);
  for (std::size_t i = 1; i < mo.states.size(); ++i) {
    const MachineState& p = mo.states[i - 1];
    const MachineState& s = mo.states[i];
    const double slowest =
        std::max({std::fabs(s.a_deg - p.a_deg) / 360, std::fabs(s.x_mm - p.x_mm) / 50,
                  std::fabs(s.y_mm - p.y_mm) / 20, std::fabs(s.b_deg - p.b_deg) / 90});
    EXPECT_GE(s.duration, slowest * (1 - 1e-12));
    EXPECT_NEAR(s.t_s, p.t_s + s.duration, 1e-9);
    if (s.duration > 0) {
      EXPECT_NEAR(s.feed, 60.0 / s.duration, 1e-9);  // linuxcnc: inverse time
    }
  }
  EXPECT_DOUBLE_EQ(mo.wind_time, mo.states.back().t_s);
  EXPECT_LE(mo.limits.velocity_ratio, 1 + 1e-9);
  EXPECT_LE(mo.limits.acceleration_ratio, 1 + 1e-9);
  EXPECT_GT(mo.limits.acceleration_ratio, 0.1);
  double sum = 0;
  for (double t : mo.circuit_time) sum += t;
  EXPECT_NEAR(sum, mo.wind_time, 1e-9);
  ASSERT_EQ(mo.circuit_time.size(), 3u);
  // A fibre speed bound slows the moves down to s / v.
  m.max_fibre_speed = 10;
  const Motion slow = compute_motion(plan, m);
  for (std::size_t i = 1; i < slow.states.size(); ++i) {
    const MachineState& p = slow.states[i - 1];
    const MachineState& s = slow.states[i];
    if (s.circuit != p.circuit) continue;
    const double laid = (s.paid_out - s.free_length) - (p.paid_out - p.free_length);
    EXPECT_GE(s.duration, laid / 10 - 1e-9);
  }
  EXPECT_GT(slow.wind_time, mo.wind_time);
}

TEST(Kinematics, PerMinuteFeedIsCombinedAxisSpeed) {
  const WindingPlan plan = test::helix_plan(40, 55, 1, 400, 2);
  MachineOptions m;  // lathe2: A and X only
  m.gcode.dialect = "marlin";
  const Motion mo = compute_motion(plan, m);
  EXPECT_FALSE(mo.inverse_time);
  for (std::size_t i = 1; i < mo.states.size(); ++i) {
    const MachineState& p = mo.states[i - 1];
    const MachineState& s = mo.states[i];
    const double da = s.a_deg - p.a_deg, dx = s.x_mm - p.x_mm;
    EXPECT_GE(s.duration, std::max(std::fabs(da) / 720, std::fabs(dx) / 500) * (1 - 1e-12));
    if (s.duration > 0) {
      EXPECT_NEAR(s.feed, 60 * std::hypot(da, dx) / s.duration, 1e-6 * s.feed);
    }
    EXPECT_EQ(s.b_deg, 0.0);
    EXPECT_NEAR(s.y_mm, 60.0, 1e-9);  // the lathe2 eye cylinder: R + clearance
  }
}

TEST(Kinematics, GeodesicOnSphereUnderDomeEnvelope) {
  // A great circle of a sphere (R = 60) tilted 30 deg from the axis plane: a closed geodesic.
  // Under the explicit dome envelope every eye is on the envelope and on its tangent line.
  const double R = 60;
  WindingPlan plan;
  Circuit c;
  const Vec3 a(1, 0, 0), b = Vec3(0, std::cos(M_PI / 6), std::sin(M_PI / 6));
  for (int i = 0; i <= 720; ++i) {
    const double t = 2 * M_PI * i / 720;
    FibrePoint p;
    p.position = R * (std::cos(t) * a + std::sin(t) * b);
    p.normal = p.position / R;
    p.tangent = -std::sin(t) * a + std::cos(t) * b;
    p.s = R * t;
    c.points.push_back(p);
  }
  plan.circuits.push_back(c);
  MachineOptions m;
  m.kind = "robot";
  for (int i = 0; i <= 40; ++i) {
    const double x = -R + 3 * i;
    m.envelope.profile.push_back({x, std::sqrt(std::max(0.0, R * R - x * x)) + 25});
  }
  m.chord_tolerance = 0.01;
  const Motion mo = compute_motion(plan, m);
  const AxisFrame f = make_axis_frame(plan.axis);
  const Envelope env = make_envelope(plan.profile, m.envelope);
  ASSERT_GT(mo.states.size(), 10u);
  for (const MachineState& s : mo.states) {
    EXPECT_NEAR(f.radius(s.eye), env.radius_at(f.axial(s.eye)), 1e-6);
    EXPECT_LT((s.eye - s.position).cross(s.direction).norm(), 1e-9);
    EXPECT_GT(s.free_length, 0.0);
  }
  EXPECT_NEAR(mo.states.back().paid_out - mo.states.back().free_length, 2 * M_PI * R, 1e-9);
}

TEST(Kinematics, TravelLimitNamesAxisValueAndPoint) {
  const WindingPlan plan = test::helix_plan(50, 45, 2, 400, 2);
  MachineOptions m;
  m.x.max = 300;  // the helix climbs to c * 4 pi = 628 mm (+ the eye's lead)
  try {
    compute_motion(plan, m);
    FAIL();
  } catch (const InputError& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("axes.X"), std::string::npos) << w;
    EXPECT_NE(w.find("circuit 0"), std::string::npos) << w;
    EXPECT_NE(w.find("300"), std::string::npos) << w;
  }
  m.x.max = 1e6;
  m.a.sign = -1;
  m.a.max = 100;  // A = -theta falls, so the machine value -A rises past 100 deg
  try {
    compute_motion(plan, m);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("axes.A"), std::string::npos) << e.what();
  }
}

// A robot's layup: a helix on the mandrel cylinder R, then one on the cylinder R2 = R + 5 its layer
// built. With the per-circuit surfaces the true-distance eye keeps the clearance from the layer in
// work: on a cylinder the tangent line reaches it at radius R + clearance, then R2 + clearance
// (the closed form: the eye leads the point by acos(R / R_e) about the axis). On the bare mandrel
// the outer circuit's eye is measured from R: at R + clearance, only clearance - 5 mm from its
// own layer.
TEST(Kinematics, RobotEyeKeepsTheClearanceFromTheLayerInWork) {
  const double R = 50, R2 = 55, clearance = 20;
  WindingPlan plan = test::helix_plan(R, 60, 2, 2000);
  Circuit outer = test::helix_plan(R2, 55, 2, 2000).circuits.front();
  outer.index = 1;
  plan.circuits.push_back(outer);
  const Mesh mandrel(test::open_cylinder(R, 900, 512, 200));  // chord sag 0.001 mm
  const Mesh built(test::open_cylinder(R2, 900, 512, 200));
  MachineOptions m;
  m.kind = "robot";
  m.tangent_window = 0.0;
  m.envelope.clearance = clearance;
  const AxisFrame f = make_axis_frame(plan.axis);
  auto worst = [&](const Motion& mo, int ordinal, double radius) {
    double w = 0.0;
    int n = 0;
    for (const MachineState& s : mo.states) {
      if (s.ordinal != ordinal) continue;
      w = std::max(w, std::fabs(f.radius(s.eye) - radius));
      // The eye leads its point by acos(R_s / R_e) about the axis (R_s its point's radius).
      const double lead = std::acos(f.radius(s.position) / f.radius(s.eye));
      const double turned =
          std::fabs(std::remainder(f.angle(s.eye) - f.angle(s.position), 2 * M_PI));
      w = std::max(w, std::fabs(turned - lead) * radius);
      ++n;
    }
    EXPECT_GT(n, 10);
    return w;
  };
  // A robot's eye is planned kRobotEyeChords chord tolerances beyond the clearance (the chords
  // between its targets keep the clearance).
  const double eye = clearance + kRobotEyeChords * m.chord_tolerance;
  const Motion own = compute_motion(plan, m, &mandrel, {nullptr, &built});
  EXPECT_LT(worst(own, 0, R + eye), 0.01);
  EXPECT_LT(worst(own, 1, R2 + eye), 0.01);
  EXPECT_NEAR(own.min_clearance, eye, 0.01);
  EXPECT_NE(own.envelope.find("layer in work"), std::string::npos) << own.envelope;
  const Motion bare = compute_motion(plan, m, &mandrel);
  EXPECT_LT(worst(bare, 1, R + eye), 0.01);
  // lathe4: each circuit's envelope is its surface's (the outer helix's eye on R2 + clearance,
  // measured on R2; on the bare mandrel's envelope it was clearance - 5 mm from R2); lathe2 too,
  // each circuit on the cylinder of its surface's largest radius + the clearance (issue #26: it
  // kept the mandrel's and measured on the mandrel whatever the surfaces), and one cylinder
  // (envelope.radius) too near the outer surface is refused naming the circuit and the distance.
  MachineOptions lathe;
  lathe.kind = "lathe4";
  const Motion l1 = compute_motion(plan, lathe, &mandrel, {nullptr, &built});
  EXPECT_LT(worst(l1, 0, R + clearance), 0.01);
  EXPECT_LT(worst(l1, 1, R2 + clearance), 0.01);
  EXPECT_NEAR(l1.min_clearance, clearance, 0.01);
  const Motion l0 = compute_motion(plan, lathe, &mandrel);
  EXPECT_LT(worst(l0, 1, R + clearance), 0.01);
  lathe.kind = "lathe2";
  const Motion c1 = compute_motion(plan, lathe, &mandrel, {nullptr, &built});
  EXPECT_LT(worst(c1, 0, R + clearance), 0.01);
  EXPECT_LT(worst(c1, 1, R2 + clearance), 0.01);
  EXPECT_NEAR(c1.min_clearance, clearance, 0.01);
  for (const MachineState& s : c1.states) {
    EXPECT_NEAR(s.y_mm, s.ordinal == 0 ? R + clearance : R2 + clearance, 0.01);
  }
  const Motion c0 = compute_motion(plan, lathe, &mandrel);
  EXPECT_LT(worst(c0, 1, R + clearance), 0.01);
  lathe.envelope.radius = R + clearance;
  try {
    compute_motion(plan, lathe, &mandrel, {nullptr, &built});
    ADD_FAILURE() << "an eye 15 mm from the outer surface was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("machine.envelope: circuit 1, point"), std::string::npos) << what;
    EXPECT_NE(what.find("is 15"), std::string::npos) << what;
    EXPECT_NE(what.find("from the surface it is wound on"), std::string::npos) << what;
  }
  lathe.envelope.radius = R2 + clearance;  // one cylinder clearing both: the clearance on each
  const Motion one = compute_motion(plan, lathe, &mandrel, {nullptr, &built});
  EXPECT_NEAR(one.min_clearance, clearance, 0.01);
  EXPECT_LT(worst(one, 0, R2 + clearance), 0.01);
}

TEST(Kinematics, FixedFreeLengthMode) {
  const WindingPlan plan = test::helix_plan(50, 45, 1, 200);
  MachineOptions m;
  m.kind = "lathe4";  // a lathe2 cannot follow a free length (no cross-feed)
  m.envelope.free_length = 123.5;
  const Motion mo = compute_motion(plan, m);
  for (const MachineState& s : mo.states) {
    EXPECT_DOUBLE_EQ(s.free_length, 123.5);
    EXPECT_NEAR((s.eye - s.position).norm(), 123.5, 1e-9);
  }
}

}  // namespace
}  // namespace windplan
