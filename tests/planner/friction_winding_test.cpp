// Friction turnarounds (planner/friction_winding.h): on a cylinder the joins, turns and the
// closing slippage against the closed forms of planner/semi_geodesic.h; the shipped
// configs/pipe_friction.yaml wound end to end with no pins, full measured coverage and every
// laid point's |k_g/k_n| <= mu; bad input names winding.slippage.
#include "planner/friction_winding.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/errors.h"
#include "planner/coverage.h"
#include "planner/pipeline.h"
#include "planner/revolution_winding.h"
#include "tests/planner/winding_fixtures.h"
#include "tests/test_data.h"

namespace windplan {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

// The circuit advance on a cylinder of radius R wound between x = 0 and L at angle a0, with the
// apexes half a band in from the ends, at slippage lambda (closed forms).
double cylinder_advance(double R, double L, double B, double a0, double lambda) {
  const double axial = R * (1.0 / std::sin(a0) - 1.0) / lambda;  // join to apex
  const double pass = L - B - 2.0 * axial;
  const double turn = -2.0 * std::log(std::tan(0.5 * a0)) / lambda;
  return 2.0 * std::tan(a0) * pass / R + 2.0 * turn;
}

TEST(FrictionWinding, CylinderClosesAtTheLargestSlippageBelowTheBound) {
  const double R = 50, L = 500, B = 12;
  WindingOptions o;
  o.angle = 55;
  o.band_width = B;
  o.slippage = 0.15;
  const std::vector<Vec2> m{{0, R}, {L, R}};
  const PatternProblem pr = pattern_problem(m, o);
  ASSERT_TRUE(wants_friction_turnarounds(pr, o));
  const FrictionWinding w = plan_friction_winding(pr, o);
  const double a0 = 55.0 * M_PI / 180.0, lambda = w.slippage;
  ASSERT_TRUE(w.friction_end[0] && w.friction_end[1]);
  EXPECT_LE(lambda, 0.15);
  EXPECT_GE(lambda, 0.15 / 4.0);
  const double axial = R * (1.0 / std::sin(a0) - 1.0) / lambda;
  EXPECT_NEAR(w.turnarounds[0].join_x, B / 2 + axial, 1e-6);
  EXPECT_NEAR(w.turnarounds[1].join_x, L - B / 2 - axial, 1e-6);
  EXPECT_NEAR(w.turnarounds[1].apex_x, L - B / 2, 1e-9);
  EXPECT_NEAR(w.pass.angle, std::tan(a0) * (L - B - 2 * axial) / R, 1e-6);
  // The advance closes the pattern: K circuits move on by p bands.
  const int K = w.pattern.circuits, p = w.pattern.skip;
  const double A = cylinder_advance(R, L, B, a0, lambda);
  EXPECT_NEAR(w.pattern.advance, A, 1e-6);
  const double frac = std::fmod(A, kTwoPi) / kTwoPi * K;
  EXPECT_NEAR(frac, std::round(frac), 1e-6);
  EXPECT_EQ(static_cast<int>(std::lround(frac)) % K, p);
  // ... at the largest lambda <= the bound that closes it: the advance at the bound is below
  // the target, and no target lies between.
  const double A_bound = cylinder_advance(R, L, B, a0, 0.15);
  EXPECT_LE(A_bound, A + 1e-9);
  const double base = kTwoPi * p / K;
  const double first = base + kTwoPi * std::ceil((A_bound - base) / kTwoPi - 1e-12);
  EXPECT_NEAR(A, first, 1e-6);
}

// The shipped pipe, the shipped cone (its pin rings replaced by friction at mu 0.3) and a pipe
// wound between stations: no pins, no dwell arc, full cover, one continuous fibre, every laid
// point's measured |k_g/k_n| <= mu.
TEST(FrictionWinding, ShippedPipeWindsWithoutPins) {
  std::vector<std::pair<std::string, Job>> jobs;
  jobs.emplace_back("pipe_friction",
                    load_job(test::source_dir() / "configs" / "pipe_friction.yaml"));
  jobs.emplace_back("cone", load_job(test::source_dir() / "configs" / "cone.yaml"));
  jobs.back().second.winding.mu = 0.3;
  jobs.back().second.winding.slippage = 0.25;
  jobs.emplace_back("stations", jobs.front().second);
  jobs.back().second.winding.start_station = 40;
  jobs.back().second.winding.end_station = 460;
  for (auto& [name, job] : jobs) {
    SCOPED_TRACE(name);
    job.cutlines.clear();
    const PipelineResult r = plan_job(job);
    ASSERT_TRUE(r.clairaut);
    const PlanMetrics& m = r.plan.metrics;
    const double mu = job.winding.mu;
    ASSERT_TRUE(m.friction_turnarounds.planned);
    EXPECT_LE(r.revolution.friction_plan.slippage, job.winding.slippage);
    EXPECT_EQ(m.turnarounds.length, 0.0);  // no dwell arc anywhere
    ASSERT_TRUE(m.coverage.measured());
    EXPECT_EQ(m.coverage.bare_fraction, 0.0);
    EXPECT_EQ(m.bridging_length, 0.0);
    const SpindleAxis& ax = r.plan.axis;
    const double B = job.winding.band_width;
    const double x0 = job.winding.has_start_station() ? job.winding.start_station : 0.0;
    const double L = job.winding.has_end_station() ? job.winding.end_station
                     : name == "cone"              ? 400.0
                                                   : 500.0;
    int worst_circuit = -1;
    double worst = 0.0;
    for (const Circuit& c : r.plan.circuits) {
      for (const CircuitSegment& s : c.segments) EXPECT_EQ(s.kind, CircuitSegment::Kind::Pass);
      double x_lo = 1e9, x_hi = -1e9, top = 0.0;
      for (const FibrePoint& q : c.points) {
        if (q.slippage > worst) worst = q.slippage, worst_circuit = c.index;
        const double x = ax.axial(q.position);
        x_lo = std::min(x_lo, x);
        x_hi = std::max(x_hi, x);
        top = std::max(top, q.winding_angle);
      }
      // Turns around on the mandrel, the band inside it.
      EXPECT_NEAR(x_lo, x0 + B / 2, 0.5);
      EXPECT_NEAR(x_hi, L - B / 2, 0.5);
      EXPECT_GT(top, 89.0);
    }
    EXPECT_LE(worst, mu) << "circuit " << worst_circuit;
    // One continuous fibre: each circuit starts where the previous one ended, and the last ends
    // where the first began.
    const int K = static_cast<int>(r.plan.circuits.size());
    for (int k = 0; k < K; ++k) {
      const Vec3& end = r.plan.circuits[k].points.back().position;
      const Vec3& next = r.plan.circuits[(k + 1) % K].points.front().position;
      EXPECT_LT((end - next).norm(), 0.05) << k;
    }
    for (const std::string& w : m.warnings) {
      EXPECT_EQ(w.find("slippage"), std::string::npos) << w;
      EXPECT_EQ(w.find("coverage"), std::string::npos) << w;
    }
  }
}

TEST(FrictionWinding, BadSlippageNamesTheKey) {
  const std::string head =
      "name: p\nmandrel:\n  source: pipe\n  pipe: {radius: 50, length: 300}\n"
      "winding:\n  angle: 55\n  band_width: 12\n  mu: 0.2\n";
  for (const char* bad : {"  slippage: -0.1\n", "  slippage: 0.3\n"}) {
    try {
      load_job_from_string(head + bad, "/tmp/p.yaml");
      FAIL() << bad;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("slippage"), std::string::npos) << e.what();
    }
  }
  // At 0.02 each turnaround needs R (1/sin 55 - 1) / 0.02 = 552 mm: not in 300 mm.
  const Job job = load_job_from_string(head + "  slippage: 0.02\n", "/tmp/p.yaml");
  try {
    plan_job(job);
    FAIL() << "a turnaround longer than the pipe was planned";
  } catch (const ConfigError& e) {
    const std::string w = e.what();
    EXPECT_EQ(w.rfind("winding.slippage = 0.020: ", 0), 0u) << w;
    const double need = 2.0 * (50.0 * (1.0 / std::sin(55.0 * M_PI / 180.0) - 1.0) / 0.02 + 6.0);
    char buf[32];
    std::snprintf(buf, sizeof buf, "need %.1f mm", need);
    EXPECT_NE(w.find(buf), std::string::npos) << w << " / " << buf;
    EXPECT_NE(w.find("300.0 mm long"), std::string::npos) << w;
  }
  // Slippage 0 keeps the dwells (pins).
  const PipelineResult r = plan_job(load_job_from_string(head, "/tmp/p.yaml"));
  EXPECT_FALSE(r.plan.metrics.friction_turnarounds.planned);
  EXPECT_GT(r.plan.metrics.turnarounds.length, 0.0);
}

}  // namespace
}  // namespace windplan

