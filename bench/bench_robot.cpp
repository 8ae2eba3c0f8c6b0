// Robot cells (issue #26): for every shipped job with an arm (machine.robot.arm), or the jobs named
// on the command line, the time per target of the inverse kinematics (export/robot/robot_motion.h),
// of writing and reading back the KRL or RAPID program and of the robot replay
// (export/robot/robot_replay.h), with the replay's figures, and the wall time of the reach check
// before planning (export/robot/cell_reach.h). Prints; asserts nothing.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "export/machine/kinematics.h"
#include "export/robot/cell_reach.h"
#include "export/robot/robot_motion.h"
#include "export/robot/robot_program.h"
#include "export/robot/robot_program_reader.h"
#include "export/robot/robot_replay.h"
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
    for (const auto& e : std::filesystem::directory_iterator(WINDPLAN_CONFIGS_DIR)) {
      if (e.path().extension() == ".yaml") jobs.push_back(e.path());
    }
    std::sort(jobs.begin(), jobs.end());
  }
  std::printf("%-12s %9s %7s %9s %9s %9s %9s | %s\n", "job", "reach ms", "targets", "IK us/pt",
              "write us", "read us", "replay us", "replay");
  for (const auto& path : jobs) {
    const Job job = load_job(path);
    if (job.machine.kind != "robot" || !job.machine.robot.has_arm()) continue;
    const PipelineResult r = plan_job(job, {});
    auto t0 = std::chrono::steady_clock::now();
    check_cell_reach(r.mandrel.winding.mesh, r.mandrel.axis, r.mandrel.profile, job.machine);
    const double t_reach = seconds_since(t0);
    const Motion mo = compute_motion(r.plan, job.machine, &r.mandrel.mesh);
    t0 = std::chrono::steady_clock::now();
    const RobotMotion rm = compute_robot_motion(mo, r.plan, job.machine);
    const double t_ik = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    const std::vector<ProgramFile> files = robot_program(rm, r.plan.job_name, job.machine);
    const double t_write = seconds_since(t0);
    std::map<std::string, std::string> texts;
    for (const ProgramFile& f : files) texts[f.name] = f.text;
    t0 = std::chrono::steady_clock::now();
    const RobotProgram p = read_robot_program(texts, files.front().name, job.machine.robot.dialect);
    const double t_read = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    const RobotReplayResult rp = replay_robot_program(p, r.plan, r.mandrel.mesh, job.machine, &mo);
    const double t_replay = seconds_since(t0);
    const double n = static_cast<double>(rm.targets.size());
    std::printf("%-12s %9.2f %7zu %9.1f %9.2f %9.2f %9.1f | %s, max %.3f mm, eye path %.4f mm\n",
                path.stem().string().c_str(), 1e3 * t_reach, rm.targets.size(), 1e6 * t_ik / n,
                1e6 * t_write / n, 1e6 * t_read / n, 1e6 * t_replay / n,
                job.machine.robot.dialect.c_str(), rp.fibre.max_deviation, rp.max_eye_deviation);
  }
  return 0;
}
