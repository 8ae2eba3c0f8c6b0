#pragma once
// Conformal coordinates of an annulus: a harmonic height h and its conjugate angle theta, which
// map the wound region onto a flat cylinder (h in [0, 1] along it, theta in [0, 2 pi) around it).
// The helices of planner/winding/helix.h are the level sets of theta -/+ 2 pi N h.
//
// h: cotangent-Laplacian harmonic function with h = 0 on loops[0] and h = 1 on loops[1]
// (Dirichlet), solved with Eigen's SimplicialLDLT on the interior vertices.
// theta: the harmonic function with a 2 pi jump across a cut and natural (Neumann) conditions on
// both loops, which is the conjugate of h up to a constant scale (both are harmonic, grad theta is
// orthogonal to grad h and its period is fixed). The cut is a dual path (a chain of faces) from
// loop 0 to loop 1; the jump lives on the halfedges it crosses. theta minimises
//   sum_edges w_ij (theta_j - theta_i + J_ij)^2   (w: cotangent weights, J: +-2 pi on the cut)
// and is stored per vertex plus a per-face corner offset (a multiple of 2 pi), so that inside
// face f the lifted angle is the linear interpolation of theta[v_k] + face_offset[f][k]. Across an
// edge the lifts of the two faces differ by a multiple of 2 pi. theta increases in the direction
// n x grad h (n the outward normal): clockwise about the axis seen from loop 1.
#include <array>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

struct HarmonicCoordinates {
  std::vector<double> height;                      ///< per vertex, in [0, 1] (dimensionless)
  std::vector<double> theta;                       ///< per vertex (radians), one lift
  std::vector<std::array<double, 3>> face_offset;  ///< per face corner: lift offset (radians)
  std::vector<int> cut_faces;                      ///< the dual path of the cut, loop 0 to loop 1
  double conformal_error = 0.0;  ///< area-weighted mean |angle(grad theta, grad h) - 90 deg| (deg)
  double time_ms = 0.0;

  /// Lifted angle of corner k of face f.
  double corner_theta(const Mesh& mesh, int f, int k) const {
    return theta[mesh.triangle(f)[k]] + face_offset[f][k];
  }
};

/// Checks that `annulus` is one component of genus 0 with exactly two boundary loops and that
/// `loops` are those loops (winding-surface vertex indices in boundary order).
/// \throw TopologyError saying what the mesh is instead (components, loops, genus); InputError
///        for loops that are empty or name vertices out of range / not on the boundary.
void check_annulus(const Mesh& annulus, const std::array<std::vector<int>, 2>& loops);

/// Computes h and theta. \throw as check_annulus; TopologyError if the cut cannot be found;
/// InputError if a sparse factorisation fails (degenerate triangles).
HarmonicCoordinates compute_harmonic_coordinates(const Mesh& annulus,
                                                 const std::array<std::vector<int>, 2>& loops);

}  // namespace windplan
