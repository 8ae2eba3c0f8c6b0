#pragma once
// The geodesic core: refines a surface path into an as-short-as-possible path.
//
// After Liu, Chen, Xin, He, Liu, Zhao, "An Optimization-Driven Approach for Computing Geodesic
// Paths on Triangle Meshes" (eq. 1-8, Algorithm 1). The path is the sequence of edges it crosses
// (geometry/surface_path.h); the crossing parameters l_i in [0, 1] minimise the total length under
// a per-face metric (geometry/path_metric.h: Euclidean, density, anisotropic) plus penalty terms
// for constraints (geometry/path_constraint.h). When l_i reaches 0 or 1 the path touches a vertex;
// the face strip is then rerouted around that vertex when the path wants to pass it on the other
// side (for the Euclidean metric: the angle on the current side is >= pi and the angle on the
// other side is < pi), lifted off the vertex when the current side's angle is < pi, and otherwise
// pinned there (a geodesic through a saddle vertex).
//
// Beyond the paper: inside a fixed strip the objective is convex with a tridiagonal Hessian
// (cyclic for loops; bordered by the constraint's extra variables), so a projected Newton step
// costs O(k) for k crossings and converges quadratically. Solver::Newton is the default;
// Solver::Lbfgs is the paper's projected L-BFGS.
//
// Globally shortest (geodesic_between, Euclidean metric, both endpoints at vertices): the
// refinement only finds the locally shortest geodesic of the corridor it starts in, and the
// local starts (two edge-graph paths, the legs between the vertices passed) missed the global
// one on 4 to 10 of 50 random pairs per benchmark mesh, every time in another corridor (8e-6
// to 9e-2 of the length away), so no tighter tolerance could help. An exact window
// propagation (geometry/geodesic_windows.h: Chen-Han/ICH windows that cut each other per edge,
// searched as A* towards the target) therefore runs first and returns the shortest path's
// corridor, which the refinement straightens; the local starts are the fallback past
// GeodesicOptions::max_windows or when that refinement does not converge. 50 of 50 pairs are
// exact on all four benchmark meshes at 0.23-0.42x FlipOut's median time per path
// (bench/README.md, session 6).
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "geometry/edge_path.h"
#include "geometry/edge_path_steiner.h"
#include "geometry/geodesic_windows.h"
#include "geometry/mesh.h"
#include "geometry/path_constraint.h"
#include "geometry/path_metric.h"
#include "geometry/surface_path.h"

namespace windplan {

enum class GeodesicSolver { Newton, Lbfgs };

/// How the penalty weight M is chosen for constraints.
enum class PenaltyMode {
  /// The paper's rule: M fixed so that the initial penalty is about 10x the length.
  Paper,
  /// Augmented Lagrangian with an increasing M until the residual is below tolerance (default).
  AugmentedLagrangian,
};

struct GeodesicOptions {
  GeodesicSolver solver = GeodesicSolver::Newton;
  /// Stop when every free crossing's projected gradient, divided by its edge length, is below
  /// this (dimensionless: the sine of the kink angle, times the density).
  double gradient_tolerance = 1e-10;
  /// Stop also when the relative objective change of an iteration is below this, twice in a row.
  double objective_tolerance = 1e-15;
  int max_iterations = 2000;
  /// Paths without constraints under the Euclidean metric: start from the exact shortest path
  /// in the strip (funnel algorithm on the unfolded strip, alternated with reroutes; loops are
  /// straightened with one crossing held at a time, alternating between two of them).
  bool funnel_start = true;
  /// geodesic_between: also refine whole paths from the shortest path in the context's
  /// Steiner-point graph (geometry/edge_path_steiner.h). It would start in the globally right
  /// corridor if the graph's excess were below the gaps between competing geodesics; it is not
  /// (see GeodesicContext::kDefaultSteinerPoints), so this is off by default. Ignored when the
  /// context has no Steiner graph.
  bool steiner_start = false;
  /// geodesic_between: also refine from two edge paths (shortest paths in the plain edge graph
  /// and in the graph with unfolded diagonals) and keep the shortest result. Local methods
  /// settle on the geodesic of the corridor they start in; more corridors find the global one
  /// more often. Without a Steiner start, the diagonal graph's start is always made.
  bool two_starts = true;
  /// geodesic_between: when the best path passes vertices, also solve the legs between them on
  /// their own (a geodesic through a saddle vertex may leave it into another corridor) and keep
  /// the joined, refined legs when they are shorter.
  bool split_at_vertices = true;
  /// geodesic_between: the legs of split_at_vertices also start from the Steiner graph (when
  /// the context has one), whatever steiner_start says: legs are short, so their Steiner
  /// search is cheap.
  bool steiner_legs = true;
  /// geodesic_between, Euclidean metric, both endpoints at vertices: instead of the starts
  /// above, the exact window propagation (geometry/geodesic_windows.h, searched as A* towards
  /// the target) finds the corridor of the shortest path, which is refined. This makes the
  /// result the globally shortest geodesic (up to round-off) instead of a locally shortest one.
  bool exact_windows = true;
  /// Upper bound on the windows of that search per query (0: none); past it the local starts
  /// above are made instead (a locally shortest geodesic, exact_complete false). The default
  /// caps a search at about 2 GB (100 bytes per window): the most windows any of 50 random
  /// paths on the 300K-face bunny needs is 4.0M (bench/README.md, session 6).
  long max_windows = 20'000'000;
  /// Upper bound on strip changes (reroutes) before giving up (0: 20 + 4 * crossings).
  int max_reroutes = 0;
  /// L-BFGS memory (pairs).
  int lbfgs_memory = 10;
  // Constraints:
  PenaltyMode penalty_mode = PenaltyMode::AugmentedLagrangian;
  /// Required max |r| relative to the path length for constraints.
  double constraint_tolerance = 1e-9;
  int max_outer_iterations = 30;
  /// Fixed penalty weight (> 0 overrides the automatic choice; units 1/mm).
  double penalty_weight = 0.0;

