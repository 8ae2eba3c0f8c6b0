// Ceres' L-BFGS (GradientProblemSolver) against windplan's projected Newton and projected L-BFGS
// on fixed face strips: the measurement behind the solver choice in README.md.
//
// For random vertex pairs on a mesh, the refined geodesic's strip is kept and its crossing
// parameters are perturbed; each solver then minimises the length on that strip from the same
// start. Ceres has no bounds, so lambda = (1 + sin s) / 2 maps an unconstrained s into [0, 1],
// and it cannot reroute; windplan's solvers keep the bounds themselves and may reroute.
//
// usage: bench_ceres_lbfgs [mesh.obj] [pairs]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <ceres/ceres.h>

#include "geometry/geodesic/geodesic.h"
#include "geometry/mesh/mesh_io.h"
#include "geometry/mesh/mesh_validation.h"

using namespace windplan;

namespace {

// Euclidean length of a fixed strip and its gradient (eq. 1-2), in s with lambda = (1+sin s)/2.
class StripLength : public ceres::FirstOrderFunction {
 public:
  StripLength(const Mesh& mesh, const SurfacePath& path) : k_(path.num_crossings()) {
    s_ = position(mesh, path.start);
    t_ = position(mesh, path.end);
    for (int h : path.halfedges) {
      a_.push_back(mesh.position(mesh.from(h)));
      d_.push_back(mesh.position(mesh.to(h)) - mesh.position(mesh.from(h)));
    }
  }
  int NumParameters() const override { return k_; }
  bool Evaluate(const double* s, double* cost, double* gradient) const override {
    std::vector<Vec3> p(k_ + 2);
    std::vector<double> dl(k_);
    p[0] = s_;
    p[k_ + 1] = t_;
    for (int i = 0; i < k_; ++i) {
      const double l = 0.5 * (1.0 + std::sin(s[i]));
      dl[i] = 0.5 * std::cos(s[i]);
      p[i + 1] = a_[i] + l * d_[i];
    }
    *cost = 0.0;
    if (gradient) std::fill(gradient, gradient + k_, 0.0);
    for (int j = 0; j <= k_; ++j) {
      const Vec3 w = p[j + 1] - p[j];
      const double n = w.norm();
      *cost += n;
      if (!gradient || n == 0.0) continue;
      const Vec3 u = w / n;
      if (j < k_) gradient[j] += d_[j].dot(u) * dl[j];
      if (j > 0) gradient[j - 1] -= d_[j - 1].dot(u) * dl[j - 1];
    }
    return true;
  }

 private:
  int k_;
  Vec3 s_, t_;
  std::vector<Vec3> a_, d_;
};

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const std::string file =
      argc > 1 ? argv[1] : std::string(WINDPLAN_SHARED_MESHES) + "/derived/bunny-remesh-20k.obj";
  const int pairs = argc > 2 ? std::atoi(argv[2]) : 20;
  Mesh mesh = build_mesh(read_mesh(file), false, nullptr, nullptr);
  const GeodesicContext ctx(mesh);
  std::mt19937 rng(2024);
  std::uniform_int_distribution<int> pick(0, mesh.num_vertices() - 1);
  std::normal_distribution<double> noise(0.0, 0.15);

  std::vector<double> t_newton, t_lbfgs, t_ceres, it_newton, it_lbfgs, it_ceres, x_newton, x_lbfgs,
      x_ceres;
  int done = 0;
  for (int trial = 0; done < pairs && trial < 10 * pairs; ++trial) {
    const auto ref = geodesic_between(ctx, SurfacePoint::at_vertex(pick(rng)),
                                      SurfacePoint::at_vertex(pick(rng)));
    if (ref.path.num_crossings() < 20) continue;
    // Reference: the optimum on this strip (Newton without reroutes from the refined path).
    SurfacePath start = ref.path;
    for (double& l : start.lambdas) l = std::clamp(l + noise(rng), 0.02, 0.98);
    // windplan's solvers from the same start, funnel off; they may reroute (Ceres cannot).
    GeodesicOptions fixed;
    fixed.funnel_start = false;
    const double best = ref.summary.final_length;

    auto t0 = std::chrono::steady_clock::now();
    const auto rn = refine_path(mesh, start, {}, fixed);
    t_newton.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    it_newton.push_back(rn.summary.iterations);
    x_newton.push_back((rn.summary.final_length - best) / best);

    GeodesicOptions lb = fixed;
    lb.solver = GeodesicSolver::Lbfgs;
    t0 = std::chrono::steady_clock::now();
    const auto rl = refine_path(mesh, start, {}, lb);
    t_lbfgs.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    it_lbfgs.push_back(rl.summary.iterations);
    x_lbfgs.push_back((rl.summary.final_length - best) / best);

    std::vector<double> s(start.num_crossings());
    for (int i = 0; i < start.num_crossings(); ++i) s[i] = std::asin(2.0 * start.lambdas[i] - 1.0);
    auto* fn = new StripLength(mesh, start);
    ceres::GradientProblem problem(fn);
    ceres::GradientProblemSolver::Options options;
    options.line_search_direction_type = ceres::LBFGS;
    options.max_num_iterations = 2000;
    options.function_tolerance = 1e-15;
    options.gradient_tolerance = 1e-12;
    options.parameter_tolerance = 1e-15;
    options.logging_type = ceres::SILENT;
    ceres::GradientProblemSolver::Summary summary;
    t0 = std::chrono::steady_clock::now();
    ceres::Solve(options, problem, s.data(), &summary);
    t_ceres.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    it_ceres.push_back(summary.iterations.size());
    x_ceres.push_back((summary.final_cost - best) / best);
    ++done;
  }
  std::printf("mesh %s, %d strips (fixed strip, perturbed start)\n", file.c_str(), done);
  std::printf(
      "| solver | median ms | median iterations | median excess over the refined geodesic |\n");
  std::printf("|---|---|---|---|\n");
  std::printf("| windplan projected Newton | %.3f | %.0f | %.2e |\n", median(t_newton),
              median(it_newton), median(x_newton));
  std::printf("| windplan projected L-BFGS | %.3f | %.0f | %.2e |\n", median(t_lbfgs),
              median(it_lbfgs), median(x_lbfgs));
  std::printf("| Ceres GradientProblemSolver L-BFGS, lambda = (1+sin s)/2 | %.3f | %.0f | %.2e |\n",
              median(t_ceres), median(it_ceres), median(x_ceres));
  return 0;
}
