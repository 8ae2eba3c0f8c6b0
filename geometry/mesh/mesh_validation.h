#pragma once
// Validation and repair of triangle soups, and the one entry point (build_mesh) that the rest of
// windplan uses to turn a file's soup into a halfedge Mesh.
//
// check_mesh works on any soup, however broken: it needs no connectivity and never throws for a
// topological problem, it counts it. repair_mesh fixes only what is safe and says what it did in
// plain words; what it cannot fix safely (non-manifold edges, non-manifold vertices unless
// asked to split them, non-orientable components) it refuses with a TopologyError naming the
// first few elements.
//
// Definitions used throughout (indices are the soup's, 0-based):
//  - an edge is an unordered vertex pair used by at least one non-degenerate triangle;
//    boundary edge: used by one triangle; non-manifold edge: used by more than two;
//  - an inconsistently oriented edge is an edge of exactly two triangles that both traverse it in
//    the same direction;
//  - a non-manifold vertex is one whose triangles form more than one fan (triangles around a
//    vertex are in the same fan when they are linked through edges incident to that vertex);
//  - components are connected through edges (triangles touching only at a vertex are separate);
//  - boundary loops are the connected components of the graph of boundary edges;
//  - degenerate triangle: repeated vertex index; zero-area triangle: distinct indices but area
//    <= zero_area_tolerance * (bounding-box diagonal)^2.
#include <array>
#include <string>
#include <vector>

#include "geometry/mesh/mesh.h"

namespace windplan {

struct MeshCheckOptions {
  /// A triangle with area <= zero_area_tolerance * bbox_diagonal^2 is "zero-area"
  /// (dimensionless, >= 0).
  double zero_area_tolerance = 1e-14;
  /// How many offending elements each list in MeshHealth keeps (the counts are always complete).
  int max_listed = 20;

  bool is_valid(std::string* why) const;
};

/// The health report of a triangle soup. Lists hold at most MeshCheckOptions::max_listed items.
struct MeshHealth {
  int num_vertices = 0;             ///< points in the soup
  int num_faces = 0;                ///< triangles in the soup
  int num_referenced_vertices = 0;  ///< vertices used by at least one valid triangle
  int num_unreferenced_vertices = 0;
  int num_duplicate_vertices = 0;    ///< points exactly equal to an earlier point
  int num_invalid_triangles = 0;     ///< an index outside [0, V) (never produced by read_mesh)
  int num_degenerate_triangles = 0;  ///< a repeated vertex index
  int num_zero_area_triangles = 0;   ///< distinct indices, area below tolerance
  int num_duplicate_triangles = 0;   ///< same vertex set as an earlier triangle (extra copies)
  int num_edges = 0;
  int num_boundary_edges = 0;
  int num_boundary_loops = 0;
  int num_nonmanifold_edges = 0;
  int num_nonmanifold_vertices = 0;
  int num_inconsistent_edges = 0;  ///< edges traversed twice in the same direction
  int num_components = 0;
  int euler_characteristic = 0;  ///< V_referenced - E + F_valid
  /// (2 - chi - boundary loops) / 2 for a single-component manifold; -1 otherwise.
  int genus = -1;
  bool closed = false;    ///< no boundary edges
  bool manifold = false;  ///< no non-manifold edge or vertex
  bool oriented = false;  ///< no inconsistently oriented edge
  BoundingBox bbox;       ///< of the referenced vertices
  double min_edge_length = 0.0;
  double mean_edge_length = 0.0;
  double max_edge_length = 0.0;

  std::vector<std::array<int, 2>> nonmanifold_edges;   ///< vertex pairs (first few)
  std::vector<int> nonmanifold_vertices;               ///< (first few)
  std::vector<std::array<int, 2>> inconsistent_edges;  ///< vertex pairs (first few)
  std::vector<int> zero_area_triangles;                ///< triangle indices (first few)
  std::vector<int> degenerate_triangles;               ///< triangle indices (first few)

  /// True when the soup can become a windplan Mesh as it is.
  bool is_valid_mesh() const {
    return manifold && oriented && num_invalid_triangles == 0 && num_degenerate_triangles == 0;
  }
  /// The problems in plain words, one per line (empty for a clean closed mesh). Open boundaries
  /// and unreferenced vertices are listed too, as facts rather than errors.
  std::vector<std::string> problems() const;
  /// The subset of problems() that stops the soup from becoming a Mesh (non-manifold edges or
  /// vertices, inconsistent orientation, degenerate or invalid triangles); empty iff
  /// is_valid_mesh().
  std::vector<std::string> blocking_problems() const;
  /// A multi-line human-readable report.
  std::string brief_report() const;
};

/// Analyses a soup. O(F log F). Never throws for a topological problem.
/// \throw ConfigError if options are invalid.
MeshHealth check_mesh(const TriangleSoup& soup, const MeshCheckOptions& options = {});

struct RepairOptions {
  /// Duplicate each non-manifold vertex once per extra fan instead of refusing.
  bool split_nonmanifold_vertices = false;
  /// Make closed components' normals point outward (positive signed volume).
  bool orient_outward = true;
  /// Passed to check_mesh (zero-area threshold).
  MeshCheckOptions check;

  bool is_valid(std::string* why) const;
};

struct RepairResult {
  TriangleSoup soup;                 ///< the repaired soup (vertices compacted)
  std::vector<std::string> changes;  ///< each change in plain words; empty when nothing changed
  std::vector<std::string> kept;     ///< problems deliberately left alone, with the reason
  MeshHealth before;
  MeshHealth after;
  int merged_vertices = 0;
  int removed_degenerate = 0;
  int removed_zero_area = 0;  ///< zero-area triangles removed by an edge flip
  int removed_duplicates = 0;
  int removed_unreferenced = 0;
  int split_vertices = 0;     ///< vertices added by splitting non-manifold vertices
  int flipped_triangles = 0;  ///< re-oriented for consistency or outward normals
};

/// Repairs what is safe, in this order: drop triangles with invalid indices; merge exactly
/// duplicate vertices (only if that creates no non-manifold edge or vertex); drop degenerate
/// triangles; drop duplicate triangles; refuse non-manifold edges; split or refuse non-manifold
/// vertices; drop unreferenced vertices; orient each component consistently (BFS, keeping the
/// majority orientation); turn closed components outward; finally remove zero-area "cap"
/// triangles by flipping their long edge, or drop those on the open boundary (no hole, no area
/// lost); the rest are kept and listed in `kept`.
/// \throw TopologyError naming the first few elements for non-manifold edges, non-manifold
///        vertices (unless split_nonmanifold_vertices) and non-orientable components.
RepairResult repair_mesh(TriangleSoup soup, const RepairOptions& options = {});

/// The one way windplan turns a soup into a Mesh: checks it, repairs it if `repair`, and builds
/// the halfedge mesh. `health_out` receives the health before repair, `changes` the repairs made.
/// \throw TopologyError naming elements when the (repaired) soup cannot be a Mesh.
Mesh build_mesh(TriangleSoup soup, bool repair, MeshHealth* health_out = nullptr,
                std::vector<std::string>* changes = nullptr, const RepairOptions& options = {});

}  // namespace windplan
