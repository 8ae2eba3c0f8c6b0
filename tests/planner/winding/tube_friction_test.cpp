// Friction layers on a bent tube (planner/winding/tube_friction.h), run through the pipeline on
// the tessellated parametric elbow and checked on the laid points by code that did not plan
// them: the angle to the centre line (tube_centre_line's frame at each point's nearest station),
// the measured |k_g/k_n| (fibre_metrics' finite differences on the mesh) against mu, the apexes
// inside the region, the straight leg's turnaround against the cylinder's closed form
// r (1 / sin a0 - 1) / lambda, the chain's continuity and even starts; and the refusals: a 3r
// elbow needs about 0.33, an angle without slippage, turnarounds that do not fit.
#include "planner/winding/tube_friction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/base/errors.h"
#include "geometry/base/parallel.h"
#include "planner/job/job.h"
#include "planner/pipeline.h"
#include "tests/test_data.h"

namespace windplan {
namespace {

std::string elbow(double bend_radius, const std::string& winding,
                  const std::string& segments = "[100, 100]",
                  const std::string& bend_angle = "90") {
  return "name: elbow\n"
         "mandrel:\n"
         "  source: bent_tube\n"
         "  linear_deflection: 0.25\n"
         "  angular_deflection: 5\n"
         "  bent_tube:\n"
         "    radius: 50\n"
         "    segments: " +
         segments +
         "\n"
         "    bends:\n"
         "      - {angle: " +
         bend_angle + ", radius: " + std::to_string(bend_radius) +
         ", plane_angle: 0}\n"
         "winding:\n" +
         winding;
}

const char* kLayer =
    "  angle: 55\n"
    "  slippage: 0.19\n"
    "  mu: 0.2\n"
    "  band_width: 12\n";

TEST(TubeFriction, ElbowLayerHoldsItsAngleWithinMu) {
  const Job job = load_job_from_string(elbow(250, kLayer), "/tmp/elbow.yaml");
  const PipelineResult r = plan_job(job);
  ASSERT_TRUE(r.tube.friction);
  const TubeFrictionWinding& w = r.tube.layer;
  EXPECT_NEAR(w.required, 0.179, 5e-4);
  EXPECT_EQ(w.K, 16);  // ceil(2 pi 50 cos 55 / 12) = ceil(15.02)
  EXPECT_TRUE(w.summary.closed) << w.summary.brief_report();
  EXPECT_LT(w.spread_deg, 1e-6);
  const std::vector<Circuit>& cs = r.plan.circuits;
  ASSERT_EQ(cs.size(), 16u);
  const TubeCentreLine line(50, {100, 100}, {{90, 250, 0}});
  const double a0 = 55.0 * M_PI / 180.0;
  double worst_angle = 0.0, worst_slip = 0.0;
  int pass_points = 0;
  for (std::size_t k = 0; k < cs.size(); ++k) {
    const Circuit& c = cs[k];
    if (k + 1 < cs.size()) {  // one continuous fibre
      EXPECT_LT((c.points.back().position - cs[k + 1].points.front().position).norm(), 1e-9);
    }
    for (const FibrePoint& q : c.points) {
      worst_slip = std::max(worst_slip, q.slippage);
      double s = 0, th = 0, d = 0;
      line.locate(q.position, &s, &th, &d);
      EXPECT_NEAR(d, 50.0, 0.3);  // on the tessellated tube
      // Inside the region, half a band from the tube ends (the apexes).
      EXPECT_GE(s, 6.0 - 0.05);
      EXPECT_LE(s, line.length() - 6.0 + 0.05);
      // Between the turnarounds (the start one ends by ~64 mm on the leg, the far one begins
      // at most ~100 mm from the far end) the fibre runs at a0 to the centre line.
      if (s > 70 && s < line.length() - 110) {
        const double ang = std::acos(std::min(1.0, std::abs(q.tangent.dot(line.frame(s).t))));
        worst_angle = std::max(worst_angle, std::abs(ang - a0));
        ++pass_points;
      }
    }
  }
  EXPECT_GT(pass_points, 5000);
  EXPECT_LT(worst_angle * 180.0 / M_PI, 0.5);
  EXPECT_LE(worst_slip, 0.2);  // measured on the laid points, every one within mu
  EXPECT_GT(worst_slip, 0.17);
  EXPECT_LE(r.plan.metrics.max_slippage, 0.2);
  // The start turnaround lies on the straight leg: both halves span
  // 2 r (1 / sin a0 - 1) / lambda of centre line.
  EXPECT_NEAR(w.turnaround_span[0], 2 * 50 * (1 / std::sin(a0) - 1) / 0.19, 1e-4);
}

// Coverage on sections normal to the centre line, from the laid points alone: at each station
// every pass crossing lays a band whose trace on the section is B / cos(a) long (a its angle to
// the centre line there); their union (both families) must be the whole section. 16 circuits
// (auto) leave up to 7.6% of a bend section bare, 23 (configs/elbow.yaml) none. The planner's
// own figures (planner/winding/tube_coverage.h, per family) agree: 16 leave 9.9% of one
// family's section bare, 23 none.
double worst_bare_section(const std::vector<Circuit>& cs, const TubeCentreLine& line, double B,
                          double from, double to) {
  std::vector<double> s;
  std::vector<const FibrePoint*> pts;
  for (const Circuit& c : cs) {
    for (const FibrePoint& q : c.points) {
      double si = 0, th = 0, d = 0;
      line.locate(q.position, &si, &th, &d);
      s.push_back(si);
      pts.push_back(&q);
    }
  }
  const double r = line.tube_radius();
  double worst = 0.0;
  for (double sc = from; sc <= to; sc += 15.0) {
    const int n = 3600;
    std::vector<char> cov(n, 0);
    const TubeFrame f = line.frame(sc);
    for (std::size_t j = 0; j + 1 < s.size(); ++j) {
      if ((s[j] - sc) * (s[j + 1] - sc) >= 0.0) continue;
      const double w = (sc - s[j]) / (s[j + 1] - s[j]);
      const Vec3 p = (1 - w) * pts[j]->position + w * pts[j + 1]->position - f.c;
      const double th = std::atan2(p.dot(f.v), p.dot(f.u));
      const double width = B / (r * std::max(1e-6, std::abs(pts[j]->tangent.dot(f.t))));
      const int a = static_cast<int>(std::floor((th - 0.5 * width) / (2 * M_PI) * n));
      for (int k = 0; k < static_cast<int>(width / (2 * M_PI) * n); ++k) {
        cov[((a + k) % n + n) % n] = 1;
      }
    }
    int bare = 0;
    for (char c : cov) bare += c ? 0 : 1;
    worst = std::max(worst, static_cast<double>(bare) / n);
  }
  return worst;
}

TEST(TubeFriction, TwentyThreeCircuitsCoverEverySectionOfTheElbow) {
  const TubeCentreLine line(50, {100, 100}, {{90, 250, 0}});
  const PipelineResult r16 = plan_job(load_job_from_string(elbow(250, kLayer), "/tmp/e.yaml"));
  const double bare16 = worst_bare_section(r16.plan.circuits, line, 12, 20, line.length() - 40);
  EXPECT_GT(bare16, 0.05);
  EXPECT_GT(r16.plan.metrics.coverage.bare_fraction, 0.05);
  const PipelineResult r23 = plan_job(
      load_job_from_string(elbow(250, std::string(kLayer) + "  circuits: 23\n"), "/tmp/e.yaml"));
  ASSERT_EQ(r23.plan.circuits.size(), 23u);
  EXPECT_EQ(worst_bare_section(r23.plan.circuits, line, 12, 20, line.length() - 40), 0.0);
  EXPECT_EQ(r23.plan.metrics.coverage.bare_fraction, 0.0);
  EXPECT_EQ(r23.plan.metrics.coverage.stations.size(), 12u);
}

// Rings of pins at the ends: the passes hold the angle between the pin circles, the dwells lie
// on them (Turnaround segments), each circuit advances by the same amount (even starts, one
// closed chain), the passes' measured |k_g/k_n| stays within mu; pins that do not fit are
// refused with the number that would.
TEST(TubeFriction, PinRingsHoldTheTurnarounds) {
  const TubeCentreLine line(50, {100, 100}, {{90, 250, 0}});
  const PipelineResult r = plan_job(load_job_from_string(
      elbow(250, std::string(kLayer) + "  circuits: 23\n  pins: {count: 24, diameter: 4}\n"),
      "/tmp/e.yaml"));
  ASSERT_TRUE(r.tube.friction);
  const TubeFrictionWinding& w = r.tube.layer;
  EXPECT_EQ(w.pins, 24);
  EXPECT_TRUE(w.summary.closed) << w.summary.brief_report();
  EXPECT_LT(w.spread_deg, 1e-6);
  EXPECT_NEAR(w.apex_s[0], 6 + 4, 1e-9);   // default offset: B / 2 + d
  EXPECT_GE(w.dwell_deg[0], 15.0 - 1e-9);  // at least one pitch
  ASSERT_EQ(r.plan.circuits.size(), 23u);
  for (const Circuit& c : r.plan.circuits) {
    ASSERT_EQ(c.segments.size(), 4u);
    for (int g : {1, 3}) {
      const CircuitSegment& seg = c.segments[g];
      EXPECT_EQ(seg.kind, CircuitSegment::Kind::Turnaround);
      for (int i = seg.first; i <= seg.last; ++i) {
        double s = 0, th = 0, d = 0;
        line.locate(c.points[i].position, &s, &th, &d);
        EXPECT_NEAR(s, w.apex_s[g == 1 ? 1 : 0], 0.3);
      }
    }
  }
  EXPECT_LE(r.plan.metrics.max_slippage, 0.2);
  EXPECT_EQ(r.plan.metrics.coverage.bare_fraction, 0.0);
  try {
    plan_job(load_job_from_string(
        elbow(250, std::string(kLayer) + "  pins: {count: 60, diameter: 4}\n"), "/tmp/e.yaml"));
    FAIL() << "60 pins of 4 mm were fitted round a 314 mm section";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("do not fit around the 314.2 mm section (at most 39"),
              std::string::npos)
        << e.what();
  }
}

// Region ends on centre-line stations (mandrel.region.centre_line): the passes turn on those
// sections, each apex half a band inside its end (from + B / 2, to - B / 2 along the whole
// tube's centre line), and every laid point lies between the two end planes.
TEST(TubeFriction, TurnaroundsOnCentreLineStationEnds) {
  std::string yaml = elbow(250, std::string(kLayer) + "  circuits: 4\n");
  const std::string at = "  angular_deflection: 5\n";
  yaml.insert(yaml.find(at) + at.size(), "  region: {centre_line: {from: 60, to: 530}}\n");
  const PipelineResult r = plan_job(load_job_from_string(yaml, "/tmp/elbow_cl.yaml"));
  ASSERT_TRUE(r.tube.friction);
  const TubeFrictionWinding& w = r.tube.layer;
  EXPECT_NEAR(w.apex_s[0], 60 + 6, 0.05);  // the loops' mean station: tessellation apart
  EXPECT_NEAR(w.apex_s[1], 530 - 6, 0.05);
  const TubeCentreLine line(50, {100, 100}, {{90, 250, 0}});
  double lo = 1e300, hi = -1e300;
  for (const Circuit& c : r.plan.circuits) {
    for (const FibrePoint& p : c.points) {
      double s = 0, th = 0, d = 0;
      line.locate(p.position, &s, &th, &d);
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
  }
  EXPECT_GT(lo, 60.0);
  EXPECT_LT(hi, 530.0);
  EXPECT_NEAR(lo, 66.0, 0.5);
  // The far apexes move inward to close the pattern (apex_moved: least and most).
  EXPECT_NEAR(hi, 524.0 - w.apex_moved[0], 0.5);
}

TEST(TubeFriction, ThreeRadiusElbowIsRefusedWithTheSlippageItNeeds) {
  const Job job = load_job_from_string(elbow(150, kLayer), "/tmp/elbow.yaml");
  try {
    plan_job(job);
    FAIL() << "a 3r elbow at 55 deg was planned within slippage 0.19";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("winding.angle 55 deg needs |k_g/k_n| up to 0.328"), std::string::npos) << m;
  }
}

TEST(TubeFriction, TurnsPerPassChooseTheAngle) {
  // The 55 deg layer's turns per pass, asked as turns, give 55 deg back.
  const TubeCentreLine line(50, {100, 100}, {{90, 250, 0}});
  const double n55 = tube_turns_per_pass(line, 0, line.length(), 55.0 * M_PI / 180.0, 0.19, 12);
  EXPECT_GT(n55, 2.0);
  WindingOptions o;
  o.turns = n55;
  o.turns_given = true;
  o.slippage = 0.19;
  o.band_width = 12;
  EXPECT_NEAR(tube_angle_for_turns(line, 0, line.length(), o) * 180.0 / M_PI, 55.0, 1e-6);
  const PipelineResult r = plan_job(load_job_from_string(
      elbow(250, "  turns: 3.2\n  slippage: 0.19\n  mu: 0.2\n  band_width: 12\n"), "/tmp/e.yaml"));
  ASSERT_TRUE(r.tube.friction);
  // The closing apex moves shorten some passes: the plan's turns are a little below 2.5.
  EXPECT_NEAR(r.tube.layer.turns_per_pass, 3.2, 0.15);
  EXPECT_LE(r.tube.layer.turns_per_pass, 3.2 + 1e-9);
  o.turns = 40;
  EXPECT_THROW(tube_angle_for_turns(line, 0, line.length(), o), ConfigError);
}

TEST(TubeFriction, RefusesWhatItCannotHonour) {
  // An angle with no slippage: a geodesic cannot hold it.
  EXPECT_THROW(
      plan_job(load_job_from_string(elbow(250, "  angle: 55\n  band_width: 12\n"), "/tmp/e.yaml")),
      ConfigError);
  // Turns and the angle: one or the other.
  EXPECT_THROW(plan_job(load_job_from_string(
                   elbow(250, "  angle: 55\n  turns: 3\n  slippage: 0.19\n  band_width: 12\n"),
                   "/tmp/e.yaml")),
               ConfigError);
  // Turnarounds that do not fit: 147 mm of tube, each half needs 58 mm at 0.19.
  try {
    plan_job(load_job_from_string(elbow(500, kLayer, "[30, 30]", "10"), "/tmp/e.yaml"));
    FAIL() << "turnarounds longer than the region were planned";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("do not fit"), std::string::npos) << e.what();
  }
  // A region cut by planes normal to the (principal) spindle axis: its ends are no sections.
  std::string cut = elbow(250, kLayer);
  cut.replace(cut.find("  bent_tube:\n"), 0, "  region: {start: -200, end: 200}\n");
  try {
    plan_job(load_job_from_string(cut, "/tmp/e.yaml"));
    FAIL() << "a region whose ends are no sections of the tube was planned";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("is no section of the tube"), std::string::npos)
        << e.what();
  }
  // Slippage off revolution on a mandrel with no known centre line.
  const std::string oval =
      "name: oval\n"
      "mandrel:\n"
      "  source: section\n"
      "  section:\n"
      "    shape: ellipse\n"
      "    semi_axes: [60, 40]\n"
      "    length: 300\n"
      "winding:\n"
      "  slippage: 0.1\n"
      "  band_width: 10\n";
  EXPECT_THROW(plan_job(load_job_from_string(oval, "/tmp/o.yaml")), ConfigError);
  // Pins anywhere but on a friction layer on a bent tube.
  std::string pinned = oval;
  pinned.replace(pinned.find("  slippage: 0.1\n"), 16, "  pins: {count: 12}\n");
  try {
    plan_job(load_job_from_string(pinned, "/tmp/o.yaml"));
    FAIL() << "pins on an oval geodesic job were ignored";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("winding.pins"), std::string::npos) << e.what();
  }
}

