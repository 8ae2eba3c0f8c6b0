#pragma once
// Tessellation of a B-rep shape into ONE welded triangle soup (OCCT BRepMesh_IncrementalMesh).
//
// Welding goes through the B-rep topology, not through point coordinates: each B-rep vertex gives
// exactly one mesh vertex; the nodes of each B-rep edge are shared by the faces on both sides of
// it (BRep_Tool::PolygonOnTriangulation maps a face's local node numbers to the edge's nodes, also
// for the two sides of a seam); nodes of degenerate edges (the apex of a sphere or dome) collapse
// onto their vertex and the triangles that collapse with them are dropped; the triangles of
// reversed faces (TopAbs_REVERSED) are flipped. A closed solid therefore gives a closed,
// manifold, consistently oriented soup; when the result is closed with a negative signed volume
// (an inward-oriented shell), every triangle is flipped so that normals point outward.
#include <string>
#include <vector>

#include "geometry/cad/cad_shape.h"
#include "geometry/mesh/mesh.h"

namespace windplan {

struct TessellateOptions {
  /// Maximum distance between the surface and the triangles (mm, > 0).
  double linear_deflection = 0.25;
  /// Maximum angle between the normals of adjacent triangles along a curved surface (degrees,
  /// in (0, 90]).
  double angular_deflection = 10.0;

  bool is_valid(std::string* why) const;
};

/// The angular deflection (degrees) fitted to a curved tube, so that geodesics on the mesh keep
/// their closed form (Clairaut's (R + r cos theta) cos alpha on a bend) to within about 1%: the
/// triangles' edges across the tightest curvature radius `radius` (mm: the tube radius, or the
/// bend's R - r when that is smaller) no longer than a quarter of the band width `band_width` (mm),
/// and never above 5 degrees; clamped to [1.5, 10]. Measured on a 3r bend (r 25, R 75, 3 turns,
/// band 8 mm), the invariant's spread along the bend: 3.2% at 10 deg, 0.9% at 5 deg, 0.3% at
/// 3 deg (tests/planner/mandrel/mandrel_builder_test.cpp).
double fitted_angular_deflection(double radius, double band_width);

/// What a B-rep face is, for selecting the wound region later.
enum class CadSurfaceKind { Plane, Cylinder, Cone, Sphere, Torus, Revolution, Other };

struct CadFaceInfo {
  CadSurfaceKind kind = CadSurfaceKind::Other;
  Vec3 plane_normal = Vec3::Zero();  ///< outward unit normal for a plane, zero otherwise
  int triangles = 0;                 ///< triangles of the soup that came from this face
};

struct Tessellation {
  TriangleSoup soup;               ///< welded, oriented (mm)
  std::vector<int> triangle_face;  ///< per soup triangle: its B-rep face index
  std::vector<CadFaceInfo> faces;  ///< per B-rep face, in TopExp::MapShapes order
  int dropped_triangles = 0;       ///< triangles collapsed at degenerate edges
  bool flipped = false;            ///< every triangle was flipped (inward shell)
  double time_ms = 0.0;            ///< meshing plus welding wall time
};

/// Tessellates and welds `shape` (its triangulation is recomputed with these deflections).
/// \throw ConfigError if options are invalid; InputError if the shape has no faces or a face
///        fails to mesh (naming the face index).
Tessellation tessellate(const CadShape& shape, const TessellateOptions& options = {});

/// "plane", "cylinder", ... for reports.
const char* to_string(CadSurfaceKind kind);

}  // namespace windplan
