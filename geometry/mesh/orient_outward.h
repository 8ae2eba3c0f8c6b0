#pragma once
// Outward normals for a consistently oriented mesh (issue 28: an open tube whose faces all point
// inward was planned and found only by a late replay error; a closed mesh read without repair
// kept its inward normals). Each connected component is closed virtually, every boundary loop
// capped by a fan to the loop's centroid, and the signed volume of that closed surface,
// sum over its triangles of p0 . (p1 x p2) / 6, tells the side the normals point to: negative is
// inward, and the component's triangles are then all reversed. This holds for any tube-like
// component (pipes, cones, bent tubes, vessels with openings), whatever its axis.
//
// - The mesh must be consistently oriented (a Mesh is); an inconsistently oriented soup is
//   repaired or refused by repair_mesh / build_mesh (geometry/mesh/mesh_validation.h) before.
// - A component whose signed volume is zero within tolerance (a flat sheet, a single strip whose
//   caps cancel) is left as it is and counted in `undecided`.
// - Only triangles are reversed: the points and the face order stay, so the face indices of the
//   result are those of the input.
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

struct OrientOutwardOptions {
  /// A component is undecided when |signed volume| <= this * (bbox diagonal)^3 (dimensionless,
  /// >= 0).
  double volume_tolerance = 1e-9;

  bool is_valid(std::string* why) const;
};

struct OrientOutwardSummary {
  int components = 0;  ///< connected components of faces
  int flipped_components = 0;
  int flipped_faces = 0;  ///< triangles reversed
  int undecided = 0;      ///< components whose side could not be told (left as they were)

  /// e.g. "1 of 1 component(s) pointed inward: 1440 triangles reversed".
  std::string brief_report() const;
};

struct OrientOutwardResult {
  Mesh mesh;  ///< the input with inward components reversed (the input itself when none)
  OrientOutwardSummary summary;
};

/// Reverses every component of `mesh` whose normals point inward (see the header comment).
/// \throw ConfigError if options are invalid.
OrientOutwardResult orient_outward(const Mesh& mesh, const OrientOutwardOptions& options = {});

/// The signed volume (mm^3) of the component `component` (ids from Mesh::face_components) of
/// `mesh` closed by its boundary loops' centroid fans: > 0 when its normals point outward.
double capped_signed_volume(const Mesh& mesh, const std::vector<int>& face_component,
                            int component);

}  // namespace windplan
