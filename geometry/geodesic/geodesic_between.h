#pragma once
// The geodesic between two surface points: the exact window search between vertices under the
// Euclidean metric (geometry/geodesic/geodesic_windows.h), the local starts otherwise or as its
// fallback (geometry/geodesic/start_search.h), each refined (geometry/geodesic/refine_path.h).
#include <memory>
#include <mutex>
#include <vector>

#include "geometry/geodesic/edge_path.h"
#include "geometry/geodesic/edge_path_steiner.h"
#include "geometry/geodesic/geodesic_options.h"
#include "geometry/geodesic/path_metric.h"
#include "geometry/geodesic/refine_path.h"
#include "geometry/geodesic/window_landmarks.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/surface_path.h"

namespace windplan {

/// Reusable state for many queries on one mesh and metric (precompute / query split). Queries
/// may run on several threads at once.
class GeodesicContext {
 public:
  /// Steiner points per edge of the start graph by default. Measured on the 20K bunny
  /// (bench/README.md, session 4): as the start of whole paths the Steiner graph finds the exact
  /// geodesic less often than the two edge starts (k = 1, 2, 3: 34, 36, 35 of 50 against 41) at
  /// 2-6x their time (its excess, ~1e-3, exceeds the gaps between competing geodesics, 1e-6 to
  /// 1e-4); as an extra start for the legs between the vertices a path passes (short, so cheap)
  /// it adds 2 of 50 (k = 2).
  static constexpr int kDefaultSteinerPoints = 2;
  /// Landmarks of the exact window search by default (measured in bench/README.md).
  static constexpr int kDefaultLandmarks = 0;
  /// \param steiner_points_per_edge k of the Steiner graph (0: none; ignored, i.e. none, under
  ///        an anisotropic metric).
  /// \param landmarks exact distance fields of the window search's A* bounds
  ///        (geometry/geodesic/geodesic_windows.h; Euclidean metric only): each costs about one
  ///        single-source exact distance field to build and makes later queries cheaper.
  GeodesicContext(const Mesh& mesh, PathMetric metric = {},
                  int steiner_points_per_edge = kDefaultSteinerPoints,
                  int landmarks = kDefaultLandmarks);
  ~GeodesicContext();
  const Mesh& mesh() const { return mesh_; }
  const PathMetric& metric() const { return metric_; }
  /// The start graphs below are built on first use (thread-safe): queries between vertices
  /// that the window search answers never need them (at 300K faces they cost 230 ms).
  /// The graph with unfolded diagonals (see build_edge_graph).
  const EdgeGraph& graph() const {
    build_graphs();
    return graph_;
  }
  /// The plain edge graph.
  const EdgeGraph& plain_graph() const {
    build_graphs();
    return plain_graph_;
  }
  /// The Steiner-point graph, or nullptr.
  const SteinerGraph* steiner_graph() const {
    build_graphs();
    return steiner_.get();
  }
  /// The window search's per-mesh data (geometry/geodesic/geodesic_windows.h; empty unless the
  /// metric is Euclidean).
  const WindowMesh& window_mesh() const { return window_mesh_; }
  /// The window search's landmarks (count 0: none).
  const Landmarks& landmarks() const { return landmarks_; }

 private:
  void build_graphs() const;

  const Mesh& mesh_;
  PathMetric metric_;
  int steiner_points_per_edge_;
  mutable std::once_flag graphs_built_;
  mutable EdgeGraph graph_, plain_graph_;
  mutable std::unique_ptr<SteinerGraph> steiner_;
  WindowMesh window_mesh_;
  Landmarks landmarks_;
};

struct OpenGeodesicResult : GeodesicResult {
  double init_ms = 0.0;     ///< initial edge path and strip
  double refine_ms = 0.0;   ///< refinement
  EdgePath edge_path;       ///< diagnostics of the initial search (edge starts)
  int steiner_settled = 0;  ///< nodes settled by the Steiner search (0 without one)
  /// Which start gave the result: 0 Steiner, 1 diagonal graph, 2 plain graph, 3 the legs
  /// between the vertices passed (split_at_vertices), 4 the exact window search.
  int start = 0;
  double exact_ms = 0.0;   ///< the exact window search (init_ms when it gave the result)
  long exact_windows = 0;  ///< windows it created (0: not run)
  /// The window search ran to its end and the result's length is its distance (to 1e-12): the
  /// globally shortest geodesic.
  bool exact_complete = false;
};

/// Geodesic between two surface points . Between two vertices
/// under the Euclidean metric, the exact window search's corridor, refined
/// (GeodesicOptions::exact_windows); otherwise, or as its fallback, start paths (Steiner
/// graph, edge graphs; see GeodesicOptions::steiner_start, two_starts), their strips,
/// refinement, the shortest converged result kept.
/// \throw InputError if the points lie on different components.
OpenGeodesicResult geodesic_between(const GeodesicContext& context, const SurfacePoint& a,
                                    const SurfacePoint& b, const GeodesicOptions& options = {},
                                    const EdgePathOptions& edge_options = {});

/// Geodesics from `a` to each of `targets` (results[i] for targets[i]), as geodesic_between
/// gives each, for less work when a is a vertex: the exact window search to the vertex targets
/// is one search resumed from target to target (shortest_paths_by_windows in
/// geometry/geodesic/geodesic_windows.h; bench/README.md, session 13).
/// \throw InputError if a target lies on another component.
std::vector<OpenGeodesicResult> geodesics_from(const GeodesicContext& context,
                                               const SurfacePoint& a,
                                               const std::vector<SurfacePoint>& targets,
                                               const GeodesicOptions& options = {},
                                               const EdgePathOptions& edge_options = {});

}  // namespace windplan
