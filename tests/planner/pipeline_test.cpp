// planner/pipeline.cpp (plan_job) and the winding: job section.
#include "planner/pipeline.h"

#include <cmath>

#include <gtest/gtest.h>

#include "geometry/base/errors.h"
#include "geometry/region/spine.h"
#include "planner/winding/coverage.h"
#include "tests/test_data.h"

namespace windplan {
namespace {

const char* const kPipe =
    "name: p\n"
    "mandrel:\n"
    "  source: pipe\n"
    "  pipe: {radius: 40, length: 200}\n"
    "winding:\n"
    "  turns: 2\n"
    "  circuits: 3\n"
    "  band_width: 10\n";

TEST(Pipeline, PipeJobGivesClosedFormHelices) {
  const Job job = load_job_from_string(kPipe, "/tmp/p.yaml");
  EXPECT_EQ(job.winding.turns, 2);
  EXPECT_EQ(job.winding.circuits, 3);
  std::vector<std::string> started;
  PipelineOptions po;
  po.on_stage_start = [&](const std::string& s) { started.push_back(s); };
  const PipelineResult r = plan_job(job, po);
  const WindingPlan& plan = r.plan;
  ASSERT_EQ(plan.circuits.size(), 3u);
  ASSERT_EQ(plan.metrics.timings.size(), started.size());
  const std::vector<std::string> stages = {"mandrel", "girth", "helices", "metrics"};
  ASSERT_EQ(started, stages);
  EXPECT_EQ(plan.metrics.circuits, 3);
  EXPECT_NEAR(plan.metrics.turns_per_pass, 2, 1e-9);
  EXPECT_TRUE(r.clairaut);  // a shape of revolution at beta 0: Clairaut's integral
  // Every pass: the helix of the (tessellated) cylinder, length ~ sqrt(L^2 + (2 pi R N)^2).
  const double smooth = std::sqrt(200.0 * 200.0 + std::pow(2.0 * M_PI * 40.0 * 2, 2));
  for (const PassReport& p : r.passes) EXPECT_NEAR(p.length, smooth, 0.01 * smooth);
  // Points carry faces of the full mesh, and lie on it.
  for (const Circuit& c : plan.circuits) {
    for (const FibrePoint& q : c.points) {
      ASSERT_GE(q.face, 0);
      ASSERT_LT(q.face, r.mandrel.mesh.num_faces());
    }
  }
  EXPECT_NEAR(plan.metrics.max_slippage, 0.0, 0.1);
  // A cylinder: no geodesic turn limit, reported as such (+inf), and no warning.
  ASSERT_TRUE(r.has_turn_limit);
  EXPECT_FALSE(r.turn_limit.bounded);
  EXPECT_TRUE(std::isinf(plan.metrics.geodesic_turn_limit));
  EXPECT_NEAR(plan.metrics.geodesic_min_radius, 40.0, 1e-9);
  for (const std::string& w : plan.metrics.warnings) {
    EXPECT_EQ(w.find("turns a geodesic can make"), std::string::npos) << w;
  }
}

// winding.turns need not be whole: YAML 0.55 gives passes of 0.55 turns, each the helix of
// length sqrt(L^2 + (2 pi R 0.55)^2); a whole number still reads as before.
TEST(Pipeline, FractionalTurnsAreReadAndWound) {
  std::string yaml = kPipe;
  yaml.replace(yaml.find("turns: 2"), 8, "turns: 0.55");
  const Job job = load_job_from_string(yaml, "/tmp/p.yaml");
  EXPECT_EQ(job.winding.turns, 0.55);
  const PipelineResult r = plan_job(job);
  EXPECT_NEAR(r.plan.metrics.turns_per_pass, 0.55, 1e-9);
  const double smooth = std::sqrt(200.0 * 200.0 + std::pow(2.0 * M_PI * 40.0 * 0.55, 2));
  ASSERT_EQ(r.passes.size(), 6u);
  for (const PassReport& p : r.passes) EXPECT_NEAR(p.length, smooth, 0.01 * smooth);
  EXPECT_NEAR(r.plan.metrics.max_slippage, 0.0, 0.1);
  EXPECT_EQ(load_job_from_string(kPipe, "/tmp/p.yaml").winding.turns, 2.0);
}

// winding.start_station / end_station: the passes run between the station planes, the
// turnarounds dwell on them, and the circuits (what export/ writes) stay continuous.
TEST(Pipeline, StationsBoundThePassesAndTheTurnarounds) {
  const double z0 = 50.0, z1 = 150.0;
  const Job job = load_job_from_string(
      std::string(kPipe) + "  start_station: 50\n  end_station: 150\n", "/tmp/p.yaml");
  EXPECT_EQ(job.winding.start_station, z0);
  EXPECT_EQ(job.winding.end_station, z1);
  const PipelineResult r = plan_job(job);
  ASSERT_EQ(r.plan.circuits.size(), 3u);
  const double smooth = std::sqrt((z1 - z0) * (z1 - z0) + std::pow(2.0 * M_PI * 40.0 * 2, 2));
  ASSERT_EQ(r.passes.size(), 6u);
  for (const PassReport& p : r.passes) EXPECT_NEAR(p.length, smooth, 0.01 * smooth);
  for (const Circuit& c : r.plan.circuits) {
    ASSERT_EQ(c.segments.size(), 4u);
    for (const FibrePoint& q : c.points) {
      EXPECT_GE(q.position.z(), z0 - 1e-6);
      EXPECT_LE(q.position.z(), z1 + 1e-6);
    }
    for (int i : {1, 3}) {
      const CircuitSegment& s = c.segments[i];
      EXPECT_EQ(s.kind, CircuitSegment::Kind::Turnaround);
      for (int j = s.first; j <= s.last; ++j) {
        EXPECT_NEAR(c.points[j].position.z(), i == 1 ? z1 : z0, 1e-6);
      }
    }
  }
  EXPECT_GT(r.plan.metrics.spacing_mean, 0.0);
  EXPECT_NEAR(r.plan.metrics.max_slippage, 0.0, 0.1);
  // The turnarounds' own figures: every dwell arc, on the station circles of a cylinder
  // (geodesics: no slippage, no bridging, no warning).
  const PlanMetrics& m = r.plan.metrics;
  double arcs = 0.0;  // the dwell arcs of the circuits: half a turn or so on each station circle
  for (const Circuit& c : r.plan.circuits) {
    for (const CircuitSegment& s : c.segments) {
      if (s.kind == CircuitSegment::Kind::Turnaround)
        arcs += c.points[s.last].s - c.points[s.first].s;
    }
  }
  EXPECT_NEAR(m.turnarounds.length, arcs, 1e-6 * arcs);
  EXPECT_GT(arcs, 3 * 2 * M_PI * 40.0 * 0.5);
  EXPECT_EQ(m.turnaround_ends[0].station, z0);
  EXPECT_EQ(m.turnaround_ends[1].station, z1);
  EXPECT_LT(m.turnarounds.max_slippage, 1e-3);
  EXPECT_EQ(m.turnarounds.slip_length, 0.0);
  EXPECT_EQ(m.turnarounds.bridging_length, 0.0);
  for (const std::string& w : m.warnings) EXPECT_EQ(w.find("turnaround"), std::string::npos) << w;
}

TEST(Pipeline, StationOutsideTheMandrelNamesTheKeyAndRange) {
  for (const std::string key : {"start_station: -5", "end_station: 250"}) {
    const Job job = load_job_from_string(std::string(kPipe) + "  " + key + "\n", "/tmp/p.yaml");
    try {
      plan_job(job);
      FAIL() << "accepted " << key;
    } catch (const ConfigError& e) {
      const std::string w = e.what();
      EXPECT_NE(w.find("winding." + key.substr(0, key.find(':'))), std::string::npos) << w;
      EXPECT_NE(w.find("(0, 200) mm"), std::string::npos) << w;
    }
  }
}

bool has_turn_warning(const PlanMetrics& m) {
  for (const std::string& w : m.warnings) {
    if (w.find("turns a geodesic can make") != std::string::npos) return true;
  }
  return false;
}

// The geodesic turn limit (planner/winding/clairaut.h) of a vessel with hemispherical domes: from
// the equator to the opening r0 a great circle tangent to the opening turns by exactly pi / 2, and
// the cylinder adds L r0 / (R sqrt(R^2 - r0^2)), so N_max = (pi + L r0 / (R sqrt(R^2 - r0^2)))
// / (2 pi) = 0.6502 for R 100, L 300, r0 30 (mm): the fewest turns a pass can make when it turns
// around on the domes. The tessellated mandrel gives it to 0.2% (the meridian's chords). N = 1
// is reached by turning around further out: Phi(c) = pi + L c / (R sqrt(R^2 - c^2)) = 2 pi gives
// c = pi R^2 / sqrt(L^2 + pi^2 R^2) = 72.3 mm, and one circuit then closes by itself (2 Phi =
// 4 pi); no warning.
TEST(Pipeline, HemisphericalVesselTurnsChooseTheTurnaround) {
  const Job job = load_job_from_string(
      "name: h\nmandrel:\n  source: vessel\n  vessel:\n    radius: 100\n    length: 300\n"
      "    dome: {type: hemispherical, polar_opening: 30}\n"
      "winding:\n  turns: 1\n  circuits: 1\n  band_width: 16\n",
      "/tmp/h.yaml");
  const PipelineResult r = plan_job(job);
  const double R = 100.0, L = 300.0, r0 = 30.0;
  const double expected = (M_PI + L * r0 / (R * std::sqrt(R * R - r0 * r0))) / (2.0 * M_PI);
  ASSERT_TRUE(r.has_turn_limit);
  ASSERT_TRUE(r.turn_limit.bounded) << r.turn_limit.reason;
  EXPECT_NEAR(r.turn_limit.turns, expected, 0.01 * expected);
  EXPECT_NEAR(r.turn_limit.min_radius, r0, 0.01);
  EXPECT_EQ(r.plan.metrics.geodesic_turn_limit, r.turn_limit.turns);
  ASSERT_TRUE(r.clairaut);
  const PatternInfo& pi = r.plan.metrics.pattern_info;
  EXPECT_NEAR(pi.turnaround_radius, M_PI * R * R / std::sqrt(L * L + M_PI * M_PI * R * R), 0.5);
  EXPECT_EQ(pi.requested_by, "winding.turns");
  EXPECT_NEAR(r.plan.metrics.turns_per_pass, 1.0, 1e-3);
  EXPECT_FALSE(has_turn_warning(r.plan.metrics));
  ASSERT_EQ(r.plan.circuits.size(), 1u);
  const Circuit& c = r.plan.circuits[0];
  EXPECT_LT((c.points.front().position - c.points.back().position).norm(), 1e-6);
}

// Between dwell ends (a cone) more turns than a geodesic can make fall back to the geodesic
// core, which wraps the passes along the smaller end, and the plan warns with a suggestion;
// with beta = 1 the density bends the passes and there is no warning.
TEST(Pipeline, ConeWithTooManyTurnsWarnsAtBetaZeroOnly) {
  Job job = load_job_from_string(
      "name: c\nmandrel:\n  source: cone\n  cone: {radius_start: 60, radius_end: 40, "
      "length: 400}\nwinding:\n  turns: 5\n  circuits: 2\n  band_width: 10\n",
      "/tmp/c.yaml");
  const PipelineResult geodesic = plan_job(job);
  EXPECT_FALSE(geodesic.clairaut);
  ASSERT_TRUE(geodesic.turn_limit.bounded) << geodesic.turn_limit.reason;
  EXPECT_TRUE(has_turn_warning(geodesic.plan.metrics));
  bool fell_back = false;
  for (const std::string& w : geodesic.plan.metrics.warnings) {
    fell_back = fell_back || w.find("pattern: winding.turns = 5") == 0;
  }
  EXPECT_TRUE(fell_back);
  job.winding.beta = 1.0;
  const PipelineResult density = plan_job(job);
  EXPECT_FALSE(has_turn_warning(density.plan.metrics));
  EXPECT_EQ(density.plan.metrics.geodesic_turn_limit, geodesic.plan.metrics.geodesic_turn_limit);
}

// Half a turn is fewer than any geodesic that turns around on the shipped vessel's domes can
// make (about 0.58 with its turnaround at the opening): the job is refused naming the key.
TEST(Pipeline, ShippedVesselWithHalfTurnsIsRefusedNamingTheKey) {
  Job job = load_job(test::source_dir() / "configs" / "vessel.yaml");
  job.cutlines.clear();
  job.winding.turns = 0.5;
  job.winding.turns_given = true;
  try {
    plan_job(job);
    FAIL() << "accepted 0.5 turns";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("winding.turns = 0.5: ", 0), 0u) << e.what();
  }
}

// More turns than the geodesic at the bosses without slippage: the geodesic turns around further
// out, and the run says the domes between are not wound; with slippage it does not (issue 19).
TEST(Pipeline, ShippedVesselAtMoreTurnsWarnsOffTheBossWithoutSlippage) {
  Job job = load_job(test::source_dir() / "configs" / "vessel_friction.yaml");
  job.cutlines.clear();
  auto off_boss = [](const PlanMetrics& m) {
    for (const std::string& w : m.warnings) {
      if (w.find("outside the bosses' turnaround") != std::string::npos) return true;
    }
    return false;
  };
  EXPECT_FALSE(off_boss(plan_job(job).plan.metrics));
  job.winding.slippage = 0.0;
  const PipelineResult geo = plan_job(job);
  EXPECT_FALSE(geo.revolution.friction);
  EXPECT_TRUE(off_boss(geo.plan.metrics));
  EXPECT_GT(geo.revolution.pattern.c, 38.11 + 4.0);
}

// What a shop checks on the shipped vessels and on a vessel with elliptical domes (issue 12):
// every pass a geodesic that turns around by itself on the domes (no dwell arc), tangent to the
// parallel r = c (every circuit's smallest radius within 0.5 mm of c), the circuits copies of
// one another (the mid-cylinder crossing relative to the circuit's start within 0.1 mm), no bare
// band at any station, neighbouring bands on the cylinder overlapping by at most 1 mm, and
// |k_g / k_n| <= mu on every pass point.
TEST(Pipeline, VesselsWindGeodesicTurnaroundsWithFullCover) {
  std::vector<std::pair<std::string, Job>> jobs;
  for (const char* f : {"vessel.yaml", "vessel_step.yaml"}) {
    jobs.emplace_back(f, load_job(test::source_dir() / "configs" / f));
  }
  jobs.emplace_back(
      "elliptical",
      load_job_from_string(
          "name: e\nmandrel:\n  source: vessel\n  remesh: 6\n  vessel:\n    radius: 100\n"
          "    length: 300\n    dome: {type: elliptical, polar_opening: 30, aspect: 0.6}\n"
          "winding:\n  band_width: 16\n",
          "/tmp/e.yaml"));
  for (auto& [name, job] : jobs) {
    SCOPED_TRACE(name);
    job.cutlines.clear();
    const PipelineResult r = plan_job(job);
    ASSERT_TRUE(r.clairaut);
    const PlanMetrics& m = r.plan.metrics;
    const PatternInfo& pi = m.pattern_info;
    EXPECT_TRUE(pi.geodesic_end[0] && pi.geodesic_end[1]);
    EXPECT_EQ(m.turnarounds.length, 0.0);
    EXPECT_GE(pi.turnaround_radius, pi.requested_radius);
    EXPECT_LE(m.max_slippage, m.friction);
    EXPECT_EQ(m.bridging_length, 0.0);
    ASSERT_TRUE(m.coverage.measured());
    EXPECT_GE(m.coverage.stations.size(), 8u);
    EXPECT_EQ(m.coverage.bare_fraction, 0.0);
    EXPECT_LE(m.coverage.widest_overlap_largest, 1.0);
    int on_cylinder = 0;  // the stations on the cylinder (the longest loops)
    for (const StationCoverage& st : m.coverage.stations) {
      if (std::abs(st.loop_length - 2 * M_PI * 100.0) < 1.0) {
        ++on_cylinder;
        EXPECT_LE(st.widest_overlap, 1.0) << st.station;
      }
    }
    EXPECT_GE(on_cylinder, 8);
    for (const std::string& w : m.warnings) EXPECT_EQ(w.find("coverage"), std::string::npos) << w;
    const SpindleAxis& ax = r.plan.axis;
    const Vec3 e1 = ax.direction.unitOrthogonal(), e2 = ax.direction.cross(e1);
    auto angle = [&](const Vec3& p) {
      const Vec3 d = p - ax.origin;
      return std::atan2(d.dot(e2), d.dot(e1));
    };
    double lo = 1e9, hi = -1e9;  // the middle of the passes' axial extent: mid-cylinder
    for (const FibrePoint& q : r.plan.circuits[0].points) {
      lo = std::min(lo, ax.axial(q.position));
      hi = std::max(hi, ax.axial(q.position));
    }
    const double mid = 0.5 * (lo + hi);
    double ref = std::nan(""), spread = 0.0;
    for (const Circuit& c : r.plan.circuits) {
      ASSERT_EQ(c.segments.size(), 2u);
      double rmin = 1e9;
      for (const FibrePoint& q : c.points) rmin = std::min(rmin, ax.radius(q.position));
      EXPECT_NEAR(rmin, pi.turnaround_radius, 0.5) << "circuit " << c.index;
      const CircuitSegment& out = c.segments[0];
      for (int i = out.first + 1; i <= out.last; ++i) {
        const Vec3 &a = c.points[i - 1].position, &b = c.points[i].position;
        const double fa = ax.axial(a) - mid, fb = ax.axial(b) - mid;
        if (fa < 0.0 && fb >= 0.0) {
          const double rel = std::remainder(
              angle(a + fa / (fa - fb) * (b - a)) - angle(c.points.front().position), 2 * M_PI);
          if (std::isnan(ref)) ref = rel;
          spread = std::max(spread, 100.0 * std::abs(std::remainder(rel - ref, 2 * M_PI)));
        }
      }
    }
    EXPECT_LT(spread, 0.1);  // mm
  }
}

// With stations the limit is taken between them: on the cone 60 -> 40 mm over 400 mm, stations at
// 100 and 300 mm (radii 55 and 45 mm) give arccos(45 / 55) / sin b = 1.952 turns (2.681 between
// the ends); N = 3 exceeds it (the warning suggests 1.95), N = 1 does not.
TEST(Pipeline, ConeTurnLimitIsTakenBetweenTheStations) {
  const std::string cone =
      "name: c\nmandrel:\n  source: cone\n  cone: {radius_start: 60, radius_end: 40, length: "
      "400}\nwinding:\n  circuits: 1\n  band_width: 10\n  start_station: 100\n"
      "  end_station: 300\n";
  const double sin_b = 20.0 / std::hypot(400.0, 20.0);
  const double expected = std::acos(45.0 / 55.0) / sin_b / (2.0 * M_PI);
  const PipelineResult three = plan_job(load_job_from_string(cone + "  turns: 3\n", "/tmp/c.yaml"));
  ASSERT_TRUE(three.turn_limit.bounded) << three.turn_limit.reason;
  EXPECT_NEAR(three.turn_limit.turns, expected, 1e-6 * expected);
  EXPECT_DOUBLE_EQ(three.turn_limit.x0, 100.0);
  EXPECT_DOUBLE_EQ(three.turn_limit.x1, 300.0);
  EXPECT_TRUE(has_turn_warning(three.plan.metrics));
  bool suggests = false;
  for (const std::string& w : three.plan.metrics.warnings) {
    suggests =
        suggests || (w.find("winding.start_station and winding.end_station") != std::string::npos &&
                     w.find("use turns <= 1.95, beta > 0") != std::string::npos);
  }
  EXPECT_TRUE(suggests);
  const PipelineResult one = plan_job(load_job_from_string(cone + "  turns: 1\n", "/tmp/c.yaml"));
  EXPECT_FALSE(has_turn_warning(one.plan.metrics));
}

// Not a shape of revolution (the bent tube): no limit is computed or reported.
TEST(Pipeline, BentTubeHasNoTurnLimit) {
  Job job = load_job(test::source_dir() / "configs" / "bent_tube.yaml");
  job.cutlines.clear();
  job.winding.circuits = 1;
  const PipelineResult r = plan_job(job);
  EXPECT_FALSE(r.has_turn_limit);
  EXPECT_TRUE(std::isnan(r.plan.metrics.geodesic_turn_limit));
  EXPECT_FALSE(has_turn_warning(r.plan.metrics));
}

// The shipped bent tube is a full layer (issue 25): no section normal to the centre line bare,
// every pass point within mu, a closed pattern of the circuits auto chose; re-measured on a
// centre line extracted from the mesh's section centroids (not the analytic one the plan used).
TEST(Pipeline, BentTubeIsAFullLayerOnSectionsNormalToTheCentreLine) {
  Job job = load_job(test::source_dir() / "configs" / "bent_tube.yaml");
  job.cutlines.clear();
  const PipelineResult r = plan_job(job);
  const PlanMetrics& m = r.plan.metrics;
  EXPECT_EQ(r.tube.centre_line.source, "bent_tube centre line");
  EXPECT_NEAR(r.tube.centre_line.spine.length(), 400 + 100 * M_PI / 2, 0.05);
  ASSERT_TRUE(m.coverage.centre_line);
  EXPECT_GE(m.coverage.stations.size(), 12u);
  EXPECT_EQ(m.coverage.bare_fraction, 0.0) << m.coverage.brief_report();
  EXPECT_LE(m.max_slippage, job.winding.mu);
  EXPECT_EQ(m.slip_fraction, 0.0);
  EXPECT_EQ(r.laid, "evenly spread helix");
  const int K = static_cast<int>(r.plan.circuits.size());
  EXPECT_EQ(K, m.circuits_for_coverage);
  EXPECT_TRUE(r.helices.summary.circuits_auto);
  const Mandrel& md = r.mandrel;
  const SpineResult extracted = extract_spine(
      md.winding.mesh, {md.winding.loops[0].vertices, md.winding.loops[1].vertices}, md.axis);
  CoverageOptions co;
  co.band_width = job.winding.band_width;
  co.stations = 30;
  co.spine = &extracted.spine;
  const CoverageReport again = measure_coverage(md.winding.mesh, md.axis, r.plan.circuits, co);
  EXPECT_EQ(again.bare_fraction, 0.0) << again.brief_report();
  // One circuit fewer leaves a section bare: auto did not add circuits for nothing.
  Job fewer = job;
  fewer.winding.circuits = K - 1;
  const PipelineResult f = plan_job(fewer);
  EXPECT_GT(f.plan.metrics.coverage.bare_fraction, 0.0);
}

// The shipped robot elbow is a full layer (issue 26; its geodesic helices left 33% bare): the
// friction layer of configs/elbow.yaml, no section bare (the planner's sections normal to the
// centre line; re-measured from the laid points alone on the same elbow and layer in
// tests/planner/winding/tube_friction_test.cpp), every laid point within mu.
TEST(Pipeline, ElbowRobotIsAFullLayerWithinMu) {
  const Job job = load_job(test::source_dir() / "configs" / "elbow_robot.yaml");
  const PipelineResult r = plan_job(job);
  const PlanMetrics& m = r.plan.metrics;
  EXPECT_TRUE(r.tube.friction);
  EXPECT_GE(m.coverage.stations.size(), 12u);
  EXPECT_EQ(m.coverage.bare_fraction, 0.0) << m.coverage.brief_report();
  EXPECT_LE(m.max_slippage, job.winding.mu);
  EXPECT_EQ(m.slip_fraction, 0.0);
  EXPECT_EQ(job.machine.kind, "robot");
  EXPECT_GT(job.machine.replay_tolerance, 0.0);
}

// The shared aerobar's arm with rounded edges (its mesh has square ones, refused): a rounded
// rectangle 32 x 10 mm, corner radius 3, one turn, band 2, pattern auto. Coverage on sections
// normal to the centre line, every pass within mu, K no fewer than the coverage needs.
TEST(Pipeline, RoundedAerobarArmIsAFullLayerWithinMu) {
  const Job job = load_job_from_string(
      "name: aerobar_round\n"
      "mandrel:\n"
      "  source: section\n"
      "  section: {shape: rounded_rectangle, width: 32, height: 10, corner_radius: 3, "
      "length: 60}\n"
      "winding: {turns: 1, pattern: auto, band_width: 2, mu: 0.2, coverage_stations: 12}\n",
      "/tmp/aerobar_round.yaml");
  const PipelineResult r = plan_job(job);
  const PlanMetrics& m = r.plan.metrics;
  EXPECT_FALSE(r.tube.centre_line.spine.empty());
  EXPECT_EQ(m.coverage.stations.size(), 12u);
  EXPECT_EQ(m.coverage.bare_fraction, 0.0) << m.coverage.brief_report();
  EXPECT_LE(m.max_slippage, 0.2);
  EXPECT_GE(static_cast<int>(r.plan.circuits.size()), m.circuits_for_coverage);
  // The sections are the rounded rectangle: 2 (32 + 10) - (8 - 2 pi) 3 = 80.85 mm around.
  for (const StationCoverage& s : m.coverage.stations) {
    EXPECT_NEAR(s.loop_length, 2.0 * (32 + 10) - (8.0 - 2.0 * M_PI) * 3.0, 0.5);
  }
}

// Where the evenly spread helices would need more friction than mu, the geodesics are laid and
// the warning gives both sets of figures and what to change.
TEST(Pipeline, BentTubeHelicesAboveMuAreNotLaid) {
  Job job = load_job(test::source_dir() / "configs" / "bent_tube.yaml");
  job.cutlines.clear();
  job.winding.turns = 8;
  job.winding.circuits = 12;
  const PipelineResult r = plan_job(job);
  EXPECT_EQ(r.laid, "geodesic");
  EXPECT_LE(r.plan.metrics.max_slippage, job.winding.mu);
  bool named = false;
  for (const std::string& w : r.plan.metrics.warnings) {
    named |= w.find("tube passes:") != std::string::npos &&
             w.find("the geodesics are laid") != std::string::npos &&
             w.find("more turns") != std::string::npos;
  }
  EXPECT_TRUE(named);
}

TEST(Pipeline, WindingSectionErrorsNameTheKey) {
  auto expect_error = [](const std::string& section, const std::string& words) {
    const std::string yaml =
        "mandrel:\n  source: pipe\n  pipe: {radius: 40, length: 200}\nwinding:\n" + section;
    try {
      load_job_from_string(yaml, "/tmp/j.yaml");
      FAIL() << "accepted: " << section;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("j.yaml"), std::string::npos) << e.what();
    }
  };
  expect_error("  turns: 0\n", "turns must be > 0 (got 0)");
  expect_error("  turns: -1\n", "turns must be > 0 (got -1)");
  expect_error("  turns: .nan\n", "key 'winding.turns': expected a number");
  expect_error("  turns: .inf\n", "key 'winding.turns': expected a number");
  expect_error("  turns: half\n", "key 'winding.turns': expected a number");
  expect_error("  circuits: 0\n", "circuits");
  expect_error("  circuits: many\n", "circuits");
  expect_error("  beta: 2\n", "beta");
  expect_error("  band_width: -1\n", "band_width");
  expect_error("  mu: -0.1\n", "mu");
  expect_error("  mu: 1e9\n", "mu must be in [0, 2]");
  expect_error("  turn: 3\n", "turn");  // unknown key
  const Job a = load_job_from_string(
      "mandrel:\n  source: pipe\n  pipe: {radius: 40, length: 200}\nwinding:\n  circuits: auto\n",
      "/tmp/j.yaml");
  EXPECT_EQ(a.winding.circuits, 0);
}

}  // namespace
}  // namespace windplan
