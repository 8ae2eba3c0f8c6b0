#pragma once
// Options and results of the geodesic core's refinement (geometry/geodesic/refine_path.h) and of
// geodesic_between (geometry/geodesic/geodesic_between.h): solver, tolerances, limits, the summary
// with its termination as data.
#include <string>
#include <vector>

#include "geometry/mesh/surface_path.h"

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
  /// Steiner-point graph (geometry/geodesic/edge_path_steiner.h). It would start in the globally
  /// right corridor if the graph's excess were below the gaps between competing geodesics; it is
  /// not (see GeodesicContext::kDefaultSteinerPoints), so this is off by default. Ignored when the
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
  /// above, the exact window propagation (geometry/geodesic/geodesic_windows.h, searched as A*
  /// towards the target) finds the corridor of the shortest path, which is refined. This makes the
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
  Converged,         ///< gradient (and constraint residual) below tolerance
  ObjectiveStalled,  ///< the objective stopped changing before the gradient test passed
  MaxIterations,
  MaxReroutes,
  LineSearchFailed,
};
const char* to_string(GeodesicTermination t);

struct GeodesicSummary {
  GeodesicTermination termination = GeodesicTermination::Converged;
  std::string message;
  double initial_length = 0.0;    ///< metric-weighted length of the initial path (mm)
  double final_length = 0.0;      ///< metric-weighted length of the result (mm)
  double euclidean_length = 0.0;  ///< plain length of the result (mm)
  int iterations = 0;
  int evaluations = 0;
  int reroutes = 0;                  ///< strip changes around a vertex
  int lifts = 0;                     ///< collapsed vertex runs lifted off a vertex
  int pinned_vertices = 0;           ///< vertices the final path passes through
  int outer_iterations = 0;          ///< constraint (augmented Lagrangian) rounds
  double constraint_residual = 0.0;  ///< max |r| over the path points (mm for planes)
  double projected_gradient = 0.0;   ///< final max normalised projected gradient
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

}  // namespace windplan
