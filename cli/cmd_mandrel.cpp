// windplan mandrel <job.yaml> [-o mesh.ply] [--winding annulus.ply] [--step out.step] [--json]
// Builds the job's mandrel (mesh file, CAD file or parametric shape), reports its health, its
// winding surface and axis, and optionally writes the meshes and the B-rep.
#include <iostream>
#include <sstream>

#include "cli/args.h"
#include "cli/commands.h"
#include "geometry/base/errors.h"
#include "geometry/base/json.h"
#include "geometry/cad/cad_export.h"
#include "geometry/mesh/mesh_io.h"
#include "planner/job/job.h"
#include "planner/mandrel/mandrel_builder.h"

namespace windplan::cli {

const char* const kMandrelHelp =
    "usage: windplan mandrel <job.yaml> [-o mesh.ply] [--winding annulus.ply] [--step out.step]\n"
    "                        [--json]\n\n"
    "Builds the job's mandrel (mandrel.source: mesh, cad, pipe, cone, vessel, bent_tube),\n"
    "reports the welded mesh (vertices, faces, closed, manifold, oriented, area), the winding\n"
    "surface (its two boundary loops with their mean radii and axial stations), the candidate\n"
    "regions (each connected part of the wound selection: axial extent, radius range, loops,\n"
    "genus), the spindle axis and the tessellation time. Warnings go to stderr. When the wound\n"
    "region is not an annulus it prints the candidate table and the suggested mandrel.region\n"
    "keys, then fails (exit 1).\n\n"
    "  -o, --out FILE   write the full welded mesh (.ply or .obj)\n"
    "  --winding FILE   write the winding surface (the annulus) (.ply or .obj)\n"
    "  --step FILE      write the mandrel's B-rep (.step, .iges or .brep; cad/parametric only)\n"
    "  --json           print the report as JSON on stdout\n";

int run_mandrel(const std::vector<std::string>& argv) {
  const Args args(argv, {"--json"}, {"-o", "--out", "--winding", "--step"});
  args.expect_positional(1, "a job file");
  const Job job = load_job(args.positional()[0]);
  Mandrel m = build_mandrel(job.mandrel, /*require_annulus=*/false);
  // The full mesh is written even when it cannot be wound (to look at it, or to use it as a
  // mesh-file mandrel with a region).
  const std::string out = args.has("-o") ? args.value("-o") : args.value("--out");
  if (!out.empty()) write_mesh(out, m.mesh);
  const bool windable = m.winding.mesh.num_faces() > 0;
  if (!windable) {
    // Say what is there: the candidate regions and the suggested keys, then fail.
    std::cout << "mandrel: " << m.description << "\n  the wound region is not an annulus; "
              << "candidate regions (axis origin (" << m.axis.origin.transpose() << "), direction ("
              << m.axis.direction.transpose() << ")):\n"
              << region_table(m.candidates, "  ");
    if (m.suggestion.found) {
      std::cout << "  suggested (under mandrel:): " << m.suggestion.keys() << "\n";
    }
    const std::string msg = m.warnings.back();
    throw TopologyError(msg);
  }
  for (const std::string& w : m.warnings) std::cerr << "windplan mandrel: warning: " << w << "\n";

  if (args.has("--winding")) write_mesh(args.value("--winding"), m.winding.mesh);
  if (args.has("--step")) {
    if (m.shape.empty()) {
      throw InputError("--step: mandrel.source '" + job.mandrel.source +
                       "' has no B-rep (only cad and parametric sources)");
    }
    export_cad(m.shape, args.value("--step"));
  }

  const MeshHealth& h = m.health;
  const double rmax =
      m.profile.empty() ? 0.0 : *std::max_element(m.profile.radius.begin(), m.profile.radius.end());
  if (args.flag("--json")) {
    JsonWriter j;
    j.begin_object();
    j.field("job", job.name);
    j.field("source", job.mandrel.source);
    j.field("description", m.description);
    j.key("mesh").begin_object();
    j.field("vertices", m.mesh.num_vertices());
    j.field("faces", m.mesh.num_faces());
    j.field("closed", h.closed);
    j.field("manifold", h.manifold);
    j.field("oriented", h.oriented);
    j.field("components", h.num_components);
    j.field("genus", h.genus);
    j.field("area", m.mesh.total_area());
    const auto el = m.mesh.edge_length_stats();
    j.field("min_edge", el[0]).field("mean_edge", el[1]).field("max_edge", el[2]);
    j.field("brep_faces", m.brep_faces);
    j.end_object();
    j.key("winding_surface").begin_object();
    j.field("faces", m.winding.mesh.num_faces());
    j.field("area", m.winding.area);
    j.key("loops").begin_array();
    for (int i = 0; i < 2; ++i) {
      const WindingLoop& L = m.winding.loops[i];
      j.begin_object();
      j.field("role", i == 0 ? "start" : "end");
      j.field("vertices", L.vertices.size());
      j.field("length", L.length);
      j.field("mean_radius", L.mean_radius);
      j.field("axial", L.axial);
      j.end_object();
    }
    j.end_array();
    j.end_object();
    j.key("regions").begin_array();
    for (const CandidateRegion& c : m.candidates) {
      j.begin_object();
      j.field("index", c.index);
      j.field("faces", c.faces);
      j.field("axial_min", c.axial_min).field("axial_max", c.axial_max);
      j.field("radius_min", c.radius_min).field("radius_max", c.radius_max);
      j.field("loops", c.loops).field("loops_around", c.loops_around).field("genus", c.genus);
      j.field("area", c.area);
      j.field("wound", c.index - 1 == m.chosen_candidate);
      j.end_object();
    }
    j.end_array();
    if (job.mandrel.region.enabled) {
      j.key("region").begin_object();
      if (job.mandrel.region.centre_line) {
        j.key("centre_line").begin_object();
        j.field("length", m.centre_line_length);
        j.field("from", m.region_stations[0]).field("to", m.region_stations[1]);
        j.end_object();
      } else {
        j.field("start", job.mandrel.region.start).field("end", job.mandrel.region.end);
      }
      j.field("split_edges", m.region_split_edges);
      j.field("moved_vertices", m.region_moved_vertices);
      j.field("max_move", m.region_max_move);
      j.end_object();
    }
    j.key("axis").begin_object();
    j.field_array("origin", {m.axis.origin.x(), m.axis.origin.y(), m.axis.origin.z()});
    j.field_array("direction", {m.axis.direction.x(), m.axis.direction.y(), m.axis.direction.z()});
    j.field("source", m.axis_source);
    j.field("revolution", m.revolution);
    j.end_object();
    j.key("profile").begin_object();
    j.field("stations", m.profile.axial.size());
    j.field("axial_min", m.profile.empty() ? 0.0 : m.profile.axial.front());
    j.field("axial_max", m.profile.empty() ? 0.0 : m.profile.axial.back());
    j.field("max_radius", rmax);
    j.end_object();
    j.key("timings_ms").begin_object();
    j.field("tessellation", m.tessellation_ms);
    j.field("remesh", m.remesh_ms);
    j.field("region", m.region_ms);
    j.field("total", m.total_ms);
    j.end_object();
    j.key("warnings").begin_array();
    for (const std::string& w : m.warnings) j.value(w);
    j.end_array();
    j.end_object();
    std::cout << j.str() << "\n";
    return 0;
  }
  std::ostringstream s;
  s << "mandrel: " << m.description << "\n";
  s << "  mesh: " << m.mesh.num_vertices() << " vertices, " << m.mesh.num_faces() << " faces, "
    << (h.closed ? "closed" : "open") << ", " << (h.manifold ? "manifold" : "NON-MANIFOLD") << ", "
    << (h.oriented ? "oriented" : "NOT ORIENTED") << ", " << h.num_components
    << " component(s), genus " << h.genus << ", area " << m.mesh.total_area() << " mm^2\n";
  s << "  winding surface: " << m.winding.mesh.num_faces() << " faces, area " << m.winding.area
    << " mm^2\n";
  for (int i = 0; i < 2; ++i) {
    const WindingLoop& L = m.winding.loops[i];
    s << "    " << (i == 0 ? "start" : "end  ") << " loop: " << L.vertices.size()
      << " vertices, length " << L.length << " mm, mean radius " << L.mean_radius << " mm, axial "
      << L.axial << " mm\n";
  }
  if (job.mandrel.region.enabled) {
    if (job.mandrel.region.centre_line) {
      s << "  region: " << m.region_stations[0] << " .. " << m.region_stations[1]
        << " mm along the tube's centre line (" << m.centre_line_length
        << " mm long), cut exactly on the sections normal to it (";
    } else {
      s << "  region: axial " << job.mandrel.region.start << " .. " << job.mandrel.region.end
        << " mm, cut exactly on both planes (";
    }
    s << m.region_split_edges << " edges split, " << m.region_moved_vertices
      << " vertices moved onto a plane, at most " << m.region_max_move << " mm)\n";
  }
  s << "  candidate regions (#" << m.chosen_candidate + 1 << " is wound):\n"
    << region_table(m.candidates, "  ");
  s << "  axis: origin (" << m.axis.origin.transpose() << "), direction ("
    << m.axis.direction.transpose() << "), " << m.axis_source
    << (m.revolution ? ", surface of revolution" : "") << "\n";
  s << "  max radius " << rmax << " mm over " << m.profile.axial.size() << " stations\n";
  s << "  time: tessellation " << m.tessellation_ms << " ms";
  if (job.mandrel.remesh > 0.0) s << ", remesh " << m.remesh_ms << " ms";
  if (job.mandrel.region.enabled) s << ", region " << m.region_ms << " ms";
  s << ", total " << m.total_ms << " ms\n";
  std::cout << s.str();
  return 0;
}

}  // namespace windplan::cli
