// windplan run <job.yaml> [--out DIR]
// The whole pipeline: mandrel -> mesh -> girth -> helices -> toolpath -> exports, one progress
// line per stage on stderr (on a terminal also a live line for the stage under way;
// cli/progress.h), every file into the output directory, the summary on stdout.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/progress.h"
#include "export/export_plan.h"
#include "export/files/design_report.h"
#include "export/files/layup_export.h"
#include "export/files/layup_report.h"
#include "export/files/manifest.h"
#include "export/files/output_set.h"
#include "export/files/report.h"
#include "export/robot/cell_reach.h"
#include "geometry/base/atomic_file.h"
#include "planner/job/job.h"
#include "planner/pipeline.h"
#include "planner/plan_layup.h"
#include "windplan_version.h"

namespace windplan::cli {

const char* const kRunHelp =
    "usage: windplan run <job.yaml> [--out DIR]\n\n"
    "Runs a job end to end: builds the mandrel, its girth field and density, plans the helices\n"
    "and circuits, computes the machine motion and writes every output file (fibre_path.csv,\n"
    "payout.csv, axes.csv, G-code, report.json/md, mesh.ply, paths.ply, development.svg,\n"
    "axes.svg, stability.svg, viewer.html, as switched by output:) into the output directory.\n"
    "Progress goes to\n"
    "stderr, one line per stage (on a terminal also a live line for the stage under way); the\n"
    "summary to stdout. Two runs of the same job write byte-identical files.\n"
    "A job with layers: winds every layer in order on the surface built by the ones under it\n"
    "into one program, and writes laminate.csv/.vtu and layer_profiles.csv/.svg besides.\n"
    "A job with design: (a vessel or pipe) is sized from its pressure by netting theory when it\n"
    "gives no layers:, and writes design.md (netting burst pressure by layer, time and cost per\n"
    "layer, pot life) and model.inp/model_plies.csv (the structural model; windplan check-fea).\n"
    "The output folder always holds one job's complete set: the files are written into a\n"
    "staging folder beside it and swapped in whole, with manifest.json (job, input hashes,\n"
    "version, every file's size and SHA-256). A second run into a folder that a running job\n"
    "holds is refused; a folder holding files windplan did not write is never replaced.\n\n"
    "  --out DIR   output directory (default: output.directory of the job, else\n"
    "              out/<job name>/ relative to the current directory)\n";

int run_run(const std::vector<std::string>& argv) {
  const Args args(argv, {}, {"--out", "-o"});
  args.expect_positional(1, "a job file");
  const Job job = load_job(args.positional()[0]);
  std::filesystem::path dir;
  if (args.has("--out")) {
    dir = args.value("--out");
  } else if (args.has("-o")) {
    dir = args.value("-o");
  } else if (!job.output.directory.empty()) {
    dir = job.output.directory;
  } else {
    dir = std::filesystem::path("out") / job.name;
  }
  if (dir.empty()) throw UsageError("option --out needs a folder name (got an empty string)");

  // The folder is locked before planning, so that a second run is refused at once; the inputs
  // are hashed now, as read (an edit during the run does not change the manifest).
  OutputSet set(dir);
  Manifest manifest;
  manifest.job = job.name;
  manifest.version = WINDPLAN_VERSION;
  manifest.inputs.push_back(manifest_entry(job.path, "job", true));
  if (!job.mandrel.file.empty()) {
    manifest.inputs.push_back(manifest_entry(job.mandrel.file, "mandrel", true));
  }
  for (const CutLineOptions& c : job.cutlines) {
    if (!c.init.empty())
      manifest.inputs.push_back(manifest_entry(c.init, "cutline " + c.name, true));
  }

  StageProgress progress(std::cerr, ::isatty(STDERR_FILENO) == 1, "windplan run");
  PipelineOptions po;
  po.on_stage_start = [&](const std::string& stage) { progress.start(stage); };
  po.on_stage = [&](const StageTiming& t) { progress.finish(t.stage, t.seconds); };
  const Mandrel* built_mandrel = nullptr;  // the mandrel of the job being planned
  if (job.machine.kind == "robot" && job.machine.robot.has_arm()) {
    // The cell's reach, before the long work (export/robot/cell_reach.h).
    po.on_mandrel = [&](const Mandrel& m) {
      check_cell_reach(m.winding.mesh, m.axis, m.profile, job.machine);
      built_mandrel = &m;
    };
    // And over the laminate each layer of a layup is wound on, before that layer is planned.
    po.on_layer_surface = [&](const Mesh& surface, const std::string& layer) {
      if (built_mandrel) {
        check_cell_reach_over(built_mandrel->winding.mesh, built_mandrel->axis, surface,
                              job.machine, layer);
      }
    };
  }
  // A job with `layers:` is a layup (planner/plan_layup.h): every layer in order, one program.
  PipelineResult r;
  LayupResult layup;
  // A design: job is a layup too (one helical layer of `winding:` when it gives no layers).
  const bool layered = !job.layers.empty() || job.design.present;
  if (layered) {
    layup = plan_layup(job, po);
  } else {
    r = plan_job(job, po);
  }
  WindingPlan& plan = layered ? layup.plan : r.plan;
  const Mandrel& mandrel = layered ? layup.mandrel : r.mandrel;
  for (const std::string& w : plan.metrics.warnings) {
    std::cerr << "windplan run: warning: " << w << "\n";
  }

  const auto t0 = std::chrono::steady_clock::now();
  progress.start("export");
  ExportContext context;
  context.wound_region = &mandrel.winding.mesh;
  context.wound_face_map = &mandrel.winding.face_map;
  context.revolution = mandrel.revolution;
  context.on_file = [&](const std::string& file, int done, int total) {
    progress.count(done, total, file);
  };
  if (layered) {
    context.circuit_surfaces = layup_circuit_surfaces(layup);
    context.also_written = layup_file_names(layup, job.output, job.design);
    write_layup_files(layup, job.output, set.staging(), job.design);
  }
  ExportResult ex =
      export_plan(plan, mandrel.mesh, job.machine, job.output, set.staging(), context);
  if (layered && job.design.present) {  // design.md (export/files/design_report.h)
    const std::vector<double> times = layer_wind_times(plan, ex.motion);
    double total = 0.0;
    for (double t : times) total += t;
    const std::string w = pot_life_warning(job.design, total);
    if (!w.empty()) std::cerr << "windplan run: warning: " << w << "\n";
    write_text_atomically(
        set.staging() / "design.md",
        design_markdown(job.design, job.sized, job.sizing, layup, times, layup.revolution));
    ex.files.push_back("design.md");
  }
  set.commit(manifest, ex.files);
  ex.directory = set.directory();
  ex.files.push_back("manifest.json");
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  plan.metrics.timings.push_back({"export", secs});
  progress.finish("export", secs,
                  " (" + std::to_string(ex.files.size()) + " files in " + dir.string() + ")");
  std::cout << summary_text(plan, ex);
  return 0;
}

}  // namespace windplan::cli
