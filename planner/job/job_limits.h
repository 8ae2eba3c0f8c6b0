#pragma once
// Up-front bounds on a job: sizes a user can type but no machine can plan (meridians: 1e9,
// linear_deflection: 1e-6 on a 500 mm mandrel, pipe.radius: 1e300) are refused before anything
// is allocated, with a message naming the key, its value and the bound; otherwise they run for
// minutes, take gigabytes or hang inside OpenCASCADE or CGAL.
//
// Three kinds of bound (JobLimits):
//  - dimensions: every length key in [1 um, 100 m] (0 where 0 means "off");
//  - counts: meridians, circuits, turns, girth samples and rings, bent-tube segments, cut-lines;
//  - estimates: triangles of the tessellation and of the remeshing, and plan points, from the
//    mandrel's size (known from the parameters of a parametric mandrel; after reading the file
//    for mesh and CAD mandrels: check_tessellation_size / check_remesh_size, called by
//    build_mandrel before meshing).
//
// The estimates (docs/bad_inputs.md): a chord of length l on a curvature radius R deviates by
// l^2 / (8 R), so linear deflection d allows l = sqrt(8 R d), and the angular deflection t allows
// l = R t; a surface of area A then holds about A / (0.433 l^2) equilateral triangles (the same
// for a remeshing length l). R is the mandrel's largest radius (a lower estimate: OCCT meshes
// tighter curves finer), so a refused job is at least that large.
#include <string>

#include "geometry/cad/tessellate.h"
#include "planner/job/config_node.h"
#include "planner/job/job.h"

