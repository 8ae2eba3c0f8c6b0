// Friction turnarounds (planner/winding/friction_winding.h): on a cylinder the joins, turns and the
// closing slippage against the closed forms of planner/winding/semi_geodesic.h; the shipped
// configs/pipe_friction.yaml wound end to end with no pins, full measured coverage and every
// laid point's |k_g/k_n| <= mu; bad input names winding.slippage.
#include "planner/winding/friction_winding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "geometry/base/errors.h"
#include "planner/pipeline.h"
#include "planner/winding/coverage.h"
#include "planner/winding/revolution_winding.h"
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

// The smallest radius and the largest |k_g/k_n| of a plan's laid points, per end (x below or
// above the middle).
struct Laid {
  std::array<double, 2> r_min = {1e9, 1e9};
  double worst = 0.0, top = 0.0;
};
Laid laid(const std::vector<Circuit>& circuits, double x_mid) {
  Laid l;
  for (const Circuit& c : circuits) {
    for (const FibrePoint& q : c.points) {
      const int e = q.position.z() < x_mid ? 0 : 1;
      l.r_min[e] = std::min(l.r_min[e], q.position.head<2>().norm());
      l.worst = std::max(l.worst, q.slippage);
      l.top = std::max(l.top, q.winding_angle);
    }
  }
  return l;
}

double parse_after(const std::string& s, const std::string& key) {
  const std::size_t at = s.find(key);
  return at == std::string::npos ? std::nan("") : std::atof(s.c_str() + at + key.size());
}

// Beyond the geodesic turns of a vessel: a geodesic turning around at the boss (opening + B / 2)
// makes a fixed number of turns per pass; asked for more (winding.turns) or for a lower angle
// (winding.angle), the passes keep turning around at the boss and friction on the domes carries
// r sin a between the boss and the cylinder's c. Without winding.slippage the geodesic moves
// its turnaround off the boss instead (more turns) or the job is refused (a lower angle).
TEST(FrictionWinding, VesselBeyondItsGeodesicTurnsTurnsAroundAtTheBoss) {
  const double R = 100, L = 300, r0 = 30, B = 16;
  const std::vector<Vec2> m = test::capsule_meridian(R, L, r0, 120, 30);
  const Mesh mesh = test::revolve(m, 128);
  const double boss = r0 + B / 2;
  const double geodesic_turns = clairaut_pass_angle(m, boss) / kTwoPi;
  WindingOptions o;
  o.band_width = B;
  o.mu = 0.2;
  o.curvature_window = 40;  // mm: over more than a facet at these angles
  o.turns = geodesic_turns + 0.06;
  o.turns_given = true;
  {
    const RevolutionWinding geo = plan_revolution_winding(mesh, {}, SpindleAxis{}, o);
    EXPECT_FALSE(geo.friction);
    EXPECT_GT(laid(geo.circuits, L / 2).r_min[0], boss + 2.0);  // moved off the boss
  }
  o.slippage = 0.15;
  WindingOptions lower = o;
  lower.turns_given = false;
  lower.angle = std::asin(33.0 / R) * 180.0 / M_PI;  // c 33 mm, below the boss
  for (const WindingOptions& k : {o, lower}) {
    SCOPED_TRACE(k.turns_given ? "more turns" : "a lower angle");
    const RevolutionWinding w = plan_revolution_winding(mesh, {}, SpindleAxis{}, k);
    ASSERT_TRUE(w.friction);
    EXPECT_FALSE(w.friction_plan.transition);
    EXPECT_EQ(w.friction_plan.friction_end, (std::array<bool, 2>{true, true}));
    EXPECT_LE(w.friction_plan.slippage, 0.15);
    if (k.turns_given) {
      EXPECT_GT(w.pattern.c, boss);
      // The pattern closes by lambda or by c within the window: the turns move a little.
      EXPECT_NEAR(w.pattern.turns_per_pass, o.turns, 0.03);
      EXPECT_GT(w.pattern.turns_per_pass, geodesic_turns + 0.03);
    } else {
      EXPECT_LT(w.pattern.c, boss);
    }
    const Laid l = laid(w.circuits, L / 2);
    EXPECT_NEAR(l.r_min[0], boss, 0.6);  // turns around at the boss, both domes
    EXPECT_NEAR(l.r_min[1], boss, 0.6);
    EXPECT_GT(l.top, 89.0);
    EXPECT_LE(l.worst, o.mu);
    EXPECT_EQ(measure_coverage(mesh, SpindleAxis{}, w.circuits, {B, 12}).bare_fraction, 0.0);
  }
  // Far below the boss at little friction: refused, naming the key and the slippage that would
  // reach; that slippage does.
  WindingOptions far = lower;
  far.angle = std::asin(24.0 / R) * 180.0 / M_PI;
  far.slippage = 0.05;
  far.mu = 1.0;
  try {
    plan_revolution_winding(mesh, {}, SpindleAxis{}, far);
    FAIL() << "c 24 at slippage 0.05 accepted";
  } catch (const ConfigError& e) {
    const std::string w = e.what();
    EXPECT_EQ(w.rfind("winding.slippage = 0.050: ", 0), 0u) << w;
    EXPECT_NE(w.find("only down to"), std::string::npos) << w;
    const double need = parse_after(w, "would need winding.slippage >= ");
    ASSERT_TRUE(need > 0.05 && need < 1.0) << w;
    far.slippage = need;
    far.turnaround_window = 8;
    EXPECT_NO_THROW(plan_revolution_winding(mesh, {}, SpindleAxis{}, far)) << need;
  }
}

