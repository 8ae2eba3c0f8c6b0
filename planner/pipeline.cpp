#include "planner/pipeline.h"

#include <chrono>
#include <cmath>

#include "planner/cutlines.h"

namespace windplan {

namespace {

class Stage {
 public:
  Stage(const std::string& name, PlanMetrics* metrics, const PipelineOptions& o)
      : name_(name), metrics_(metrics), options_(o), t0_(std::chrono::steady_clock::now()) {
    if (options_.on_stage_start) options_.on_stage_start(name_);
  }
  void done() {
    StageTiming t{name_,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count()};
    metrics_->timings.push_back(t);
    if (options_.on_stage) options_.on_stage(t);
  }

 private:
  std::string name_;
  PlanMetrics* metrics_;
  const PipelineOptions& options_;
  std::chrono::steady_clock::time_point t0_;
};

}  // namespace

PipelineResult plan_job(const Job& job, const PipelineOptions& options) {
  PipelineResult r;
  PlanMetrics timings;  // collected here, moved into the plan at the end

  Stage mandrel("mandrel", &timings, options);
  r.mandrel = build_mandrel(job);
  mandrel.done();
  const Mandrel& md = r.mandrel;
  const WindingSurface& ws = md.winding;
  const std::array<std::vector<int>, 2> loops{ws.loops[0].vertices, ws.loops[1].vertices};

  // Girth: needed for the density (beta > 0) and, off a shape of revolution, for the spacing
  // normalisation; on a shape of revolution with beta = 0, 2 pi r is the exact girth.
  Stage girth("girth", &timings, options);
  const WindingOptions& wo = job.winding;
  if (wo.beta > 0.0 || !md.revolution) {
    r.girth = compute_girth_field(ws.mesh, loops, job.girth);
    r.face_girth = r.girth.face_girth(ws.mesh);
    r.has_girth = true;
  } else {
    r.face_girth.resize(ws.mesh.num_faces());
    for (int f = 0; f < ws.mesh.num_faces(); ++f) {
      r.face_girth[f] = 2.0 * M_PI * md.axis.radius(ws.mesh.face_centroid(f));
    }
  }
  girth.done();

  Stage helices("helices", &timings, options);
  std::vector<double> rho;
  if (wo.beta > 0.0) rho = density_from_girth(ws.mesh, r.face_girth, wo.beta);
  r.helices = plan_helices(ws.mesh, loops, rho, md.axis, wo);
  helices.done();

  Stage metrics("metrics", &timings, options);
  WindingPlan& plan = r.plan;
  plan.job_name = job.name;
  plan.axis = md.axis;
  plan.profile = md.profile;
  plan.circuits = build_circuits(ws.mesh, r.helices, ws.face_map, md.axis, wo);
  plan.metrics = compute_plan_metrics(ws.mesh, r.helices, plan.circuits, r.face_girth, md.axis,
                                      md.revolution, wo);
  for (const std::string& w : md.warnings) plan.metrics.warnings.push_back("mandrel: " + w);
  r.passes = pass_reports(r.helices, plan.circuits, md.axis);
  metrics.done();

  if (!job.cutlines.empty()) {
    Stage cut("cutlines", &timings, options);
    plan.cutlines = compute_cutlines(md, job.cutlines);
    cut.done();
  }

  plan.metrics.timings = std::move(timings.timings);
  return r;
}

}  // namespace windplan