// Off a bent tube: a straight tube of elliptical section (80 x 50, mandrel.source: section) is
// planned on the fitted mesh surface (planner/winding/mesh_tube_surface.h). Read back with the
// ellipse's own arc length: the outgoing passes cross the mid station evenly along the loop
// (the pattern is closed on the even angle, not on theta), every laid point is within mu, and
// the coverage is measured on the section loops.
TEST(TubeFriction, OvalSectionLaysAClosedPatternEvenlyAlongTheLoop) {
  const std::string yaml =
      "name: oval\n"
      "mandrel:\n"
      "  source: section\n"
      "  linear_deflection: 0.25\n"
      "  angular_deflection: 5\n"
      "  section:\n"
      "    shape: ellipse\n"
      "    semi_axes: [80, 50]\n"
      "    length: 400\n"
      "    ends: {type: flat}\n"
      "winding:\n"
      "  angle: 55\n"
      "  slippage: 0.15\n"
      "  band_width: 12\n"
      "  mu: 0.2\n";
  const PipelineResult r = plan_job(load_job_from_string(yaml, "/tmp/oval.yaml"));
  ASSERT_TRUE(r.tube.friction);
  ASSERT_TRUE(r.tube.surface);
  const TubeFrictionWinding& w = r.tube.layer;
  EXPECT_TRUE(w.summary.closed) << w.summary.brief_report();
  EXPECT_LT(w.required, 0.01);  // developable: the passes are geodesics
  // K = ceil(girth cos 55 / 12): the ellipse's girth is 413.9 mm.
  EXPECT_EQ(w.K, 20);
  EXPECT_LE(r.plan.metrics.max_slippage, 0.2);
  const CoverageReport& cov = r.plan.metrics.coverage;
  ASSERT_TRUE(cov.measured());
  ASSERT_GE(cov.stations.size(), 12u);
  for (const StationCoverage& st : cov.stations) {
    EXPECT_NEAR(st.loop_length, 413.9, 0.5);
    EXPECT_LT(st.family_bare[0], 0.005) << st.station;  // the evenly spread family covers
  }
  // The + family at z = 200, by the ellipse's arc length (Simpson, independent of the planner).
  auto arc = [](double t) {
    auto f = [](double u) { return std::hypot(80.0 * std::sin(u), 50.0 * std::cos(u)); };
    const int n = 4000;
    double sum = f(0.0) + f(t);
    for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(t * i / n);
    return sum * t / n / 3.0;
  };
  const double girth = arc(2.0 * M_PI);
  std::vector<double> at;
  for (const Circuit& c : r.plan.circuits) {
    for (std::size_t i = 0; i + 1 < c.points.size(); ++i) {
      const Vec3 a = c.points[i].position, b = c.points[i + 1].position;
      if (!(a.z() < 200.0 && b.z() >= 200.0)) continue;
      const Vec3 p = a + (200.0 - a.z()) / (b.z() - a.z()) * (b - a);
      double t = std::atan2(p.y() / 50.0, p.x() / 80.0);
      if (t < 0.0) t += 2.0 * M_PI;
      at.push_back(arc(t));
    }
  }
  ASSERT_EQ(at.size(), 20u);
  std::sort(at.begin(), at.end());
  for (std::size_t i = 0; i < at.size(); ++i) {
    const double gap = i + 1 < at.size() ? at[i + 1] - at[i] : at[0] + girth - at[i];
    EXPECT_NEAR(gap, girth / 20.0, 0.5) << i;
  }
}

