// bench_girth: the girth field (planner/girth/girth.h) on the shipped vessel (R 100, L 300,
// isotensoid domes, 30 mm polar openings) tessellated finely enough for ~100K winding-surface
// faces. Prints the mesh size, the samples, the time, the sampling error bound, the time of one
// exact evaluation, and the interpolation error at held-out vertices (direct evaluation). Asserts
// nothing.
//   usage: bench_girth [remesh_mm=0] [samples=64] [linear_deflection_mm=0.02]
// The default, linear deflection 0.02 mm without remeshing, gives ~89K winding-surface faces
// (the cylinder is long sliver triangles, edges up to 300 mm). mandrel.remesh (first argument,
// mm) gives a more isotropic mesh, but at 2.0 and 2.5 mm build_mandrel currently fails with a
// non-manifold vertex and at 3.0 mm it keeps 300 mm edges.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <vector>

#include "planner/girth/girth.h"
#include "planner/job/job.h"
#include "planner/mandrel/mandrel_builder.h"

using namespace windplan;

int main(int argc, char** argv) {
  const double remesh = argc > 1 ? std::atof(argv[1]) : 0.0;
  const int samples = argc > 2 ? std::max(4, std::atoi(argv[2])) : 64;
  const double deflection = argc > 3 ? std::atof(argv[3]) : 0.02;
  MandrelOptions m;
  m.source = "vessel";
  m.vessel.radius = 100;
  m.vessel.length = 300;
  m.vessel.dome_start.type = m.vessel.dome_end.type = DomeType::Isotensoid;
  m.vessel.dome_start.polar_opening = m.vessel.dome_end.polar_opening = 30;
  m.tessellation.linear_deflection = deflection;
  m.tessellation.angular_deflection = 10.0;
  m.remesh = remesh;
  const Mandrel md = build_mandrel(m);
  const Mesh& mesh = md.winding.mesh;
  const std::array<std::vector<int>, 2> loops{md.winding.loops[0].vertices,
                                              md.winding.loops[1].vertices};
  const auto el = mesh.edge_length_stats();
  std::printf(
      "vessel R=100 L=300 isotensoid r0=30, linear deflection %.3f mm, remesh %.2f mm: "
      "winding surface %d vertices, %d faces, edges %.2f/%.2f/%.2f mm (min/mean/max), mandrel %.0f "
      "ms\n",
      deflection, remesh, mesh.num_vertices(), mesh.num_faces(), el[0], el[1], el[2], md.total_ms);

  std::printf("%10s %8s %10s %10s %10s %10s %12s %12s %6s\n", "placement", "samples", "time_ms",
              "ms/sample", "min_g", "max_g", "bound_mm", "heldout_err", "unconv");
  const GirthContext context(mesh, loops);
  for (const char* placement : {"rings", "farthest"}) {
    GirthOptions options;
    options.samples = samples;
    options.placement = placement;
    const GirthField field = compute_girth_field(mesh, loops, options);
    const auto [lo, hi] = std::minmax_element(field.vertex_girth.begin(), field.vertex_girth.end());
    // Held-out vertices: every (V / 20)-th vertex that is not a sample, evaluated directly.
    std::set<int> sampled;
    for (const GirthSample& s : field.samples) sampled.insert(s.vertex);
    double worst = 0.0;
    for (int v = 11; v < mesh.num_vertices(); v += mesh.num_vertices() / 20) {
      if (sampled.count(v)) continue;
      const double exact = context.girth(v).girth;
      worst = std::max(worst, std::abs(field.vertex_girth[v] - exact));
    }
    std::printf("%10s %8zu %10.1f %10.2f %10.2f %10.2f %12.2f %12.3f %6d\n", placement,
                field.samples.size(), field.time_ms, field.time_ms / field.samples.size(), *lo, *hi,
                field.lipschitz_bound, worst, field.unconverged_samples);
  }
  // One exact evaluation (no distance field), for the cost of girth_at on this mesh.
  const auto t0 = std::chrono::steady_clock::now();
  const GirthContext::Loop one = context.girth(mesh.num_vertices() / 2);
  const double one_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("one exact loop at vertex %d: g = %.3f mm, %d crossings, %.1f ms (%s)\n",
              mesh.num_vertices() / 2, one.girth, one.path.num_crossings(), one_ms,
              one.summary.brief_report().c_str());
  return 0;
}