  bool is_valid(std::string* why) const;
};

enum class GeodesicTermination {
  Converged,             ///< gradient (and constraint residual) below tolerance
  ObjectiveStalled,      ///< the objective stopped changing before the gradient test passed
  MaxIterations,
  MaxReroutes,
  LineSearchFailed,
};
const char* to_string(GeodesicTermination t);

struct GeodesicSummary {
  GeodesicTermination termination = GeodesicTermination::Converged;
  std::string message;
  double initial_length = 0.0;     ///< metric-weighted length of the initial path (mm)
  double final_length = 0.0;       ///< metric-weighted length of the result (mm)
  double euclidean_length = 0.0;   ///< plain length of the result (mm)
  int iterations = 0;
  int evaluations = 0;
  int reroutes = 0;                ///< strip changes around a vertex
  int lifts = 0;                   ///< collapsed vertex runs lifted off a vertex
  int pinned_vertices = 0;         ///< vertices the final path passes through
  int outer_iterations = 0;        ///< constraint (augmented Lagrangian) rounds
  double constraint_residual = 0.0;///< max |r| over the path points (mm for planes)
  double projected_gradient = 0.0; ///< final max normalised projected gradient
  double time_ms = 0.0;
  bool converged() const {
    return termination == GeodesicTermination::Converged ||
           termination == GeodesicTermination::ObjectiveStalled;
  }
  std::string brief_report() const;
};

struct GeodesicResult {
  SurfacePath path;
  GeodesicSummary summary;
  std::vector<double> constraint_variables;  ///< final z of the constraint (e.g. the plane)
};

/// Refines `initial` (open or closed) into a locally shortest path under `metric`, subject to an
/// optional penalty constraint. Endpoints of open paths stay fixed.
/// \throw InputError when the initial path is invalid (see is_valid_path).
GeodesicResult refine_path(const Mesh& mesh, const SurfacePath& initial,
                           const PathMetric& metric = {}, const GeodesicOptions& options = {},
                           PathConstraint* constraint = nullptr);

/// The objective of the refinement on a fixed strip, exposed for diagnostics and for checking
/// the analytic derivatives: value = weighted length + sum_q (mu_q r_q + M/2 r_q^2), gradient
/// over (lambda_0..lambda_{k-1}, z), and the tridiagonal Hessian of the length part plus the
/// Gauss-Newton Hessian of the penalty (diag, off[i] coupling i and i+1, cyclic off[k-1]).
struct PathObjective {
  double value = 0.0;
  double length = 0.0;
  std::vector<double> gradient;
  std::vector<double> hessian_diag, hessian_off;
};
PathObjective evaluate_path_objective(const Mesh& mesh, const SurfacePath& path,
                                      const PathMetric& metric = {},
                                      PathConstraint* constraint = nullptr,
                                      const std::vector<double>& z = {}, double penalty_weight = 0.0,
                                      const std::vector<double>& multipliers = {});

/// A vertex the path passes through, with the angles on its two sides (radians, Euclidean):
/// a locally shortest Euclidean path has both >= pi (Mitchell, Mount, Papadimitriou).
struct VertexPassage {
  int vertex = -1;
  int first_crossing = 0, last_crossing = 0;
  double strip_angle = 0.0;  ///< on the side of the path's face strip
  double other_angle = 0.0;  ///< cone angle minus strip_angle (0 for a boundary vertex)
};
std::vector<VertexPassage> vertex_passages(const Mesh& mesh, const SurfacePath& path);

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
  ///        (geometry/geodesic_windows.h; Euclidean metric only): each costs about one
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
  /// The window search's per-mesh data (geometry/geodesic_windows.h; empty unless the
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
  double init_ms = 0.0;    ///< initial edge path and strip
  double refine_ms = 0.0;  ///< refinement
  EdgePath edge_path;      ///< diagnostics of the initial search (edge starts)
  int steiner_settled = 0; ///< nodes settled by the Steiner search (0 without one)
  /// Which start gave the result: 0 Steiner, 1 diagonal graph, 2 plain graph, 3 the legs
  /// between the vertices passed (split_at_vertices), 4 the exact window search.
  int start = 0;
  double exact_ms = 0.0;   ///< the exact window search (init_ms when it gave the result)
  long exact_windows = 0;  ///< windows it created (0: not run)
  /// The window search ran to its end and the result's length is its distance (to 1e-12): the
  /// globally shortest geodesic.
  bool exact_complete = false;
};

/// Geodesic between two surface points (geometry/geodesic_between.cpp). Between two vertices
/// under the Euclidean metric, the exact window search's corridor, refined
/// (GeodesicOptions::exact_windows); otherwise, or as its fallback, start paths (Steiner
/// graph, edge graphs; see GeodesicOptions::steiner_start, two_starts), their strips,
/// refinement, the shortest converged result kept.
/// \throw InputError if the points lie on different components.
OpenGeodesicResult geodesic_between(const GeodesicContext& context, const SurfacePoint& a,
                                    const SurfacePoint& b, const GeodesicOptions& options = {},
                                    const EdgePathOptions& edge_options = {});

}  // namespace windplan
