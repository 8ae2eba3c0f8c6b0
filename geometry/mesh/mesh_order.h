#pragma once
// A mesh renumbered for memory locality: the same surface with its vertices in the order of a
// space-filling curve (Morton's Z-order of their positions) and its faces in the order of their
// first vertex on that curve, so that the elements near each other on the surface lie near each
// other in memory. Searches that wander across a large mesh (the exact window search,
// geometry/geodesic/geodesic_windows.h) run on such a copy: meshes as files give them are often
// numbered at random (bunny-remesh-300k: the vertices of one face lie 56K indices apart at the
// median), and every step of such a search then reads a new cache line (bench/README.md,
// session 12: 5-8 % less time per path at the median, 4-7 % at the mean).
//
// - Every face keeps its corners in their order, so interior halfedge k of face f is interior
//   halfedge k of the face's new index, with the same from and to vertices, and every length,
//   angle and frame is bit for bit the original's.
// - The maps go both ways for vertices, and from the copy to the original for faces and
//   halfedges (boundary halfedges through their twins).
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/mesh/surface_path.h"

namespace windplan {

struct MeshOrder {
  Mesh mesh;                           ///< the renumbered copy
  std::vector<int> vertex_to_local;    ///< original vertex -> its index in `mesh`
  std::vector<int> vertex_from_local;  ///< index in `mesh` -> original vertex
  std::vector<int> face_from_local;    ///< face of `mesh` -> original face

  /// The original halfedge of halfedge h of `mesh` (`original` is the mesh this was made from).
  int halfedge_from_local(const Mesh& original, int h) const;
  /// A point or path on `mesh` as the same point or path on the original.
  SurfacePoint point_from_local(const Mesh& original, const SurfacePoint& p) const;
  SurfacePath path_from_local(const Mesh& original, const SurfacePath& path) const;
};

/// The renumbered copy of `mesh` and its maps (O(V log V + F log F)).
MeshOrder order_for_locality(const Mesh& mesh);

}  // namespace windplan
