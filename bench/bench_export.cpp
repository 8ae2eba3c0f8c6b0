// Export figures on a closed-form plan (helices on a cylinder, R = 50 mm, alpha = 40 deg):
// time of the payout-eye solve + resampling (compute_motion), of each G-code dialect, of the
// CSV/SVG/report text, and of a whole export_plan; the eye residual on the envelope; the
// resampling ratio and chord deviation. Usage: bench_export [circuits] [points_per_circuit]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "export/export_plan.h"
#include "export/files/report.h"
#include "export/plots/svg.h"
#include "export/plots/unroll.h"
#include "export/plots/viewer.h"
#include "export/program/gcode.h"
#include "tests/export/plan_fixtures.h"

using namespace windplan;

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const int circuits = argc > 1 ? std::atoi(argv[1]) : 12;
  const int n = argc > 2 ? std::atoi(argv[2]) : 40000;
  const WindingPlan plan = test::helix_plan(50, 40, 1.5, n, circuits);
  MachineOptions m;
  m.kind = "lathe4";
  std::printf("plan: %d circuits x %d points = %d dense points\n", circuits, n, circuits * n);

  auto t0 = std::chrono::steady_clock::now();
  const Motion mo = compute_motion(plan, m);
  const double t_motion = seconds_since(t0);
  std::printf(
      "compute_motion: %.3f s (%.2f us per dense point), %zu machine points (%.2f%%), "
      "max chord deviation %.4f mm (tolerance %.3f), max eye iterations %d\n",
      t_motion, 1e6 * t_motion / (circuits * n), mo.states.size(),
      100.0 * mo.states.size() / (circuits * n), mo.max_chord_deviation, m.chord_tolerance,
      mo.max_eye_iterations);

  const AxisFrame f = make_axis_frame(plan.axis);
  const Envelope env = make_envelope(plan.profile, m.envelope);
  double max_res = 0, max_line = 0;
  for (const MachineState& s : mo.states) {
    max_res = std::max(max_res, std::fabs(f.radius(s.eye) - env.radius_at(f.axial(s.eye))));
    max_line = std::max(max_line, (s.eye - s.position).cross(s.direction).norm());
  }
  std::printf("eye residual on the envelope: max %.3e mm; off the tangent line: max %.3e mm\n",
              max_res, max_line);

  for (const char* d : {"linuxcnc", "marlin", "fanuc"}) {
    m.gcode.dialect = d;
    t0 = std::chrono::steady_clock::now();
    const std::string g = gcode_program(mo, plan.job_name, m);
    std::printf("gcode %-8s: %.3f s, %.1f MB\n", d, seconds_since(t0), g.size() / 1e6);
  }
  m.gcode.dialect = "linuxcnc";
  t0 = std::chrono::steady_clock::now();
  std::ostringstream csv;
  write_csv(csv, fibre_path_table(plan));
  write_csv(csv, axes_table(mo));
  write_csv(csv, payout_table(mo));
  std::printf("csv text: %.3f s, %.1f MB\n", seconds_since(t0), csv.str().size() / 1e6);
  t0 = std::chrono::steady_clock::now();
  const std::string svg = development_svg(plan, Unrolling::make(plan, Mesh()));
  std::printf("development.svg: %.3f s, %.2f MB\n", seconds_since(t0), svg.size() / 1e6);
  t0 = std::chrono::steady_clock::now();
  const ViewerPage page = viewer_page(plan, Mesh(), mo);
  std::printf("viewer.html: %.3f s, %.2f MB, %d of %d fibre points, %d of %d machine points\n",
              seconds_since(t0), page.html.size() / 1e6, page.points_kept, page.points,
              page.states_kept, page.states);

  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "windplan_bench_export";
  t0 = std::chrono::steady_clock::now();
  const ExportResult r = export_plan(plan, Mesh(), m, OutputOptions{}, dir);
  std::printf("export_plan (all files): %.3f s, wind time %.1f s\n", seconds_since(t0),
              r.motion.wind_time);
  std::filesystem::remove_all(dir);
  return 0;
}
