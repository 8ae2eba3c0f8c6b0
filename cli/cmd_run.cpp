// windplan run <job.yaml> [--out DIR]
// The whole pipeline: mandrel -> mesh -> girth -> helices -> toolpath -> exports, one progress
// line per stage on stderr, every file into the output directory, the summary on stdout.
#include <chrono>
#include <cstdio>
#include <iostream>

#include "cli/args.h"
#include "cli/commands.h"
#include "export/export_plan.h"
#include "export/manifest.h"
#include "export/output_set.h"
#include "export/report.h"
#include "planner/job.h"
#include "planner/pipeline.h"
#include "windplan_version.h"

namespace windplan::cli {

const char* const kRunHelp =
    "usage: windplan run <job.yaml> [--out DIR]\n\n"
    "Runs a job end to end: builds the mandrel, its girth field and density, plans the helices\n"
    "and circuits, computes the machine motion and writes every output file (fibre_path.csv,\n"
    "payout.csv, axes.csv, G-code, report.json/md, mesh.ply, paths.ply, development.svg, as\n"
    "switched by output:) into the output directory. Progress goes to stderr, one line per\n"
    "stage; the summary to stdout. Two runs of the same job write byte-identical files.\n\n"
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
    if (!c.init.empty()) manifest.inputs.push_back(manifest_entry(c.init, "cutline " + c.name, true));
  }

  PipelineOptions po;
  po.on_stage = [](const StageTiming& t) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "windplan run: %-8s done in %.2f s", t.stage.c_str(), t.seconds);
    std::cerr << buf << "\n";
  };
  PipelineResult r = plan_job(job, po);
  for (const std::string& w : r.plan.metrics.warnings) {
    std::cerr << "windplan run: warning: " << w << "\n";
  }

  const auto t0 = std::chrono::steady_clock::now();
  ExportResult ex = export_plan(r.plan, r.mandrel.mesh, job.machine, job.output, set.staging());
  set.commit(manifest, ex.files);
  ex.directory = set.directory();
  ex.files.push_back("manifest.json");
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.plan.metrics.timings.push_back({"export", secs});
  {
    char buf[160];
    std::snprintf(buf, sizeof buf, "windplan run: %-8s done in %.2f s (%zu files in %s)", "export",
                  secs, ex.files.size(), dir.string().c_str());
    std::cerr << buf << "\n";
  }
  std::cout << summary_text(r.plan, ex);
  return 0;
}

}  // namespace windplan::cli
