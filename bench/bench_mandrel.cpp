// bench_mandrel: tessellation time and size of the shipped vessel (R 100, L 300, isotensoid
// domes, 30 mm polar openings) at the default deflection and at finer ones, plus the whole
// build_mandrel (welding, checks, axis, winding surface). Prints a table; asserts nothing.
//   usage: bench_mandrel [repeats=3]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "geometry/cad/parametric_mandrel.h"
#include "geometry/cad/tessellate.h"
#include "geometry/mesh/mesh.h"
#include "planner/job/job.h"
#include "planner/mandrel/mandrel_builder.h"

using namespace windplan;

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  MandrelOptions m;
  m.source = "vessel";
  m.vessel.radius = 100;
  m.vessel.length = 300;
  m.vessel.dome_start.type = m.vessel.dome_end.type = DomeType::Isotensoid;
  m.vessel.dome_start.polar_opening = m.vessel.dome_end.polar_opening = 30;
  const CadShape shape = make_vessel(m.vessel);
  // Exact area of the B-rep for the relative area error of each tessellation.
  const double exact = cad_shape_info(shape).area;

  std::printf("vessel R=100 L=300 isotensoid domes r0=30, angular deflection 10 deg, best of %d\n",
              repeats);
  std::printf("%10s %9s %9s %13s %12s %12s %10s\n", "lin.defl", "vertices", "faces",
              "tessellate_ms", "build_ms", "area_rel_err", "max_edge");
  for (double defl : {0.25, 0.1, 0.05, 0.02, 0.015}) {
    m.tessellation.linear_deflection = defl;
    m.tessellation.angular_deflection = 10.0;
    double best_tess = 1e300, best_build = 1e300;
    int V = 0, F = 0;
    double area = 0, max_edge = 0;
    for (int r = 0; r < repeats; ++r) {
      const Tessellation t = tessellate(shape, m.tessellation);
      best_tess = std::min(best_tess, t.time_ms);
      const Mandrel md = build_mandrel(m);
      best_build = std::min(best_build, md.total_ms);
      V = md.mesh.num_vertices();
      F = md.mesh.num_faces();
      area = md.mesh.total_area();
      max_edge = md.mesh.edge_length_stats()[2];
    }
    std::printf("%10.3f %9d %9d %13.1f %12.1f %12.2e %10.2f%s\n", defl, V, F, best_tess, best_build,
                (exact - area) / exact, max_edge, defl == 0.25 ? "  (default)" : "");
  }
  return 0;
}
