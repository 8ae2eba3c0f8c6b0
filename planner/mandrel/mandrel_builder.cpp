#include "planner/mandrel/mandrel_builder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "geometry/base/errors.h"
#include "geometry/cad/cad_import.h"
#include "geometry/cad/parametric_mandrel.h"
#include "geometry/cad/section_mandrel.h"
#include "geometry/cad/tessellate.h"
#include "geometry/mesh/orient_outward.h"
#include "geometry/mesh/remesh.h"
#include "geometry/region/centre_line_region.h"
#include "geometry/region/planar_end_caps.h"
#include "geometry/region/spine.h"
#include "planner/job/job_limits.h"
#include "planner/mandrel/mandrel_mesh.h"
#include "planner/mandrel/tube_spine.h"

namespace windplan {

namespace {

using Clock = std::chrono::steady_clock;

// Relative change of the mandrel's area by remeshing above which a warning is given.
constexpr double kRemeshAreaTolerance = 0.01;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

std::string describe(const MandrelOptions& m, const std::string& selected) {
  std::ostringstream s;
  if (m.source == "mesh") {
    s << "mesh file " << m.file.filename().string();
  } else if (m.source == "cad") {
    s << "CAD file " << m.file.filename().string() << ", body '" << selected << "'";
  } else if (m.source == "pipe") {
    s << "pipe R=" << m.pipe.radius << " L=" << m.pipe.length << " mm";
  } else if (m.source == "cone") {
    s << "cone R=" << m.cone.radius_start << ".." << m.cone.radius_end << " L=" << m.cone.length
      << " mm";
  } else if (m.source == "vessel") {
    const VesselParams& v = m.vessel;
    auto dome = [&](const DomeParams& d) {
      std::ostringstream o;
      o << to_string(d.type);
      if (d.type == DomeType::Elliptical) o << " (aspect " << d.aspect << ")";
      o << " dome, opening r=" << dome_opening_radius(d, v.radius);
      return o.str();
    };
    s << "vessel R=" << v.radius << " L=" << v.length << " mm, start: " << dome(v.dome_start)
      << ", end: " << dome(v.dome_end);
  } else if (m.source == "section") {
    const SectionParams& p = m.section;
    if (p.shape == SectionShape::Ellipse) {
      s << "elliptical section " << 2 * p.semi_x << " x " << 2 * p.semi_y << " mm";
    } else {
      s << "rounded-rectangle section " << p.width << " x " << p.height
        << " mm, corners r=" << p.corner_radius;
    }
    s << ", L=" << p.length << " mm, ends: " << (p.end_start.dome ? "dome" : "flat") << "/"
      << (p.end_end.dome ? "dome" : "flat");
  } else if (m.source == "bent_tube") {
    s << "bent tube R=" << m.bent_tube.radius << " mm, " << m.bent_tube.segments.size()
      << " segment(s), " << m.bent_tube.bends.size() << " bend(s), centreline "
      << bent_tube_length(m.bent_tube) << " mm";
  }
  const MandrelFeatures& f = m.features;
  if (!f.empty()) {
    s << "; features:";
    if (f.bore > 0.0) s << " bore r=" << f.bore;
    if (f.shaft_start.radius > 0.0 || f.shaft_end.radius > 0.0) s << " shafts";
    if (!f.flanges.empty()) s << " " << f.flanges.size() << " flange(s)";
    if (!f.tabs.empty()) s << " " << f.tabs.size() << " tab row(s)";
  }
  return s.str();
}

std::string radius_text(double r) {
  std::ostringstream s;
  s << std::setprecision(4) << r;
  return s.str();
}

// The body's distance from the axis at angle theta (for placing tabs on the wall).
double body_outline(const MandrelOptions& m, double theta) {
  if (m.source == "pipe") return m.pipe.radius;
  if (m.source == "cone") return std::max(m.cone.radius_start, m.cone.radius_end);
  if (m.source == "vessel") return m.vessel.radius;
  if (m.source == "section") return section_radius(m.section, theta);
  return 0.0;
}

// mandrel.region.centre_line: the whole tube's wound faces (the selection without a region, or
// without its two planar end caps), its centre line, and the region between the sections normal
// to it at the two stations.
RegionSelection centre_line_region(const MandrelOptions& m, const std::vector<int>& patch,
                                   const std::vector<char>& patch_wound, Mandrel* out) {
  std::vector<char> whole(out->mesh.num_faces(), 0);
  for (int f = 0; f < out->mesh.num_faces(); ++f) whole[f] = patch_wound[patch[f]];
  WindingSurface tube;
  try {
    tube = extract_winding_surface(out->mesh, whole, out->axis);
  } catch (const TopologyError& e) {
    const PlanarEndCaps caps = planar_end_caps(out->mesh, whole);
    if (!caps.found) {
      throw ConfigError(std::string("mandrel.region.centre_line: the mandrel is not a tube with ") +
                        "two ends (" + e.what() + "; and " + caps.brief() +
                        "): give region.start/end along the axis instead");
    }
    tube = extract_winding_surface(out->mesh, caps.keep, out->axis);
  }
  const TubeSpine ts = tube_spine(tube, out->axis, m);
  if (ts.spine.empty()) {
    throw ConfigError("mandrel.region.centre_line: the tube's centre line was not found (" +
                      ts.why + "): give region.start/end along the axis instead");
  }
  const double L = ts.spine.length();
  CentreLineEnds ends;
  ends.from = m.region.from_fraction ? m.region.from * L : m.region.from;
  ends.to = m.region.to_fraction ? m.region.to * L : m.region.to;
  if (m.region.from_fraction) ends.from_key += "_fraction";
  if (m.region.to_fraction) ends.to_key += "_fraction";
  RegionSelection sel = select_centre_line_region(out->mesh, ts.spine, ends, out->axis,
                                                  m.region.component, m.region.cut);
  out->centre_line_length = L;
  out->region_stations = {ends.from, ends.to};
  out->region_end_centres = {ts.spine.point(ends.from), ts.spine.point(ends.to)};
  return sel;
}

}  // namespace

CadShape mandrel_shape(const MandrelOptions& m, std::vector<std::string>* warnings) {
  if (m.source == "pipe" || m.source == "cone" || m.source == "vessel" || m.source == "section") {
    const CadShape body = m.source == "pipe"     ? make_pipe(m.pipe)
                          : m.source == "cone"   ? make_cone(m.cone)
                          : m.source == "vessel" ? make_vessel(m.vessel)
                                                 : make_section_mandrel(m.section);
    return add_mandrel_features(body, m.features,
                                [&m](double theta) { return body_outline(m, theta); });
  }
  if (m.source == "bent_tube") return make_bent_tube(m.bent_tube);
  if (m.source == "cad") {
    CadImportOptions io;
    io.solid = m.solid;
    io.brep_unit_to_mm = to_millimetres(m.units);
    CadImport imp = import_cad(m.file, io);
    if (warnings) warnings->insert(warnings->end(), imp.warnings.begin(), imp.warnings.end());
    return imp.shape;
  }
  throw ConfigError("mandrel.source: " + m.source + " has no CAD shape (only cad and parametric)");
}

Mandrel build_mandrel(const MandrelOptions& m, bool require_annulus) {
  std::string why;
  if (!m.is_valid(&why)) throw ConfigError("mandrel: " + why);
  const auto t0 = Clock::now();
  Mandrel out;
  std::string selected;
  TriangleSoup soup;
  // Per face: a patch id (its B-rep face, or wound/not wound for meshes) that survives remeshing,
  // and per patch whether it is wound.
  std::vector<int> patch;
  std::vector<char> patch_wound;
  const bool parametric = m.source == "pipe" || m.source == "cone" || m.source == "vessel" ||
                          m.source == "bent_tube" || m.source == "section";
  std::vector<Vec3> plane_normal;  // per B-rep face: the plane's normal, zero when not planar

  if (m.source == "mesh") {
    std::vector<std::string> changes;
    out.mesh = load_mandrel_mesh(m, nullptr, &changes);
    check_mandrel_extent({out.mesh.bounding_box().diagonal_length(), 0.0, 0.0, 0.0},
                         "mandrel (" + m.file.string() + ")");
    for (const std::string& c : changes) out.warnings.push_back("repaired: " + c);
    // Consistently oriented but inward (an open tube exported with its normals flipped, or a
    // closed mesh read without repair): turned outward here, not found by a late replay error
    // (issue 28).
    OrientOutwardResult o = orient_outward(out.mesh);
    if (o.summary.flipped_faces > 0) {
      out.warnings.push_back(m.file.string() + ": the faces' normals pointed into the mandrel (" +
                             o.summary.brief_report() + "); re-oriented outward");
      out.mesh = std::move(o.mesh);
    }
  } else if (parametric || m.source == "cad") {
    if (m.source == "cad") {
      CadImportOptions io;
      io.solid = m.solid;
      io.brep_unit_to_mm = to_millimetres(m.units);
      CadImport imp = import_cad(m.file, io);
      out.warnings.insert(out.warnings.end(), imp.warnings.begin(), imp.warnings.end());
      out.shape = imp.shape;
      selected = imp.selected;
      // The model's size is known only now: refuse deflections it cannot be meshed with.
      MandrelSize size;
      size.area = cad_shape_info(out.shape).area;
      size.radius = std::sqrt(size.area / (4.0 * M_PI));  // of a sphere of that area
      size.size = 2.0 * size.radius;
      check_mandrel_extent(size, "mandrel (" + m.file.string() + ")");
      check_tessellation_size(size, m.tessellation);
    } else {
      out.shape = mandrel_shape(m);
    }
    Tessellation tess = tessellate(out.shape, m.tessellation);
    out.tessellation_ms = tess.time_ms;
    out.brep_faces = static_cast<int>(tess.faces.size());
    patch = tess.triangle_face;
    for (const CadFaceInfo& f : tess.faces) {
      patch_wound.push_back(f.kind != CadSurfaceKind::Plane);
      plane_normal.push_back(f.kind == CadSurfaceKind::Plane ? f.plane_normal : Vec3::Zero());
    }
    soup = std::move(tess.soup);
  } else {
    throw ConfigError("mandrel.source: unknown source '" + m.source + "'");
  }

  if (out.mesh.num_faces() == 0) {
    // B-rep sources: the welded soup must already be a valid oriented manifold.
    out.health = check_mesh(soup);
    if (!out.health.is_valid_mesh()) {
      std::string problems;
      for (const std::string& p : out.health.problems())
        problems += (problems.empty() ? "" : "; ") + p;
      throw TopologyError("mandrel (" + describe(m, selected) +
                          "): the tessellation is not a valid mesh: " + problems);
    }
    out.mesh = Mesh(soup);
  } else {
    out.health = check_mesh(TriangleSoup{out.mesh.points(), out.mesh.triangles()});
  }
  // A mesh of degenerate triangles only (collinear or repeated vertices) was reported by the
  // axis inference without the file (issue 28).
  if (!(out.mesh.total_area() > 0.0)) {
    throw InputError("mandrel (" + describe(m, selected) + "): the mesh has zero area (" +
                     std::to_string(out.mesh.num_faces()) +
                     " triangles, all degenerate: collinear or repeated vertices)");
  }
  // Axis.
  if (m.has_axis) {
    out.axis = m.axis;
    out.axis.direction.normalize();
    out.axis_source = "job";
    out.revolution =
        radius_spread(out.mesh, out.axis) <= AxisInferenceOptions{}.revolution_tolerance;
  } else if (m.source == "pipe" || m.source == "cone" || m.source == "vessel" ||
             m.source == "section") {
    out.axis = SpindleAxis{};
    out.axis_source = "parametric";
    // The wound wall of pipe, cone and vessel is one of revolution (features are left out by
    // mandrel.region); an elliptical or rounded-rectangle section is not.
    out.revolution = m.source != "section" || (m.section.shape == SectionShape::Ellipse &&
                                               m.section.semi_x == m.section.semi_y);
  } else {
    const AxisInference inf = infer_spindle_axis(out.mesh);
    out.axis = inf.axis;
    out.axis_source = inf.method;
    out.revolution = inf.revolution;
    if (!inf.revolution) {
      std::ostringstream w;
      w << "the mandrel is not a surface of revolution (radius spread " << inf.radius_spread * 100
        << "% of its radius): using its principal axis; set mandrel.axis to choose";
      out.warnings.push_back(w.str());
    }
  }

  // Wound region. B-rep planar faces are end caps, except those along the axis (normal
  // perpendicular to it within 1 degree: the flat sides of a rounded-rectangle boom), wound.
  for (std::size_t i = 0; i < plane_normal.size(); ++i) {
    if (plane_normal[i].norm() > 0.5) {
      patch_wound[i] = std::abs(plane_normal[i].dot(out.axis.direction)) < std::sin(M_PI / 180.0);
    }
  }
  if (m.source == "mesh") {
    patch.assign(out.mesh.num_faces(), 1);
    patch_wound = {0, 1};
    if (out.mesh.is_closed()) {
      const double c = std::cos(M_PI / 180.0);
      for (int f = 0; f < out.mesh.num_faces(); ++f) {
        patch[f] = std::abs(out.mesh.face_normal(f).dot(out.axis.direction)) < c ? 1 : 0;
      }
    }
  }
  // The region: cut on its planes; per face a patch id that also records "wound".
  std::vector<char> keep;
  if (m.region.enabled) {
    const auto t_region = Clock::now();
    RegionSelection sel = m.region.centre_line ? centre_line_region(m, patch, patch_wound, &out)
                                               : select_region(out.mesh, out.axis, m.region);
    std::vector<int> cut_patch(sel.mesh.num_faces());
    for (int f = 0; f < sel.mesh.num_faces(); ++f) {
      cut_patch[f] = 2 * patch[sel.face_parent[f]] + (sel.keep[f] ? 1 : 0);
    }
    patch = std::move(cut_patch);
    patch_wound.assign(2 * patch_wound.size(), 0);
    for (std::size_t i = 1; i < patch_wound.size(); i += 2) patch_wound[i] = 1;
    out.mesh = std::move(sel.mesh);
    out.health = check_mesh(TriangleSoup{out.mesh.points(), out.mesh.triangles()});
    out.region_split_edges = sel.split_edges;
    out.region_moved_vertices = sel.moved_vertices;
    out.region_max_move = sel.max_move;
    out.candidates = std::move(sel.candidates);
    out.chosen_candidate = sel.chosen;
    out.region_ms = ms_since(t_region);
  }
  if (m.remesh > 0.0) {
    MandrelSize size;
    size.size = out.mesh.bounding_box().diagonal_length();
    size.area = out.mesh.total_area();
    check_remesh_size(size, m.remesh);
    RemeshOptions ro;
    ro.target_edge_length = m.remesh;
    RemeshResult r = remesh_isotropic(out.mesh, patch, ro);
    out.mesh = std::move(r.mesh);
    patch = std::move(r.face_patch);
    out.remesh_ms = r.time_ms;
    out.health = check_mesh(TriangleSoup{out.mesh.points(), out.mesh.triangles()});
    // A remeshing length too coarse for the curvature cuts the surface short (remesh: 1e6 once
    // kept 6 % of the area): say by how much.
    const double change = out.mesh.total_area() / size.area - 1.0;
    if (std::fabs(change) > kRemeshAreaTolerance) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "remesh = %g mm changed the mandrel's area by %+.1f %% (%.4g -> %.4g mm^2; "
                    "more than %.0f %%): use a smaller mandrel.remesh",
                    m.remesh, 100.0 * change, size.area, out.mesh.total_area(),
                    100.0 * kRemeshAreaTolerance);
      out.warnings.push_back(buf);
    }
  }
  keep.assign(out.mesh.num_faces(), 0);
  for (int f = 0; f < out.mesh.num_faces(); ++f) keep[f] = patch_wound[patch[f]];
  if (std::find(keep.begin(), keep.end(), 1) == keep.end()) {
    throw TopologyError("mandrel (" + describe(m, selected) + "): no wound region: " +
                        (m.source == "mesh"
                             ? std::string("every triangle is normal to the axis")
                             : "all " + std::to_string(out.brep_faces) +
                                   " B-rep faces are planar (planar faces are taken as end caps)") +
                        "; the winding surface must be an annulus");
  }
  if (!m.region.enabled) out.candidates = candidate_regions(out.mesh, keep, out.axis);
  out.description = describe(m, selected);
  try {
    try {
      out.winding = extract_winding_surface(out.mesh, keep, out.axis);
    } catch (const TopologyError&) {
      // A closed tube whose flat end caps are not normal to the axis (a bent pipe's legs).
      if (m.region.enabled || m.source != "mesh" || m.remesh > 0.0) throw;
      PlanarEndCaps caps = planar_end_caps(out.mesh, keep);
      if (!caps.found) throw;
      out.winding = extract_winding_surface(out.mesh, caps.keep, out.axis);
      out.candidates = candidate_regions(out.mesh, caps.keep, out.axis);
      out.warnings.push_back(
          "the mesh's faces normal to the axis are no end caps of a tube: "
          "wound without its " +
          caps.brief());
    }
    if (!m.region.enabled) out.chosen_candidate = 0;  // the selection is one annulus
    if (m.region.centre_line) {
      // Loop 0 is the end at centre_line.from.
      std::array<Vec3, 2> c;
      for (int e = 0; e < 2; ++e) {
        std::vector<Vec3> pts;
        for (int v : out.winding.loops[e].vertices) pts.push_back(out.winding.mesh.position(v));
        c[e] = loop_centroid(pts);
      }
      if ((c[0] - out.region_end_centres[0]).norm() > (c[1] - out.region_end_centres[0]).norm()) {
        std::swap(out.winding.loops[0], out.winding.loops[1]);
      }
    }
  } catch (const TopologyError& e) {
    out.suggestion = suggest_region(out.mesh, out.axis);
    std::string list;
    for (const CandidateRegion& c : out.candidates) list += (list.empty() ? "" : "; ") + c.brief();
    const std::string msg =
        "mandrel (" + out.description + "): " + e.what() + ". Candidate regions: " + list +
        (out.suggestion.found
             ? ". Set mandrel." + out.suggestion.keys() + " to wind the outer wall (mean radius " +
                   radius_text(out.suggestion.radius) + " mm)"
             : ". No axial range with a clean outer wall was found: set mandrel.region "
               "{start, end} (mm along the axis) and mandrel.axis by hand");
    if (require_annulus) throw TopologyError(msg);
    out.warnings.push_back(msg);
  }
  out.profile = compute_radius_profile(out.mesh, out.axis);
  out.description = describe(m, selected);
  out.total_ms = ms_since(t0);
  return out;
}

}  // namespace windplan
