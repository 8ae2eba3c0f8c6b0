// windplan mesh: load a mesh (or a job's mandrel), check it, optionally repair and write it, and
// print its health report.
#include <algorithm>
#include <iostream>

#include "cli/args.h"
#include "cli/commands.h"
#include "geometry/base/errors.h"
#include "geometry/base/json.h"
#include "geometry/mesh/mesh_io.h"
#include "geometry/mesh/mesh_validation.h"
#include "planner/job/job.h"
#include "planner/mandrel/mandrel_mesh.h"

namespace windplan::cli {

const char* const kMeshHelp =
    "usage: windplan mesh <mesh-file | job.yaml> [--repair] [--split-nonmanifold]\n"
    "                     [-o out.ply|out.obj] [--json]\n"
    "\n"
    "Loads a triangle mesh (OBJ, PLY, STL, OFF; or the mandrel of a job file .yaml/.yml, scaled\n"
    "to mm by its 'units:'), checks it and prints its health report: vertices, faces, components,\n"
    "boundary loops, genus, closed / manifold / oriented, bounding box, edge lengths, degenerate\n"
    "triangles and the problems found. A mesh with problems still gets its report (exit 0).\n"
    "\n"
    "options:\n"
    "  --repair             repair what is safe: merge duplicate vertices, drop degenerate,\n"
    "                       duplicate and unreferenced elements, flip zero-area caps away,\n"
    "                       orient consistently, normals outward; each change is listed.\n"
    "                       A job's 'mandrel: repair: true' (the default) has the same effect.\n"
    "  --split-nonmanifold  with --repair: split non-manifold vertices into one per fan\n"
    "                       (otherwise they are refused)\n"
    "  -o, --output FILE    write the (repaired) mesh as .ply (binary) or .obj; fails with exit 1\n"
    "                       naming the elements if it is not a valid oriented 2-manifold\n"
    "  --json               print the report as one JSON object\n"
    "  -h, --help           this text\n";

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

void health_fields(JsonWriter& j, const MeshHealth& h) {
  j.field("vertices", h.num_vertices);
  j.field("faces", h.num_faces);
  j.field("edges", h.num_edges);
  j.field("referenced_vertices", h.num_referenced_vertices);
  j.field("unreferenced_vertices", h.num_unreferenced_vertices);
  j.field("components", h.num_components);
  j.field("boundary_loops", h.num_boundary_loops);
  j.field("boundary_edges", h.num_boundary_edges);
  j.field("euler_characteristic", h.euler_characteristic);
  j.key("genus");
  if (h.genus >= 0)
    j.value(h.genus);
  else
    j.null();
  j.field("closed", h.closed);
  j.field("manifold", h.manifold);
  j.field("oriented", h.oriented);
  j.field("valid_mesh", h.is_valid_mesh());
  j.key("bbox").begin_object();
  j.field_array("min", {h.bbox.min.x(), h.bbox.min.y(), h.bbox.min.z()});
  j.field_array("max", {h.bbox.max.x(), h.bbox.max.y(), h.bbox.max.z()});
  j.end_object();
  j.key("edge_length").begin_object();
  j.field("min", h.min_edge_length);
  j.field("mean", h.mean_edge_length);
  j.field("max", h.max_edge_length);
  j.end_object();
  j.field("degenerate_triangles", h.num_degenerate_triangles);
  j.field("zero_area_triangles", h.num_zero_area_triangles);
  j.field("duplicate_triangles", h.num_duplicate_triangles);
  j.field("duplicate_vertices", h.num_duplicate_vertices);
  j.field("nonmanifold_edges", h.num_nonmanifold_edges);
  j.field("nonmanifold_vertices", h.num_nonmanifold_vertices);
  j.field("inconsistent_edges", h.num_inconsistent_edges);
  j.key("problems").begin_array();
  for (const std::string& p : h.problems()) j.value(p);
  j.end_array();
}

void string_array(JsonWriter& j, const std::string& key, const std::vector<std::string>& v) {
  j.key(key).begin_array();
  for (const std::string& s : v) j.value(s);
  j.end_array();
}

}  // namespace