// Unequal polar openings: each dome turns around geodesically on its own boss (opening + B / 2)
// and the passes join the two on the cylinder by friction. On a cylinder of radius R the
// transition from c_0 to c_1 at lambda spans R |R / c_0 - R / c_1| / lambda of axis
// (planner/winding/semi_geodesic.h).
TEST(FrictionWinding, UnequalOpeningsJoinGeodesicDomesOnTheCylinder) {
  const double R = 100, L = 300, B = 16;
  const std::vector<Vec2> small = test::capsule_meridian(R, L, 30, 120, 30);
  const std::vector<Vec2> large = test::capsule_meridian(R, L, 34, 120, 30);
  std::vector<Vec2> m(small.begin(), small.begin() + 120 + 31);  // dome r0 30, cylinder
  m.insert(m.end(), large.end() - 120, large.end());             // dome r1 34
  const Mesh mesh = test::revolve(m, 128);
  WindingOptions o;
  o.band_width = B;
  o.mu = 0.2;
  o.curvature_window = 40;
  o.slippage = 0.15;
  const RevolutionWinding w = plan_revolution_winding(mesh, {}, SpindleAxis{}, o);
  ASSERT_TRUE(w.friction);
  const FrictionWinding& f = w.friction_plan;
  ASSERT_TRUE(f.transition);
  EXPECT_EQ(w.geodesic_end, (std::array<bool, 2>{true, true}));
  EXPECT_LE(f.slippage, 0.15);
  const FrictionTransition& T = f.transition_path;
  const double moved = w.pattern.moved;
  EXPECT_GE(moved, 0.0);
  EXPECT_LE(moved, B / 4 + 1e-9);
  EXPECT_NEAR(T.c_from, 38.0 + moved, 1e-6);
  EXPECT_NEAR(T.c_to, 42.0 + moved, 1e-6);
  EXPECT_NEAR(T.end_x - T.start_x, R * (R / T.c_from - R / T.c_to) / f.slippage, 0.01 * L);
  EXPECT_GE(T.start_x, 0.0);  // on the cylinder
  EXPECT_LE(T.end_x, L);
  const Laid l = laid(w.circuits, L / 2);
  EXPECT_NEAR(l.r_min[0], T.c_from, 0.3);  // geodesic turnarounds on each boss
  EXPECT_NEAR(l.r_min[1], T.c_to, 0.3);
  EXPECT_LE(l.worst, o.mu);
  EXPECT_EQ(measure_coverage(mesh, SpindleAxis{}, w.circuits, {B, 12}).bare_fraction, 0.0);
  // Too little friction for the cylinder: the error gives what it would need, near the closed
  // form R |R / c_0 - R / c_1| / (the cylinder's length).
  o.slippage = 0.05;
  try {
    plan_revolution_winding(mesh, {}, SpindleAxis{}, o);
    FAIL() << "slippage 0.05 accepted";
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("winding.slippage = 0.050: ", 0), 0u) << msg;
    const double need = parse_after(msg, "would need winding.slippage >= ");
    EXPECT_NEAR(need, R * (R / 38.0 - R / 42.0) / L, 0.01) << msg;
  }
}

// The shipped friction vessels: configs/vessel_friction.yaml (more turns than the geodesic at
// the bosses) and configs/vessel_unequal.yaml (openings 30 and 34 mm): every laid point within
// mu, no bare band, the turnarounds on the bosses.
TEST(FrictionWinding, ShippedVesselsWindByFriction) {
  for (const char* name : {"vessel_friction", "vessel_unequal"}) {
    SCOPED_TRACE(name);
    Job job = load_job(test::source_dir() / "configs" / (std::string(name) + ".yaml"));
    job.cutlines.clear();
    const PipelineResult r = plan_job(job);
    ASSERT_TRUE(r.clairaut);
    const PlanMetrics& m = r.plan.metrics;
    ASSERT_TRUE(m.friction_turnarounds.planned);
    EXPECT_LE(r.revolution.friction_plan.slippage, job.winding.slippage);
    EXPECT_EQ(m.coverage.bare_fraction, 0.0);
    const double B = job.winding.band_width;
    const std::array<double, 2> boss = {job.mandrel.vessel.dome_start.polar_opening + B / 2,
                                        job.mandrel.vessel.dome_end.polar_opening + B / 2};
    const Laid l = laid(r.plan.circuits, job.mandrel.vessel.length / 2);
    EXPECT_LE(l.worst, job.winding.mu);
    const bool unequal = std::string(name) == "vessel_unequal";
    EXPECT_EQ(r.revolution.friction_plan.transition, unequal);
    for (int e : {0, 1}) {
      const double expect = unequal ? boss[e] + r.revolution.pattern.moved : boss[e];
      EXPECT_NEAR(l.r_min[e], expect, 0.6) << e;
    }
    if (!unequal) {
      const double geodesic = clairaut_pass_angle(r.revolution.meridian, boss[0]) / kTwoPi;
      EXPECT_GT(m.turns_per_pass, geodesic + 0.03);  // 0.636 at the bosses
      EXPECT_NEAR(m.turns_per_pass, job.winding.turns, 0.03);
    }
  }
}

}  // namespace
}  // namespace windplan
