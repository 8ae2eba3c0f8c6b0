#pragma once
// The local refinement of the geodesic core (Liu et al., eq. 1-8, Algorithm 1): a surface path
// refined into a locally shortest path of its corridor (see geometry/geodesic/geodesic.h for the
// method; refiner.h for how the implementation is split).
#include <vector>

#include "geometry/geodesic/geodesic_options.h"
#include "geometry/geodesic/path_constraint.h"
#include "geometry/geodesic/path_metric.h"
#include "geometry/mesh/mesh.h"
#include "geometry/mesh/surface_path.h"

namespace windplan {

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
                                      const std::vector<double>& z = {},
                                      double penalty_weight = 0.0,
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

}  // namespace windplan