int run_mesh(const std::vector<std::string>& argv) {
  const Args args(argv, {"--repair", "--json", "--split-nonmanifold"}, {"-o", "--output"});
  args.expect_positional(1, "one mesh file or job file");
  const std::filesystem::path input = args.positional()[0];
  const std::string out = args.has("-o") ? args.value("-o") : args.value("--output");
  if (args.has("-o") && args.has("--output")) throw UsageError("give -o or --output, not both");
  if (!out.empty()) {
    const std::string ext = lower(std::filesystem::path(out).extension().string());
    const auto& w = writable_mesh_extensions();
    if (std::find(w.begin(), w.end(), ext) == w.end()) {
      throw UsageError("-o " + out + ": the output must end in .ply or .obj");
    }
  }

  MandrelOptions mandrel;
  bool repair = args.flag("--repair");
  const std::string ext = lower(input.extension().string());
  if (ext == ".yaml" || ext == ".yml") {
    const Job job = load_job(input);
    mandrel = job.mandrel;
    repair = repair || job.mandrel.repair;
    if (mandrel.source != "mesh") {
      throw InputError(input.string() + ": the mandrel's source is '" + mandrel.source +
                       "'; windplan mesh reads mesh files only (see windplan mandrel)");
    }
  } else {
    mandrel.file = input;
  }
  const TriangleSoup soup = load_mandrel_soup(mandrel);

  RepairOptions options;
  options.split_nonmanifold_vertices = args.flag("--split-nonmanifold");
  const MeshHealth input_health = check_mesh(soup, options.check);
  MeshHealth health = input_health;
  RepairResult repaired;
  std::string refused;
  bool have_repair = false;
  if (repair) {
    try {
      repaired = repair_mesh(soup, options);
      health = repaired.after;
      have_repair = true;
    } catch (const TopologyError& e) {
      refused = e.what();
    }
  }

  if (!out.empty()) {
    if (!health.is_valid_mesh() || !refused.empty()) {
      std::string why = refused;
      if (why.empty()) {
        for (const std::string& p : health.blocking_problems())
          why += (why.empty() ? "" : "; ") + p;
      }
      throw TopologyError(mandrel.file.string() + ": cannot write " + out +
                          ": the mesh is not a valid oriented 2-manifold: " + why +
                          (repair ? "" : " (try --repair)"));
    }
    const Mesh mesh(have_repair ? repaired.soup : soup);
    write_mesh(out, mesh);
  }

  if (args.flag("--json")) {
    JsonWriter j;
    j.begin_object();
    j.field("file", mandrel.file.string());
    if (ext == ".yaml" || ext == ".yml") j.field("job", input.string());
    j.field("units", std::string("mm"));
    health_fields(j, health);
    j.key("repair").begin_object();
    j.field("requested", repair);
    string_array(j, "changes", have_repair ? repaired.changes : std::vector<std::string>{});
    string_array(j, "kept", have_repair ? repaired.kept : std::vector<std::string>{});
    j.key("refused");
    if (refused.empty())
      j.null();
    else
      j.value(refused);
    j.end_object();
    if (repair) {
      j.key("input").begin_object();
      health_fields(j, input_health);
      j.end_object();
    }
    if (!out.empty()) j.field("written", out);
    j.end_object();
    std::cout << j.str() << "\n";
    return 0;
  }

  std::cout << "mesh: " << mandrel.file.string() << " (units: mm)\n" << health.brief_report();
  const auto problems = health.problems();
  std::cout << "problems:" << (problems.empty() ? " none\n" : "\n");
  for (const std::string& p : problems) std::cout << "  - " << p << "\n";
  if (repair) {
    const auto& changes = repaired.changes;
    std::cout << "repaired:" << (have_repair && changes.empty() ? " nothing to repair\n" : "\n");
    for (const std::string& c : changes) std::cout << "  - " << c << "\n";
    for (const std::string& c : repaired.kept) std::cout << "  - " << c << "\n";
    if (!refused.empty()) std::cout << "  - refused: " << refused << "\n";
  }
  if (!out.empty()) std::cout << "written: " << out << "\n";
  return 0;
}

}  // namespace windplan::cli
