// windplan cutline <job.yaml | mesh-file> [--name N] [--plane nx,ny,nz,d | --station z]
//                  [--normal-mode free|fixed|cone] [--max-tilt deg] [--json] [-o cut.csv]
// Computes coplanar cut-lines (planner/cutlines/cutlines.h): a job's `cutlines:` list, or one
// cut-line given by the flags, on the job's winding surface or on a mesh file.
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "cli/args.h"
#include "cli/commands.h"
#include "export/files/cutlines_csv.h"
#include "geometry/base/errors.h"
#include "geometry/base/json.h"
#include "geometry/mesh/mesh_io.h"
#include "geometry/mesh/mesh_validation.h"
#include "geometry/region/winding_surface.h"
#include "planner/cutlines/cutlines.h"
#include "planner/job/job.h"
#include "planner/mandrel/mandrel_builder.h"

namespace windplan::cli {

const char* const kCutlineHelp =
    "usage: windplan cutline <job.yaml | mesh-file> [--name N] [--plane nx,ny,nz,d | --station z]\n"
    "                        [--normal-mode free|fixed|cone] [--max-tilt deg] [--free-offset]\n"
    "                        [--json] [-o cut.csv]\n\n"
    "Computes coplanar cut-lines (trim lines): the shortest planar loop around the mandrel near a\n"
    "start plane (the paper's coplanar geodesic, eq. 7/8). With a job file: its cutlines: list\n"
    "(--name picks one) on the winding surface, or one cut-line from the flags. With a mesh file\n"
    "(.obj, .ply, .stl, .off, mm): one cut-line from the flags on the whole mesh, the axis\n"
    "inferred. Prints the length, the final plane (n . p = d), the plane residual and the\n"
    "refinement's termination; warnings go to stderr.\n\n"
    "  --name N           the job's cut-line named N (or the name of the flags' cut-line)\n"
    "  --plane nx,ny,nz,d start plane: normal and offset (mm, along the unit normal)\n"
    "  --station z        start plane normal to the spindle axis at axial position z (mm, from\n"
    "                     the axis origin: mandrel.axis, the parametric origin, or the area\n"
    "                     centroid when the axis is inferred)\n"
    "  --normal-mode M    free (default for --plane), fixed (default for --station: the\n"
    "                     station's own plane), cone\n"
    "  --free-offset      let the plane slide along the mandrel too (by default it keeps its\n"
    "                     start offset and only turns about the point where it meets the axis)\n"
    "  --max-tilt DEG     for cone: largest angle from the start normal (default 90)\n"
    "  --json             print the result as JSON on stdout\n"
    "  -o, --out FILE     write the points as CSV (name, index, x, y, z)\n";

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::vector<double> parse_numbers(const std::string& option, const std::string& text,
                                  std::size_t count) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string cell;
  while (std::getline(ss, cell, ',')) {
    const char* b = cell.c_str();
    char* e = nullptr;
    const double v = std::strtod(b, &e);
    if (e == b || *e != '\0' || !std::isfinite(v)) {
      throw UsageError(option + ": '" + text + "' is not " + std::to_string(count) +
                       " comma-separated numbers");
    }
    out.push_back(v);
  }
  if (out.size() != count) {
    throw UsageError(option + ": '" + text + "' is not " + std::to_string(count) +
                     " comma-separated numbers");
  }
  return out;
}

}  // namespace

