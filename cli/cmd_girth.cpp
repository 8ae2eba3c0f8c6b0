// windplan girth <job.yaml> [-o girth.csv] [--json]
// Builds the job's mandrel, computes the girth field on its winding surface (planner/girth/girth.h)
// and reports it; optionally writes the per-vertex field as CSV.
#include <algorithm>
#include <iostream>
#include <sstream>

#include "cli/args.h"
#include "cli/commands.h"
#include "export/files/csv.h"
#include "geometry/base/json.h"
#include "planner/girth/girth.h"
#include "planner/job/job.h"
#include "planner/mandrel/mandrel_builder.h"

namespace windplan::cli {

const char* const kGirthHelp =
    "usage: windplan girth <job.yaml> [-o girth.csv] [--json]\n\n"
    "Builds the job's mandrel and computes the girth field on its winding surface: g(p) is the\n"
    "length of the shortest loop through p that winds once around the mandrel. g is computed\n"
    "exactly at girth.samples vertices (placement: rings | farthest) and interpolated to every\n"
    "vertex; the report gives the samples, min/max girth, the sampling error bound\n"
    "(|g(p) - g(q)| <= 2 d(p, q): twice the largest distance to the nearest sample) and the "
    "time.\n\n"
    "  -o, --out FILE   write the per-vertex field as CSV: vertex, x, y, z [mm], girth [mm]\n"
    "                   (winding-surface vertices; positions in the job's frame)\n"
    "  --json           print the report as JSON on stdout\n";

int run_girth(const std::vector<std::string>& argv) {
  const Args args(argv, {"--json"}, {"-o", "--out"});
  args.expect_positional(1, "a job file");
  const Job job = load_job(args.positional()[0]);
  const Mandrel m = build_mandrel(job);
  for (const std::string& w : m.warnings) std::cerr << "windplan girth: warning: " << w << "\n";
  const Mesh& annulus = m.winding.mesh;
  const GirthField field = compute_girth_field(
      annulus, {m.winding.loops[0].vertices, m.winding.loops[1].vertices}, job.girth);

  const std::string out = args.has("-o") ? args.value("-o") : args.value("--out");
  if (!out.empty()) {
    CsvTable table;
    table.header = {"vertex", "x [mm]", "y [mm]", "z [mm]", "girth [mm]"};
    table.rows.reserve(annulus.num_vertices());
    for (int v = 0; v < annulus.num_vertices(); ++v) {
      const Vec3& p = annulus.position(v);
      table.rows.push_back({double(v), p.x(), p.y(), p.z(), field.vertex_girth[v]});
    }
    write_csv_file(out, table);
  }

  double gmin = 0.0, gmax = 0.0, smin = 0.0, smax = 0.0;
  if (!field.vertex_girth.empty()) {
    const auto [lo, hi] = std::minmax_element(field.vertex_girth.begin(), field.vertex_girth.end());
    gmin = *lo;
    gmax = *hi;
  }
  if (!field.samples.empty()) {
    smin = smax = field.samples.front().girth;
    for (const GirthSample& s : field.samples) {
      smin = std::min(smin, s.girth);
      smax = std::max(smax, s.girth);
    }
  }
  if (args.flag("--json")) {
    JsonWriter j;
    j.begin_object();
    j.field("job", job.name);
    j.field("vertices", annulus.num_vertices());
    j.field("faces", annulus.num_faces());
    j.field("placement", job.girth.placement);
    j.field("samples", field.samples.size());
    j.field("unconverged_samples", field.unconverged_samples);
    j.field("min_girth", gmin);
    j.field("max_girth", gmax);
    j.field("min_sample_girth", smin);
    j.field("max_sample_girth", smax);
    j.field("lipschitz_bound", field.lipschitz_bound);
    j.field("time_ms", field.time_ms);
    j.key("sample_points").begin_array();
    for (const GirthSample& s : field.samples) {
      j.begin_object();
      j.field("vertex", s.vertex);
      j.field_array("position", {s.position.x(), s.position.y(), s.position.z()});
      j.field("girth", s.girth);
      j.end_object();
    }
    j.end_array();
    if (!out.empty()) j.field("csv", out);
    j.end_object();
    std::cout << j.str() << "\n";
    return 0;
  }
  std::ostringstream s;
  s << "girth field: " << m.description << "\n";
  s << "  winding surface: " << annulus.num_vertices() << " vertices, " << annulus.num_faces()
    << " faces\n";
  s << "  samples: " << field.samples.size() << " (" << job.girth.placement << ")";
  if (field.unconverged_samples > 0) s << ", " << field.unconverged_samples << " not converged";
  s << "\n";
  s << "  girth: min " << gmin << " mm, max " << gmax << " mm (samples " << smin << " .. " << smax
    << " mm)\n";
  s << "  sampling error bound: " << field.lipschitz_bound
    << " mm (2 x the largest distance to the nearest sample)\n";
  s << "  time: " << field.time_ms << " ms (mandrel " << m.total_ms << " ms)\n";
  if (!out.empty()) s << "  wrote " << out << "\n";
  std::cout << s.str();
  return 0;
}

}  // namespace windplan::cli
