#pragma once
// Writes every output file of a plan into a directory (all through write_file_atomically, so an
// interrupted run never leaves a partial file under a real name; temporaries are "*.tmp.<pid>").
// Two exports of the same plan and options give byte-identical files: no timestamps, fixed number
// formats, stage timings only with output.timings (default off).
//
// Files (each group switched by OutputOptions):
//   csv:    fibre_path.csv  circuit, index, x, y, z, nx, ny, nz, tx, ty, tz, s, winding angle,
//                           k_n, k_g, slippage (every dense plan point)
//           payout.csv      circuit, index, eye x, y, z, free length, cumulative fibre length
//                           (resampled points; cumulative = laid length so far + free length)
//           axes.csv        circuit, index, t_s, A_deg, X_mm, Y_mm, B_deg, F (resampled points)
//           eye_pose.csv    (machine.kind robot only) circuit, index, t_s, A, eye position and
//                           unit fibre direction and unit radial direction of the eye (its full
//                           pose: the third axis is their cross product) in the mandrel frame
//   gcode:  toolpath.ngc | toolpath.gcode | toolpath.nc (lathe2/lathe4; see export/program/gcode.h)
//   report: report.json, report.md (see export/files/report.h)
//   ply:    mesh.ply (the mandrel), paths.ply (see export/files/ply_polylines.h)
//   svg:    development.svg (see export/plots/svg.h), axes.svg (export/plots/axes_svg.h)
//   viewer: viewer.html (see export/plots/viewer.h)
// "index" is always the index of the point in its circuit's dense points.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "export/files/csv.h"
#include "export/files/export_result.h"
#include "export/machine/kinematics.h"
#include "export/program/replay.h"
#include "geometry/mesh/mesh.h"
#include "planner/job/machine_options.h"
#include "planner/plan/plan.h"

namespace windplan {

/// What export_plan may use besides the plan: the wound region and a progress hook.
struct ExportContext {
  /// The annulus the plan was made on (Mandrel::winding.mesh, whose faces FibrePoint::face
  /// names): development.svg unrolls a tube that is not a shape of revolution in its conformal
  /// coordinates. Null: the mandrel mesh is used.
  const Mesh* wound_region = nullptr;
  /// Per face of wound_region, the mandrel mesh's face (WindingSurface::face_map; FibrePoint::face
  /// indexes the mandrel mesh). Null: the identity.
  const std::vector<int>* wound_face_map = nullptr;
  /// The mandrel is a surface of revolution about the plan's axis (Mandrel::revolution):
  /// development.svg unrolls it about the axis. Unset: judged from the plan
  /// (PlanMetrics::geodesic_turn_limit is a number).
  std::optional<bool> revolution;
  /// Called after each file with its name, the files written so far and their number.
  std::function<void(const std::string& file, int done, int total)> on_file;
  /// Files another writer puts into the directory (a layup's laminate files,
  /// export/files/layup_export.h): listed in ExportResult::files and the reports, before them.
  std::vector<std::string> also_written;
  /// Per circuit of the plan, the mesh of the surface it was wound on (a layup's layers:
  /// planner/plan_layup.h layup_circuit_surfaces): the G-code and robot replays walk each
  /// circuit on it, and a robot's eye keeps its clearance from it (compute_motion). Empty or null
  /// entries: the mandrel mesh.
  std::vector<const Mesh*> circuit_surfaces;
};

/// Computes the motion, replays the G-code (export/program/replay.h) and writes the files.
/// \throw InputError (bad envelope, clearance, axis limits; see compute_motion; a replay that
///        deviates more than machine.replay_tolerance from the plan: then no file is written),
///        IoError (cannot write).
ExportResult export_plan(const WindingPlan& plan, const Mesh& mandrel_mesh,
                         const MachineOptions& machine, const OutputOptions& output,
                         const std::filesystem::path& dir, const ExportContext& context = {});

/// Where a job's files go: output.directory when set (already resolved against the job file's
/// directory by the job loader), else "<job name>.out" beside the job file.
std::filesystem::path resolve_output_directory(const OutputOptions& output,
                                               const std::filesystem::path& job_file,
                                               const std::string& job_name);

/// The CSV tables, for tests and other writers.
CsvTable fibre_path_table(const WindingPlan& plan);
CsvTable payout_table(const Motion& motion);
CsvTable axes_table(const Motion& motion);
CsvTable eye_pose_table(const Motion& motion);

}  // namespace windplan
