#include "geometry/geodesic/start_search.h"

#include <chrono>
#include <cmath>

#include "geometry/base/errors.h"

namespace windplan {

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// Rounds of split_at_vertices (each one only while the path gets shorter).
constexpr int kSplitRounds = 3;

}  // namespace

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

}  // namespace windplan