// The pattern's 48 sampled circuits are traced in parallel: the plan is the same, bit for bit,
// on one thread and on two.
TEST(TubeFriction, OvalPlanIsTheSameOnOneThreadAndOnTwo) {
  const std::string yaml =
      "name: oval\n"
      "mandrel:\n"
      "  source: section\n"
      "  linear_deflection: 0.5\n"
      "  angular_deflection: 8\n"
      "  section:\n"
      "    shape: ellipse\n"
      "    semi_axes: [80, 50]\n"
      "    length: 300\n"
      "    ends: {type: flat}\n"
      "winding:\n"
      "  angle: 55\n"
      "  slippage: 0.15\n"
      "  band_width: 12\n"
      "  mu: 0.2\n"
      "  circuits: 5\n";
  const Job job = load_job_from_string(yaml, "/tmp/oval.yaml");
  std::vector<std::vector<Vec3>> by_threads;
  for (int threads : {1, 2}) {
    const ThreadLimit limit(threads);
    const PipelineResult r = plan_job(job);
    ASSERT_TRUE(r.tube.friction);
    std::vector<Vec3> points;
    for (const Circuit& c : r.plan.circuits) {
      for (const FibrePoint& q : c.points) points.push_back(q.position);
    }
    by_threads.push_back(points);
  }
  ASSERT_FALSE(by_threads[0].empty());
  ASSERT_EQ(by_threads[0].size(), by_threads[1].size());
  for (std::size_t i = 0; i < by_threads[0].size(); ++i) {
    ASSERT_EQ(by_threads[0][i], by_threads[1][i]) << "point " << i;
  }
}

