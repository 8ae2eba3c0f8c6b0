// windplan geodesic / windplan loop: the geodesic core (geometry/geodesic/geodesic.h) on the
// command line. A geodesic between two surface points, or a closed geodesic loop refined from a
// curve, under the Euclidean, a density or an anisotropic metric; the result as text, JSON or CSV.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>

#include "cli/args.h"
#include "cli/commands.h"
#include "cli/pairs_reader.h"
#include "cli/progress.h"
#include "export/files/csv.h"
#include "geometry/base/atomic_file.h"
#include "geometry/base/errors.h"
#include "geometry/base/json.h"
#include "geometry/base/parallel.h"
#include "geometry/geodesic/edge_path.h"
#include "geometry/geodesic/exact_geodesic.h"
#include "geometry/geodesic/geodesic.h"
#include "geometry/mesh/closest_point.h"
#include "geometry/mesh/mesh_io.h"
#include "geometry/mesh/mesh_validation.h"
#include "planner/job/job.h"
#include "planner/mandrel/mandrel_builder.h"

namespace windplan::cli {

#define WINDPLAN_GEODESIC_COMMON_HELP                                                              \
  "Mesh: a mesh file (OBJ, PLY, STL, OFF; loaded as is, not repaired, so vertex indices are\n"     \
  "the file's) or a job file (.yaml/.yml: its mandrel, in mm).\n"                                  \
  "\n"                                                                                             \
  "options:\n"                                                                                     \
  "  --density FILE     density metric: one value rho > 0 per face (whitespace separated, in\n"    \
  "                     face order); the length of a segment in face f is rho_f times |w|\n"       \
  "  --metric FILE      anisotropic metric: three values a b c per face, the symmetric positive\n" \
  "                     definite [[a, b], [b, c]] in the face frame (e1 along the face's first\n"  \
  "                     edge, e2 = n x e1); cannot be combined with --density\n"                   \
  "  --solver NAME      newton (default: projected Newton) or lbfgs (the paper's L-BFGS)\n"        \
  "  --snap-tolerance MM  largest distance of a given point from the mesh (default: 1e-3 times\n"  \
  "                     the bounding-box diagonal)\n"                                              \
  "  --json             print one JSON object: length, initial_length, euclidean_length,\n"        \
  "                     iterations, reroutes, termination, time_ms (= init_ms + refine_ms),\n"     \
  "                     init_ms, refine_ms, setup_ms and points (the polyline, [x, y, z])\n"       \
  "  -o FILE            write the polyline as CSV: x [mm], y [mm], z [mm]\n"                       \
  "  -h, --help         this text\n"                                                               \
  "\n"                                                                                             \
  "Exit codes: 0 ok (also when the solver did not converge: see termination), 1 bad input\n"       \
  "(missing file, a point far from the mesh, a vertex out of range, endpoints on different\n"      \
  "components, a density <= 0, a metric that is not positive definite), 2 usage error.\n"

const char* const kGeodesicHelp =
    "usage: windplan geodesic <mesh | job.yaml> --from <vertex | x,y,z> --to <vertex | x,y,z>\n"
    "                         [--density faces.txt | --metric faces.txt] [--solver newton|lbfgs]\n"
    "                         [--json] [-o path.csv]\n"
    "       windplan geodesic <mesh | job.yaml> --pairs pairs.txt [--json] [-o table]\n"
    "                         [--threads N] [--landmarks L] [--density ... | --metric ...]\n"
    "                         [--solver ...]\n"
    "\n"
    "Computes a geodesic path between two surface points. Between two vertices under the\n"
    "Euclidean metric it is the globally shortest one: an exact window search (A* towards the\n"
    "target) finds its corridor of faces. Otherwise it is a locally shortest one, from the\n"
    "shortest paths along mesh edges turned into strips of faces. Either strip is refined over\n"
    "its edge crossings (Liu et al., an optimization-driven approach for geodesic paths on\n"
    "triangle meshes). A point is a vertex index (0-based) or x,y,z (mm), projected to the\n"
    "closest surface point.\n"
    "\n"
    "  --pairs FILE       batch: one pair per line, 'FROM TO' separated by spaces or a tab,\n"
    "                     each a vertex index or x,y,z (no spaces inside); blank lines and lines\n"
    "                     starting with '#' are skipped. The mesh is loaded once and the pairs\n"
    "                     are solved in parallel (--threads N, default all cores). One row per\n"
    "                     pair, in file order: CSV (header line, from, to, length, ...) or with\n"
    "                     --json one JSON object per line; to stdout or to -o FILE. Columns /\n"
    "                     keys: line (of the pairs file), from, to, length (17 significant\n"
    "                     digits), euclidean_length, converged, termination, iterations,\n"
    "                     reroutes, pinned_vertices, crossings, time_ms (that pair's solve, wall\n"
    "                     time; the only column that differs between runs). A bad line (text,\n"
    "                     a vertex out of range, a point off the mesh) names the file and line,\n"
    "                     exits 1 and writes nothing.\n"
    "  --landmarks L      exact distance fields from L vertices (0..64, default 0), built once\n"
    "                     (in parallel) and used to bound the window search: each costs a few\n"
    "                     long queries, and shortens the later ones (on the kitten, 8 landmarks\n"
    "                     take 7.3 s on 2 cores and cut the median path from 31 to 15.5 ms:\n"
    "                     worth it past about 500 pairs; Euclidean metric only). Each field\n"
    "                     is a full window propagation holding only its wavefront: at 300K\n"
    "                     faces 8 fields took 35 s on 2 threads, 0.56 GB (bench/README.md)\n"
    "  --exact            also compute the exact polyhedral geodesic distance (CGAL, Euclidean\n"
    "                     metric only; seconds and GBs above 100K faces) and the relative\n"
    "                     excess (length - exact) / exact; JSON keys exact_length, excess\n"
    "\n" WINDPLAN_GEODESIC_COMMON_HELP;

const char* const kLoopHelp =
    "usage: windplan loop <mesh | job.yaml> --init curve.csv\n"
    "                     [--density faces.txt | --metric faces.txt] [--solver newton|lbfgs]\n"
    "                     [--json] [-o loop.csv]\n"
    "       windplan loop <mesh | job.yaml> --curves curves.txt [--json] [-o table]\n"
    "                     [--threads N] [--density ... | --metric ...] [--solver ...]\n"
    "\n"
    "Refines a closed curve into a closed geodesic loop. The curve file holds one point x,y,z\n"
    "(mm) per line, comma or space separated, first point not repeated at the end; an optional\n"
    "header line and lines starting with '#' are skipped. Each point is snapped to the surface,\n"
    "consecutive points are joined by shortest edge paths, and the closed strip is refined.\n"
    "\n"
    "  --curves FILE      batch: one closed curve per line, its points x,y,z separated by spaces\n"
    "                     (at least 3); blank lines and lines starting with '#' are skipped. The\n"
    "                     mesh is loaded once and the loops are refined in parallel (--threads N,\n"
    "                     default all cores). One row per curve, in file order, as for\n"
    "                     'windplan geodesic --pairs' (CSV or --json lines, to stdout or -o\n"
    "                     FILE), with the column points (the curve's point count) instead of\n"
    "                     from, to. A bad line names the file and line, exits 1, writes nothing.\n"
    "\n" WINDPLAN_GEODESIC_COMMON_HELP;

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// %.17g: every double prints back to itself.
std::string full(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// A mesh file as is (indices kept), or a job's mandrel.
Mesh load_geodesic_mesh(const std::filesystem::path& input) {
  const std::string ext = lower(input.extension().string());
  if (ext == ".yaml" || ext == ".yml") return build_mandrel(load_job(input)).mesh;
  return build_mesh(read_mesh(input), false);
}

/// Whitespace-separated numbers of a file, each with its 1-based line number.
struct NumberToken {
  double value;
  int line;
  std::string text;
};
std::vector<NumberToken> read_numbers(const std::filesystem::path& file) {
  const std::string text = read_text_file(file);
  std::vector<NumberToken> out;
  std::istringstream in(text);
  std::string line;
  int no = 0;
  while (std::getline(in, line)) {
    ++no;
    std::istringstream ls(line);
    std::string tok;
    while (ls >> tok) {
      if (tok[0] == '#') break;
      double v = 0.0;
      if (!parse_double(tok, &v)) {
        throw InputError(file.string() + ":" + std::to_string(no) + ": '" + tok +
                         "' is not a number");
      }
      out.push_back({v, no, tok});
    }
  }
  return out;
}

std::string where(const std::filesystem::path& file, const NumberToken& t) {
  return file.string() + ":" + std::to_string(t.line);
}

PathMetric load_density(const Mesh& mesh, const std::filesystem::path& file) {
  const std::vector<NumberToken> v = read_numbers(file);
  const int F = mesh.num_faces();
  if (static_cast<int>(v.size()) != F) {
    const std::string at =
        v.size() > static_cast<std::size_t>(F)
            ? where(file, v[F]) + ": value " + std::to_string(F + 1) + " is one too many"
            : file.string() + ": ends after " + std::to_string(v.size()) + " values";
    throw InputError(at + ": a density file needs one value per face, the mesh has " +
                     std::to_string(F) + " faces (found " + std::to_string(v.size()) + ")");
  }
  std::vector<double> rho(F);
  for (int f = 0; f < F; ++f) {
    if (!(std::isfinite(v[f].value) && v[f].value > 0.0)) {
      throw InputError(where(file, v[f]) + ": density of face " + std::to_string(f) + " is " +
                       v[f].text + "; it must be a finite number > 0");
    }
    rho[f] = v[f].value;
  }
  return PathMetric::density(mesh, std::move(rho));
}

PathMetric load_anisotropic(const Mesh& mesh, const std::filesystem::path& file) {
  const std::vector<NumberToken> v = read_numbers(file);
  const int F = mesh.num_faces();
  if (v.size() != 3 * static_cast<std::size_t>(F)) {
    const std::string at =
        v.size() > 3 * static_cast<std::size_t>(F)
            ? where(file, v[3 * static_cast<std::size_t>(F)]) + ": value " +
                  std::to_string(3 * F + 1) + " is one too many"
            : file.string() + ": ends after " + std::to_string(v.size()) + " values";
    throw InputError(at + ": a metric file needs three values (a b c) per face, the mesh has " +
                     std::to_string(F) + " faces, so " + std::to_string(3 * F) + " values (found " +
                     std::to_string(v.size()) + ")");
  }
  std::vector<std::array<double, 3>> abc(F);
  for (int f = 0; f < F; ++f) {
    const double a = v[3 * f].value, b = v[3 * f + 1].value, c = v[3 * f + 2].value;
    if (!(std::isfinite(a) && std::isfinite(b) && std::isfinite(c) && a > 0.0 &&
          a * c - b * b > 0.0)) {
      throw InputError(where(file, v[3 * f]) + ": the metric of face " + std::to_string(f) + " [[" +
                       v[3 * f].text + ", " + v[3 * f + 1].text + "], [" + v[3 * f + 1].text +
                       ", " + v[3 * f + 2].text +
                       "]] is not symmetric positive definite (needs a > 0 and a c - b^2 > 0)");
    }
    abc[f] = {a, b, c};
  }
  return PathMetric::anisotropic(mesh, abc);
}

/// The curve of `loop --init`: x,y,z per line.
std::vector<Vec3> read_curve(const std::filesystem::path& file) {
  const std::string text = read_text_file(file);
  std::istringstream in(text);
  std::string line;
  std::vector<Vec3> points;
  int no = 0;
  while (std::getline(in, line)) {
    ++no;
    for (char& c : line)
      if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
    std::istringstream ls(line);
    std::vector<std::string> toks;
    std::string tok;
    while (ls >> tok) toks.push_back(tok);
    if (toks.empty() || toks[0][0] == '#') continue;
    Vec3 p;
    bool ok = toks.size() == 3;
    for (int k = 0; ok && k < 3; ++k) ok = parse_double(toks[k], &p[k]) && std::isfinite(p[k]);
    if (!ok) {
      double d = 0.0;
      if (points.empty() && !parse_double(toks[0], &d)) continue;  // a header line
      throw InputError(file.string() + ":" + std::to_string(no) +
                       ": expected three finite numbers x,y,z, got '" + line + "'");
    }
    points.push_back(p);
  }
  if (points.size() < 3) {
    throw InputError(file.string() + ": a closed curve needs at least 3 points (found " +
                     std::to_string(points.size()) + ")");
  }
  return points;
}

struct Setup {
  Mesh mesh;
  PathMetric metric;
  GeodesicOptions options;
  double tolerance = 0.0;
  double setup_ms = 0.0;
  int landmarks = 0;  ///< --landmarks (GeodesicContext)
};

Setup setup(const Args& args, Clock::time_point t0) {
  if (args.has("--density") && args.has("--metric")) {
    throw UsageError("give --density or --metric, not both");
  }
  Setup s;
  const std::string solver = args.value("--solver", "newton");
  if (solver == "newton") {
    s.options.solver = GeodesicSolver::Newton;
  } else if (solver == "lbfgs") {
    s.options.solver = GeodesicSolver::Lbfgs;
  } else {
    throw UsageError("--solver must be newton or lbfgs, got '" + solver + "'");
  }
  s.mesh = load_geodesic_mesh(args.positional()[0]);
  if (s.mesh.num_faces() == 0) {
    throw InputError(args.positional()[0] + ": the mesh has no faces");
  }
  if (args.has("--density")) s.metric = load_density(s.mesh, args.value("--density"));
  if (args.has("--metric")) s.metric = load_anisotropic(s.mesh, args.value("--metric"));
  if (args.has("--landmarks")) {
    const double n = args.number("--landmarks", 0.0);
    if (!(n >= 0.0 && n <= 64.0 && n == std::floor(n))) {
      throw UsageError("--landmarks must be a whole number in 0..64, got '" +
                       args.value("--landmarks") + "'");
    }
    if (s.metric.kind() != PathMetric::Kind::Euclidean) {
      throw UsageError("--landmarks bound the Euclidean window search: drop --density/--metric");
    }
    s.landmarks = static_cast<int>(n);
  }
  s.tolerance = 1e-3 * s.mesh.bounding_box().diagonal_length();
  if (args.has("--snap-tolerance")) {
    s.tolerance = args.number("--snap-tolerance", s.tolerance);
    if (!(s.tolerance >= 0.0)) throw UsageError("--snap-tolerance must be >= 0");
  }
  s.setup_ms = ms_since(t0);
  return s;
}

const char* metric_name(const PathMetric& m) {
  switch (m.kind()) {
    case PathMetric::Kind::Euclidean:
      return "euclidean";
    case PathMetric::Kind::Density:
      return "density";
    case PathMetric::Kind::Anisotropic:
      return "anisotropic";
  }
  return "?";
}

int report(const Args& args, const Setup& s, const GeodesicResult& r, double init_ms,
           double refine_ms, bool closed, const double* exact = nullptr) {
  const std::vector<Vec3> points = polyline(s.mesh, r.path);
  if (args.has("-o")) {
    CsvTable table;
    table.header = {"x [mm]", "y [mm]", "z [mm]"};
    table.digits = 17;
    for (const Vec3& p : points) table.rows.push_back({p.x(), p.y(), p.z()});
    write_csv_file(args.value("-o"), table);
  }
  const GeodesicSummary& m = r.summary;
  if (args.flag("--json")) {
    JsonWriter j(2, 17);
    j.begin_object();
    j.field("closed", closed);
    j.field("metric", metric_name(s.metric));
    j.field("solver", s.options.solver == GeodesicSolver::Newton ? "newton" : "lbfgs");
    j.field("length", m.final_length);
    j.field("initial_length", m.initial_length);
    j.field("euclidean_length", m.euclidean_length);
    j.field("iterations", m.iterations);
    j.field("reroutes", m.reroutes);
    j.field("pinned_vertices", m.pinned_vertices);
    j.field("termination", to_string(m.termination));
    j.field("converged", m.converged());
    j.field("crossings", r.path.num_crossings());
    j.field("time_ms", init_ms + refine_ms);
    j.field("init_ms", init_ms);
    j.field("refine_ms", refine_ms);
    j.field("setup_ms", s.setup_ms);
    if (exact) {
      j.field("exact_length", *exact);
      j.field("excess", (m.final_length - *exact) / *exact);
    }
    j.key("points").begin_array();
    for (const Vec3& p : points) {
      j.begin_array();
      j.value(p.x()).value(p.y()).value(p.z());
      j.end_array();
    }
    j.end_array();
    if (args.has("-o")) j.field("written", args.value("-o"));
    j.end_object();
    std::cout << j.str() << "\n";
    return 0;
  }
  std::cout << (closed ? "loop" : "geodesic") << ": " << metric_name(s.metric) << " metric, "
            << (s.options.solver == GeodesicSolver::Newton ? "newton" : "lbfgs") << " solver\n"
            << "  length " << full(m.final_length) << " mm (initial " << full(m.initial_length)
            << ", euclidean " << full(m.euclidean_length) << ")\n"
            << "  " << r.path.num_crossings() << " edge crossings, " << points.size() << " points, "
            << m.iterations << " iterations, " << m.reroutes << " reroutes, " << m.pinned_vertices
            << " pinned vertices\n"
            << "  termination: " << to_string(m.termination)
            << (m.message.empty() ? "" : " (" + m.message + ")") << "\n"
            << "  time: init " << init_ms << " ms, refine " << refine_ms << " ms (setup "
            << s.setup_ms << " ms)\n";
  if (exact) {
    std::cout << "  exact (CGAL) " << full(*exact) << " mm, relative excess "
              << (m.final_length - *exact) / *exact << "\n";
  }
  if (args.has("-o")) std::cout << "written: " << args.value("-o") << "\n";
  return 0;
}

/// Batches of at least this many pairs show their progress on stderr.
constexpr int kProgressFromPairs = 1000;

std::vector<BatchLine> batch_lines(const std::filesystem::path& file) {
  return batch_lines_of(read_text_file(file), file.string());
}

std::vector<BatchPair> read_pairs(const std::filesystem::path& file, const Mesh& mesh,
                                  const ClosestPointQuery& query, double tolerance) {
  return read_pairs_of(read_text_file(file), file.string(), mesh, query, tolerance);
}

/// One row of a batch: the input line, its identifying text columns, the result.
struct BatchRow {
  int line = 0;
  std::vector<std::pair<std::string, std::string>> ids;
  GeodesicSummary summary;
  int crossings = 0;
  double time_ms = 0.0;
};

/// The batch table (CSV with a header, or JSON lines), to -o FILE (atomically) or stdout.
int write_batch(const Args& args, const char* command, const char* what,
                const std::vector<BatchRow>& rows, double solve_ms, double setup_ms) {
  std::ostringstream out;
  const bool json = args.flag("--json");
  auto quoted = [](const std::string& t) {
    return t.find(',') == std::string::npos ? t : "\"" + t + "\"";
  };
  if (!json && !rows.empty()) {
    out << "line";
    for (const auto& id : rows.front().ids) out << "," << id.first;
    out << ",length,euclidean_length,converged,termination,iterations,reroutes,"
           "pinned_vertices,crossings,time_ms\n";
  }
  for (const BatchRow& row : rows) {
    const GeodesicSummary& m = row.summary;
    if (json) {
      JsonWriter j(0, 17);
      j.begin_object();
      j.field("line", row.line);
      for (const auto& id : row.ids) j.field(id.first, id.second);
      j.field("length", m.final_length);
      j.field("euclidean_length", m.euclidean_length);
      j.field("converged", m.converged());
      j.field("termination", to_string(m.termination));
      j.field("iterations", m.iterations);
      j.field("reroutes", m.reroutes);
      j.field("pinned_vertices", m.pinned_vertices);
      j.field("crossings", row.crossings);
      j.field("time_ms", row.time_ms);
      j.end_object();
      std::string text = j.str();
      for (char& c : text)
        if (c == '\n') c = ' ';
      out << text << "\n";
    } else {
      out << row.line;
      for (const auto& id : row.ids) out << "," << quoted(id.second);
      out << "," << full(m.final_length) << "," << full(m.euclidean_length) << ","
          << (m.converged() ? "true" : "false") << "," << to_string(m.termination) << ","
          << m.iterations << "," << m.reroutes << "," << m.pinned_vertices << "," << row.crossings
          << "," << full(row.time_ms) << "\n";
    }
  }
  if (args.has("-o")) {
    write_text_atomically(args.value("-o"), out.str());
    std::cerr << "windplan " << command << ": " << rows.size() << " " << what << " in " << solve_ms
              << " ms on up to " << max_threads() << " threads (setup " << setup_ms
              << " ms); written: " << args.value("-o") << "\n";
  } else {
    std::cout << out.str();
  }
  return 0;
}

int run_geodesic_batch(const Args& args, Setup& s) {
  if (args.has("--from") || args.has("--to") || args.flag("--exact")) {
    throw UsageError("--pairs replaces --from/--to; --exact is for single pairs");
  }
  const std::filesystem::path file = args.value("--pairs");
  const ClosestPointQuery query(s.mesh);
  const std::vector<BatchPair> pairs = read_pairs(file, s.mesh, query, s.tolerance);
  const auto t1 = Clock::now();
  const GeodesicContext ctx(s.mesh, s.metric, GeodesicContext::kDefaultSteinerPoints, s.landmarks);
  s.setup_ms += ms_since(t1);
  const int n = static_cast<int>(pairs.size());
  std::vector<OpenGeodesicResult> results(n);
  std::vector<double> times(n, 0.0);
  const auto t2 = Clock::now();
  // Progress for long batches (1e6 pairs took minutes without a word): on a terminal the live
  // line of cli/progress.h, in a log a line every 10 %.
  const bool show = n >= kProgressFromPairs;
  const bool tty = ::isatty(STDERR_FILENO) == 1;
  std::unique_ptr<StageProgress> progress;
  if (show) {
    progress = std::make_unique<StageProgress>(std::cerr, tty, "windplan geodesic");
    progress->start("pairs");
  }
  // The pairs from one vertex are answered together, up to kPairsPerGroup of them in the
  // file's order (geodesics_from: one exact window search resumed from target to target,
  // bench/README.md, session 13); the groups run in parallel. (A fixed group size: the rows
  // do not depend on the thread count, and a file of pairs from one vertex still runs on every
  // thread and shows its progress.)
  constexpr std::size_t kPairsPerGroup = 16;
  std::vector<std::vector<int>> groups;
  std::map<int, std::size_t> open_group;  // vertex -> its group still filling
  for (int i = 0; i < n; ++i) {
    if (pairs[i].a.kind != SurfacePoint::Kind::Vertex) {
      groups.push_back({i});
      continue;
    }
    const auto it = open_group.find(pairs[i].a.element);
    if (it == open_group.end() || groups[it->second].size() >= kPairsPerGroup) {
      open_group[pairs[i].a.element] = groups.size();
      groups.push_back({i});
    } else {
      groups[it->second].push_back(i);
    }
  }
  const int num_groups = static_cast<int>(groups.size());
  // A group's first pair (in the file's order) that has no path, and why.
  std::vector<int> failed(num_groups, -1);
  std::vector<std::string> failure(num_groups);
  std::atomic<int> done{0};
  std::mutex log;
  parallel_for_index(num_groups, [&](int g) {
    const std::vector<int>& group = groups[g];
    std::vector<SurfacePoint> targets;
    for (const int i : group) targets.push_back(pairs[i].b);
    try {
      std::vector<OpenGeodesicResult> r =
          geodesics_from(ctx, pairs[group[0]].a, targets, s.options);
      for (std::size_t k = 0; k < group.size(); ++k) {
        times[group[k]] = r[k].init_ms + r[k].refine_ms;
        results[group[k]] = std::move(r[k]);
      }
    } catch (const InputError& e) {
      // One pair at a time, to name the first that fails (the group's first line when none
      // fails alone).
      failed[g] = group[0];
      failure[g] = e.what();
      for (const int i : group) {
        try {
          results[i] = geodesic_between(ctx, pairs[i].a, pairs[i].b, s.options);
        } catch (const InputError& alone) {
          failed[g] = i;
          failure[g] = alone.what();
          return;
        }
      }
      return;
    }
    if (!show) return;
    const int before = done.fetch_add(static_cast<int>(group.size()));
    const int d = before + static_cast<int>(group.size());
    const int step = std::max(1, n / 1000), tenth = std::max(1, n / 10);
    if (tty && (d / step != before / step || d == n)) progress->count(d, n, "");
    if (!tty && d / tenth != before / tenth && d < n) {
      const std::lock_guard<std::mutex> lock(log);
      std::cerr << "windplan geodesic: " << d << " of " << n << " pairs ("
                << static_cast<long long>(100.0 * d / n) << " %), " << ms_since(t2) / 1000.0
                << " s\n";
    }
  });
  int first = -1;
  std::string why;
  for (int g = 0; g < num_groups; ++g) {
    if (failed[g] >= 0 && (first < 0 || failed[g] < first)) {
      first = failed[g];
      why = failure[g];
    }
  }
  if (first >= 0)
    throw InputError(file.string() + ":" + std::to_string(pairs[first].line) + ": " + why);
  const double solve_ms = ms_since(t2);
  if (progress) progress->finish("pairs", solve_ms / 1000.0, " (" + std::to_string(n) + " pairs)");
  std::vector<BatchRow> rows(n);
  for (int i = 0; i < n; ++i) {
    rows[i] = {pairs[i].line,
               {{"from", pairs[i].from}, {"to", pairs[i].to}},
               results[i].summary,
               results[i].path.num_crossings(),
               times[i]};
  }
  return write_batch(args, "geodesic", "pairs", rows, solve_ms, s.setup_ms);
}

/// `loop --curves`: one closed curve per line, points x,y,z separated by spaces.
struct BatchCurve {
  int line = 0;
  int points = 0;
  SurfacePath init;
};

std::vector<BatchCurve> read_curves(const std::filesystem::path& file, const Mesh& mesh,
                                    const EdgeGraph& graph, double tolerance) {
  std::vector<BatchCurve> curves;
  for (const BatchLine& bl : batch_lines(file)) {
    const int no = bl.number;
    const std::vector<std::string>& toks = bl.tokens;
    const std::string at = file.string() + ":" + std::to_string(no) + ": ";
    std::vector<Vec3> points;
    for (const std::string& t : toks) {
      Vec3 p;
      std::istringstream ps(t);
      std::string part;
      int k = 0;
      bool ok = true;
      while (ok && std::getline(ps, part, ',')) {
        double d = 0.0;
        ok = k < 3 && parse_double(part, &d) && std::isfinite(d);
        if (ok) p[k++] = d;
      }
      if (!ok || k != 3) throw InputError(at + "'" + t + "' is not a point x,y,z");
      points.push_back(p);
    }
    if (points.size() < 3) {
      throw InputError(at + "a closed curve needs at least 3 points x,y,z (found " +
                       std::to_string(points.size()) + ")");
    }
    BatchCurve c;
    c.line = no;
    c.points = static_cast<int>(points.size());
    try {
      c.init = path_from_curve(mesh, graph, points, true, tolerance);
    } catch (const Error& e) {
      throw InputError(at + e.what());
    }
    curves.push_back(std::move(c));
  }
  if (curves.empty()) throw InputError(file.string() + ": no curves (one closed curve per line)");
  return curves;
}

int run_loop_batch(const Args& args, Setup& s) {
  if (args.has("--init")) throw UsageError("give --init or --curves, not both");
  const std::filesystem::path file = args.value("--curves");
  const auto t1 = Clock::now();
  const EdgeGraph graph = build_edge_graph(s.mesh, s.metric);
  s.setup_ms += ms_since(t1);
  const std::vector<BatchCurve> curves = read_curves(file, s.mesh, graph, s.tolerance);
  const int n = static_cast<int>(curves.size());
  std::vector<GeodesicResult> results(n);
  std::vector<double> times(n, 0.0);
  const auto t2 = Clock::now();
  parallel_for_index(n, [&](int i) {
    const auto t = Clock::now();
    results[i] = refine_path(s.mesh, curves[i].init, s.metric, s.options);
    times[i] = ms_since(t);
  });
  const double solve_ms = ms_since(t2);
  std::vector<BatchRow> rows(n);
  for (int i = 0; i < n; ++i) {
    rows[i] = {curves[i].line,
               {{"points", std::to_string(curves[i].points)}},
               results[i].summary,
               results[i].path.num_crossings(),
               times[i]};
  }
  return write_batch(args, "loop", "curves", rows, solve_ms, s.setup_ms);
}

const std::set<std::string> kFlags = {"--json"};
const std::set<std::string> kGeodesicFlags = {"--json", "--exact"};

}  // namespace

int run_geodesic(const std::vector<std::string>& argv) {
  const auto t0 = Clock::now();
  const Args args(argv, kGeodesicFlags,
                  {"--from", "--to", "--density", "--metric", "--solver", "-o", "--snap-tolerance",
                   "--pairs", "--landmarks"});
  args.expect_positional(1, "one mesh file or job file");
  if (args.has("--pairs")) {
    Setup s = setup(args, t0);
    return run_geodesic_batch(args, s);
  }
  if (!args.has("--from") || !args.has("--to")) {
    throw UsageError("--from and --to are required (or --pairs FILE)");
  }
  Setup s = setup(args, t0);
  const ClosestPointQuery query(s.mesh);
  const SurfacePoint a = parse_point(s.mesh, query, s.tolerance, "--from", args.value("--from"));
  const SurfacePoint b = parse_point(s.mesh, query, s.tolerance, "--to", args.value("--to"));
  const auto t1 = Clock::now();
  const GeodesicContext ctx(s.mesh, s.metric, GeodesicContext::kDefaultSteinerPoints, s.landmarks);
  s.setup_ms += ms_since(t1);
  if (args.flag("--exact") && s.metric.kind() != PathMetric::Kind::Euclidean) {
    throw UsageError("--exact compares with the Euclidean exact geodesic: drop --density/--metric");
  }
  const OpenGeodesicResult r = geodesic_between(ctx, a, b, s.options);
  if (args.flag("--exact")) {
    const double exact = exact_geodesic_distance(s.mesh, a, b);
    return report(args, s, r, r.init_ms, r.refine_ms, false, &exact);
  }
  return report(args, s, r, r.init_ms, r.refine_ms, false);
}

int run_loop(const std::vector<std::string>& argv) {
  const auto t0 = Clock::now();
  const Args args(
      argv, kFlags,
      {"--init", "--density", "--metric", "--solver", "-o", "--snap-tolerance", "--curves"});
  args.expect_positional(1, "one mesh file or job file");
  if (args.has("--curves")) {
    Setup s = setup(args, t0);
    return run_loop_batch(args, s);
  }
  if (!args.has("--init")) throw UsageError("--init curve.csv is required (or --curves FILE)");
  Setup s = setup(args, t0);
  const std::vector<Vec3> curve = read_curve(args.value("--init"));
  const auto t1 = Clock::now();
  const EdgeGraph graph = build_edge_graph(s.mesh, s.metric);
  s.setup_ms += ms_since(t1);
  const auto t2 = Clock::now();
  SurfacePath init;
  try {
    init = path_from_curve(s.mesh, graph, curve, true, s.tolerance);
  } catch (const InputError& e) {
    throw InputError(args.value("--init") + ": " + e.what());
  }
  const double init_ms = ms_since(t2);
  const auto t3 = Clock::now();
  const GeodesicResult r = refine_path(s.mesh, init, s.metric, s.options);
  const double refine_ms = ms_since(t3);
  return report(args, s, r, init_ms, refine_ms, true);
}

}  // namespace windplan::cli
