// geodesic_between and its context (declared in geometry/geodesic.h): the start corridors of an
// open geodesic and the choice among their refinements (the refinement is geometry/geodesic.cpp).
#include "geometry/geodesic.h"

#include <chrono>
#include <cmath>
#include <limits>

#include "geometry/errors.h"
#include "geometry/geodesic_windows.h"

namespace windplan {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// The refinements of the start corridors (see GeodesicOptions), the best one kept.
OpenGeodesicResult best_of_starts(const GeodesicContext& context, const SurfacePoint& a,
                                  const SurfacePoint& b, const GeodesicOptions& options,
                                  const EdgePathOptions& edge_options);

// Rounds of split_at_vertices (each one only while the path gets shorter).
constexpr int kSplitRounds = 3;

// split_at_vertices: the legs between the vertices the path passes, solved on their own.
void split_at_passed_vertices(const GeodesicContext& context, const SurfacePoint& a,
                              const SurfacePoint& b, const GeodesicOptions& options,
                              const EdgePathOptions& edge_options, OpenGeodesicResult* result);

// The exact window search (unbounded, searched as A*) and the refinement of the shortest
// path's corridor it returns: the globally shortest geodesic. False, with *exact the
// search's distance when it has one (else NaN), when the search stopped at
// options.max_windows, could not build its corridor, or the corridor's refinement did not
// converge (the result then holds that refinement, if any).
// \throw InputError when the vertices lie on different components.
bool exact_window_search(const GeodesicContext& context, int a, int b,
                         const GeodesicOptions& options, OpenGeodesicResult* result,
                         double* exact) {
  WindowSearchOptions search;
  search.max_windows = options.max_windows;
  const WindowSearchResult w = shortest_path_by_windows(context.mesh(), context.window_mesh(), a, b,
                                                        search, &context.landmarks());
  result->exact_windows = w.windows;
  result->exact_ms = w.time_ms;
  result->init_ms = w.time_ms;
  result->start = 4;
  *exact = w.complete && std::isfinite(w.distance) ? w.distance
                                                   : std::numeric_limits<double>::quiet_NaN();
  if (!w.found && w.complete && !std::isfinite(w.distance)) {
    throw InputError("no path from " + to_string(context.mesh(), SurfacePoint::at_vertex(a)) +
                     " to " + to_string(context.mesh(), SurfacePoint::at_vertex(b)) +
                     ": the points lie on different components of the mesh");
  }
  if (!w.found) return false;
  const auto t0 = Clock::now();
  GeodesicResult r = refine_path(context.mesh(), w.path, context.metric(), options);
  result->refine_ms = ms_since(t0);
  const bool at_distance = std::abs(r.summary.final_length - w.distance) <= 1e-12 * w.distance;
  // A refinement stopped by its reroute or iteration limits on the exact corridor, at the
  // window search's distance, is the global minimum: converged in the sense that matters.
  if (!r.summary.converged() && at_distance) {
    r.summary.message = std::string("stopped (") + to_string(r.summary.termination) +
                        ") at the exact window distance";
    r.summary.termination = GeodesicTermination::Converged;
  }
  result->exact_complete = r.summary.converged() && at_distance;
  result->path = std::move(r.path);
  result->summary = r.summary;
  result->summary.time_ms += w.time_ms;
  result->constraint_variables = std::move(r.constraint_variables);
  return result->summary.converged();
}

}  // namespace

GeodesicContext::GeodesicContext(const Mesh& mesh, PathMetric metric, int steiner_points_per_edge,
                                 int landmarks)
    : mesh_(mesh), metric_(std::move(metric)), steiner_points_per_edge_(steiner_points_per_edge) {
  if (metric_.kind() == PathMetric::Kind::Euclidean) {
    window_mesh_ = prepare_window_mesh(mesh);
    landmarks_ = compute_landmarks(mesh, window_mesh_, landmarks);
  }
}

GeodesicContext::~GeodesicContext() = default;

void GeodesicContext::build_graphs() const {
  std::call_once(graphs_built_, [this] {
    graph_ = build_edge_graph(mesh_, metric_, true);
    plain_graph_ = build_edge_graph(mesh_, metric_, false);
    if (steiner_points_per_edge_ > 0 && metric_.kind() != PathMetric::Kind::Anisotropic) {
      steiner_ = std::make_unique<SteinerGraph>(mesh_, metric_, steiner_points_per_edge_);
    }
  });
}

namespace {

OpenGeodesicResult best_of_starts(const GeodesicContext& context, const SurfacePoint& a,
                                  const SurfacePoint& b, const GeodesicOptions& options,
                                  const EdgePathOptions& edge_options) {
  OpenGeodesicResult result;
  const Mesh& mesh = context.mesh();
  const bool steiner = options.steiner_start && context.steiner_graph() != nullptr;
  std::vector<int> starts;
  if (steiner) starts.push_back(0);
  if (!steiner || options.two_starts) starts.push_back(1);
  if (options.two_starts && !context.graph().via.empty()) starts.push_back(2);
  bool have = false;
  for (const int s : starts) {
    const auto t0 = Clock::now();
    EdgePath edge_path;
    SurfacePath init;
    if (s == 0) {
      const SteinerPath sp = shortest_steiner_path(*context.steiner_graph(), a, b);
      result.steiner_settled = sp.settled;
      if (!sp.found) {
        throw InputError("no path from " + to_string(mesh, a) + " to " + to_string(mesh, b) +
                         ": the points lie on different components of the mesh");
      }
      init = strip_from_steiner_path(*context.steiner_graph(), a, sp, b);
    } else {
      init = initial_open_path(mesh, s == 1 ? context.graph() : context.plain_graph(), a, b,
                               edge_options, &edge_path);
    }
    result.init_ms += ms_since(t0);
    const auto t1 = Clock::now();
    GeodesicResult r = refine_path(mesh, init, context.metric(), options);
    result.refine_ms += ms_since(t1);
    if (!have ||
        (r.summary.converged() &&
         (!result.summary.converged() || r.summary.final_length < result.summary.final_length))) {
      const double time = result.summary.time_ms;
      result.path = std::move(r.path);
      result.summary = r.summary;
      result.summary.time_ms += time;
      result.constraint_variables = std::move(r.constraint_variables);
      result.edge_path = std::move(edge_path);
      result.start = s;
      have = true;
    } else {
      result.summary.time_ms += r.summary.time_ms;
    }
  }
  return result;
}

}  // namespace

