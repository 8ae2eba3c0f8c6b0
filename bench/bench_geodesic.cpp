// Table 2 of Liu et al. (an optimization-driven approach for geodesic paths on triangle meshes):
// time per geodesic path between random vertex pairs on meshes of 20K to 300K faces, for both
// solvers of the geodesic core (projected Newton, projected L-BFGS), with the length excess over
// the CGAL exact geodesic (geometry/geodesic/exact_geodesic.h). Prints a markdown table and
// per-mesh details; see bench/README.md. Needs ../shared/data/meshes (or mesh files as arguments).
//
// usage: bench_geodesic [--pairs N] [--targets-per-source K] [--exact-sources S]
//                       [--exact-sources-small S] [--seed N] [--repeat R] [--quick]
//                       [mesh files...]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <time.h>

#include "geometry/geodesic/exact_geodesic.h"
#include "geometry/geodesic/geodesic.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/mesh_io.h"
#include "geometry/mesh/mesh_validation.h"

using namespace windplan;
using Clock = std::chrono::steady_clock;

namespace {

/// CPU time of the calling thread (ms): the machine is shared, so wall time measures the load.
double thread_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

double ms_since(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

/// Quantile q in [0, 1] (nearest rank) of a copy of v.
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t i =
      std::min(v.size() - 1, static_cast<std::size_t>(std::ceil(q * v.size())) - (q > 0.0 ? 1 : 0));
  return v[i];
}

double mean_of(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? std::nan("") : sum / static_cast<double>(v.size());
}

struct Pair {
  int source, target;
};

struct SolverRun {
  std::vector<double> init, refine, total, cpu, iterations, length, exact_ms, windows;
  int not_converged = 0;
  int corrected = 0;  // pairs the local starts alone miss (relative excess > 1e-9)
  std::vector<std::string> failures;
};

std::string fmt(double v, const char* f = "%.3g") {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// Largest distance from the points of `a` to the polyline `b` (both ways: the larger).
double polyline_gap(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  auto one_sided = [](const std::vector<Vec3>& p, const std::vector<Vec3>& q) {
    double worst = 0.0;
    for (const Vec3& x : p) {
      double best = std::numeric_limits<double>::infinity();
      for (std::size_t k = 1; k < q.size(); ++k) {
        const Vec3 d = q[k] - q[k - 1];
        const double t =
            std::clamp((x - q[k - 1]).dot(d) / std::max(d.squaredNorm(), 1e-300), 0.0, 1.0);
        best = std::min(best, (x - (q[k - 1] + t * d)).norm());
      }
      worst = std::max(worst, best);
    }
    return worst;
  };
  return std::max(one_sided(a, b), one_sided(b, a));
}

double load_average() {
  std::ifstream in("/proc/loadavg");
  double l = std::nan("");
  in >> l;
  return l;
}

}  // namespace

int main(int argc, char** argv) {
  int num_pairs = 50, per_source = 5, exact_sources = 1, exact_sources_small = -1;
  unsigned seed = 20240611;
  int repeat = 1;  // solves per pair; the fastest init and refine are kept
  int steiner = GeodesicContext::kDefaultSteinerPoints;
  bool edge_starts = false, lbfgs = false, split = true, by_source = false;
  bool steiner_start = GeodesicOptions{}.steiner_start;
  bool exact_windows = GeodesicOptions{}.exact_windows;
  int landmarks = GeodesicContext::kDefaultLandmarks;
  std::filesystem::path write_pairs, reference, write_times;
  std::vector<std::filesystem::path> best_of;  // earlier rounds' per-pair times (--best-of)
  std::vector<std::filesystem::path> files;
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // progress shows when redirected to a file
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> int {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return std::atoi(argv[++i]);
    };
    if (a == "--pairs")
      num_pairs = next();
    else if (a == "--targets-per-source")
      per_source = next();
    else if (a == "--exact-sources")
      exact_sources = next();
    else if (a == "--exact-sources-small")
      exact_sources_small = next();
    else if (a == "--seed")
      seed = static_cast<unsigned>(next());
    else if (a == "--repeat")
      repeat = std::max(1, next());
    else if (a == "--steiner")
      steiner = next();
    else if (a == "--edge-starts")
      edge_starts = next() != 0;
    else if (a == "--landmarks")
      landmarks = next();
    else if (a == "--exact-windows")
      exact_windows = next() != 0;
    else if (a == "--steiner-start")
      steiner_start = next() != 0;
    else if (a == "--split")
      split = next() != 0;
    else if (a == "--write-pairs" && i + 1 < argc)
      write_pairs = argv[++i];
    else if (a == "--reference" && i + 1 < argc)
      reference = argv[++i];
    else if (a == "--write-times" && i + 1 < argc)
      write_times = argv[++i];
    else if (a == "--best-of" && i + 1 < argc)
      best_of.emplace_back(argv[++i]);
    else if (a == "--lbfgs")
      lbfgs = true;
    else if (a == "--by-source")
      by_source = true;
    else if (a == "--quick") {
      num_pairs = 10;
      exact_sources = 0;
      exact_sources_small = 1;
    } else if (a == "-h" || a == "--help") {
      std::printf(
          "usage: bench_geodesic [--pairs N] [--targets-per-source K] [--exact-sources S]\n"
          "       [--exact-sources-small S] [--seed N] [--repeat R] [--quick] [--steiner K]\n"
          "       [--edge-starts 0|1] [--lbfgs] [--exact-windows 0|1] [--landmarks L]\n"
          "       [mesh files...]\n"
          "--exact-windows 0: no exact window pass (the local starts only)\n"
          "--by-source: each source's targets in one call (geodesics_from: one window search\n"
          "  resumed from target to target); a pair's thread CPU is its source's total shared\n"
          "  in proportion to the pairs' own search and refinement times (the mean is exact)\n"
          "--landmarks L: the context's window search uses L landmark fields (default 0)\n"
          "--steiner K: Steiner points per edge of the start graph (0: edge-graph starts only)\n"
          "--edge-starts 1: also refine from the two edge-graph starts\n"
          "--lbfgs: also run the paper's L-BFGS solver\n"
          "--write-pairs DIR: write DIR/<mesh file name>.pairs ('source target' per line)\n"
          "--reference DIR: read DIR/<mesh file name>.ref ('source target exact other_length\n"
          "  other_cpu_ms' per pair, e.g. an exact MMP distance and FlipOut's length and time on\n"
          "  the same pairs) instead of running CGAL, and print the side-by-side table\n"
          "--write-times DIR: write DIR/<mesh file name>.times ('source target length\n"
          "  thread_cpu_ms' per pair)\n"
          "--best-of DIR (repeatable): per pair, the smallest thread CPU time of this run and of\n"
          "  DIR/<mesh file name>.times, an earlier round (rounds interleaved with the reference\n"
          "  program's, each pair's minimum kept on both sides)\n"
          "--repeat R: each pair is solved R times and its fastest init and refine are kept\n"
          "(the machine is shared: this removes scheduling noise, not work).\n"
          "Pairs are drawn as sources with K targets each; the CGAL exact distance is\n"
          "computed for S sources (one sequence tree each) on meshes above 50K faces and\n"
          "for all sources below (or --exact-sources-small).\n");
      return 0;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    } else {
      files.emplace_back(a);
    }
  }
  if (files.empty()) {
    const std::filesystem::path root = WINDPLAN_SHARED_MESHES;
    for (const char* name : {"derived/bunny-remesh-20k.obj", "derived/bunny-remesh-100k.obj",
                             "derived/bunny-remesh-300k.obj", "kitten-106k.obj"})
      files.push_back(root / name);
  }
  per_source = std::max(1, per_source);
  const int num_sources = (num_pairs + per_source - 1) / per_source;