namespace windplan {

struct JobLimits {
  double min_length = 1e-3;               ///< mm: the smallest length a key may give (1 um)
  double max_length = 1e5;                ///< mm: the largest length or coordinate (100 m)
  int max_meridians = 10000;              ///< winding.meridians (count)
  int max_circuits = kMaxCircuits;        ///< winding.circuits, given or auto (count)
  double max_turns = 100.0;               ///< winding.turns (turns; 100 on a pipe: hoop winding)
  int max_girth_samples = 2000;           ///< girth.samples (count)
  int max_girth_rings = 1000;             ///< girth.rings (count)
  int max_segments = 1000;                ///< bent_tube.segments (count)
  int max_cutlines = 100;                 ///< cutlines (count)
  double max_triangles = 2e6;             ///< estimated triangles of the tessellation or remeshing
  double max_plan_points = 5e6;           ///< estimated dense plan points (all passes)
  double min_relative_deflection = 1e-5;  ///< linear_deflection / mandrel size (dimensionless)
  double max_relative_remesh = 0.1;       ///< remesh / mandrel size (dimensionless)
  /// Plausibility (check_plausibility): the clearance at least this many chord tolerances
  /// (dimensionless; 2 measured failing, 4 passing on the pipe).
  double min_clearance_chords = 4.0;
  /// The payout eye's lead along the axis at most this many mandrel lengths when the machine's
  /// X travel is not given (dimensionless).
  double max_relative_eye_lead = 10.0;
  /// mm: ... but at least this (a small part may still sit on a machine whose eye is 20 mm out).
  double min_eye_lead_bound = 1000.0;
  /// mm: the fibre the plan lays (2 K passes), estimated (10 km; 2e7 replay sub-steps of 0.5 mm).
  double max_fibre_length = 1e7;
};

/// Rough size of a mandrel for the estimates (mm, mm^2).
struct MandrelSize {
  double size = 0.0;    ///< the bounding-box diagonal
  double area = 0.0;    ///< surface area
  double radius = 0.0;  ///< largest radius (curvature radius for the deflections)
  double axial = 0.0;   ///< length along the axis (or the centre line)
};

/// The size of a parametric mandrel from its parameters; size == 0 for mesh and CAD sources.
MandrelSize parametric_mandrel_size(const MandrelOptions& m);

/// Estimated triangles of a tessellation with `t` of a surface of `area` whose curvature radius
/// is about `radius` (see the header comment).
double estimate_tessellation_triangles(double area, double radius, const TessellateOptions& t);

/// Checks every bound that the job alone decides (dimensions, counts, and for parametric
/// mandrels the estimates). \throw ConfigError "<file>:<line>: key 'k' = v <bound>".
void check_job_limits(const Job& job, const ConfigNode& root,
                      const JobLimits& limits = JobLimits());

/// For CAD mandrels, once the file is read: deflections against the model's size and the
/// estimated triangles. \throw ConfigError naming mandrel.linear_deflection / angular_deflection.
void check_tessellation_size(const MandrelSize& s, const TessellateOptions& t,
                             const JobLimits& limits = JobLimits());

/// For mesh and CAD mandrels once read: the size within [1 um, 100 m] (`what` names the mandrel).
/// \throw ConfigError suggesting mandrel.units.
void check_mandrel_extent(const MandrelSize& s, const std::string& what,
                          const JobLimits& limits = JobLimits());

/// For every mandrel before remeshing: the remeshing length against its size, and the estimated
/// triangles. \throw ConfigError naming mandrel.remesh.
void check_remesh_size(const MandrelSize& s, double remesh, const JobLimits& limits = JobLimits());

/// Estimated plan points of the winding (2 K passes of (N 2 pi R + L) / l edge crossings, twice
/// that with the triangles' diagonals; K auto = 2 pi R / band width) on a mandrel whose wound
/// mesh has largest radius R, axial length L and mean edge length l (mm).
double estimate_plan_points(const WindingOptions& w, double radius, double axial, double edge);

/// For mesh and CAD mandrels once built (the pipeline, before planning): the estimated plan
/// points against the bound. \throw ConfigError naming winding.turns and circuits.
void check_plan_size(const WindingOptions& w, double radius, double axial, double edge,
                     const JobLimits& limits = JobLimits());

/// Plausibility (issue 28): combinations of valid values that no winder can wind, refused before
/// any long stage with the cause named (each was found before only by minutes of work and a late
/// replay error, or not at all), on a mandrel of largest radius R and axial length L (mm):
///  - clearance below min_clearance_chords chord tolerances: the resampled eye and fibre paths
///    each stray by up to a chord tolerance, so the eye grazes the mandrel;
///  - the eye's lead along the axis, sqrt(c (2 R + c)) / tan(alpha) for an eye c out along a
///    tangent at the winding angle alpha (tan alpha = 2 pi R N / L from the turns; sin alpha =
///    c_t / R from the turnaround or angle), beyond the machine's X travel (when given) or
///    max(max_relative_eye_lead L, min_eye_lead_bound): names winding.turns (or angle) when alpha
///    is under 10 deg, else machine.envelope.clearance;
///  - the eye radius R + c beyond the Y axis travel (lathe4, when given);
///  - a mesh or CAD mandrel's length beyond the X travel (when given): check mandrel.units;
///  - the fibre laid, 2 K sqrt((2 pi R N)^2 + L^2) (K auto = 2 pi R / band width), above
///    max_fibre_length: check mandrel.units, or a wider band.
/// Parametric mandrels are checked by check_job_limits at load (with the key's line); mesh and
/// CAD mandrels once built. \throw ConfigError "<job>: key 'k' = v ...".
void check_plausibility(const Job& job, const WindingOptions& w, double radius, double axial,
                        const JobLimits& limits = JobLimits());

/// The same for a built mandrel: R and L from its winding surface `wound` about `axis`.
void check_plausibility(const Job& job, const Mesh& wound, const SpindleAxis& axis,
                        const JobLimits& limits = JobLimits());

/// The same for a built mandrel (the pipeline, before planning; mesh and CAD mandrels are known
/// only now): R, L and l from its winding surface `wound` (Mandrel::winding.mesh) about `axis`.
void check_plan_size(const WindingOptions& w, const Mesh& wound, const SpindleAxis& axis,
                     const JobLimits& limits = JobLimits());

}  // namespace windplan
