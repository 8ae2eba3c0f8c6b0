#pragma once
// Exact cut of a triangle mesh by planes normal to the spindle axis (axial stations).
//
// Every triangle that crosses a station plane is split along it, so that afterwards no triangle
// straddles a plane and the cut is a chain of mesh edges lying on the plane. The split points
// are computed on the crossing edge and then moved along the axis onto the plane, so their
// axial coordinate equals the station to rounding (|axial - station| <= 1e-12 of the mesh size).
// A split edge is split once, at one new vertex shared by both of its triangles, so a closed
// (or open) oriented 2-manifold stays one, with the same orientation.
//
// No slivers: an edge whose crossing lies closer to one of its end vertices than `min_fraction`
// of that vertex's shortest edge is not split; the vertex is moved onto the plane instead (to
// the crossing point on the edge, so it stays on the piecewise-linear surface). A vertex so moves
// by less than min_fraction of its shortest edge (its triangles cannot fold), and every new
// vertex lies at least that far from the corners of the edge it splits. Vertices already within
// 1e-12 of the mesh size are put exactly on the plane.
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"
#include "geometry/region/axis.h"

namespace windplan {

struct PlaneCutOptions {
  /// A crossing closer to an edge's end vertex than this fraction of the vertex's shortest edge
  /// moves the vertex onto the plane instead of splitting the edge (dimensionless, [0, 0.5)).
  double min_fraction = 0.05;
  bool is_valid(std::string* why) const;
};

struct PlaneCutResult {
  Mesh mesh;                       ///< the cut mesh (the input's vertices first, new ones after)
  std::vector<int> face_parent;    ///< per face of `mesh`: the input face it lies in
  std::vector<int> vertex_parent;  ///< per vertex of `mesh`: the input vertex, or -1 if new
  int split_edges = 0;             ///< edges split (new vertices)
  int split_faces = 0;             ///< input faces split into 2 or 3
  int moved_vertices = 0;          ///< vertices moved onto a plane (no-sliver rule)
  double max_move = 0.0;           ///< mm, the largest such move
};

/// Cuts `mesh` by the planes {p : axis.axial(p) = s} for every s in `stations` (mm).
/// \throw ConfigError for invalid options; TopologyError (from Mesh) only if the input was not an
///        oriented manifold.
PlaneCutResult cut_at_stations(const Mesh& mesh, const SpindleAxis& axis,
                               const std::vector<double>& stations,
                               const PlaneCutOptions& options = {});

}  // namespace windplan
