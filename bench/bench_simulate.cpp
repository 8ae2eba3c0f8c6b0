// Replay time of the shipped jobs' G-code programs (export/program/replay.h), with the motion
// figures of issue #13: reversals, axis limits, clearance, replay deviation, wind time. Usage:
// bench_simulate [job.yaml ...]   (default: every configs/*.yaml; vessel first)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "export/machine/kinematics.h"
#include "export/program/gcode.h"
#include "export/program/gcode_reader.h"
#include "export/program/replay.h"
#include "planner/job/job.h"
#include "planner/pipeline.h"

using namespace windplan;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::filesystem::path> jobs;
  for (int i = 1; i < argc; ++i) jobs.emplace_back(argv[i]);
  if (jobs.empty()) {
    jobs.push_back(std::filesystem::path(WINDPLAN_CONFIGS_DIR) / "vessel.yaml");
    std::vector<std::filesystem::path> rest;
    for (const auto& e : std::filesystem::directory_iterator(WINDPLAN_CONFIGS_DIR)) {
      if (e.path().extension() == ".yaml" && e.path().stem() != "vessel") rest.push_back(e.path());
    }
    std::sort(rest.begin(), rest.end());
    jobs.insert(jobs.end(), rest.begin(), rest.end());
  }
  for (const auto& path : jobs) {
    try {
      const Job job = load_job(path);
      const PipelineResult r = plan_job(job, {});
      const Motion mo = compute_motion(r.plan, job.machine, &r.mandrel.mesh);
      if (job.machine.kind == "robot") {
        std::printf(
            "%-12s %2zu circuits | robot (no G-code) | X reversals %d (max %d per circuit, "
            "%d mid-pass) | A reversals %d | v %.3f a %.3f of limit | clearance min %.3f "
            "mm | wind %.1f s | eye X %.0f..%.0f mm, free length <= %.0f mm\n",
            path.stem().string().c_str(), mo.circuit_time.size(), mo.carriage_reversals,
            mo.max_carriage_reversals_per_circuit, mo.mid_pass_carriage_reversals,
            mo.spindle_reversals, mo.limits.velocity_ratio, mo.limits.acceleration_ratio,
            mo.min_clearance, mo.wind_time, mo.x.min, mo.x.max, mo.free_length.max);
        continue;
      }
      const std::string text = gcode_program(mo, r.plan.job_name, job.machine);
      auto t0 = std::chrono::steady_clock::now();
      const GcodeProgram p = read_gcode(text, job.machine, "toolpath");
      const double t_read = seconds_since(t0);
      std::vector<double> times;
      ReplayResult rp;
      for (int k = 0; k < 3; ++k) {
        rp = replay_program(p, r.plan, r.mandrel.mesh, job.machine);
        times.push_back(rp.seconds);
      }
      std::sort(times.begin(), times.end());
      int circuits = static_cast<int>(mo.circuit_time.size());
      double cmin = 1e300, cmax = 0;
      for (double t : mo.circuit_time) {
        cmin = std::min(cmin, t);
        cmax = std::max(cmax, t);
      }
      std::printf(
          "%-12s %2d circuits | X reversals %4d (max %d per circuit, %d mid-pass) | A reversals "
          "%d (%d in passes) | v %.3f a %.3f of limit | clearance min %.3f mm (req %.0f) | "
          "replay max %.3f mean %.4f mm | wind %.1f s (circuit %.2f..%.2f) | X %.0f..%.0f mm | "
          "read %.3f s, replay %d blocks %d substeps %.3f s (median of 3)\n",
          path.stem().string().c_str(), circuits, mo.carriage_reversals,
          mo.max_carriage_reversals_per_circuit, mo.mid_pass_carriage_reversals,
          mo.spindle_reversals, mo.spindle_reversals_in_passes, mo.limits.velocity_ratio,
          mo.limits.acceleration_ratio, mo.min_clearance, mo.required_clearance, rp.max_deviation,
          rp.mean_deviation, mo.wind_time, cmin, cmax, mo.x.min, mo.x.max, t_read, rp.blocks,
          rp.substeps, times[1]);
    } catch (const std::exception& e) {
      std::printf("%-12s error: %s\n", path.stem().string().c_str(), e.what());
    }
  }
  return 0;
}
