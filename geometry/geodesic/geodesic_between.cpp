// geodesic_between and its context: the exact window search first, the local starts
// (start_search.cpp) as its fallback, each refined (refine_path.cpp).
#include "geometry/geodesic/geodesic_between.h"

#include <chrono>
#include <cmath>
#include <limits>

#include "geometry/base/errors.h"
#include "geometry/geodesic/geodesic_windows.h"
#include "geometry/geodesic/start_search.h"

namespace windplan {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// The window search's options from the geodesic's.
WindowSearchOptions window_search_options(const GeodesicOptions& options) {
  WindowSearchOptions search;
  search.max_windows = options.max_windows;
  return search;
}

// The window search's result `w` for the vertices a -> b, refined (as exact_window_search).
bool refine_window_result(const GeodesicContext& context, int a, int b, const WindowSearchResult& w,
                          const GeodesicOptions& options, OpenGeodesicResult* result,
                          double* exact) {
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

// The exact window search (unbounded, searched as A*) and the refinement of the shortest
// path's corridor it returns: the globally shortest geodesic. False, with *exact the
// search's distance when it has one (else NaN), when the search stopped at
// options.max_windows, could not build its corridor, or the corridor's refinement did not
// converge (the result then holds that refinement, if any).
// \throw InputError when the vertices lie on different components.
bool exact_window_search(const GeodesicContext& context, int a, int b,
                         const GeodesicOptions& options, OpenGeodesicResult* result,
                         double* exact) {
  const WindowSearchResult w =
      shortest_path_by_windows(context.mesh(), context.window_mesh(), a, b,
                               window_search_options(options), &context.landmarks());
  return refine_window_result(context, a, b, w, options, result, exact);
}

// geodesic_between after the window search `search` (exact: its distance, or NaN) did not
// give a converged result: the local starts, the shorter result kept.
OpenGeodesicResult after_window_search(const GeodesicContext& context, const SurfacePoint& a,
                                       const SurfacePoint& b, const GeodesicOptions& options,
                                       const EdgePathOptions& edge_options,
                                       OpenGeodesicResult search, double exact) {
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
  return after_window_search(context, a, b, options, edge_options, std::move(search), exact);
}

std::vector<OpenGeodesicResult> geodesics_from(const GeodesicContext& context,
                                               const SurfacePoint& a,
                                               const std::vector<SurfacePoint>& targets,
                                               const GeodesicOptions& options,
                                               const EdgePathOptions& edge_options) {
  std::vector<OpenGeodesicResult> results(targets.size());
  const bool windows = options.exact_windows && !context.window_mesh().pseudo_source.empty() &&
                       a.kind == SurfacePoint::Kind::Vertex;
  // The vertex targets other than a: one window search, resumed from target to target.
  std::vector<int> at, vertices;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (windows && targets[i].kind == SurfacePoint::Kind::Vertex &&
        targets[i].element != a.element) {
      at.push_back(static_cast<int>(i));
      vertices.push_back(targets[i].element);
    } else {
      results[i] = geodesic_between(context, a, targets[i], options, edge_options);
    }
  }
  if (vertices.empty()) return results;
  const std::vector<WindowSearchResult> found =
      shortest_paths_by_windows(context.mesh(), context.window_mesh(), a.element, vertices,
                                window_search_options(options), &context.landmarks());
  for (std::size_t k = 0; k < at.size(); ++k) {
    OpenGeodesicResult r;
    double exact = std::numeric_limits<double>::quiet_NaN();
    const SurfacePoint& b = targets[at[k]];
    results[at[k]] =
        refine_window_result(context, a.element, b.element, found[k], options, &r, &exact)
            ? std::move(r)
            : after_window_search(context, a, b, options, edge_options, std::move(r), exact);
  }
  return results;
}

}  // namespace windplan