int run_cutline(const std::vector<std::string>& argv) {
  const Args args(argv, {"--json", "--free-offset"},
                  {"-o", "--out", "--name", "--plane", "--station", "--normal-mode", "--max-tilt"});
  args.expect_positional(1, "a job file or a mesh file");
  const std::filesystem::path input = args.positional()[0];
  const bool is_job =
      lower(input.extension().string()) == ".yaml" || lower(input.extension().string()) == ".yml";
  if (args.has("--plane") && args.has("--station")) {
    throw UsageError("give --plane or --station, not both");
  }
  const bool from_flags = args.has("--plane") || args.has("--station");
  if (!from_flags &&
      (args.has("--normal-mode") || args.has("--max-tilt") || args.flag("--free-offset"))) {
    throw UsageError("--normal-mode, --max-tilt and --free-offset go with --plane or --station");
  }

  std::vector<CutLineOptions> cuts;
  if (from_flags) {
    CutLineOptions c;
    c.name = args.has("--name") ? args.value("--name") : std::string("cut");
    if (args.has("--plane")) {
      const std::vector<double> v = parse_numbers("--plane", args.value("--plane"), 4);
      c.has_plane = true;
      c.normal = Vec3(v[0], v[1], v[2]);
      c.offset = v[3];
    } else {
      c.has_station = true;
      c.station = args.number("--station", 0.0);
    }
    c.normal_mode = args.value("--normal-mode", c.normal_mode);
    c.max_tilt_deg = args.number("--max-tilt", c.max_tilt_deg);
    c.keep_offset = !args.flag("--free-offset");
    if (std::string why; !c.is_valid(&why)) throw UsageError("cut-line from the flags: " + why);
    cuts.push_back(c);
  }

  Mesh mesh;
  SpindleAxis axis;
  std::string job_name;
  std::vector<std::string> warnings;
  if (is_job) {
    const Job job = load_job(input);
    job_name = job.name;
    if (!from_flags) {
      for (const CutLineOptions& c : job.cutlines) {
        if (!args.has("--name") || c.name == args.value("--name")) cuts.push_back(c);
      }
      if (job.cutlines.empty()) {
        throw InputError(input.string() +
                         ": the job has no cutlines: section (or give --plane "
                         "or --station)");
      }
      if (cuts.empty()) {
        std::string names;
        for (const CutLineOptions& c : job.cutlines) names += (names.empty() ? "" : ", ") + c.name;
        throw InputError(input.string() + ": no cut-line named '" + args.value("--name") +
                         "' (the job has: " + names + ")");
      }
    }
    Mandrel m = build_mandrel(job);
    warnings = m.warnings;
    mesh = std::move(m.winding.mesh);
    axis = m.axis;
  } else {
    if (!from_flags) throw UsageError("a mesh file needs --plane or --station");
    job_name = input.stem().string();
    mesh = build_mesh(read_mesh(input), true);
    axis = infer_spindle_axis(mesh).axis;
  }
  for (const std::string& w : warnings) std::cerr << "windplan cutline: warning: " << w << "\n";

  std::vector<CutLine> lines;
  std::vector<CutLineSummary> sums;
  for (const CutLineOptions& c : cuts) {
    CutLineSummary s;
    lines.push_back(compute_cutline(mesh, c, axis, {}, &s));
    for (const std::string& w : s.warnings) std::cerr << "windplan cutline: warning: " << w << "\n";
    sums.push_back(std::move(s));
  }
  const std::string out = args.has("-o") ? args.value("-o") : args.value("--out");
  if (!out.empty()) write_cutlines_csv(out, lines);

  if (args.flag("--json")) {
    JsonWriter j;
    j.begin_object();
    j.field("job", job_name);
    j.key("cutlines").begin_array();
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const CutLine& c = lines[i];
      const CutLineSummary& s = sums[i];
      j.begin_object();
      j.field("name", c.name);
      j.field("closed", c.closed);
      j.field("points", c.points.size());
      j.field("length_mm", c.length);
      j.field_array("plane_normal", {c.plane_normal.x(), c.plane_normal.y(), c.plane_normal.z()});
      j.field("plane_offset_mm", c.plane_offset);
      j.field("residual_mm", c.residual);
      j.field("start", s.start);
      j.field("initial_length_mm", s.initial_length);
      j.field_array("initial_normal",
                    {s.initial_normal.x(), s.initial_normal.y(), s.initial_normal.z()});
      j.field("initial_offset_mm", s.initial_offset);
      j.field("tilt_deg", s.tilt_deg);
      j.field("method", s.method);
      j.field("polish_evaluations", s.polish_evaluations);
      j.field("polish_ms", s.polish_ms);
      j.field("time_ms", s.time_ms);
      j.key("refine_path").begin_object();
      j.field("termination", to_string(s.geodesic.termination));
      j.field("length_mm", s.refine_length);
      j.field("residual_mm", s.refine_residual);
      j.field("iterations", s.geodesic.iterations);
      j.field("reroutes", s.geodesic.reroutes);
      j.field("time_ms", s.geodesic.time_ms);
      j.end_object();
      j.key("warnings").begin_array();
      for (const std::string& w : s.warnings) j.value(w);
      j.end_array();
      j.end_object();
    }
    j.end_array();
    j.end_object();
    std::cout << j.str() << "\n";
    return 0;
  }
  std::ostringstream o;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const CutLine& c = lines[i];
    const CutLineSummary& s = sums[i];
    o << "cut-line " << c.name << ": " << (c.closed ? "closed loop" : "open curve") << ", "
      << c.points.size() << " points, length " << c.length << " mm (start " << s.start << ", "
      << s.initial_length << " mm)\n";
    o << "  plane: normal (" << c.plane_normal.x() << ", " << c.plane_normal.y() << ", "
      << c.plane_normal.z() << "), offset " << c.plane_offset << " mm, residual " << c.residual
      << " mm, tilt " << s.tilt_deg << " deg from the start\n";
    o << "  by " << s.method;
    if (s.polish_evaluations > 0) {
      o << " (" << s.polish_evaluations << " sections, " << s.polish_ms << " ms)";
    }
    o << "; refine_path: " << to_string(s.geodesic.termination) << ", length " << s.refine_length
      << " mm, residual " << s.refine_residual << " mm, " << s.geodesic.iterations
      << " iterations, " << s.geodesic.time_ms << " ms; total " << s.time_ms << " ms\n";
  }
  std::cout << o.str();
  return 0;
}

}  // namespace windplan::cli