OpenGeodesicResult geodesic_between(const GeodesicContext& context, const SurfacePoint& a,
                                    const SurfacePoint& b, const GeodesicOptions& options,
                                    const EdgePathOptions& edge_options) {
  const bool windows = options.exact_windows && !context.window_mesh().pseudo_source.empty() &&
                       a.kind == SurfacePoint::Kind::Vertex &&
                       b.kind == SurfacePoint::Kind::Vertex && a.element != b.element;
  OpenGeodesicResult search;
  double exact = std::numeric_limits<double>::quiet_NaN();
  if (windows) {
    // The window search first, unbounded: it finds the shortest path's corridor by itself
    // (searched as A*), and the local starts would only have given it an upper bound that
    // prunes about the same windows (bench/README.md, session 6).
    if (exact_window_search(context, a.element, b.element, options, &search, &exact)) return search;
    // Stopped by max_windows, or its corridor not refined: the local starts, as without
    // windows.
  }
  OpenGeodesicResult result = best_of_starts(context, a, b, options, edge_options);
  if (options.split_at_vertices && result.summary.converged())
    split_at_passed_vertices(context, a, b, options, edge_options, &result);
  // Neither converged: the shorter path.
  if (!result.summary.converged() && search.summary.final_length > 0.0 &&
      search.summary.final_length < result.summary.final_length) {
    search.init_ms += result.init_ms;
    search.refine_ms += result.refine_ms;
    return search;
  }
  result.exact_windows = search.exact_windows;
  result.exact_ms = search.exact_ms;
  result.init_ms += search.exact_ms;
  // Globally shortest when the complete search's distance confirms it.
  result.exact_complete = result.summary.converged() && std::isfinite(exact) &&
                          std::abs(result.summary.final_length - exact) <= 1e-12 * exact;
  return result;
}

namespace {

void split_at_passed_vertices(const GeodesicContext& context, const SurfacePoint& a,
                              const SurfacePoint& b, const GeodesicOptions& options,
                              const EdgePathOptions& edge_options, OpenGeodesicResult* out) {
  OpenGeodesicResult& result = *out;
  // A geodesic through a saddle vertex v leaves v in any direction within an angle: the legs
  // a -> v and v -> b are independent shortest-path problems, and each may have a shorter
  // geodesic in another corridor than the one the whole path's strip fixed. Solve the legs
  // between the vertices passed on their own; when they add up to less, join them at the
  // vertices and refine the joined path (it lifts off vertices it need not touch).
  // The joined path may pass other vertices: split again while it gets shorter.
  const Mesh& mesh = context.mesh();
  for (int round = 0; round < kSplitRounds; ++round) {
    const std::vector<VertexPassage> passages = vertex_passages(mesh, result.path);
    if (passages.empty()) break;
    std::vector<SurfacePoint> points{a};
    for (const VertexPassage& p : passages) points.push_back(SurfacePoint::at_vertex(p.vertex));
    points.push_back(b);
    double legs_length = 0.0;
    SurfacePath joined;
    bool legs_ok = true;
    for (std::size_t i = 0; i + 1 < points.size() && legs_ok; ++i) {
      GeodesicOptions leg_options = options;
      leg_options.steiner_start = options.steiner_start || options.steiner_legs;
      const OpenGeodesicResult leg =
          best_of_starts(context, points[i], points[i + 1], leg_options, edge_options);
      result.init_ms += leg.init_ms;
      result.refine_ms += leg.refine_ms;
      result.summary.time_ms += leg.summary.time_ms;
      legs_ok = leg.summary.converged();
      legs_length += leg.summary.final_length;
      joined = i == 0 ? leg.path : join_at_vertex(mesh, joined, leg.path, points[i].element);
      legs_ok = legs_ok && joined.start_face >= 0;
    }
    if (!legs_ok || !(legs_length < result.summary.final_length * (1.0 - 1e-14))) break;
    const auto t0 = Clock::now();
    GeodesicResult r = refine_path(mesh, joined, context.metric(), options);
    result.refine_ms += ms_since(t0);
    result.summary.time_ms += r.summary.time_ms;
    if (!r.summary.converged() || !(r.summary.final_length < result.summary.final_length)) break;
    const double time = result.summary.time_ms;
    result.path = std::move(r.path);
    result.summary = r.summary;
    result.summary.time_ms = time;
    result.constraint_variables = std::move(r.constraint_variables);
    result.start = 3;
  }
}

}  // namespace

}  // namespace windplan