// A rounded rectangle (120 x 80, 15 mm corners): its flat sides no longer read as a bridge (the
// fit keeps the section convex, planner/winding/mesh_tube_surface.h, and a straight fibre on a
// flat needs no friction), but the fit rounds the corners over a few millimetres, so a
// turnaround planned on it turns where the mesh is still flat: the laid points measure k_n ~ 0
// with k_g > 0 there. Refused with one line saying so, after the first plan (no replanning at
// lower slippage, which cannot help).
TEST(TubeFriction, RoundedRectangleTurnaroundsOnTheFlatsAreRefusedInOneLine) {
  const std::string yaml =
      "name: rr\n"
      "mandrel:\n"
      "  source: section\n"
      "  linear_deflection: 0.25\n"
      "  angular_deflection: 5\n"
      "  section:\n"
      "    shape: rounded_rectangle\n"
      "    width: 120\n"
      "    height: 80\n"
      "    corner_radius: 15\n"
      "    length: 600\n"
      "    ends: {type: flat}\n"
      "winding:\n"
      "  angle: 55\n"
      "  slippage: 0.15\n"
      "  band_width: 12\n"
      "  mu: 0.2\n";
  try {
    plan_job(load_job_from_string(yaml, "/tmp/rr.yaml"));
    FAIL() << "turnarounds on a rounded rectangle's flats were laid";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find("would bridge"), std::string::npos) << m;
    EXPECT_NE(m.find("turns on a flat side of the mandrel"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

// The shared bent-pipe.stl (units m, r 185, remeshed at 20 mm, region on centre-line stations):
// 55 deg needs more than winding.slippage 0.15 on its bend; the refusal names the figure, found on
// the fitted surface of the mesh, before anything is traced.
TEST(TubeFriction, BentPipeMeshRefusesAnAngleFrictionCannotHold) {
  WINDPLAN_REQUIRE_SHARED_MESH(path, "bent-pipe.stl");
  const std::string yaml =
      "name: bentpipe\n"
      "mandrel:\n"
      "  source: mesh\n"
      "  file: " +
      path.string() +
      "\n"
      "  units: m\n"
      "  remesh: 20\n"
      "  region:\n"
      "    centre_line: {from: 50, to: 970}\n"
      "winding:\n"
      "  angle: 55\n"
      "  slippage: 0.15\n"
      "  band_width: 20\n"
      "  mu: 0.2\n";
  try {
    plan_job(load_job_from_string(yaml, "/tmp/bentpipe.yaml"));
    FAIL() << "55 deg on bent-pipe.stl was planned within slippage 0.15";
  } catch (const ConfigError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("winding.angle 55 deg needs |k_g/k_n| up to 0.19"), std::string::npos) << m;
    EXPECT_NE(m.find("above winding.slippage 0.15"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace windplan
