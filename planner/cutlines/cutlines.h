#pragma once
// Coplanar cut-lines (trim lines): the shortest planar curve on the mandrel near a start curve.
//
// After curing, the ends of a wound part are trimmed off and parts wound on one mandrel are
// separated; the saw follows a plane, so the trim line must be planar and short. This is the
// coplanar geodesic of Liu, Chen, Xin, He, Liu, Zhao, "An Optimization-Driven Approach for
// Computing Geodesic Paths on Triangle Meshes", section 5.3.2 (eq. 7/8): minimise the length
// subject to every point lying in one plane (n, d), the plane being a variable too
// (geometry/geodesic/path_constraint.h PlaneConstraint, refined by geometry/geodesic/geodesic.h
// refine_path).
//
// Closed cut-lines (loops around the mandrel):
//  - the start is the planar section of the mesh by an initial plane (`plane:` normal + offset,
//    or `station:` an axial position with the spindle axis as normal): plane_section() marches
//    over the faces (edge crossings where the signed distance changes sign, chained into loops)
//    and keeps the loop that winds around the axis (the longest if several do); that section is
//    the initial path (an exact face strip, so the initial residual is zero);
//  - or a closed curve given as points in a CSV file (`init:`), snapped to the surface and
//    chained with edge paths (path_from_curve); the initial plane is the least-squares plane of
//    the points.
//  Then refine_path with the plane constraint: on a cylinder an oblique start converges to the
//  perpendicular circle, in the bend of a bent tube to the circular cross-section there.
// Open cut-lines between two surface points `from` and `to` (the paper's figure 9): the start is
// the geodesic between them; the initial plane contains both points (normal perpendicular to
// to - from: the given plane's normal projected, or the best fit to the geodesic); the
// constraint's residuals at the endpoints keep the plane through them, its rotation about the
// line through them is free.
// Normal modes: "free" (n and d free), "fixed" (the normal is kept, the plane only translates),
// "cone" (free within max_tilt_deg of the initial normal).
//
// Units: mm and degrees. Frames: the mesh frame.
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/geodesic/geodesic.h"
#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"
#include "geometry/region/plane_section.h"
#include "planner/plan/plan.h"

namespace windplan {

/// One entry of the job's `cutlines:` list (docs/config.md).
struct CutLineOptions {
  std::string name;  ///< label in reports and cutlines.csv
  // Exactly one start for closed cut-lines: a plane, an axial station or a CSV curve.
  bool has_plane = false;
  Vec3 normal = Vec3::UnitZ();  ///< plane normal (any length > 0; normalised when used)
  double offset = 0.0;          ///< mm: the plane is {p : n . p = offset} with n normalised
  bool has_station = false;
  double station = 0.0;        ///< mm, axial position along the spindle axis (normal = axis)
  std::filesystem::path init;  ///< CSV of x,y,z points (mm) of a closed curve near the surface
  bool closed = true;          ///< loop around the mandrel (true) or open curve from -> to
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();  ///< open curves: the two surface points (mm)
  /// free | fixed (only translate) | cone; "" (default): fixed for a station, free otherwise.
  std::string normal_mode;
  /// Closed cut-lines from a plane or station: the plane keeps its start offset, turning only
  /// about the centre of its start loop (with normal_mode fixed: the start plane's own section).
  /// false: the offset is free too (the plane may slide along the mandrel).
  bool keep_offset = true;
  double max_tilt_deg = 90.0;  ///< deg, for "cone": max angle between final and initial normal
  bool is_valid(std::string* why) const;
};

/// Diagnostics of one cut-line.
struct CutLineSummary {
  std::string start;            ///< "plane", "station", "init", "geodesic" (open curves)
  double initial_length = 0.0;  ///< mm, the start curve (the planar section for plane/station)
  Vec3 initial_normal = Vec3::UnitZ();
  double initial_offset = 0.0;         ///< mm
  double tilt_deg = 0.0;               ///< angle between the final and the initial normal
  double max_surface_distance = 0.0;   ///< mm, largest distance of a result point from the mesh
  GeodesicSummary geodesic;            ///< the refinement (termination, iterations, residual, time)
  double refine_length = 0.0;          ///< mm, the loop refine_path gave
  double refine_residual = 0.0;        ///< mm, its max distance from its plane
  Vec3 refine_normal = Vec3::UnitZ();  ///< its plane's normal
  /// Where the result comes from: "refine_path" or "section polish" (closed loops: the exact
  /// section of the plane that minimises the section length, started at refine_path's plane).
  std::string method;
  int polish_evaluations = 0;         ///< plane sections evaluated by the polish
  double polish_ms = 0.0;             ///< wall time of the polish
  double time_ms = 0.0;               ///< wall time of the whole cut-line
  std::vector<std::string> warnings;  ///< e.g. residual above 1e-6 of the length
  std::string brief_report() const;
};

/// Reads a curve from a CSV file: one point per line as x,y,z (mm); blank lines, lines starting
/// with '#' and a non-numeric header line are skipped. \throw IoError naming the file (and line).
std::vector<Vec3> read_curve_csv(const std::filesystem::path& file);

/// Computes one cut-line on `mesh` (the winding surface for loops around the mandrel).
/// \param axis the spindle axis (station planes, choice of the section loop)
/// \param geodesic options of refine_path (the constraint tolerance is tightened to 1e-9 at most)
/// \throw InputError/ConfigError naming the cut-line for invalid options, a plane that misses
///        the mesh, an init curve that is not closed, points too far from the surface.
CutLine compute_cutline(const Mesh& mesh, const CutLineOptions& cut, const SpindleAxis& axis,
                        const GeodesicOptions& geodesic = {}, CutLineSummary* summary = nullptr);

/// All cut-lines of a job on the mandrel's winding surface (Mandrel::winding.mesh), in order.
/// \param summaries optional, filled with one summary per cut-line
std::vector<CutLine> compute_cutlines(const Mesh& winding_surface, const SpindleAxis& axis,
                                      const std::vector<CutLineOptions>& cuts,
                                      const GeodesicOptions& geodesic = {},
                                      std::vector<CutLineSummary>* summaries = nullptr);

}  // namespace windplan
