// bench_helices: helix planning speed and the plan figures of every shipped job.
//   bench_helices [configs_dir] [--shipped]
// 1. 24 circuits of 5 turns (48 passes) on the vessel and the pipe: trace and refinement times
//    (the geodesic core's route; skipped with --shipped).
// 2. For every configs/*.yaml: plan_job, then the route, pattern, measured coverage, spacing and
//    stability figures and the planning time.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "planner/pipeline.h"

using namespace windplan;

namespace {

void bench_24x5(const std::filesystem::path& job_file, double beta) {
  Job job = load_job(job_file);
  const Mandrel md = build_mandrel(job);
  const WindingSurface& ws = md.winding;
  const std::array<std::vector<int>, 2> loops{ws.loops[0].vertices, ws.loops[1].vertices};
  WindingOptions o = job.winding;
  o.turns = 5;
  o.circuits = 24;
  o.beta = beta;
  std::vector<double> rho;
  double girth_s = 0.0;
  if (beta > 0.0) {
    // As plan_job does: 2 pi r on a shape of revolution, the girth field otherwise (its time is
    // printed apart, not in the total).
    std::vector<double> g(ws.mesh.num_faces());
    if (md.revolution) {
      for (int f = 0; f < ws.mesh.num_faces(); ++f) {
        g[f] = 2.0 * M_PI * md.axis.radius(ws.mesh.face_centroid(f));
      }
    } else {
      const auto tg = std::chrono::steady_clock::now();
      g = compute_girth_field(ws.mesh, loops, job.girth).face_girth(ws.mesh);
      girth_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - tg).count();
    }
    rho = density_from_girth(ws.mesh, g, beta);
  }
  const auto t0 = std::chrono::steady_clock::now();
  const HelixPlan plan = plan_helices(ws.mesh, loops, rho, md.axis, o);
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double worst = 0.0;
  for (const HelixPass& p : plan.passes) worst = std::max(worst, p.summary.time_ms);
  if (std::getenv("WINDPLAN_BENCH_VERBOSE")) {
    for (const HelixPass& p : plan.passes) {
      const GeodesicSummary& s = p.summary;
      std::printf("  pass c%d%+d: %d crossings, %d it, %d evals, %d reroutes, %d lifts, %s (pg %.1e), %.1f ms\n",
                  p.circuit, p.hand, p.path.num_crossings(), s.iterations, s.evaluations,
                  s.reroutes, s.lifts, to_string(s.termination), s.projected_gradient, s.time_ms);
    }
  }
  std::printf(
      "%-12s beta %.1f: %d faces, 24 circuits x 5 turns (%zu passes): total %.3f s "
      "(harmonic %.3f s, trace %.3f s, refine %.3f s, worst pass %.1f ms), "
      "%d not converged%s\n",
      job.name.c_str(), beta, ws.mesh.num_faces(), plan.passes.size(), total,
      plan.summary.harmonic_ms / 1e3, plan.summary.trace_ms / 1e3, plan.summary.refine_ms / 1e3,
      worst, plan.summary.not_converged,
      girth_s > 0.0 ? (" (girth field " + std::to_string(girth_s) + " s, apart)").c_str() : "");
}

}  // namespace

int main(int argc, char** argv) {
  std::filesystem::path dir = WINDPLAN_CONFIGS_DIR;
  bool shipped_only = false;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--shipped") {
      shipped_only = true;
    } else {
      dir = argv[i];
    }
  }
  try {
    if (!shipped_only) {
      std::printf("== 24 circuits of 5 turns ==\n");
      for (const char* job : {"pipe.yaml", "cone.yaml", "bent_tube.yaml", "vessel.yaml"}) {
        bench_24x5(dir / job, 0.0);
        bench_24x5(dir / job, 1.0);
      }
    }
    std::printf("\n== shipped jobs (their winding: sections) ==\n");
    std::map<std::string, std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
      if (e.path().extension() == ".yaml") files[e.path().filename().string()] = e.path();
    }
    for (const auto& [name, path] : files) {
      const Job job = load_job(path);
      const PipelineResult r = plan_job(job);
      const PlanMetrics& m = r.plan.metrics;
      double total = 0.0;
      for (const StageTiming& t : m.timings) total += t.seconds;
      const CoverageReport& cv = m.coverage;
      std::printf(
          "%-16s %s N=%.4f K=%d beta=%.1f | c %.2f mm | bare %.2f%%, gap %.1f mm, overlap %.2f "
          "mm (largest sections %.2f), stack %d, cover %.3f, %zu stations | spacing CV %.3f | "
          "max |kg/kn| %.3f (mu %.2f), above mu %.1f%%, bridging %.1f mm | dwell arcs %.0f mm, "
          "max |kg/kn| %.3f | %.2f s\n",
          name.c_str(), r.clairaut ? "clairaut" : "core    ", m.turns_per_pass, m.circuits,
          job.winding.beta, m.pattern_info.turnaround_radius, 100.0 * cv.bare_fraction,
          cv.widest_gap, cv.widest_overlap, cv.widest_overlap_largest, cv.max_stack,
          cv.cover_factor, cv.stations.size(), m.spacing_cv, m.max_slippage, m.friction,
          100.0 * m.slip_fraction, m.bridging_length, m.turnarounds.length,
          m.turnarounds.max_slippage, total);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_helices: %s\n", e.what());
    return 1;
  }
  return 0;
}