  std::printf("# bench_geodesic: %d vertex pairs per mesh (%d sources x %d targets), seed %u\n",
              num_sources * per_source, num_sources, per_source, seed);
  std::printf("# load average at start: %.2f\n\n", load_average());

  struct Row {
    std::string mesh;
    int faces = 0;
    std::string solver;
    SolverRun run;
    std::vector<double> excess;  // per pair with an exact distance
    int pairs = 0;
  };
  std::vector<Row> rows;
  std::vector<std::string> notes;
  std::vector<std::string> side;  // the side-by-side table with --reference

  for (const auto& file : files) {
    if (!std::filesystem::exists(file)) {
      std::printf("%s: missing, skipped\n", file.c_str());
      continue;
    }
    auto t = Clock::now();
    const Mesh mesh = build_mesh(read_mesh(file), false);
    const double load_ms = ms_since(t);
    t = Clock::now();
    double context_cpu = thread_cpu_ms();
    const GeodesicContext ctx(mesh, PathMetric{}, steiner, landmarks);
    context_cpu = thread_cpu_ms() - context_cpu;
    const double context_ms = ms_since(t);
    const std::string name = file.filename().string();
    std::printf(
        "## %s: V=%d F=%d, load %.0f ms, context (edge graphs, Steiner k=%d, %d landmarks) "
        "%.1f ms wall, %.1f ms thread CPU\n",
        name.c_str(), mesh.num_vertices(), mesh.num_faces(), load_ms, steiner,
        ctx.landmarks().count, context_ms, context_cpu);

    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> pick(0, mesh.num_vertices() - 1);
    std::vector<Pair> pairs;
    for (int s = 0; s < num_sources; ++s) {
      int v = pick(rng);
      while (mesh.vertex_halfedge(v) < 0) v = pick(rng);
      for (int k = 0; k < per_source; ++k) {
        int w = pick(rng);
        while (w == v || mesh.vertex_halfedge(w) < 0) w = pick(rng);
        pairs.push_back({v, w});
      }
    }

    if (!write_pairs.empty()) {
      std::ofstream out(write_pairs / (name + ".pairs"));
      for (const Pair& p : pairs) out << p.source << " " << p.target << "\n";
    }
    std::vector<double> other_length(pairs.size(), std::nan("")), other_ms = other_length;
    std::vector<double> exact(pairs.size(), std::nan(""));
    if (!reference.empty()) {
      std::ifstream in(reference / (name + ".ref"));
      if (!in) {
        std::fprintf(stderr, "%s: missing\n", (reference / (name + ".ref")).c_str());
        return 1;
      }
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        int s0 = -1, t0 = -1;
        if (!(in >> s0 >> t0 >> exact[i] >> other_length[i] >> other_ms[i]) ||
            s0 != pairs[i].source || t0 != pairs[i].target) {
          std::fprintf(stderr, "%s: pair %zu does not match\n", name.c_str(), i);
          return 1;
        }
      }
    }
    // Exact distances: one CGAL tree per source, for the first sources.
    const int sources_exact = !reference.empty() ? 0
                              : mesh.num_faces() <= 50000
                                  ? (exact_sources_small < 0 ? num_sources : exact_sources_small)
                                  : exact_sources;
    if (sources_exact > 0) {
      t = Clock::now();
      ExactGeodesic cgal(mesh);
      for (int s = 0; s < std::min(sources_exact, num_sources); ++s) {
        std::vector<SurfacePoint> targets;
        for (int k = 0; k < per_source; ++k)
          targets.push_back(SurfacePoint::at_vertex(pairs[s * per_source + k].target));
        const auto t1 = Clock::now();
        const std::vector<double> d =
            cgal.distances(SurfacePoint::at_vertex(pairs[s * per_source].source), targets);
        std::printf("   CGAL tree for source %d: %.0f ms\n", pairs[s * per_source].source,
                    ms_since(t1));
        for (int k = 0; k < per_source; ++k) exact[s * per_source + k] = d[k];
      }
      std::printf("   CGAL exact total: %.0f ms\n", ms_since(t));
    }

