#pragma once
// The CGAL side of geometry/mesh/cgal_mesh.h. Include this ONLY from CGAL translation units (it
// pulls in CGAL, ~15 s and >1 GB to compile), never from a header that other code includes, and
// never together with OCCT headers (OCCT's Handle macro breaks CGAL).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include "geometry/mesh/cgal_mesh.h"

namespace windplan {

using CgalKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalPoint = CgalKernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<CgalPoint>;

/// Mesh -> Surface_mesh: vertex i -> SurfaceMesh::Vertex_index(i), face f ->
/// SurfaceMesh::Face_index(f) with the same cyclic vertex order.
/// \throw InvariantError if CGAL rejects a face (cannot happen for a valid Mesh).
SurfaceMesh to_surface_mesh(const Mesh& mesh);

/// Surface_mesh -> Mesh. Removed (garbage) elements are skipped and the remaining indices
/// compacted in order, so a garbage-free Surface_mesh keeps its indices.
/// \throw TopologyError if a face is not a triangle or the result is not a valid Mesh.
Mesh from_surface_mesh(const SurfaceMesh& sm);

struct CgalMesh::Impl {
  SurfaceMesh mesh;
};

}  // namespace windplan