namespace windplan {
namespace {

// Beyond the geodesic reach of the domes: a pass at a winding angle whose Clairaut constant is
// below the polar opening turns around by friction on both domes; with unequal openings a
// pass whose c lies between them turns around geodesically on the small opening's dome and by
// friction on the large one. Every laid point within mu, no bare band.
TEST(FrictionWinding, DomesBeyondTheGeodesicReachAndUnequalOpenings) {
  // Friction moves r sin a slowly on a vessel (d(r sin a)/ds = -lambda r sin^2 a / R on the
  // cylinder): the apexes half a (narrow) band in from the openings, c a little below.
  const double R = 100, L = 1000;
  const std::vector<Vec2> small = test::capsule_meridian(R, L, 20, 120, 30);
  const std::vector<Vec2> large = test::capsule_meridian(R, L, 30, 120, 30);
  std::vector<Vec2> unequal(small.begin(), small.begin() + 120 + 31);  // dome r0 20, cylinder
  unequal.insert(unequal.end(), large.end() - 120, large.end());       // dome r1 30
  struct Case {
    const char* name;
    std::vector<Vec2> meridian;
    double c;
    std::array<bool, 2> friction;
  };
  for (const Case& k : {Case{"openings 20, c 18.5", small, 18.5, {true, true}},
                        Case{"openings 20 / 30, c 28.5", unequal, 28.5, {false, true}}}) {
    SCOPED_TRACE(k.name);
    const Mesh mesh = test::revolve(k.meridian, 128);
    WindingOptions o;
    o.band_width = 4;
    o.mu = 0.25;
    o.turnaround = k.c;
    o.circuits = 5;  // few circuits keep the test short (no full cover); skip: auto
    o.turnaround_window = 6;
    // At 10 deg a fibre crosses a 4.9 mm facet of this mesh over 26 mm: measure the curvatures
    // over more than that, or the flat facets read as k_n = 0.
    o.curvature_window = 40;  // mm: the pattern closes by moving c (lambda alone cannot)
    EXPECT_THROW(plan_revolution_winding(mesh, {}, SpindleAxis{}, o), ConfigError);
    o.slippage = 0.2;
    const RevolutionWinding w = plan_revolution_winding(mesh, {}, SpindleAxis{}, o);
    ASSERT_TRUE(w.friction);
    EXPECT_EQ(w.friction_plan.friction_end, k.friction);
    EXPECT_EQ(w.geodesic_end[0], !k.friction[0]);
    EXPECT_LE(w.friction_plan.slippage, 0.2);
    double worst = 0.0, top = 0.0;
    for (const Circuit& c : w.circuits) {
      for (const FibrePoint& q : c.points) {
        if (q.slippage > o.mu) {
          ADD_FAILURE() << "circuit " << c.index << " at " << q.position.transpose() << " s " << q.s
                        << " k_n " << q.k_n << " k_g " << q.k_g << " of " << c.points.back().s;
        }
        worst = std::max(worst, q.slippage);
        top = std::max(top, q.winding_angle);
      }
    }
    EXPECT_LE(worst, o.mu);
    EXPECT_GT(top, 89.0);
    // The far end's apex stays half a band in from the opening, above it.
    EXPECT_GT(w.friction_plan.turnarounds[1].apex_r, k.meridian.back().y());
  }
  // Too far below the opening for the bound: the error names the key and the reach.
  const Mesh mesh = test::revolve(small, 128);
  WindingOptions o;
  o.band_width = 4;
  o.mu = 0.25;
  o.slippage = 0.2;
  o.turnaround = 12;
  try {
    plan_revolution_winding(mesh, {}, SpindleAxis{}, o);
    FAIL() << "c 12 accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("winding.slippage = 0.200: ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("only down to"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace windplan
