#pragma once
// Isotropic remeshing to a target edge length (CGAL Polygon_mesh_processing::isotropic_remeshing:
// Botsch & Kobbelt, "A remeshing approach to multiresolution modeling", SGP 2004 - split long
// edges, collapse short ones, flip towards valence 6, relax tangentially, project back).
//
// CAD tessellations of cylinders are long thin triangles that hurt geodesic paths and girth
// loops; this evens them out. Faces carry a patch id (e.g. their B-rep face, or wound / not
// wound) that survives remeshing; edges on the mesh boundary and between patches are first split
// to the target length along their straight line, then protected (never moved, split or
// collapsed), so the boundary loops and patch borders keep their place. A first iteration at a
// coarser target (RemeshOptions::coarse_factor) breaks long slivers up cheaply, after their long
// sides were cut into pieces of that target and the slivers into strips; in both passes every
// moved vertex is projected onto the input faces of its own patch. Patches that are manifolds on
// their own are remeshed apart, in parallel, and sewn back along their protected borders: the
// result is the same at any thread count (vessel_unequal's 3 mm remesh: 6.3 s -> 1.7-2.1 s on 2
// threads, bench/README.md session 18).
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

struct RemeshOptions {
  /// Target edge length (mm, > 0).
  double target_edge_length = 1.0;
  /// Remeshing iterations (count, >= 1).
  int iterations = 3;
  /// One iteration at coarse_factor * target_edge_length first (dimensionless, 0 = none, else
  /// > 1): much faster on long slivers, the result as accurate (vertices are projected onto the
  /// input surface in both passes).
  double coarse_factor = 4.0;

  bool is_valid(std::string* why) const;
};

struct RemeshResult {
  Mesh mesh;                    ///< the remeshed surface (mm)
  std::vector<int> face_patch;  ///< per face of `mesh`: the patch id of the input face it came from
  int faces_before = 0;
  int faces_after = 0;
  double time_ms = 0.0;
};

/// Remeshes `mesh` isotropically.
/// \param face_patch one id (>= 0) per face of `mesh` (empty: all in patch 0)
/// \post every output face has the patch of the input face it lies in, and every edge between
///       two patches is a protected border edge: a union of patches has the same boundary loops
///       before and after (up to the splitting of their edges).
/// \throw ConfigError for invalid options; InputError when face_patch has the wrong size or a
///        negative id; TopologyError if the result is not a valid mesh; InvariantError if the
///        patches come out of CGAL broken (a face without a patch, an unprotected patch border).
RemeshResult remesh_isotropic(const Mesh& mesh, const std::vector<int>& face_patch,
                              const RemeshOptions& options = {});

}  // namespace windplan
