#pragma once
// A windplan job: one YAML file per mandrel maps to one Job struct made of the stages' Options
// (house style rule 13). The schema, with units and defaults, is documented in docs/config.md.
//
// Each section is decoded by its own decode_* function in job.cpp, which reads the keys into the
// stage's Options, rejects unknown keys (file, line and key named) and calls is_valid().
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/cad/parametric_mandrel.h"
#include "geometry/cad/section_mandrel.h"
#include "geometry/cad/tessellate.h"
#include "geometry/region/axis.h"
#include "geometry/region/mandrel_region.h"
#include "planner/cutlines/cutlines.h"
#include "planner/girth/girth.h"
#include "planner/job/machine_options.h"
#include "planner/layup/design.h"
#include "planner/layup/layers.h"
#include "planner/layup/material.h"
#include "planner/winding/winding_options.h"

namespace windplan {

/// Length unit of an input file; windplan works in millimetres internally.
enum class LengthUnit { Millimetre, Metre, Inch };
/// Factor that converts a length in `u` to millimetres.
double to_millimetres(LengthUnit u);
/// Parses "mm", "m" or "in". \throw InputError otherwise.
LengthUnit parse_length_unit(const std::string& s);

/// The `mandrel:` section: a mesh file, a CAD file or a parametric shape (docs/config.md).
struct MandrelOptions {
  /// Where the mandrel comes from: "mesh" (a triangle-mesh file), "cad" (STEP/IGES/BREP),
  /// or a parametric shape: "pipe", "cone", "vessel", "bent_tube", "section".
  std::string source = "mesh";
  /// Mesh or CAD file, resolved relative to the job file's directory when loaded from a job.
  std::filesystem::path file;
  /// Unit of the coordinates in `file` (mesh and BREP files; STEP/IGES carry their own unit);
  /// converted to mm. Parametric dimensions are always in mm.
  LengthUnit units = LengthUnit::Millimetre;
  /// Repair what is safe (re-orient, drop degenerate/duplicate/unreferenced elements).
  bool repair = true;
  /// cad: the body to take from a file with several: its name or 1-based index ("" = largest).
  std::string solid;
  /// cad and parametric: tessellation deflections (linear mm, angular degrees). A bent_tube
  /// without `angular_deflection` gets it fitted to its radius and winding.band_width by the job
  /// loader (fitted_angular_deflection, geometry/cad/tessellate.h).
  TessellateOptions tessellation;
  bool angular_deflection_given = false;  ///< the job gave mandrel.angular_deflection
  /// Isotropic remeshing target edge length (mm); 0 = off.
  double remesh = 0.0;
  /// The spindle axis, when given (`axis: {origin, direction}`); otherwise it is inferred.
  bool has_axis = false;
  SpindleAxis axis;
  /// The wound region (`region: {start, end, surface, component}`): an axial range and the
  /// surface around the axis in it; when absent, every non-planar face (see mandrel_builder.h).
  RegionOptions region;
  /// Parameters of the parametric sources (mm, degrees).
  PipeParams pipe;
  ConeParams cone;
  VesselParams vessel;
  BentTubeParams bent_tube;
  SectionParams section;  ///< ellipse or rounded-rectangle section (geometry/cad/section_mandrel.h)
  /// Parametric sources except bent_tube: bore, shafts, flanges with bolt holes, screw tabs.
  MandrelFeatures features;

  bool is_valid(std::string* why) const;
};

struct Job {
  /// Job name: the `name:` key, or the job file's stem.
  std::string name;
  /// The job file itself (absolute); relative paths in the job resolve against its directory.
  std::filesystem::path path;
  MandrelOptions mandrel;
  MachineOptions machine;  ///< `machine:` (kinematics, axes, G-code)
  OutputOptions output;    ///< `output:` (files written, directory)
  WindingOptions winding;  ///< `winding:` (helices, coverage, stability; planner/winding/helix.h)
  GirthOptions girth;      ///< `girth:` (girth field sampling, planner/girth/girth.h)
  std::vector<CutLineOptions>
      cutlines;  ///< `cutlines:` (planar trim lines, planner/cutlines/cutlines.h)
  /// `layers:` (planner/layup/layers.h), innermost first; empty: one helical layer made of
  /// `winding`.
  std::vector<LayerOptions> layers;
  MaterialOptions material;  ///< `material:` (the tow and the composite, planner/layup/material.h)
  /// `design:` (planner/layup/design.h): pressure, ply, dome model, stagger, pot life, FEA mesh.
  DesignOptions design;
  /// A `design:` with a pressure and no `layers:` is sized: `layers` then holds the sized
  /// laminate and `sizing` its figures.
  bool sized = false;
  DesignLayup sizing;
};

/// A job name becomes a folder name (out/<name>): it must not be empty, absolute, contain '/',
/// '\\', '..' or control characters, or start with '.'. Sets *why when it is not valid.
bool is_valid_job_name(const std::string& name, std::string* why);

/// Loads and validates a job file.
/// \throw IoError if the file is missing; ConfigError for malformed YAML, unknown or mistyped keys
///        and invalid values, naming file, line and key.
Job load_job(const std::filesystem::path& file);

/// Same from YAML text; `file` is used for messages and relative paths.
Job load_job_from_string(const std::string& yaml, const std::filesystem::path& file);

}  // namespace windplan
