#pragma once
// The mandrel of a job, ready for planning: the full welded mesh, the wound region (an annulus)
// with its two boundary loops, the spindle axis and the radius profile.
//
// build_mandrel dispatches on mandrel.source:
//   "mesh"                            -> load_mandrel_mesh (planner/mandrel/mandrel_mesh.h),
//   "cad"                             -> import_cad + tessellate (geometry/cad/cad_import.h),
//   "pipe", "cone", "vessel", "bent_tube" -> the parametric solid + tessellate,
// then finds the axis, optionally remeshes (mandrel.remesh, geometry/mesh/remesh.h: B-rep face and
// wound-region borders are protected) and cuts out the winding surface.
//
// The wound region: with mandrel.region, the full mesh is cut exactly on the region's two station
// planes and the chosen surface around the axis between them is wound
// (geometry/region/mandrel_region.h); otherwise, for B-rep sources every face that is not planar,
// and the planar faces along the axis (normal perpendicular to it within 1 degree: a
// rounded-rectangle boom's flat sides); other planar faces are end caps (pipe/cone/tube ends, the
// vessel's polar-opening disks, a CAD model's flat ends) and are left out; for a mesh file, the
// whole mesh when it is open, otherwise every triangle whose normal is not parallel to the axis
// (within 1 degree): flat end caps are dropped. The axis is the job's `mandrel.axis`, or the known
// axis of pipe/cone/vessel/section (+Z through the origin), or inferred
// (geometry/region/winding_surface.h) for CAD, mesh and bent-tube mandrels.
//
// When the wound region is not an annulus, the TopologyError lists the candidate regions (each
// connected part: axial extent, radius range, loops) and suggests the mandrel.region keys of a
// range whose outer surface is one.
#include <array>
#include <string>
#include <vector>

#include "geometry/cad/cad_shape.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/mesh_validation.h"
#include "geometry/region/axis.h"
#include "geometry/region/winding_surface.h"
#include "planner/job/job.h"

namespace windplan {

struct Mandrel {
  /// The whole mandrel (mm), shafts, flanges, tabs and bores included, cut on the region's
  /// planes when mandrel.region is set; closed for a solid. This is what the machine must clear:
  /// export/ keeps the payout eye's clearance from it (and from `profile`), not from the
  /// winding surface. winding.face_map and winding.vertex_map index it.
  Mesh mesh;
  MeshHealth health;        ///< check_mesh of the full mesh's soup
  WindingSurface winding;   ///< the annulus, its face/vertex maps to `mesh`, its two loops
  SpindleAxis axis;         ///< the spindle axis
  std::string axis_source;  ///< "job", "parametric", "revolution axis" or "principal axis ..."
  bool revolution = false;  ///< the mandrel is a surface of revolution about `axis`
  RadiusProfile profile;    ///< largest radius of the whole `mesh` along the axis (clearance)
  /// The connected parts of the wound-face selection (of the faces between the region's planes
  /// when mandrel.region is set), largest first, and the one wound (-1 when none is an annulus).
  /// Their face_list indexes `mesh` before remeshing (mandrel.remesh renumbers faces).
  std::vector<CandidateRegion> candidates;
  int chosen_candidate = -1;
  RegionSuggestion suggestion;    ///< a clean outer-wall range, when the selection is not one
  int region_split_edges = 0;     ///< plane cut: edges split on the region planes
  int region_moved_vertices = 0;  ///< plane cut: vertices moved onto a plane (no slivers)
  double region_max_move = 0.0;   ///< mm
  /// mandrel.region.centre_line: the whole tube's centre-line length (mm), the two stations
  /// (mm along it) and the centre-line points there (the centres of the region's end sections).
  double centre_line_length = 0.0;
  std::array<double, 2> region_stations{0.0, 0.0};
  std::array<Vec3, 2> region_end_centres{Vec3::Zero(), Vec3::Zero()};
  CadShape shape;              ///< the B-rep (cad and parametric sources), empty for meshes
  int brep_faces = 0;          ///< B-rep faces (0 for meshes)
  std::string description;     ///< one line: source, shape and dimensions
  double tessellation_ms = 0;  ///< B-rep meshing and welding (0 for meshes)
  double remesh_ms = 0;        ///< isotropic remeshing (0 when off)
  double region_ms = 0;        ///< mandrel.region: plane cut and candidates (0 when not set)
  double total_ms = 0;         ///< the whole build
  std::vector<std::string> warnings;

  /// The start loop (lower axial position) and end loop, as winding-surface vertex indices.
  const std::vector<int>& start_loop() const { return winding.loops[0].vertices; }
  const std::vector<int>& end_loop() const { return winding.loops[1].vertices; }
};

/// Builds the mandrel of a `mandrel:` section (paths already resolved).
/// \param require_annulus when false, a wound region that is not an annulus leaves `winding`
///        empty and `chosen_candidate` -1 instead of throwing (for `windplan mandrel`'s table)
/// \throw IoError/InputError naming the file for unreadable mesh or CAD files, ConfigError for
///        invalid options and mandrel.region problems, TopologyError when the wound region is
///        not an annulus (with the candidate regions and suggested keys).
Mandrel build_mandrel(const MandrelOptions& mandrel, bool require_annulus = true);

/// Same for a loaded job.
inline Mandrel build_mandrel(const Job& job) { return build_mandrel(job.mandrel); }

/// The CAD shape of a parametric or CAD `mandrel:` section without meshing it (for STEP export).
/// \throw ConfigError for a mesh source.
CadShape mandrel_shape(const MandrelOptions& mandrel, std::vector<std::string>* warnings = nullptr);

}  // namespace windplan