    std::vector<GeodesicSolver> solvers = {GeodesicSolver::Newton};
    if (lbfgs) solvers.push_back(GeodesicSolver::Lbfgs);
    for (const GeodesicSolver solver : solvers) {
      Row row;
      row.mesh = name;
      row.faces = mesh.num_faces();
      row.solver = solver == GeodesicSolver::Newton ? "Newton" : "L-BFGS";
      GeodesicOptions options;
      options.solver = solver;
      options.steiner_start = steiner > 0 && steiner_start;
      options.two_starts = edge_starts || !options.steiner_start;
      options.split_at_vertices = split;
      options.exact_windows = exact_windows;
      // --by-source: the current source's results and their shares of its thread CPU.
      std::vector<OpenGeodesicResult> group;
      std::vector<double> group_cpu;
      std::size_t group_start = 0;
      for (std::size_t i = 0; i < pairs.size(); ++i) {
        // (Pairs come in runs of one source: a run ends where the last group's results do.)
        if (by_source && i == group_start + group.size()) {
          group_start = i;
          std::size_t end = i;
          while (end < pairs.size() && pairs[end].source == pairs[i].source) ++end;
          std::vector<SurfacePoint> targets;
          for (std::size_t k = i; k < end; ++k)
            targets.push_back(SurfacePoint::at_vertex(pairs[k].target));
          double total = std::numeric_limits<double>::infinity();
          for (int rep = 0; rep < repeat; ++rep) {
            const double c0 = thread_cpu_ms();
            std::vector<OpenGeodesicResult> g =
                geodesics_from(ctx, SurfacePoint::at_vertex(pairs[i].source), targets, options);
            const double c = thread_cpu_ms() - c0;
            if (c < total) {
              total = c;
              group = std::move(g);
            }
          }
          double wall = 0.0;
          for (const OpenGeodesicResult& g : group) wall += g.init_ms + g.refine_ms;
          group_cpu.clear();
          for (const OpenGeodesicResult& g : group)
            group_cpu.push_back(wall > 0.0 ? total * (g.init_ms + g.refine_ms) / wall
                                           : total / group.size());
        }
        double cpu = 0.0;
        OpenGeodesicResult r;
        if (by_source) {
          r = group[i - group_start];
          cpu = group_cpu[i - group_start];
        } else {
          cpu = thread_cpu_ms();
          r = geodesic_between(ctx, SurfacePoint::at_vertex(pairs[i].source),
                               SurfacePoint::at_vertex(pairs[i].target), options);
          cpu = thread_cpu_ms() - cpu;
        }
        for (int rep = 1; rep < repeat && !by_source; ++rep) {
          double cpu2 = thread_cpu_ms();
          const OpenGeodesicResult again =
              geodesic_between(ctx, SurfacePoint::at_vertex(pairs[i].source),
                               SurfacePoint::at_vertex(pairs[i].target), options);
          cpu = std::min(cpu, thread_cpu_ms() - cpu2);
          r.init_ms = std::min(r.init_ms, again.init_ms);
          r.refine_ms = std::min(r.refine_ms, again.refine_ms);
        }
        row.run.cpu.push_back(cpu);
        row.run.exact_ms.push_back(r.exact_ms);
        row.run.windows.push_back(static_cast<double>(r.exact_windows));
        if (r.start == 4) {
          // What the window search gives that the local starts alone (untimed, for this
          // column) miss: the local result on the same corridor, not converged tightly
          // enough, or a locally shortest geodesic in another corridor.
          GeodesicOptions local = options;
          local.exact_windows = false;
          const OpenGeodesicResult l =
              geodesic_between(ctx, SurfacePoint::at_vertex(pairs[i].source),
                               SurfacePoint::at_vertex(pairs[i].target), local);
          const double gap = polyline_gap(polyline(mesh, l.path), polyline(mesh, r.path));
          const double len = r.summary.final_length;
          if ((l.summary.final_length - len) / len > 1e-9) {
            ++row.run.corrected;
            notes.push_back(
                name + " local starts missed " + std::to_string(pairs[i].source) + "->" +
                std::to_string(pairs[i].target) + ": local excess " +
                fmt((l.summary.final_length - len) / len) + " (" +
                std::to_string(l.summary.pinned_vertices) + " vertices passed, start " +
                std::to_string(l.start) + "), exact " + std::to_string(r.summary.pinned_vertices) +
                " vertices passed; paths apart by " + fmt(gap / len) + " of the length: " +
                (gap < 1e-6 * len ? "same corridor (precision)" : "other corridor"));
          }
        }
        row.run.init.push_back(r.init_ms);
        row.run.refine.push_back(r.refine_ms);
        row.run.total.push_back(r.init_ms + r.refine_ms);
        row.run.iterations.push_back(r.summary.iterations);
        row.run.length.push_back(r.summary.final_length);
        if (!r.summary.converged()) {
          ++row.run.not_converged;
          row.run.failures.push_back(std::to_string(pairs[i].source) + "->" +
                                     std::to_string(pairs[i].target) + ": " +
                                     r.summary.brief_report());
        }
        if (std::isfinite(exact[i])) {
          const double e = (r.summary.final_length - exact[i]) / exact[i];
          row.excess.push_back(e);
          if (e > 1e-9) {
            notes.push_back(name + " " + row.solver + " " + std::to_string(pairs[i].source) + "->" +
                            std::to_string(pairs[i].target) + ": excess " + fmt(e) + " (" +
                            fmt(r.summary.final_length, "%.9g") + " vs exact " +
                            fmt(exact[i], "%.9g") + ", " + to_string(r.summary.termination) + ", " +
                            std::to_string(r.summary.reroutes) + " reroutes, " +
                            std::to_string(r.summary.pinned_vertices) + " vertices passed, start " +
                            std::to_string(r.start) + ", window search " +
                            (r.exact_complete ? "complete, " : "incomplete, ") +
                            std::to_string(r.exact_windows) + " windows)");
          } else if (e < -1e-9) {
            notes.push_back(name + " " + row.solver + " " + std::to_string(pairs[i].source) + "->" +
                            std::to_string(pairs[i].target) + ": SHORTER than exact, excess " +
                            fmt(e));
          }
        }
      }
      row.pairs = static_cast<int>(pairs.size());
      for (const std::filesystem::path& dir : best_of) {
        std::ifstream in(dir / (name + ".times"));
        for (std::size_t i = 0; i < pairs.size(); ++i) {
          int s0 = -1, t0 = -1;
          double len = 0.0, ms = 0.0;
          if (!(in >> s0 >> t0 >> len >> ms) || s0 != pairs[i].source || t0 != pairs[i].target) {
            std::fprintf(stderr, "%s: pair %zu does not match\n", (dir / (name + ".times")).c_str(),
                         i);
            return 1;
          }
          row.run.cpu[i] = std::min(row.run.cpu[i], ms);
        }
      }
      if (!write_times.empty()) {
        std::ofstream out(write_times / (name + ".times"));
        char buf[96];
        for (std::size_t i = 0; i < pairs.size(); ++i) {
          std::snprintf(buf, sizeof buf, "%d %d %.17g %.6f\n", pairs[i].source, pairs[i].target,
                        row.run.length[i], row.run.cpu[i]);
          out << buf;
        }
      }
      if (!reference.empty()) {
        std::vector<double> ours_equal_cpu;
        int ours_equal = 0, other_equal = 0;
        for (std::size_t i = 0; i < pairs.size(); ++i) {
          if ((row.run.length[i] - exact[i]) / exact[i] <= 1e-9) ++ours_equal;
          if ((other_length[i] - exact[i]) / exact[i] <= 1e-9) ++other_equal;
        }
        const double ours_med = quantile(row.run.cpu, 0.5), other_med = quantile(other_ms, 0.5);
        const double ours_mean = mean_of(row.run.cpu), other_mean = mean_of(other_ms);
        side.push_back(
            "| " + name + " | " + std::to_string(mesh.num_faces()) + " | " + fmt(ours_med) + " / " +
            fmt(ours_mean) + " / " + fmt(quantile(row.run.cpu, 0.9)) + " | " + fmt(other_med) +
            " / " + fmt(other_mean) + " / " + fmt(quantile(other_ms, 0.9)) + " | " +
            fmt(ours_med / other_med, "%.2f") + " / " + fmt(ours_mean / other_mean, "%.2f") +
            " | " + std::to_string(ours_equal) + " / " + std::to_string(pairs.size()) + " | " +
            std::to_string(other_equal) + " / " + std::to_string(pairs.size()) + " |");
      }
      for (const std::string& f : row.run.failures)
        notes.push_back(name + " " + row.solver + " not converged " + f);
      rows.push_back(std::move(row));
    }
  }

  std::printf(
      "\n| mesh | faces | solver | init ms (med / p90) | refine ms (med / p90) | "
      "total ms (med / p90) | thread CPU ms per path (med / mean) | window search ms (med / p90) | "
      "windows (med / p90) | local starts alone missed | iterations (med / p90) | not conv. | "
      "exact pairs | "
      "excess median | excess max | equal to exact (1e-9) | within 1e-4 |\n");
  std::printf(
      "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Row& r : rows) {
    int within = 0, equal = 0;
    for (double e : r.excess) {
      if (e <= 1e-4) ++within;
      if (e <= 1e-9) ++equal;
    }
    double mean_cpu = 0.0;
    for (double c : r.run.cpu) mean_cpu += c / std::max<std::size_t>(1, r.run.cpu.size());
    const bool have = !r.excess.empty();
    std::printf(
        "| %s | %d | %s | %s / %s | %s / %s | %s / %s | %s / %s | %s / %s | %s / %s | %d | %s / %s "
        "| "
        "%d | %d | %s | %s | "
        "%s | %s |\n",
        r.mesh.c_str(), r.faces, r.solver.c_str(), fmt(quantile(r.run.init, 0.5)).c_str(),
        fmt(quantile(r.run.init, 0.9)).c_str(), fmt(quantile(r.run.refine, 0.5)).c_str(),
        fmt(quantile(r.run.refine, 0.9)).c_str(), fmt(quantile(r.run.total, 0.5)).c_str(),
        fmt(quantile(r.run.total, 0.9)).c_str(), fmt(quantile(r.run.cpu, 0.5)).c_str(),
        fmt(mean_cpu).c_str(), fmt(quantile(r.run.exact_ms, 0.5)).c_str(),
        fmt(quantile(r.run.exact_ms, 0.9)).c_str(),
        fmt(quantile(r.run.windows, 0.5), "%.0f").c_str(),
        fmt(quantile(r.run.windows, 0.9), "%.0f").c_str(), r.run.corrected,
        fmt(quantile(r.run.iterations, 0.5), "%.0f").c_str(),
        fmt(quantile(r.run.iterations, 0.9), "%.0f").c_str(), r.run.not_converged,
        static_cast<int>(r.excess.size()),
        have ? fmt(quantile(r.excess, 0.5), "%.1e").c_str() : "-",
        have ? fmt(quantile(r.excess, 1.0), "%.1e").c_str() : "-",
        have ? (std::to_string(equal) + "/" + std::to_string(r.excess.size())).c_str() : "-",
        have ? (std::to_string(within) + "/" + std::to_string(r.excess.size())).c_str() : "-");
  }
  if (!side.empty()) {
    std::printf(
        "\n| mesh | faces | windplan thread CPU ms per path (median / mean / p90) | reference "
        "(FlipOut) ms (median / mean / p90) | ratio (median / mean) | windplan equal to exact "
        "(1e-9) | reference equal to exact |\n|---|---:|---:|---:|---:|---:|---:|\n");
    for (const std::string& l : side) std::printf("%s\n", l.c_str());
  }
  if (!notes.empty()) {
    std::printf("\nnotes:\n");
    for (const std::string& n : notes) std::printf("- %s\n", n.c_str());
  }
  std::printf("\n# load average at end: %.2f\n", load_average());
  return 0;
}
