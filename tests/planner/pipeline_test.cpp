// planner/pipeline.cpp (plan_job) and the winding: job section.
#include "planner/pipeline.h"

#include <cmath>

#include <gtest/gtest.h>

#include "geometry/errors.h"

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
  EXPECT_EQ(plan.metrics.turns_per_pass, 2);
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
  expect_error("  turns: 0\n", "turns");
  expect_error("  circuits: 0\n", "circuits");
  expect_error("  circuits: many\n", "circuits");
  expect_error("  beta: 2\n", "beta");
  expect_error("  band_width: -1\n", "band_width");
  expect_error("  mu: -0.1\n", "mu");
  expect_error("  turn: 3\n", "turn");  // unknown key
  const Job a = load_job_from_string(
      "mandrel:\n  source: pipe\n  pipe: {radius: 40, length: 200}\nwinding:\n  circuits: auto\n",
      "/tmp/j.yaml");
  EXPECT_EQ(a.winding.circuits, 0);
}

}  // namespace
}  // namespace windplan
